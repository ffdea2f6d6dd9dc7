#include "glint/samplers/sampler.h"
#include "glint/samplers/sobol_kernels.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <set>
#include <vector>

#include "stats.h"

namespace glint {
namespace {

TEST(Sobol, FirstPointsOfBothDimensions) {
    // Dimension 0, van der Corput: the bits of i mirrored. Dimension 1: the xor of the direction
    // numbers v1 = 1/2, v2 = 3/4, v3 = 5/8 (m = 1, 3, 5 from m_k = 2 m_{k-1} xor m_{k-1}) for
    // the bits set in i, indexed directly by i (not in Gray-code order): i = 4 -> 5/8,
    // 5 -> 5/8 ^ 1/2 = 1/8, 6 -> 5/8 ^ 3/4 = 3/8, 7 -> 5/8 ^ 3/4 ^ 1/2 = 7/8.
    const double d0[] = {0, 0.5, 0.25, 0.75, 0.125, 0.625, 0.375, 0.875};
    const double d1[] = {0, 0.5, 0.75, 0.25, 0.625, 0.125, 0.375, 0.875};
    for (std::uint32_t i = 0; i < 8; ++i) {
        EXPECT_EQ(sobol_0(i) / 4294967296.0, d0[i]) << i;
        EXPECT_EQ(sobol_1(i) / 4294967296.0, d1[i]) << i;
    }
}

TEST(Sobol, OwenScrambleIsABijectionThatKeepsIntervals) {
    // On 8-bit prefixes: distinct inputs stay distinct, and inputs sharing their top k bits
    // share them after scrambling too (a nested permutation).
    std::set<std::uint32_t> seen;
    for (std::uint32_t i = 0; i < 256; ++i) seen.insert(owen_scramble(i << 24, 77) >> 24);
    EXPECT_EQ(seen.size(), 256u);
    for (std::uint32_t i = 0; i < 256; i += 2) {
        EXPECT_EQ(owen_scramble(i << 24, 5) >> 25, owen_scramble((i + 1) << 24, 5) >> 25);
    }
}

// Every elementary interval [a/2^k, (a+1)/2^k) x [b/2^(m-k), (b+1)/2^(m-k)) holds exactly one
// of the 2^m points: the (0, m, 2)-net property.
void expect_net(const std::vector<Sample2>& points, int m) {
    for (int k = 0; k <= m; ++k) {
        std::set<std::pair<int, int>> cells;
        for (const Sample2& p : points) {
            cells.insert({static_cast<int>(p.x * static_cast<float>(1 << k)),
                          static_cast<int>(p.y * static_cast<float>(1 << (m - k)))});
        }
        EXPECT_EQ(cells.size(), points.size()) << "k=" << k;
    }
}

TEST(Sobol, PowerOfTwoCountsFormA02Net) {
    for (int m : {2, 4, 6, 8}) {
        const auto spp = static_cast<std::uint32_t>(1 << m);
        for (std::uint32_t pixel : {1u, 12345u}) {
            for (std::uint32_t dim : {0u, 1u, 7u}) {
                const PixelSampler s(SamplerType::kSobol, spp, pixel);
                std::vector<Sample2> pts;
                for (std::uint32_t i = 0; i < spp; ++i) pts.push_back(s.get_2d(i, dim));
                expect_net(pts, m);
            }
        }
    }
}

// The half images (even- and odd-numbered samples) are stratified estimates too: each half of a
// power-of-two count is a (0, m-1, 2)-net in every pair, so their difference measures the error
// of a net, as the denoiser and adaptive sampling assume (sampler.cpp, sobol_index).
TEST(Sobol, EvenAndOddSamplesAreEachANet) {
    for (int m : {2, 4, 6, 8}) {
        const auto spp = static_cast<std::uint32_t>(1 << m);
        for (std::uint32_t pixel : {1u, 12345u, 987654321u}) {
            const PixelSampler s(SamplerType::kSobol, spp, pixel);
            for (std::uint32_t dim : {0u, 1u, 2u, 7u}) {
                for (std::uint32_t parity : {0u, 1u}) {
                    std::vector<Sample2> pts;
                    for (std::uint32_t i = parity; i < spp; i += 2) pts.push_back(s.get_2d(i, dim));
                    expect_net(pts, m - 1);
                }
            }
        }
    }
}

TEST(Sobol, IndependentSamplerIsNotANetButIsUniform) {
    // The baseline shows the net test can fail...
    const PixelSampler s(SamplerType::kIndependent, 64, 3);
    std::set<std::pair<int, int>> cells;
    for (std::uint32_t i = 0; i < 64; ++i) {
        const Sample2 p = s.get_2d(i, 0);
        cells.insert({static_cast<int>(p.x * 8), static_cast<int>(p.y * 8)});
    }
    EXPECT_LT(cells.size(), 64u);
    // ...and it is uniform: chi-square over an 8 x 8 grid, many pixels.
    std::vector<double> observed(64, 0), expected(64, 0);
    const int pixels = 2000;
    for (std::uint32_t px = 0; px < pixels; ++px) {
        const PixelSampler ps(SamplerType::kIndependent, 16, pixel_seed(9, px, 0));
        for (std::uint32_t i = 0; i < 16; ++i) {
            const Sample2 p = ps.get_2d(i, 0);
            observed[static_cast<std::size_t>(static_cast<int>(p.x * 8) * 8 + static_cast<int>(p.y * 8))] += 1;
        }
    }
    for (double& e : expected) e = pixels * 16.0 / 64;
    EXPECT_LT(testing::chi_square(observed, expected), testing::chi_square_critical_1e4(63));
}

TEST(Sobol, DimensionsAndPixelsAreDecorrelated) {
    // Over many pixels, the scrambled points of two dimension pairs are independent: the mean
    // of x0 * x1 is 1/4 (it would be 1/3 if the pairs were identical).
    double product = 0;
    int n = 0;
    for (std::uint32_t px = 0; px < 4000; ++px) {
        const PixelSampler s(SamplerType::kSobol, 16, pixel_seed(1, px, 7));
        for (std::uint32_t i = 0; i < 16; ++i) {
            product += static_cast<double>(s.get_2d(i, 0).x) * s.get_2d(i, 1).x;
            ++n;
        }
    }
    EXPECT_NEAR(product / n, 0.25, 0.005);
}

TEST(Sampler, PairsComputedAtOnceAreTheScalarPairsBitForBit) {
    // get_2d_x4, get_2d_x8 and get_2d_batch (SIMD for the Sobol sampler at power-of-two spp, a
    // loop otherwise; one sampler for all of a pixel's indices, so that its kept keys serve later
    // calls, and six first dimensions, more than it keeps), and the eight- and sixteen-lane
    // kernels (the latter also from kept keys) called directly where this CPU has their
    // instruction sets (so that each is checked whichever one the dispatch picks), against
    // get_2d, the reference: every sampler, counts that are and are not powers of two (and the
    // small ones the SIMD path leaves to the loop), every index, dimensions near 0 and near the
    // time pair, and many pixels.
    const auto bits = [](float f) { return std::bit_cast<std::uint32_t>(f); };
    const bool avx2 = cpu_runs_sobol_avx2(), avx512 = cpu_runs_sobol_avx512();
    int kernel_checks = 0;
    for (const SamplerType type : {SamplerType::kSobol, SamplerType::kStratified, SamplerType::kIndependent}) {
        for (const std::uint32_t spp : {1u, 2u, 3u, 4u, 8u, 12u, 64u, 100u, 256u, 4096u, 1u << 20}) {
            const bool simd = type == SamplerType::kSobol && spp >= 4 && (spp & (spp - 1)) == 0;
            for (std::uint32_t px = 0; px < 12; ++px) {
                const std::uint32_t seed = pixel_seed(px * 977u, px, 3 * px);
                const PixelSampler s(type, spp, seed);
                for (std::uint32_t i = 0; i < std::min(spp, 70u); ++i) {
                    const std::uint32_t index = spp > 70 ? (i * 2654435761u) % spp : i;
                    for (const std::uint32_t first : {0u, 1u, 2u, 6u, 37u, kTimeDimension - 3}) {
                        const auto check = [&](const Sample2* got, int n, const char* what) {
                            for (int k = 0; k < n; ++k) {
                                const Sample2 one = s.get_2d(index, first + static_cast<std::uint32_t>(k));
                                ASSERT_EQ(bits(got[k].x), bits(one.x)) << what << " " << spp << " " << index << " " << first + k;
                                ASSERT_EQ(bits(got[k].y), bits(one.y)) << what << " " << spp << " " << index << " " << first + k;
                            }
                        };
                        Sample2 four[4], eight[8], batch[16];
                        s.get_2d_x4(index, first, four);
                        check(four, 4, "x4");
                        s.get_2d_x8(index, first, eight);
                        check(eight, 8, "x8");
                        const int n = s.get_2d_batch(index, first, batch);
                        ASSERT_TRUE(n == 8 || n == 16);
                        check(batch, n, "batch");
                        if (simd && avx2) {
                            sobol_pairs_avx2(seed, spp, index, first, eight);
                            check(eight, 8, "avx2");
                            ++kernel_checks;
                        }
                        if (simd && avx512) {
                            sobol_pairs_avx512(seed, spp, index, first, batch);
                            check(batch, 16, "avx512");
                            alignas(64) std::uint32_t keys[7 * 16];
                            sobol_keys_avx512(seed, first, keys);
                            sobol_pairs_keyed_avx512(keys, spp, index, batch);
                            check(batch, 16, "avx512 keyed");
                            ++kernel_checks;
                        }
                    }
                }
            }
        }
    }
    if (avx2) EXPECT_GT(kernel_checks, 1000);
}

TEST(Sampler, AStreamHandsOutThePairsInOrder) {
    // A stream draws pairs first_pair, first_pair + 1, ... whatever it computes ahead.
    const PixelSampler s(SamplerType::kSobol, 64, pixel_seed(9, 4, 2));
    SampleStream stream(s, 13, 2);
    for (std::uint32_t d = 2; d < 40; ++d) {
        const Sample2 a = stream.next_2d(), b = s.get_2d(13, d);
        ASSERT_EQ(a.x, b.x) << d;
        ASSERT_EQ(a.y, b.y) << d;
    }
}

}  // namespace
}  // namespace glint
