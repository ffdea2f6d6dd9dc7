// MIP pyramids and filtered lookups against independent computations: every level against a
// brute-force area average of the level before, means kept, memory within a third; trilinear and EWA
// at their limits (a footprint under a texel is the bilinear lookup, one over the whole image
// the mean); EWA's weights centred (a ramp reads its value at the centre) and normalised (a
// constant reads itself), and averaging a texel checker to grey where bilinear cannot.
#include "glint/textures/mipmap.h"

#include <gtest/gtest.h>

#include <cmath>

#include "glint/samplers/hash.h"

namespace glint {
namespace {

float rnd(std::uint32_t seed, std::uint32_t i) { return to_unit_float(hash_combine(seed, i)); }

Image random_image(int w, int h, std::uint32_t seed) {
    Image image{w, h, {}, {}};
    for (int i = 0; i < w * h; ++i) {
        const auto u = static_cast<std::uint32_t>(i);
        image.texels.push_back(Color{rnd(seed, 3 * u), rnd(seed, 3 * u + 1), rnd(seed, 3 * u + 2)});
    }
    return image;
}

double mean_g(const Image& image) {
    double s = 0;
    for (const Color& c : image.texels) s += c.g;
    return s / static_cast<double>(image.texels.size());
}

// A texel (x, y) of the next level should be the mean of `base` (the level before) over the
// square it covers: here by point sampling base (nearest texel) on a fine grid over that square.
double brute_force_texel(const Image& base, const Image& level, int x, int y) {
    const double sx = static_cast<double>(base.width) / level.width, sy = static_cast<double>(base.height) / level.height;
    constexpr int kN = 96;
    double sum = 0;
    for (int j = 0; j < kN; ++j) {
        for (int i = 0; i < kN; ++i) {
            const double px = (x + (i + 0.5) / kN) * sx, py = (y + (j + 0.5) / kN) * sy;
            sum += base.texel(static_cast<int>(px), static_cast<int>(py)).g;
        }
    }
    return sum / (kN * kN);
}

TEST(MipMap, EveryLevelIsTheAreaMeanOfTheImage) {
    for (const auto& [w, h] : {std::pair{8, 8}, {13, 7}, {5, 17}, {1, 6}}) {
        const Image base = random_image(w, h, static_cast<std::uint32_t>(w * 31 + h));
        const MipPyramid p = MipPyramid::build(base);
        const Image& top = p.level(base, p.count() - 1);
        EXPECT_EQ(top.width, 1);
        EXPECT_EQ(top.height, 1);
        for (int k = 1; k < p.count(); ++k) {
            const Image& l = p.level(base, k);
            EXPECT_EQ(l.width, std::max(1, (p.level(base, k - 1).width + 1) / 2));
            EXPECT_NEAR(mean_g(l), mean_g(base), 1e-5) << w << "x" << h << " level " << k;
            for (int y = 0; y < l.height; ++y)
                for (int x = 0; x < l.width; ++x)
                    EXPECT_NEAR(l.texel(x, y).g, brute_force_texel(p.level(base, k - 1), l, x, y), 0.02)
                        << w << "x" << h << " level " << k << " texel " << x << "," << y;
        }
    }
    // By hand: a 2 x 2 block of 0, 1, 2, 3 becomes 1.5.
    const Image tiny{2, 2, {Color{0}, Color{1}, Color{2}, Color{3}}, {}};
    EXPECT_FLOAT_EQ(MipPyramid::build(tiny).levels.at(0).texel(0, 0).g, 1.5f);
}

TEST(MipMap, TheLevelsAddAThirdOfTheTexels) {
    const Image base = random_image(1024, 768, 5);
    const MipPyramid p = MipPyramid::build(base);
    EXPECT_LE(static_cast<double>(base.texels.size() + p.texels()), 1.34 * static_cast<double>(base.texels.size()));
}

TEST(MipMap, TrilinearGoesFromBilinearToTheMean) {
    const Image base = random_image(64, 32, 9);
    const MipPyramid p = MipPyramid::build(base);
    for (std::uint32_t i = 0; i < 50; ++i) {
        const Point2 uv{rnd(20, i), rnd(21, i)};
        const Color fine = trilinear(base, p, uv, 0.5f / 64, WrapMode::kRepeat, WrapMode::kRepeat);
        EXPECT_EQ(fine.g, bilinear(base, uv, WrapMode::kRepeat).g);
        const Color whole = trilinear(base, p, uv, 2, WrapMode::kRepeat, WrapMode::kRepeat);
        EXPECT_NEAR(whole.g, mean_g(base), 1e-5);
    }
}

TEST(MipMap, EwaWeightsAreCentredAndNormalised) {
    // The weights' first moments vanish about the centre for any ellipse.
    for (std::uint32_t i = 0; i < 200; ++i) {
        const float s = 10 + rnd(30, i), t = 20 + rnd(31, i);
        const Point2 d0{6 * rnd(32, i) - 3, 6 * rnd(33, i) - 3}, d1{6 * rnd(34, i) - 3, 6 * rnd(35, i) - 3};
        double mx = 0, my = 0;
        const double total = ewa_weights(s, t, d0, d1, [&](int x, int y, double w) {
            EXPECT_GT(w, 0);
            mx += w * (x - s);
            my += w * (y - t);
        });
        ASSERT_GT(total, 0);
        // Texel centres are discrete: the moments vanish up to the grid's asymmetry.
        EXPECT_LT(std::abs(mx / total), 0.25) << i;
        EXPECT_LT(std::abs(my / total), 0.25) << i;
    }
    // A constant image reads itself; a ramp in u, away from the wrap, its value at the centre.
    Image ramp{64, 64, {}, {}};
    Image constant{64, 64, std::vector<Color>(64 * 64, Color{0.3f}), {}};
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) ramp.texels.push_back(Color{static_cast<float>(x)});
    const MipPyramid pr = MipPyramid::build(ramp), pc = MipPyramid::build(constant);
    const Point2 d0{3.0f / 64, 1.0f / 64}, d1{-0.5f / 64, 2.0f / 64};
    const Point2 uv{0.5f, 0.5f};
    EXPECT_NEAR(ewa(constant, pc, uv, d0, d1, WrapMode::kClamp, WrapMode::kClamp).g, 0.3f, 1e-6);
    // u = 0.5 is x = 31.5 in texel coordinates.
    EXPECT_NEAR(ewa(ramp, pr, uv, d0, d1, WrapMode::kClamp, WrapMode::kClamp).g, 31.5f, 0.3f);
}

TEST(MipMap, EwaAveragesACheckerThatBilinearAliases) {
    Image checker{64, 64, {}, {}};
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) checker.texels.push_back(Color{static_cast<float>((x + y) % 2)});
    const MipPyramid p = MipPyramid::build(checker);
    double worst = 0;
    for (std::uint32_t i = 0; i < 100; ++i) {
        const Point2 uv{rnd(40, i), rnd(41, i)};
        // A footprint of 4 x 12 texels, tilted.
        const Point2 d0{4.0f / 64, 4.0f / 64}, d1{-12.0f / 64, 12.0f / 64};
        worst = std::max(worst, std::abs(ewa(checker, p, uv, d0, d1, WrapMode::kRepeat, WrapMode::kRepeat).g - 0.5));
    }
    EXPECT_LT(worst, 0.05);
}

}  // namespace
}  // namespace glint
