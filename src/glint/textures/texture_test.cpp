#include "glint/textures/texture.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

namespace glint {
namespace {

const Color kEven{1, 1, 1}, kOdd{0, 0, 0};

TEST(Checker, ParityOfTheCellSum) {
    const CheckerTexture c{1, kEven, kOdd};
    EXPECT_EQ(c.eval({0.5f, 0.5f, 0.5f}), kEven);     // 0 + 0 + 0
    EXPECT_EQ(c.eval({1.5f, 0.5f, 0.5f}), kOdd);      // 1
    EXPECT_EQ(c.eval({-0.5f, 0.5f, 0.5f}), kOdd);     // -1: floor, not truncation
    EXPECT_EQ(c.eval({-0.5f, -0.5f, 0.5f}), kEven);   // -2
    // On the plane y = -1 (Figure 14's floor), parity flips: floor(x) + floor(z) even is odd.
    EXPECT_EQ(c.eval({0.5f, -1, 0.5f}), kOdd);
}

TEST(Checker, SizeScalesTheCells) {
    const CheckerTexture c{2.5f, kEven, kOdd};
    EXPECT_EQ(c.eval({2.4f, 0.1f, 0.1f}), kEven);
    EXPECT_EQ(c.eval({2.6f, 0.1f, 0.1f}), kOdd);
}

TEST(Checker, ExtremeCoordinatesDoNotOverflow) {
    // Cell indices past 2^62, infinite or NaN must not be converted to integers (UB).
    const CheckerTexture tiny{1e-39f, kEven, kOdd};
    const Float inf = std::numeric_limits<Float>::infinity();
    EXPECT_EQ(tiny.eval({1, 0, 0}), kEven);  // 1 / 1e-39 = inf: treated as cell 0
    const CheckerTexture c{1, kEven, kOdd};
    EXPECT_EQ(c.eval({inf, -inf, std::numeric_limits<Float>::quiet_NaN()}), kEven);
    EXPECT_EQ(c.eval({1e30f, 0.5f, 0.5f}), kEven);
}

}  // namespace
}  // namespace glint

