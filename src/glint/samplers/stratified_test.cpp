#include "glint/samplers/stratified.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <vector>

#include "glint/samplers/hash.h"
#include "stats.h"

namespace glint {
namespace {

TEST(Stratified, PermuteIndexIsABijection) {
    for (std::uint32_t n : {1u, 2u, 3u, 7u, 16u, 17u, 100u, 1000u}) {
        for (std::uint32_t seed : {0u, 1u, 0xdeadbeefu}) {
            std::set<std::uint32_t> seen;
            for (std::uint32_t i = 0; i < n; ++i) {
                const std::uint32_t p = permute_index(i, n, seed);
                EXPECT_LT(p, n);
                seen.insert(p);
            }
            EXPECT_EQ(seen.size(), n) << "n=" << n << " seed=" << seed;
        }
    }
}

// Over seeds, the permutations are a rich family: where 0 and 1 go does not fix where 2 goes.
// (The bijective hash used before produced only n^2 of the n(n-1)(n-2) ordered triples, which
// left the Sobol sampler's padded dimension pairs correlated.) And where 0 goes is uniform.
TEST(Stratified, PermutationsOverSeedsReachEveryTripleAndAreUniform) {
    for (std::uint32_t n : {16u, 64u}) {
        std::set<std::uint32_t> triples;
        std::vector<double> first(n, 0), expected(n, 0);
        const int seeds = 200000;
        for (int s = 0; s < seeds; ++s) {
            const std::uint32_t seed = mix32(static_cast<std::uint32_t>(s) + 1000);
            const std::uint32_t a = permute_index(0, n, seed), b = permute_index(1, n, seed),
                                c = permute_index(2, n, seed);
            triples.insert((a * n + b) * n + c);
            first[a] += 1;
        }
        for (double& e : expected) e = seeds / static_cast<double>(n);
        // n = 16: 3360 triples, each expected 60 times. n = 64: 249,984 triples, 0.8 times each:
        // a uniform draw reaches 1 - e^-0.8 = 55 % of them.
        const double cells = n * (n - 1.0) * (n - 2.0);
        EXPECT_GT(static_cast<double>(triples.size()), (n == 16 ? 0.999 : 0.5) * cells) << "n=" << n;
        EXPECT_LT(testing::chi_square(first, expected), testing::chi_square_critical_1e4(static_cast<int>(n) - 1))
            << "n=" << n;
    }
}

TEST(Stratified, SquareCountsFillEveryCellAndEveryRow) {
    // 16 samples: one in each cell of the 4x4 grid, and one in each of the 16 thin strips in x
    // and in y (multi-jittered / n-rooks).
    const std::uint32_t n = 16;
    for (std::uint32_t seed : {3u, 99u, 123456u}) {
        std::set<int> cells, xs, ys;
        for (std::uint32_t i = 0; i < n; ++i) {
            const Sample2 s = stratified_sample(i, n, seed);
            ASSERT_GE(s.x, 0.0f);
            ASSERT_LT(s.x, 1.0f);
            ASSERT_GE(s.y, 0.0f);
            ASSERT_LT(s.y, 1.0f);
            cells.insert(static_cast<int>(s.x * 4) + 4 * static_cast<int>(s.y * 4));
            xs.insert(static_cast<int>(s.x * 16));
            ys.insert(static_cast<int>(s.y * 16));
        }
        EXPECT_EQ(cells.size(), 16u);
        EXPECT_EQ(xs.size(), 16u);
        EXPECT_EQ(ys.size(), 16u);
    }
}

TEST(Stratified, OtherCountsOccupyDistinctCells) {
    for (std::uint32_t n : {2u, 3u, 5u, 7u, 10u, 33u}) {
        const auto m = static_cast<std::uint32_t>(std::sqrt(static_cast<double>(n)));
        const std::uint32_t k = (n + m - 1) / m;
        std::set<std::uint32_t> cells;
        for (std::uint32_t i = 0; i < n; ++i) {
            const Sample2 s = stratified_sample(i, n, 7);
            cells.insert(static_cast<std::uint32_t>(s.x * m) + m * static_cast<std::uint32_t>(s.y * k));
        }
        EXPECT_EQ(cells.size(), n) << "n=" << n;
    }
}

TEST(Stratified, MeanOfManyPixelsIsCentred) {
    // Over many pixels the samples are uniform: the mean is 1/2 within statistical noise
    // (standard error of the mean of U(0,1) over 64k values ~ 0.0011).
    double sx = 0, sy = 0;
    int count = 0;
    for (std::uint32_t px = 0; px < 4096; ++px) {
        const std::uint32_t seed = pixel_seed(42, px, px / 64);
        for (std::uint32_t i = 0; i < 16; ++i) {
            const Sample2 s = stratified_sample(i, 16, seed);
            sx += s.x, sy += s.y;
            ++count;
        }
    }
    EXPECT_NEAR(sx / count, 0.5, 0.005);
    EXPECT_NEAR(sy / count, 0.5, 0.005);
}

TEST(Stratified, SamplesArePureFunctionsOfSeedAndIndex) {
    EXPECT_EQ(pixel_seed(1, 2, 3), pixel_seed(1, 2, 3));
    EXPECT_NE(pixel_seed(1, 2, 3), pixel_seed(1, 3, 2));
    EXPECT_NE(pixel_seed(1, 2, 3), pixel_seed(2, 2, 3));
    const Sample2 a = stratified_sample(5, 9, 77), b = stratified_sample(5, 9, 77);
    EXPECT_EQ(a.x, b.x);
    EXPECT_EQ(a.y, b.y);
}

}  // namespace
}  // namespace glint
