#include "glint/samplers/sampler.h"

#include <algorithm>
#include <bit>

#include "glint/samplers/hash.h"

#if defined(__SSE4_1__)
#include <immintrin.h>
#endif

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

#if defined(__SSE4_1__)
namespace {

// The scalar steps above, four lanes at a time (unsigned 32-bit arithmetic: wrapping multiplies
// and logical shifts, as in the scalar code).
using U4 = __m128i;
U4 splat(std::uint32_t v) { return _mm_set1_epi32(static_cast<int>(v)); }
U4 mul(U4 a, U4 b) { return _mm_mullo_epi32(a, b); }
U4 mul(U4 a, std::uint32_t b) { return _mm_mullo_epi32(a, splat(b)); }
U4 shr(U4 a, unsigned n) { return _mm_srl_epi32(a, _mm_cvtsi32_si128(static_cast<int>(n))); }
U4 shl(U4 a, unsigned n) { return _mm_sll_epi32(a, _mm_cvtsi32_si128(static_cast<int>(n))); }
// (^, & and | on __m128i are GCC's and clang's bitwise vector operators; + would add 64-bit
// lanes, so additions are spelled out.)
U4 add(U4 a, U4 b) { return _mm_add_epi32(a, b); }

U4 mix32_x4(U4 x) {
    x = x ^ _mm_srli_epi32(x, 16);
    x = mul(x, 0x7feb352dU);
    x = x ^ _mm_srli_epi32(x, 15);
    x = mul(x, 0x846ca68bU);
    return x ^ _mm_srli_epi32(x, 16);
}
U4 hash_combine_x4(U4 seed, U4 v) {
    return mix32_x4(seed ^ add(add(v, splat(0x9e3779b9U)), add(_mm_slli_epi32(seed, 6), _mm_srli_epi32(seed, 2))));
}
U4 rotl_x4(U4 x, unsigned n) { return n == 0 ? x : shl(x, n) | shr(x, 32 - n); }

U4 reverse_bits_x4(U4 v) {
    v = _mm_shuffle_epi8(v, _mm_setr_epi8(3, 2, 1, 0, 7, 6, 5, 4, 11, 10, 9, 8, 15, 14, 13, 12));
    const U4 m1 = splat(0x55555555U), m2 = splat(0x33333333U), m4 = splat(0x0f0f0f0fU);
    v = (_mm_srli_epi32(v, 1) & m1) | _mm_slli_epi32(v & m1, 1);
    v = (_mm_srli_epi32(v, 2) & m2) | _mm_slli_epi32(v & m2, 2);
    return (_mm_srli_epi32(v, 4) & m4) | _mm_slli_epi32(v & m4, 4);
}

U4 owen_scramble_reversed_x4(U4 v, U4 seed) {
    v = v ^ mul(v, 0x3d20adeaU);
    v = add(v, seed);
    v = mul(v, _mm_srli_epi32(seed, 16) | splat(1));
    v = v ^ mul(v, 0x05526c56U);
    return v ^ mul(v, 0x53a22864U);
}

// permute_index(i, n, seed) for a power of two n >= 2, where the Feistel network's output is
// always below n and no cycle walk is needed.
U4 permute_index_pow2_x4(U4 i, std::uint32_t n, U4 seed) {
    const auto bits = static_cast<unsigned>(std::bit_width(n - 1));
    const unsigned a = bits / 2, c = bits - a;
    const U4 keys[2] = {seed, mix32_x4(seed)};
    U4 left = shr(i, c), right = i & splat((1U << c) - 1U);
    unsigned left_bits = a, right_bits = c;
    for (unsigned round = 0; round < 4; ++round) {
        const U4 k = rotl_x4(keys[round & 1], round * 5);
        const U4 f = mul(mul(right ^ k, 0x9e3779b1U) ^ k, 0x85ebca6bU);
        const U4 t = left_bits == 0 ? left : left ^ shr(f, 32 - left_bits);
        left = right;
        right = t;
        std::swap(left_bits, right_bits);
    }
    return shl(left, right_bits) | right;
}

void store_x4(U4 xs, U4 ys, Sample2 out[4]) {
    const __m128 scale = _mm_set1_ps(1.0f / 16777216.0f);
    const __m128 x = _mm_mul_ps(_mm_cvtepi32_ps(_mm_srli_epi32(xs, 8)), scale);
    const __m128 y = _mm_mul_ps(_mm_cvtepi32_ps(_mm_srli_epi32(ys, 8)), scale);
    _mm_storeu_ps(&out[0].x, _mm_unpacklo_ps(x, y));
    _mm_storeu_ps(&out[2].x, _mm_unpackhi_ps(x, y));
}

}  // namespace
#endif

void PixelSampler::get_2d_x4(std::uint32_t index, std::uint32_t first_dimension, Sample2 out[4]) const {
    static_assert(sizeof(Sample2) == 2 * sizeof(float));
#if defined(__SSE4_1__)
    if (type_ == SamplerType::kSobol && spp_ >= 4 && (spp_ & (spp_ - 1)) == 0) {
        const U4 dims = add(splat(first_dimension), _mm_setr_epi32(0, 1, 2, 3));
        const U4 seed = hash_combine_x4(splat(seed_), dims);
        // sobol_index(index, spp, hash_combine(seed, 0x5eed)), lane by lane.
        const U4 index_seed = hash_combine_x4(seed, splat(0x5eed));
        const U4 side = (splat(index) ^ _mm_srli_epi32(index_seed, 31)) & splat(1);
        const std::uint32_t half = spp_ / 2;
        const U4 i = add(mul(side, half), permute_index_pow2_x4(splat(index >> 1), half, hash_combine_x4(index_seed, side)));
        // sobol_1_reversed(i): the columns v = 1, 3, 5, 15, ... xored where i has a bit.
        U4 sobol1 = _mm_setzero_si128();
        std::uint32_t v = 1;
        for (unsigned b = 0, n = static_cast<unsigned>(std::bit_width(spp_ - 1)); b < n; ++b, v ^= v << 1)
            sobol1 = sobol1 ^ (splat(v) & _mm_sub_epi32(_mm_setzero_si128(), shr(i, b) & splat(1)));
        const U4 xs = reverse_bits_x4(owen_scramble_reversed_x4(i, hash_combine_x4(seed, splat(1))));
        const U4 ys = reverse_bits_x4(owen_scramble_reversed_x4(sobol1, hash_combine_x4(seed, splat(2))));
        store_x4(xs, ys, out);
        return;
    }
#endif
    for (std::uint32_t k = 0; k < 4; ++k) out[k] = get_2d(index, first_dimension + k);
}

}  // namespace glint

namespace glint {

std::uint32_t SampleStream::stream_seed() const {
    return hash_combine(hash_combine(sampler_->seed(), 0x6d656469U /* "medi" */), index_);
}

}  // namespace glint
