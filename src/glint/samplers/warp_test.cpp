#include "glint/samplers/warp.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "glint/samplers/hash.h"
#include "stats.h"

namespace glint {
namespace {

Sample2 uniform(std::uint32_t i) {
    return {to_unit_float(mix32(2 * i + 0x1234567)), to_unit_float(mix32(2 * i + 0x89abcde))};
}

TEST(Warp, ConcentricDiskHandValues) {
    const Point2 c = sample_uniform_disk_concentric({0.5f, 0.5f});
    EXPECT_EQ(c.x, 0);
    EXPECT_EQ(c.y, 0);
    const Point2 right = sample_uniform_disk_concentric({1, 0.5f});  // a = 1, b = 0: (1, 0)
    EXPECT_NEAR(right.x, 1, 1e-6);
    EXPECT_NEAR(right.y, 0, 1e-6);
    const Point2 corner = sample_uniform_disk_concentric({1, 1});  // a = b = 1: r = 1 at 45 deg
    EXPECT_NEAR(corner.x, std::sqrt(0.5), 1e-6);
    EXPECT_NEAR(corner.y, std::sqrt(0.5), 1e-6);
}

TEST(Warp, QuarterPiSineAndCosineMatchDoublePrecision) {
    // The concentric map's polynomials against libm's double sin and cos, on a fine grid of
    // [-1, 1] with both ends: within 1.2e-7 (about two float ulps at 1), and exactly 0 and 1 at 0.
    double worst = 0;
    for (int i = -200000; i <= 200000; ++i) {
        const float t = static_cast<float>(i) / 200000.0f;
        const SinCos sc = sin_cos_quarter_pi(t);
        const double phi = std::numbers::pi / 4 * static_cast<double>(t);
        worst = std::max({worst, std::abs(sc.sin - std::sin(phi)), std::abs(sc.cos - std::cos(phi))});
        ASSERT_LE(sc.sin * sc.sin + sc.cos * sc.cos, 1 + 3e-7) << t;
    }
    EXPECT_LT(worst, 1.2e-7);
    EXPECT_EQ(sin_cos_quarter_pi(0).sin, 0.0f);
    EXPECT_EQ(sin_cos_quarter_pi(0).cos, 1.0f);
}

TEST(Warp, ConcentricDiskIsUniformByArea) {
    // 8 rings of equal area (radii sqrt(i/8)) x 16 sectors: 128 equal-area cells.
    const int rings = 8, sectors = 16, n = 256000;
    std::vector<double> observed(rings * sectors, 0), expected(rings * sectors, double(n) / (rings * sectors));
    for (int i = 0; i < n; ++i) {
        const Point2 p = sample_uniform_disk_concentric(uniform(static_cast<std::uint32_t>(i)));
        const double r2 = p.x * p.x + p.y * p.y;
        ASSERT_LE(r2, 1 + 1e-6);
        const int ring = std::min(rings - 1, static_cast<int>(r2 * rings));
        double phi = std::atan2(p.y, p.x);
        if (phi < 0) phi += 2 * std::numbers::pi;
        const int sector = std::min(sectors - 1, static_cast<int>(phi / (2 * std::numbers::pi) * sectors));
        observed[static_cast<std::size_t>(ring * sectors + sector)] += 1;
    }
    EXPECT_LT(testing::chi_square(observed, expected),
              testing::chi_square_critical_1e4(rings * sectors - 1));
}

TEST(Warp, ConcentricDiskFailsTheTestIfNotUniform) {
    // The test above can fail: the naive r = u1 (not sqrt) map crowds the centre and is caught.
    const int rings = 8, n = 64000;
    std::vector<double> observed(rings, 0), expected(rings, double(n) / rings);
    for (int i = 0; i < n; ++i) {
        const double r = uniform(static_cast<std::uint32_t>(i)).x;
        observed[static_cast<std::size_t>(std::min(rings - 1, static_cast<int>(r * r * rings)))] += 1;
    }
    EXPECT_GT(testing::chi_square(observed, expected), testing::chi_square_critical_1e4(rings - 1));
}

TEST(Warp, TriangleBarycentricsAreUniformByArea) {
    // Scaled by k = 8, the barycentric triangle is cut by the integer grid into k^2 congruent
    // small triangles: the lower-left half of square (ix, iy) when ix + iy <= k - 1, its upper
    // right half when ix + iy <= k - 2. Uniform samples fill those k^2 cells evenly.
    const int k = 8, n = 128000;
    std::vector<double> counts(2 * k * k, 0);
    for (int i = 0; i < n; ++i) {
        const Point2 b = sample_uniform_triangle(uniform(static_cast<std::uint32_t>(i)));
        ASSERT_GE(b.x, 0);
        ASSERT_GE(b.y, 0);
        ASSERT_LE(b.x + b.y, 1 + 1e-6);
        const double x = b.x * k, y = b.y * k;
        const int ix = std::min(k - 1, static_cast<int>(x)), iy = std::min(k - 1, static_cast<int>(y));
        const int upper = (x - ix) + (y - iy) > 1 ? 1 : 0;
        counts[static_cast<std::size_t>((ix * k + iy) * 2 + upper)] += 1;
    }
    std::vector<double> observed;
    double outside = 0;
    for (int ix = 0; ix < k; ++ix) {
        for (int iy = 0; iy < k; ++iy) {
            for (int upper = 0; upper < 2; ++upper) {
                const double c = counts[static_cast<std::size_t>((ix * k + iy) * 2 + upper)];
                if (ix + iy + upper <= k - 1) {
                    observed.push_back(c);
                } else {
                    outside += c;
                }
            }
        }
    }
    ASSERT_EQ(observed.size(), static_cast<std::size_t>(k * k));
    EXPECT_LE(outside, 2);  // only round-off right on the hypotenuse
    const std::vector<double> expected(observed.size(), double(n) / (k * k));
    EXPECT_LT(testing::chi_square(observed, expected), testing::chi_square_critical_1e4(k * k - 1));
}

}  // namespace
}  // namespace glint
