// The padded Sobol sampler sixteen pairs at a time (sobol_lanes.inl), compiled with AVX-512:
// one call spans four bounces of a path where the eight-lane kernel spans two, for about the same
// latency (docs/performance.md, step 14).
#include <bit>
#include <cstdint>
#include <utility>

#include "glint/samplers/sobol_kernels.h"

namespace glint {
namespace {

#include "glint/samplers/sobol_lanes.inl"

}  // namespace

void sobol_pairs_avx512(std::uint32_t pixel_seed, std::uint32_t spp, std::uint32_t index, std::uint32_t first_dimension,
                        Sample2 out[16]) {
    sobol_pairs_lanes<16>(pixel_seed, spp, index, first_dimension, out);
}

void sobol_keys_avx512(std::uint32_t pixel_seed, std::uint32_t first_dimension, std::uint32_t keys[7 * 16]) {
    sobol_keys_lanes<16>(pixel_seed, first_dimension, keys);
}

void sobol_pairs_keyed_avx512(const std::uint32_t keys[7 * 16], std::uint32_t spp, std::uint32_t index,
                              Sample2 out[16]) {
    sobol_pairs_keyed_lanes<16>(keys, spp, index, out);
}

}  // namespace glint
