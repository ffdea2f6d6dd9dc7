// Media against closed forms: the phase function's density and sampling, transmittance by delta
// and ratio tracking against exp(-sigma d) and against the optical depth of a linear density,
// the majorant walk against brute-force lookups, the blackbody colour, and .vdb round trips.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>

#include "glint/image/image_io.h"
#include "glint/assets/vdb.h"
#include "glint/media/medium.h"
#include "glint/media/transmittance.h"
#include "sphere_chi2.h"

#include "testing.h"

namespace glint {
namespace {

TEST(HgPhase, IntegratesToOneForEveryG) {
    for (const float g : {-0.9f, -0.5f, 0.0f, 0.3f, 0.8f, 0.95f}) {
        // p depends on cos only: integral = 2 pi int_{-1}^{1} p(mu) dmu, by Simpson's rule.
        const int n = 20000;
        double sum = 0;
        for (int i = 0; i <= n; ++i) {
            const double mu = -1 + 2.0 * i / n;
            const double w = i == 0 || i == n ? 1 : (i % 2 ? 4 : 2);
            sum += w * HgPhase::eval_cos(static_cast<float>(mu), g);
        }
        EXPECT_NEAR(2 * std::numbers::pi * sum * (2.0 / n) / 3, 1, 2e-3) << "g = " << g;
    }
}

TEST(HgPhase, IsotropicIsOneOverFourPi) {
    const HgPhase iso{0};
    EXPECT_FLOAT_EQ(iso.p({0, 0, 1}, {0.6f, 0, 0.8f}), 0.25f / std::numbers::pi_v<float>);
}

TEST(HgPhase, SamplingMatchesDensityChiSquare) {
    const Vector3 wo = normalize(Vector3{0.3f, -0.5f, 0.8f});
    for (const float g : {-0.7f, 0.0f, 0.4f, 0.9f}) {
        HgPhase phase{g};
        std::uint32_t state = 12345;
        const auto fit = testing::fit_sphere(
            [&](int) -> std::optional<Vector3> {
                HashRng rng{state++};
                const PhaseSample s = phase.sample(wo, {rng.next(), rng.next()});
                EXPECT_NEAR(s.pdf, phase.pdf(wo, s.wi), 2e-3f * s.pdf + 1e-6f);
                return s.wi;
            },
            [&](Vector3 wi) { return phase.pdf(wo, wi); }, 400000);
        EXPECT_TRUE(fit.ok()) << "g = " << g << ": " << fit.report();
        EXPECT_NEAR(fit.pdf_integral, 1, 2e-3) << "g = " << g;
    }
}

TEST(HgPhase, MeanCosineIsG) {
    // The defining property: E[cos(theta)] between the incoming travel direction (-wo) and wi is g.
    const Vector3 wo{0, 0, 1};
    for (const float g : {-0.6f, 0.2f, 0.85f}) {
        const HgPhase phase{g};
        double sum = 0;
        const int n = 200000;
        for (int i = 0; i < n; ++i) {
            HashRng rng{static_cast<std::uint32_t>(i)};
            sum += dot(-wo, phase.sample(wo, {rng.next(), rng.next()}).wi);
        }
        EXPECT_NEAR(sum / n, g, 0.01) << "g = " << g;
    }
}

// The fraction of delta-tracking walks that reach distance d with no real collision is
// exp(-sigma_t d) (a binomial proportion: checked within 4 standard deviations).
// Equiangular distance sampling: its density is proportional to 1/|x(t) - c|^2 (checked at
// every sample), integrates to 1 over the interval (Simpson's rule), and the distance drawn
// for u is the u-quantile of that density (the density integrated numerically up to it).
TEST(Equiangular, DensityFollowsInverseSquareAndSamplesItsQuantiles) {
    struct Case { Point3 c; float t_max; };
    const Ray ray{{1, 2, 3}, normalize(Vector3{0.2f, -0.1f, 1})};
    for (const Case k : {Case{{1.5f, 2.5f, 8}, 12}, Case{{0, 0, 0}, 5}, Case{{3, 2, 40}, 20},
                         Case{{1.2f, 2.3f, 6}, std::numeric_limits<float>::infinity()}}) {
        const auto eq = Equiangular::make(ray, k.t_max, k.c);
        ASSERT_TRUE(eq);
        const auto simpson = [&](double a, double b) {
            const int n = 20000;
            double h = (b - a) / n, sum = eq->pdf(float(a)) + eq->pdf(float(b));
            for (int i = 1; i < n; ++i) sum += (i % 2 ? 4 : 2) * eq->pdf(float(a + i * h));
            return sum * h / 3;
        };
        if (!std::isinf(k.t_max)) EXPECT_NEAR(simpson(0, k.t_max), 1, 1e-4);
        double ratio0 = 0;
        for (const float u : {0.01f, 0.2f, 0.5f, 0.8f, 0.99f}) {
            const float t = eq->sample(u);
            ASSERT_GE(t, 0);
            if (!std::isinf(k.t_max)) ASSERT_LE(t, k.t_max);
            const Vector3 d = ray.at(t) - k.c;
            const double r2 = dot(d, d);
            if (ratio0 == 0) ratio0 = eq->pdf(t) * r2;
            EXPECT_NEAR(eq->pdf(t) * r2 / ratio0, 1, 1e-4);
            EXPECT_NEAR(simpson(0, t), u, 1e-4) << "u = " << u;
        }
    }
    // A point on the ray's line has no equiangular density.
    EXPECT_FALSE(Equiangular::make(ray, 10, ray.at(4)));
}

TEST(Transmittance, DeltaTrackingHomogeneousMatchesClosedForm) {
    const Medium m = HomogeneousMedium{Color{0.3f}, Color{0.5f}, Color{0}, {}};
    const Ray ray{{0, 0, 0}, {0, 0, 1}};
    for (const float d : {0.5f, 2.0f, 4.0f}) {
        const int n = 100000;
        int passed = 0;
        for (int i = 0; i < n; ++i) {
            HashRng rng{static_cast<std::uint32_t>(i * 7 + 1)};
            bool collided = false;
            sample_t_maj(m, ray, d, rng.next(), rng, 0, [&](Point3, const MediumPoint&, Color, Color) {
                collided = true;
                return false;
            });
            passed += collided ? 0 : 1;
        }
        const double expect = std::exp(-0.8 * d);
        const double sd = std::sqrt(expect * (1 - expect) / n);
        EXPECT_NEAR(double(passed) / n, expect, 4 * sd + 1e-9) << "d = " << d;
    }
}

// Ratio tracking with a majorant twice sigma_t, in a chromatic medium with a random hero
// channel: the spectral-MIS estimate tr / average(r) is exp(-sigma_c d) per channel.
TEST(Transmittance, RatioTrackingChromaticHomogeneousMatchesClosedForm) {
    const Color sigma{0.2f, 0.7f, 1.5f};
    const Medium m = HomogeneousMedium{sigma, Color{0}, Color{0}, {}};
    const Ray ray{{1, 2, 3}, normalize(Vector3{1, 1, 0})};
    const float d = 1.7f;
    const int n = 200000;
    double sum[3] = {0, 0, 0}, sum2[3] = {0, 0, 0};
    for (int i = 0; i < n; ++i) {
        HashRng rng{static_cast<std::uint32_t>(i) * 2654435761U};
        const int hero = std::min(2, static_cast<int>(rng.next() * 3));
        Color r{1};
        const Color tr = ratio_tracking(m, ray, d, rng, hero, r, 2.0f);
        const Color est = tr / ((r.r + r.g + r.b) / 3);
        for (int c = 0; c < 3; ++c) sum[c] += est[c], sum2[c] += est[c] * est[c];
    }
    for (int c = 0; c < 3; ++c) {
        const double mean = sum[c] / n, var = sum2[c] / n - mean * mean;
        EXPECT_NEAR(mean, std::exp(-sigma[c] * d), 4 * std::sqrt(var / n) + 1e-4) << "channel " << c;
    }
}

// A grid whose density rises linearly along x (trilinear interpolation reproduces a linear
// function exactly): ratio tracking against exp(-sigma (a L + b (x1^2 - x0^2) / 2)), the grid
// placed in the world by a scale and a translation.
TEST(Transmittance, RatioTrackingLinearGridMatchesOpticalDepth) {
    GridMedium g;
    const float a = 0.5f, b = 0.25f;  // density = a + b i, i the index-space x
    g.density = VoxelGrid::from_function({0, 0, 0}, {17, 6, 6}, [&](int i, int, int) { return a + b * float(i); });
    g.majorant = MajorantGrid(g.density, 4);
    g.sigma_a = Color{0.2f};
    g.sigma_s = Color{0.3f};
    g.transform = Transform::translate({-1, 2, 0}) * Transform::scale({0.5f, 0.5f, 0.5f});
    const Medium m = g;
    // World ray along x at index-space y = z = 2.5, from index x0 = 2 to x1 = 14.
    const float x0 = 2, x1 = 14;
    const Point3 start = g.transform.point({x0, 2.5f, 2.5f});
    const Ray ray{start, {1, 0, 0}};
    const float world_len = (x1 - x0) * 0.5f;
    const double depth_index = a * (x1 - x0) + b * (x1 * x1 - x0 * x0) / 2;  // in index units
    const double expect = std::exp(-0.5 * depth_index * 0.5);  // sigma_t 0.5, 0.5 world per index
    const int n = 100000;
    double sum = 0, sum2 = 0;
    for (int i = 0; i < n; ++i) {
        HashRng rng{static_cast<std::uint32_t>(i) + 99};
        Color r{1};
        const Color tr = ratio_tracking(m, ray, world_len, rng, i % 3, r);
        const double e = tr.g / ((r.r + r.g + r.b) / 3);
        sum += e, sum2 += e * e;
    }
    const double mean = sum / n, var = sum2 / n - mean * mean;
    EXPECT_NEAR(mean, expect, 4 * std::sqrt(var / n) + 1e-4);
}

TEST(Transmittance, EmptyGridIsExactlyOne) {
    GridMedium g;
    g.density = VoxelGrid({0, 0, 0}, {8, 8, 8});
    g.majorant = MajorantGrid(g.density);
    g.sigma_s = Color{5};
    HashRng rng{1};
    Color r{1};
    const Color tr = ratio_tracking(Medium{g}, Ray{{-1, 4, 4}, {1, 0, 0}}, 10, rng, 0, r);
    EXPECT_EQ(tr, Color{1});
    EXPECT_EQ(r, Color{1});
}

TEST(VoxelGrid, TrilinearBetweenCentresAndZeroOutside) {
    VoxelGrid v({-2, 0, 0}, {3, 2, 2});
    v.set(-2, 0, 0, 1);
    v.set(-1, 0, 0, 3);
    EXPECT_FLOAT_EQ(v.lookup({-2, 0, 0}), 1);
    EXPECT_FLOAT_EQ(v.lookup({-1.5f, 0, 0}), 2);
    EXPECT_FLOAT_EQ(v.lookup({-1.5f, 0.5f, 0}), 1);   // halfway to the empty row y = 1
    EXPECT_FLOAT_EQ(v.lookup({-2.5f, 0, 0}), 0.5f);   // halfway to the outside (0)
    EXPECT_FLOAT_EQ(v.lookup({50, 0, 0}), 0);
    EXPECT_FLOAT_EQ(v.lookup({std::nanf(""), 0, 0}), 0);
    EXPECT_EQ(v.brick_count(), 1u);
}

// Property: every majorant segment bounds the density at any point of it, and the segments
// tile the clipped ray without gaps.
TEST(MajorantGrid, SegmentsTileTheRayAndBoundTheDensity) {
    const VoxelGrid v = VoxelGrid::from_function({-5, 0, 3}, {40, 23, 31}, [](int i, int j, int k) {
        const float s = std::sin(0.3f * float(i)) * std::cos(0.2f * float(j) + 0.1f * float(k));
        return s > 0.2f ? s : 0.0f;
    });
    const MajorantGrid maj(v);
    const Bounds3 box = v.support();
    HashRng rng{7};
    for (int trial = 0; trial < 300; ++trial) {
        const Point3 o{box.lo.x - 5 + 50 * rng.next(), box.lo.y - 5 + 33 * rng.next(), box.lo.z - 5 + 41 * rng.next()};
        const Vector3 d = normalize(Vector3{rng.next() - 0.5f, rng.next() - 0.5f, rng.next() - 0.5f});
        MajorantWalk walk(maj, o, d, 0, 200);
        MajorantSegment s;
        float last = -1;
        while (walk.next(s)) {
            if (last >= 0) {
                EXPECT_NEAR(s.t0, last, 1e-3f);
            }
            EXPECT_LE(s.t0, s.t1);
            last = s.t1;
            for (int k = 0; k < 8; ++k) {
                const float t = s.t0 + (s.t1 - s.t0) * rng.next();
                EXPECT_LE(v.lookup(o + d * t), s.sigma * (1 + 1e-5f) + 1e-6f);
            }
        }
        // Outside the walked segments the density is 0.
        for (int k = 0; k < 16; ++k) {
            const float t = 200 * rng.next();
            bool covered = false;
            MajorantWalk again(maj, o, d, 0, 200);
            while (again.next(s)) covered |= t >= s.t0 - 1e-3f && t <= s.t1 + 1e-3f;
            if (!covered) {
                EXPECT_EQ(v.lookup(o + d * t), 0);
            }
        }
    }
}

TEST(Blackbody, WhiteNearD65AndRedderWhenCooler) {
    const Color d65 = blackbody_rgb(6504);
    EXPECT_NEAR(d65.r / d65.g, 1, 0.08);
    EXPECT_NEAR(d65.b / d65.g, 1, 0.08);
    const Color candle = blackbody_rgb(1900);
    EXPECT_GT(candle.r, 2 * candle.g);
    EXPECT_GT(candle.g, candle.b);
    EXPECT_EQ(blackbody_rgb(0), Color{0});
    // Normalised to its spectral peak: at 1000 K the peak lies in the infrared (2.9 um, Wien), so
    // little of it is visible, and that little is red; from 3000 K on the visible part is of order 1.
    const Color ember = blackbody_rgb(1000);
    EXPECT_GT(ember.r, 0);
    EXPECT_LT(ember.r, 1e-3f);
    EXPECT_GT(ember.r, 10 * ember.b);
    for (const float t : {3000.0f, 10000.0f, 20000.0f}) {
        const Color c = blackbody_rgb(t);
        EXPECT_GT(c.max_component(), 0.01f) << t;
        EXPECT_LT(c.max_component(), 3.0f) << t;
    }
}

TEST(Vdb, RoundTripKeepsValuesAndTransform) {
    const testing::TempDir tmp;  // removed at the end of the test, whatever fails
    const std::filesystem::path& dir = tmp.path();
    const auto path = dir / "grid.vdb";
    const VoxelGrid v = VoxelGrid::from_function({-3, 1, 2}, {12, 9, 10}, [](int i, int j, int k) {
        return float((i + 3) * 100 + j * 10 + k) / 1000.0f;
    });
    write_vdb(path, {{"smoke", &v}}, 0.25f);
    const auto names = vdb_grids(path);
    ASSERT_EQ(names.size(), 1u);
    EXPECT_EQ(names[0].first, "smoke");
    EXPECT_EQ(names[0].second, "float");
    const VdbGrid g = read_vdb_grid(path, "smoke");
    EXPECT_FLOAT_EQ(g.grid.voxel(-3, 1, 2), v.voxel(-3, 1, 2));
    EXPECT_FLOAT_EQ(g.grid.voxel(8, 9, 11), v.voxel(8, 9, 11));
    EXPECT_FLOAT_EQ(g.grid.voxel(4, 5, 6), v.voxel(4, 5, 6));
    const Point3 w = g.index_to_world.point({4, 8, -2});
    EXPECT_FLOAT_EQ(w.x, 1);
    EXPECT_FLOAT_EQ(w.y, 2);
    EXPECT_FLOAT_EQ(w.z, -0.5f);
    EXPECT_THROW(read_vdb_grid(path, "density"), IoError);
    EXPECT_THROW(read_vdb_grid(dir / "missing.vdb", "smoke"), IoError);
}

}  // namespace
}  // namespace glint
