#include "glint/textures/texture.h"

#include <gtest/gtest.h>

#include <limits>

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
