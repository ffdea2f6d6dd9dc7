#pragma once
// Stateless hashing for deterministic per-pixel randomness: every random number is a pure
// function of (scene seed, pixel, sample index, dimension), so the image does not depend on the
// number of threads or the order tiles are rendered in. Never rand(), never a shared RNG.
#include <cstdint>

namespace glint {

/// A 32-bit integer finaliser (xorshift-multiply, "lowbias32" constants by C. Wellons): a
/// bijection on uint32 with good avalanche.
constexpr std::uint32_t mix32(std::uint32_t x) {
    x ^= x >> 16;
    x *= 0x7feb352dU;
    x ^= x >> 15;
    x *= 0x846ca68bU;
    x ^= x >> 16;
    return x;
}

/// A 64-bit finaliser (Stafford's "variant 13", as in splitmix64): for checksums and
/// fingerprints (session/checkpoint.cpp).
constexpr std::uint64_t mix64(std::uint64_t h) {
    h ^= h >> 30;
    h *= 0xbf58476d1ce4e5b9ULL;
    h ^= h >> 27;
    h *= 0x94d049bb133111ebULL;
    h ^= h >> 31;
    return h;
}

constexpr std::uint32_t hash_combine(std::uint32_t seed, std::uint32_t v) {
    return mix32(seed ^ (v + 0x9e3779b9U + (seed << 6) + (seed >> 2)));
}

/// Uniform float in [0, 1) from 24 hash bits.
constexpr float to_unit_float(std::uint32_t bits) {
    return static_cast<float>(bits >> 8) * (1.0f / 16777216.0f);
}

}  // namespace glint

namespace glint {

/// A stream of uniform floats from a counter hashed with a seed: for randomness whose count is
/// not known in advance (free-flight sampling in media draws as many numbers as collisions), so
/// that it cannot shift the sampler's dimensions. Deterministic from its seed.
struct HashRng {
    std::uint32_t seed = 0;
    std::uint32_t counter = 0;
    float next() { return to_unit_float(hash_combine(seed, counter++)); }
};

}  // namespace glint
