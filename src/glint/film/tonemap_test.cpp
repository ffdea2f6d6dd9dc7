#include "glint/film/tonemap.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

namespace glint {
namespace {

const DisplaySettings kRaw{Encoding::kRaw, ToneCurve::kClamp, 0};
const DisplaySettings kSrgb{};

TEST(Tonemap, SrgbCurveMatchesTheStandard) {
    EXPECT_FLOAT_EQ(srgb_encode(0), 0);
    EXPECT_NEAR(srgb_encode(1), 1, 1e-6);
    EXPECT_NEAR(srgb_encode(0.002f), 12.92f * 0.002f, 1e-7);       // linear toe
    EXPECT_NEAR(srgb_encode(0.5f), 1.055 * std::pow(0.5, 1 / 2.4) - 0.055, 1e-6);  // 0.735357
}

TEST(Tonemap, RawEncodingIsClampTimes255Rounded) {
    EXPECT_EQ(encode_8bit(0.5f, kRaw), 128);  // 127.5 rounds up
    EXPECT_EQ(encode_8bit(0.1f, kRaw), 26);   // 25.5
    EXPECT_EQ(encode_8bit(1.0f, kRaw), 255);
    EXPECT_EQ(encode_8bit(7.0f, kRaw), 255);
    EXPECT_EQ(encode_8bit(-1.0f, kRaw), 0);
    EXPECT_EQ(encode_8bit(std::numeric_limits<float>::quiet_NaN(), kRaw), 0);
}

TEST(Tonemap, SrgbEncodingOfMidGrey) {
    EXPECT_EQ(encode_8bit(0.5f, kSrgb), 188);  // 0.735357 * 255 = 187.5
    EXPECT_EQ(encode_8bit(0.18f, kSrgb), 118);  // 0.4614 * 255 = 117.7
}

TEST(Tonemap, ExposureIsInStops) {
    // +1 stop doubles: 0.25 -> 0.5 -> 128 (raw); -2 stops quarters: 1 -> 0.25 -> 64.
    EXPECT_EQ(encode_8bit(0.25f, {Encoding::kRaw, ToneCurve::kClamp, 1}), 128);
    EXPECT_EQ(encode_8bit(1.0f, {Encoding::kRaw, ToneCurve::kClamp, -2}), 64);  // 63.75
}

TEST(Tonemap, ReinhardIsVOverOnePlusV) {
    EXPECT_FLOAT_EQ(tone_curve(1, ToneCurve::kReinhard), 0.5f);
    EXPECT_FLOAT_EQ(tone_curve(3, ToneCurve::kReinhard), 0.75f);
    EXPECT_EQ(encode_8bit(1000.0f, {Encoding::kRaw, ToneCurve::kReinhard, 0}), 255);  // 0.999 -> 254.7
    EXPECT_EQ(encode_8bit(1.0f, {Encoding::kRaw, ToneCurve::kReinhard, 0}), 128);
}

TEST(Tonemap, AcesFitHandValues) {
    // x (2.51 x + 0.03) / (x (2.43 x + 0.59) + 0.14): 0 -> 0; 1 -> 2.54 / 3.16 = 0.8038;
    // 0.18 -> 0.0867 / 0.3288 = 0.2637 (mid grey); huge -> 2.51 / 2.43 clamped to 1.
    EXPECT_FLOAT_EQ(tone_curve(0, ToneCurve::kAces), 0);
    EXPECT_NEAR(tone_curve(1, ToneCurve::kAces), 2.54 / 3.16, 1e-6);
    EXPECT_NEAR(tone_curve(0.18f, ToneCurve::kAces),
                0.18 * (2.51 * 0.18 + 0.03) / (0.18 * (2.43 * 0.18 + 0.59) + 0.14), 1e-6);
    EXPECT_EQ(tone_curve(1e6f, ToneCurve::kAces), 1.0f);
    // Monotonic over the range that matters.
    float previous = 0;
    for (float v = 0.01f; v < 20; v *= 1.1f) {
        const float t = tone_curve(v, ToneCurve::kAces);
        EXPECT_GE(t, previous) << v;
        previous = t;
    }
}

// The array form is the scalar one, value for value, on every setting: the raw-and-clamp loop
// (written as selects) on the special values, the rounding boundaries k/255 +- 0.5/255 and
// their neighbouring floats, and a sweep; exposures that scale up, down and to infinity.
TEST(Tonemap, ArrayFormGivesTheScalarCodes) {
    std::vector<float> values = {0.0f, -0.0f, -1.0f, 1.0f, 7.0f, std::numeric_limits<float>::quiet_NaN(),
                                 std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity(),
                                 std::numeric_limits<float>::denorm_min(), std::numeric_limits<float>::max()};
    for (int k = 0; k <= 255; ++k) {
        const float edge = (static_cast<float>(k) + 0.5f) / 255.0f;
        values.push_back(edge);
        values.push_back(std::nextafter(edge, 0.0f));
        values.push_back(std::nextafter(edge, 2.0f));
    }
    for (float v = 1e-6f; v < 4; v *= 1.0007f) values.push_back(v);
    std::vector<std::uint8_t> codes(values.size());
    for (const Encoding e : {Encoding::kRaw, Encoding::kSrgb})
        for (const ToneCurve c : {ToneCurve::kClamp, ToneCurve::kReinhard, ToneCurve::kAces})
            for (const float exposure : {0.0f, 1.0f, -2.5f, 200.0f}) {
                const DisplaySettings d{e, c, exposure};
                encode_8bit(values.data(), values.size(), codes.data(), d);
                // Independently of either form: infinity and the largest float saturate, NaN and
                // negatives are black (UBSan caught the curves' inf/inf once).
                EXPECT_EQ(encode_8bit(std::numeric_limits<float>::infinity(), d), 255);
                EXPECT_EQ(encode_8bit(std::numeric_limits<float>::max(), d), 255);
                EXPECT_EQ(encode_8bit(std::numeric_limits<float>::quiet_NaN(), d), 0);
                EXPECT_EQ(encode_8bit(-1.0f, d), 0);
                for (std::size_t i = 0; i < values.size(); ++i)
                    ASSERT_EQ(codes[i], encode_8bit(values[i], d)) << values[i] << " exposure " << exposure;
            }
}

}  // namespace
}  // namespace glint
