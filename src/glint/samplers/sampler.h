#pragma once
// Per-pixel sample patterns. A sample is a pure function of (pixel seed, sample index,
// dimension), so images are bit-identical for any thread count and tile order.
//
//  - kSobol (the default): Owen-scrambled Sobol points, "padded" as in pbrt-v4: every 2D
//    dimension pair uses the first two Sobol dimensions (van der Corput, and the dimension with
//    direction numbers v_k = v_{k-1} xor (v_{k-1} >> 1)), with its own nested uniform (Owen)
//    scramble and its own permutation of the sample indices. For spp = 2^m the points of each
//    pair form a (0, m, 2)-net: every elementary interval of area 1/spp holds exactly one.
//  - kStratified: correlated multi-jittered samples (stratified.h), for any spp.
//  - kIndependent: uniform random points, no stratification (a baseline for comparisons).
#include <cstdint>

#include "glint/samplers/stratified.h"

namespace glint {

enum class SamplerType { kSobol, kStratified, kIndependent };

/// The i-th point of Sobol dimension 0 (van der Corput) and 1, as 32-bit binary fractions.
std::uint32_t sobol_0(std::uint32_t i);
std::uint32_t sobol_1(std::uint32_t i);

/// Nested scrambling of a 32-bit binary fraction: bit b is flipped or not by a function of the
/// seed and the bits above b, so every subinterval is permuted on its own (Owen 1995), computed
/// with Laine and Karras's hash (sampler.cpp).
std::uint32_t owen_scramble(std::uint32_t v, std::uint32_t seed);

class PixelSampler {
public:
    PixelSampler(SamplerType type, std::uint32_t spp, std::uint32_t pixel_seed)
        : type_(type), spp_(spp), seed_(pixel_seed) {}
    /// Sample `index` (< spp) of the 2D dimension pair `dimension`, in [0, 1)^2.
    Sample2 get_2d(std::uint32_t index, std::uint32_t dimension) const;
    /// The four pairs first_dimension .. first_dimension + 3 of sample `index`, equal to
    /// get_2d's bit for bit: for the Sobol sampler at a power-of-two spp, computed four lanes at
    /// once (sobol_lanes.inl: SSE4.1 integer multiplies; every step is integer arithmetic, so no
    /// lane can round differently from the scalar code).
    [[gnu::noinline]] void get_2d_x4(std::uint32_t index, std::uint32_t first_dimension, Sample2 out[4]) const;
    /// The eight pairs first_dimension .. first_dimension + 7, the same way: eight lanes at once
    /// where the CPU has AVX2 (sampler_avx2.cpp), two get_2d_x4 otherwise.
    [[gnu::noinline]] void get_2d_x8(std::uint32_t index, std::uint32_t first_dimension, Sample2 out[8]) const;
    /// The pairs first_dimension, first_dimension + 1, ... of sample `index`, as many as one call
    /// computes best on this CPU: sixteen in the lanes of one 512-bit vector where the CPU has
    /// AVX-512 (sampler_avx512.cpp; the Sobol sampler at a power-of-two spp), else get_2d_x8's
    /// eight. Returns how many it wrote; each is get_2d's bits. With AVX-512, what the first
    /// kKeptBatches distinct batches depend on besides the index is kept for the pixel's later
    /// samples (so a PixelSampler is for one thread).
    [[gnu::noinline]] int get_2d_batch(std::uint32_t index, std::uint32_t first_dimension, Sample2 out[16]) const;
    std::uint32_t seed() const { return seed_; }

private:
    SamplerType type_;
    std::uint32_t spp_;
    std::uint32_t seed_;
    static constexpr int kKeptBatches = 2;
    mutable int kept_ = 0;  ///< batches whose keys are in keys_
    mutable std::uint32_t kept_first_[kKeptBatches];
    alignas(64) mutable std::uint32_t keys_[kKeptBatches][7 * 16];  ///< sobol_keys_avx512's rows
};

/// The dimension pair whose first number is a camera sample's time over the shutter, drawn only
/// where something moves (far past any pair a path uses, so that drawing it changes no other).
inline constexpr std::uint32_t kTimeDimension = 0x7fffu;

/// The dimensions of one camera sample, handed out in order: an integrator draws what it needs
/// per bounce, and the same path always gets the same numbers. Pairs 0 (pixel) and 1 (lens)
/// belong to the camera; the integrator's start at pair 2. The pairs are computed eight or
/// sixteen at a time (get_2d_batch) and handed out one by one: a pair's value depends only on its
/// number, so computing one that is never drawn changes nothing.
class SampleStream {
public:
    SampleStream(const PixelSampler& sampler, std::uint32_t index, std::uint32_t first_pair = 2)
        : sampler_(&sampler), index_(index), pair_(first_pair) {}
    // Inlined where it is drawn (the path loop): three of four calls are a load and an increment,
    // and the call itself would cost as much (the loop outgrew GCC's inlining limits once).
    [[gnu::always_inline]] Sample2 next_2d() {
        if (next_ == filled_) {
            filled_ = sampler_->get_2d_batch(index_, pair_, buffer_);
            pair_ += static_cast<std::uint32_t>(filled_);
            next_ = 0;
        }
        return buffer_[next_++];
    }
    /// One number: the first coordinate of a fresh pair (which stays stratified on its own).
    float next_1d() { return next_2d().x; }
    /// A seed for this sample's own random stream (HashRng), a function of (pixel seed, index)
    /// that draws no dimension.
    std::uint32_t stream_seed() const;

private:
    const PixelSampler* sampler_;
    std::uint32_t index_;
    std::uint32_t pair_;  ///< the first pair not yet computed
    int next_ = 0;        ///< the next of buffer_ to hand out
    int filled_ = 0;      ///< how many of buffer_ hold pairs
    Sample2 buffer_[16];
};

}  // namespace glint
