#pragma once
// The padded Sobol sampler's SIMD kernels: eight lanes compiled for AVX2 (sampler_avx2.cpp),
// sixteen compiled for AVX-512 (sampler_avx512.cpp); each called only on a CPU that has its
// instruction set (PixelSampler asks).
#include <cstdint>

#include "glint/samplers/stratified.h"

namespace glint {

/// Whether this CPU runs each kernel (asked once, at start-up): what PixelSampler dispatches on.
bool cpu_runs_sobol_avx2();
bool cpu_runs_sobol_avx512();

/// Pairs first_dimension .. first_dimension + 7 of sample `index` of the pixel with seed
/// `pixel_seed`, for a power-of-two spp >= 4: PixelSampler::get_2d's bits.
void sobol_pairs_avx2(std::uint32_t pixel_seed, std::uint32_t spp, std::uint32_t index, std::uint32_t first_dimension,
                      Sample2 out[8]);

/// The same for the sixteen pairs first_dimension .. first_dimension + 15.
void sobol_pairs_avx512(std::uint32_t pixel_seed, std::uint32_t spp, std::uint32_t index, std::uint32_t first_dimension,
                        Sample2 out[16]);

/// What the sixteen pairs first_dimension .. first_dimension + 15 depend on besides the sample
/// index (seven rows of sixteen lanes: the index seeds' top bits, the permutations' round keys for
/// either half, the scramble seeds), computed once for all of a pixel's samples.
void sobol_keys_avx512(std::uint32_t pixel_seed, std::uint32_t first_dimension, std::uint32_t keys[7 * 16]);
/// sobol_pairs_avx512's pairs of sample `index` from those keys: the same bits.
void sobol_pairs_keyed_avx512(const std::uint32_t keys[7 * 16], std::uint32_t spp, std::uint32_t index,
                              Sample2 out[16]);

}  // namespace glint
