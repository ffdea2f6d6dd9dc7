#pragma once
// The padded Sobol sampler's eight-lane kernel, compiled for AVX2 (sampler_avx2.cpp); called
// only on a CPU that has it (PixelSampler::get_2d_x8 asks).
#include <cstdint>

#include "glint/samplers/stratified.h"

namespace glint {

/// Pairs first_dimension .. first_dimension + 7 of sample `index` of the pixel with seed
/// `pixel_seed`, for a power-of-two spp >= 4: PixelSampler::get_2d's bits.
void sobol_pairs_avx2(std::uint32_t pixel_seed, std::uint32_t spp, std::uint32_t index, std::uint32_t first_dimension,
                      Sample2 out[8]);

}  // namespace glint
