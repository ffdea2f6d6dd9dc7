#include "glint/samplers/sampler.h"

#include <algorithm>

#include "glint/samplers/hash.h"

namespace glint {

namespace {

std::uint32_t reverse_bits(std::uint32_t v) {
    v = ((v >> 1) & 0x55555555U) | ((v & 0x55555555U) << 1);
    v = ((v >> 2) & 0x33333333U) | ((v & 0x33333333U) << 2);
    v = ((v >> 4) & 0x0f0f0f0fU) | ((v & 0x0f0f0f0fU) << 4);
    v = ((v >> 8) & 0x00ff00ffU) | ((v & 0x00ff00ffU) << 8);
    return (v >> 16) | (v << 16);
}

// A 32-bit binary fraction to a float in [0, 1): the top 24 bits, exactly.
float to_float(std::uint32_t v) { return static_cast<float>(v >> 8) * (1.0f / 16777216.0f); }

}  // namespace

std::uint32_t sobol_0(std::uint32_t i) { return reverse_bits(i); }

std::uint32_t sobol_1(std::uint32_t i) {
    std::uint32_t v = 1U << 31, result = 0;
    for (; i != 0; i >>= 1, v ^= v >> 1) {
        if (i & 1U) result ^= v;
    }
    return result;
}

std::uint32_t owen_scramble(std::uint32_t v, std::uint32_t seed) {
    // Laine and Karras's hash-based nested scramble (as refined in pbrt-v4): with the bits
    // reversed, each step (xor with an even multiple, add, multiply by an odd number) changes a
    // bit only as a function of the bits below it, i.e. of the more significant bits of the
    // original fraction. That is exactly a nested uniform permutation, in six operations instead
    // of one hash per bit.
    v = reverse_bits(v);
    v ^= v * 0x3d20adeaU;
    v += seed;
    v *= (seed >> 16) | 1U;
    v ^= v * 0x05526c56U;
    v ^= v * 0x53a22864U;
    return reverse_bits(v);
}

Sample2 PixelSampler::get_2d(std::uint32_t index, std::uint32_t dimension) const {
    const std::uint32_t seed = hash_combine(seed_, dimension);
    switch (type_) {
        case SamplerType::kStratified: return stratified_sample(index, spp_, seed);
        case SamplerType::kIndependent:
            return {to_unit_float(hash_combine(seed, 2 * index)),
                    to_unit_float(hash_combine(seed, 2 * index + 1))};
        case SamplerType::kSobol: {
            const std::uint32_t i = permute_index(index, spp_, hash_combine(seed, 0x5eed));
            const float x = to_float(owen_scramble(sobol_0(i), hash_combine(seed, 1)));
            const float y = to_float(owen_scramble(sobol_1(i), hash_combine(seed, 2)));
            return {x, y};
        }
    }
    return {0.5f, 0.5f};
}

}  // namespace glint

namespace glint {

std::uint32_t SampleStream::stream_seed() const {
    return hash_combine(hash_combine(sampler_->seed(), 0x6d656469U /* "medi" */), index_);
}

}  // namespace glint
