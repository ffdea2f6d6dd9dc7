#include "glint/samplers/sampler.h"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <utility>

#include "glint/samplers/hash.h"
#include "glint/samplers/sobol_kernels.h"

namespace glint {

namespace {

std::uint32_t reverse_bits(std::uint32_t v) {
    v = __builtin_bswap32(v);
    v = ((v >> 1) & 0x55555555U) | ((v & 0x55555555U) << 1);
    v = ((v >> 2) & 0x33333333U) | ((v & 0x33333333U) << 2);
    return ((v >> 4) & 0x0f0f0f0fU) | ((v & 0x0f0f0f0fU) << 4);
}

// Sobol dimension 1 with its bits reversed: the generator's columns reversed, so that
// reverse_bits(sobol_1_reversed(i)) == sobol_1(i).
std::uint32_t sobol_1_reversed(std::uint32_t i) {
    std::uint32_t v = 1, result = 0;
    for (; i != 0; i >>= 1, v ^= v << 1) {
        if (i & 1U) result ^= v;
    }
    return result;
}

// The nested scramble on a bit-reversed fraction (owen_scramble without its two reversals).
std::uint32_t owen_scramble_reversed(std::uint32_t v, std::uint32_t seed) {
    // Laine and Karras's hash-based nested scramble (as refined in pbrt-v4): with the bits
    // reversed, each step (xor with an even multiple, add, multiply by an odd number) changes a
    // bit only as a function of the bits below it, i.e. of the more significant bits of the
    // original fraction. That is exactly a nested uniform permutation, in six operations instead
    // of one hash per bit.
    v ^= v * 0x3d20adeaU;
    v += seed;
    v *= (seed >> 16) | 1U;
    v ^= v * 0x05526c56U;
    v ^= v * 0x53a22864U;
    return v;
}

// A 32-bit binary fraction to a float in [0, 1): the top 24 bits, exactly.
float to_float(std::uint32_t v) { return static_cast<float>(v >> 8) * (1.0f / 16777216.0f); }

// Sample `index`'s place among the first spp points of the Sobol sequence, for one dimension
// pair: a random permutation per pair decorrelates the pairs (the padding). For a power-of-two
// spp the even-numbered samples take one half of the points, [0, spp/2) or [spp/2, spp), and the
// odd-numbered ones the other, each half in its own random order. Both halves are
// (0, m-1, 2)-nets, so the two half images (even and odd samples) are stratified estimates like
// the whole, and their difference measures the error of a stratified estimate: what the denoiser
// and adaptive sampling read as the pixel's variance. With one permutation of all spp points each
// half would be a random subset, and its difference the error of unstratified sampling (8 times
// larger on the Cornell box at 16 spp; docs/denoising.md).
std::uint32_t sobol_index(std::uint32_t index, std::uint32_t spp, std::uint32_t seed) {
    if (spp < 2 || (spp & (spp - 1)) != 0) return permute_index(index, spp, seed);
    const std::uint32_t half = spp / 2;
    const std::uint32_t side = (index ^ (seed >> 31)) & 1U;  // which half the even samples take
    return side * half + permute_index(index >> 1, half, hash_combine(seed, side));
}

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
    return reverse_bits(owen_scramble_reversed(reverse_bits(v), seed));
}

Sample2 PixelSampler::get_2d(std::uint32_t index, std::uint32_t dimension) const {
    const std::uint32_t seed = hash_combine(seed_, dimension);
    switch (type_) {
        case SamplerType::kStratified: return stratified_sample(index, spp_, seed);
        case SamplerType::kIndependent:
            return {to_unit_float(hash_combine(seed, 2 * index)),
                    to_unit_float(hash_combine(seed, 2 * index + 1))};
        case SamplerType::kSobol: {
            const std::uint32_t i = sobol_index(index, spp_, hash_combine(seed, 0x5eed));
            // owen_scramble(sobol_0(i)) and owen_scramble(sobol_1(i)), with the reversals that
            // cancel left out (sobol_0 is itself a reversal): two instead of five.
            const float x = to_float(reverse_bits(owen_scramble_reversed(i, hash_combine(seed, 1))));
            const float y = to_float(reverse_bits(owen_scramble_reversed(sobol_1_reversed(i), hash_combine(seed, 2))));
            return {x, y};
        }
    }
    return {0.5f, 0.5f};
}

namespace {

#include "glint/samplers/sobol_lanes.inl"

// Whether the CPU runs the eight-lane kernel (sampler_avx2.cpp) and the sixteen-lane one
// (sampler_avx512.cpp, compiled for x86-64-v4).
const bool kAvx2 = [] {
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx2") != 0;
}();
const bool kAvx512 = [] {
    __builtin_cpu_init();
    return kAvx2 && __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") &&
           __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512dq") &&
           __builtin_cpu_supports("avx512cd");
}();

}  // namespace

bool cpu_runs_sobol_avx2() { return kAvx2; }
bool cpu_runs_sobol_avx512() { return kAvx512; }

void PixelSampler::get_2d_x4(std::uint32_t index, std::uint32_t first_dimension, Sample2 out[4]) const {
    static_assert(sizeof(Sample2) == 2 * sizeof(float));
    if (type_ == SamplerType::kSobol && spp_ >= 4 && (spp_ & (spp_ - 1)) == 0) {
        sobol_pairs_lanes<4>(seed_, spp_, index, first_dimension, out);
        return;
    }
    for (std::uint32_t k = 0; k < 4; ++k) out[k] = get_2d(index, first_dimension + k);
}

void PixelSampler::get_2d_x8(std::uint32_t index, std::uint32_t first_dimension, Sample2 out[8]) const {
    if (kAvx2 && type_ == SamplerType::kSobol && spp_ >= 4 && (spp_ & (spp_ - 1)) == 0) {
        sobol_pairs_avx2(seed_, spp_, index, first_dimension, out);
        return;
    }
    get_2d_x4(index, first_dimension, out);
    get_2d_x4(index, first_dimension + 4, out + 4);
}

int PixelSampler::get_2d_batch(std::uint32_t index, std::uint32_t first_dimension, Sample2 out[16]) const {
    if (kAvx512 && type_ == SamplerType::kSobol && spp_ >= 4 && (spp_ & (spp_ - 1)) == 0) {
        for (int b = 0; b < kept_; ++b) {
            if (kept_first_[b] == first_dimension) {
                sobol_pairs_keyed_avx512(keys_[b], spp_, index, out);
                return 16;
            }
        }
        if (kept_ == kKeptBatches) {
            sobol_pairs_avx512(seed_, spp_, index, first_dimension, out);
            return 16;
        }
        kept_first_[kept_] = first_dimension;
        sobol_keys_avx512(seed_, first_dimension, keys_[kept_]);
        sobol_pairs_keyed_avx512(keys_[kept_++], spp_, index, out);
        return 16;
    }
    get_2d_x8(index, first_dimension, out);
    return 8;
}

}  // namespace glint

namespace glint {

std::uint32_t SampleStream::stream_seed() const {
    return hash_combine(hash_combine(sampler_->seed(), 0x6d656469U /* "medi" */), index_);
}

}  // namespace glint