namespace glint {
namespace {

// 2 x 2 grey image: row 0 (the top, v near 1) is 0, 1; row 1 (the bottom, v near 0) is 2, 3.
Image two_by_two() { return Image{2, 2, {Color{0}, Color{1}, Color{2}, Color{3}}, {}}; }

TEST(ImageTexture, BilinearHandValues) {
    const Image img = two_by_two();
    // Texel centres at u = (i + 1/2) / 2, v = 1 - (j + 1/2) / 2.
    EXPECT_FLOAT_EQ(bilinear(img, {0.25f, 0.75f}, WrapMode::kClamp).r, 0);
    EXPECT_FLOAT_EQ(bilinear(img, {0.75f, 0.75f}, WrapMode::kClamp).r, 1);
    EXPECT_FLOAT_EQ(bilinear(img, {0.25f, 0.25f}, WrapMode::kClamp).r, 2);
    EXPECT_FLOAT_EQ(bilinear(img, {0.5f, 0.75f}, WrapMode::kClamp).r, 0.5f);  // between 0 and 1
    EXPECT_FLOAT_EQ(bilinear(img, {0.5f, 0.5f}, WrapMode::kClamp).r, 1.5f);   // all four
}

TEST(ImageTexture, RepeatWrapsAndClampHoldsTheEdge) {
    const Image img = two_by_two();
    // u = 0 is half a texel left of texel 0's centre: repeat blends with texel 1 (the last
    // column), clamp with texel 0 itself.
    EXPECT_FLOAT_EQ(bilinear(img, {0, 0.75f}, WrapMode::kRepeat).r, 0.5f);
    EXPECT_FLOAT_EQ(bilinear(img, {0, 0.75f}, WrapMode::kClamp).r, 0);
    // Repeat: u + 1 is u; clamp: far outside is the edge.
    EXPECT_FLOAT_EQ(bilinear(img, {1.75f, 0.75f}, WrapMode::kRepeat).r, 1);
    EXPECT_FLOAT_EQ(bilinear(img, {-7.25f, 1.25f}, WrapMode::kRepeat).r,
                    bilinear(img, {0.75f, 0.25f}, WrapMode::kRepeat).r);
    EXPECT_FLOAT_EQ(bilinear(img, {50, -50}, WrapMode::kClamp).r, 3);  // bottom-right
    // Non-finite uv does not crash or read out of bounds.
    EXPECT_TRUE(is_finite(bilinear(img, {std::numeric_limits<float>::infinity(), 0}, WrapMode::kRepeat)));
}

TEST(Textures, ScaleMultipliesAndMixInterpolates) {
    const std::vector<Texture> t{ConstantTexture{Color{0.5f, 1, 2}},      // 0
                                 ConstantTexture{Color{2, 2, 0.25f}},     // 1
                                 ScaleTexture{0, 1},                      // 2: product
                                 ConstantTexture{Color{0, 0.5f, 1}},      // 3: amounts
                                 MixTexture{0, 1, 3}};                    // 4
    const TextureContext ctx{{0, 0, 0}, {0, 0}};
    EXPECT_EQ(evaluate(t, {}, 2, ctx), (Color{1, 2, 0.5f}));
    // Per channel: r all a (0.5), g halfway (1.5), b all b (0.25).
    EXPECT_EQ(evaluate(t, {}, 4, ctx), (Color{0.5f, 1.5f, 0.25f}));
}

// The closed-form box-filtered checker against the mean of point lookups over the same box.
TEST(Checker, FilteredIsTheBoxMeanOfThePointLookups) {
    const CheckerTexture c{0.5f, Color{0.9f}, Color{0.1f}};
    for (int k = 0; k < 60; ++k) {
        const Point3 p{0.37f * k - 7, 0.11f * k - 2, 0.23f * k - 5};
        const Vector3 dpdx{0.05f * (k % 7), 0.02f * (k % 3), 0.1f * (k % 5) + 0.01f};
        const Vector3 dpdy{0.03f * (k % 4), 0.07f * (k % 2), 0.02f * (k % 6)};
        const float hx = 0.5f * (std::abs(dpdx.x) + std::abs(dpdy.x));
        const float hy = 0.5f * (std::abs(dpdx.y) + std::abs(dpdy.y));
        const float hz = 0.5f * (std::abs(dpdx.z) + std::abs(dpdy.z));
        constexpr int kN = 40;
        double sum = 0;
        for (int i = 0; i < kN; ++i)
            for (int j = 0; j < kN; ++j)
                for (int l = 0; l < kN; ++l)
                    sum += c.eval({p.x + hx * (2 * (i + 0.5f) / kN - 1), p.y + hy * (2 * (j + 0.5f) / kN - 1),
                                   p.z + hz * (2 * (l + 0.5f) / kN - 1)}).g;
        EXPECT_NEAR(c.eval_filtered(p, dpdx, dpdy).g, sum / (kN * kN * kN), 0.03) << k;
    }
    // No footprint: the point lookup itself.
    EXPECT_EQ(c.eval_filtered({0.1f, 0.2f, 0.7f}, {}, {}).g, c.eval({0.1f, 0.2f, 0.7f}).g);
}

// pbrt-v4's 2D checkerboard: cells of `size` over (s, t) = (u_scale u + u_offset, v_scale v + v_offset),
// `even` where floor(s / size) + floor(t / size) is even; the point does not matter.
TEST(Checker, OnUvTheCellsFollowTheScaledAndShiftedCoordinates) {
    CheckerTexture c{1, kEven, kOdd};
    c.on_uv = true;
    c.u_scale = 8;
    c.v_scale = 4;
    c.u_offset = 0.5f;
    // s = 8u + 0.5, t = 4v: (0, 0) is in cell (0, 0); u = 0.07 gives s = 1.06, cell 1.
    EXPECT_EQ(c.eval_uv({0.0f, 0.0f}), kEven);
    EXPECT_EQ(c.eval_uv({0.07f, 0.0f}), kOdd);
    EXPECT_EQ(c.eval_uv({0.07f, 0.3f}), kEven);  // t = 1.2
    EXPECT_EQ(c.eval_uv({-0.07f, 0.0f}), kOdd);  // s = -0.06, cell -1
    c.size = 2;                                   // cells of 2 in (s, t)
    EXPECT_EQ(c.eval_uv({0.07f, 0.3f}), kEven);  // s / 2 = 0.53, t / 2 = 0.6
    EXPECT_EQ(c.eval_uv({0.2f, 0.3f}), kOdd);    // s / 2 = 1.05
    // Through evaluate: the uv of the context, not its point.
    const std::vector<Texture> t{c};
    EXPECT_EQ(evaluate(t, {}, 0, TextureContext{{0.5f, 0.5f, 0.5f}, {0.2f, 0.3f}}), kOdd);
}

// The uv checker's closed-form box filter against the mean of point lookups over the uv box.
TEST(Checker, OnUvFilteredIsTheBoxMeanOfThePointLookups) {
    CheckerTexture c{0.5f, Color{0.9f}, Color{0.1f}};
    c.on_uv = true;
    c.u_scale = 3;
    c.v_scale = -2;
    c.u_offset = 0.3f;
    c.v_offset = 0.1f;
    for (int k = 0; k < 60; ++k) {
        const Point2 uv{0.137f * k - 3, 0.071f * k - 1};
        const Point2 dx{0.05f * (k % 7), 0.02f * (k % 3) + 0.01f}, dy{0.03f * (k % 4), 0.07f * (k % 2)};
        const float hu = 0.5f * (std::abs(dx.x) + std::abs(dy.x)), hv = 0.5f * (std::abs(dx.y) + std::abs(dy.y));
        constexpr int kN = 200;
        double sum = 0;
        for (int i = 0; i < kN; ++i)
            for (int j = 0; j < kN; ++j)
                sum += c.eval_uv({uv.x + hu * (2 * (i + 0.5f) / kN - 1), uv.y + hv * (2 * (j + 0.5f) / kN - 1)}).g;
        EXPECT_NEAR(c.eval_uv_filtered(uv, dx, dy).g, sum / (kN * kN), 0.01) << k;
    }
    EXPECT_EQ(c.eval_uv_filtered({0.1f, 0.2f}, {}, {}).g, c.eval_uv({0.1f, 0.2f}).g);
}

}  // namespace
}  // namespace glint
