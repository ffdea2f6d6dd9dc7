// The padded Sobol sampler eight pairs at a time (sobol_lanes.inl), compiled with AVX2.
#include <bit>
#include <cstdint>
#include <utility>

#include "glint/samplers/sobol_kernels.h"

namespace glint {
namespace {

#include "glint/samplers/sobol_lanes.inl"

}  // namespace

void sobol_pairs_avx2(std::uint32_t pixel_seed, std::uint32_t spp, std::uint32_t index, std::uint32_t first_dimension,
                      Sample2 out[8]) {
    sobol_pairs_lanes<8>(pixel_seed, spp, index, first_dimension, out);
}

}  // namespace glint
