#include "glint/film/tonemap.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace glint {
namespace {

TEST(Tonemap, SrgbCurveMatchesTheStandard) {
    EXPECT_FLOAT_EQ(srgb_encode(0), 0);
    EXPECT_NEAR(srgb_encode(1), 1, 1e-6);
    EXPECT_NEAR(srgb_encode(0.002f), 12.92f * 0.002f, 1e-7);       // linear toe
    EXPECT_NEAR(srgb_encode(0.5f), 1.055 * std::pow(0.5, 1 / 2.4) - 0.055, 1e-6);  // 0.735357
}

TEST(Tonemap, RawEncodingIsClampTimes255Rounded) {
    EXPECT_EQ(encode_8bit(0.5f, Encoding::kRaw), 128);  // 127.5 rounds up
    EXPECT_EQ(encode_8bit(0.1f, Encoding::kRaw), 26);   // 25.5
    EXPECT_EQ(encode_8bit(1.0f, Encoding::kRaw), 255);
    EXPECT_EQ(encode_8bit(7.0f, Encoding::kRaw), 255);
    EXPECT_EQ(encode_8bit(-1.0f, Encoding::kRaw), 0);
    EXPECT_EQ(encode_8bit(std::numeric_limits<float>::quiet_NaN(), Encoding::kRaw), 0);
}

TEST(Tonemap, SrgbEncodingOfMidGrey) {
    EXPECT_EQ(encode_8bit(0.5f, Encoding::kSrgb), 188);  // 0.735357 * 255 = 187.5
    EXPECT_EQ(encode_8bit(0.18f, Encoding::kSrgb), 118);  // 0.4614 * 255 = 117.7
}

}  // namespace
}  // namespace glint
