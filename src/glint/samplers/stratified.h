#pragma once
// Stratified pixel samples for any count n: correlated multi-jittered sampling (Kensler 2013).
// The n samples occupy distinct cells of an m x k grid (m = floor(sqrt n), k = ceil(n/m)), and
// the offsets inside the cells are permuted so that the x and y projections are stratified too
// (n-rooks). All from stateless hashes of (pixel seed, index): deterministic per pixel.
#include <cstdint>

namespace glint {

struct Sample2 {
    float x, y;
};

/// A pseudo-random permutation of [0, n): a Feistel network on the next power of two, walked
/// until it lands below n.
std::uint32_t permute_index(std::uint32_t i, std::uint32_t n, std::uint32_t seed);

/// Sample `index` of `count` inside the unit square for the pixel with this seed.
Sample2 stratified_sample(std::uint32_t index, std::uint32_t count, std::uint32_t pixel_seed);

/// The per-pixel seed for pixel (x, y) under the scene seed.
std::uint32_t pixel_seed(std::uint64_t scene_seed, std::uint32_t x, std::uint32_t y);

}  // namespace glint
