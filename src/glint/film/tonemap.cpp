#include "glint/film/tonemap.h"

#include <algorithm>
#include <cmath>

namespace glint {

float srgb_encode(float v) {
    return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
}

float tone_curve(float v, ToneCurve curve) {
    switch (curve) {
        case ToneCurve::kClamp: return v;
        case ToneCurve::kReinhard: return v / (1 + v);
        case ToneCurve::kAces: {
            // Narkowicz 2015: x (a x + b) / (x (c x + d) + e), fitted to ODT(RRT(x)).
            constexpr float a = 2.51f, b = 0.03f, c = 2.43f, d = 0.59f, e = 0.14f;
            return std::clamp(v * (a * v + b) / (v * (c * v + d) + e), 0.0f, 1.0f);
        }
    }
    return v;
}

std::uint8_t encode_8bit(float v, const DisplaySettings& display) {
    if (!(v > 0)) return 0;  // also catches NaN
    if (display.exposure != 0) v *= std::exp2(display.exposure);
    // Saturate before the curve: Reinhard's and ACES's ratios are inf/inf = NaN at infinity (a
    // float's maximum overflows there too), and every curve is at its top long before 1e6.
    v = v < 1e6f ? v : 1e6f;
    v = std::min(tone_curve(v, display.curve), 1.0f);
    if (display.encoding == Encoding::kSrgb) v = srgb_encode(v);
    return static_cast<std::uint8_t>(v * 255.0f + 0.5f);  // v in [0, 1]: round half up
}

void encode_8bit(const float* in, std::size_t n, std::uint8_t* out, const DisplaySettings& display) {
    if (display.curve != ToneCurve::kClamp || display.encoding != Encoding::kRaw) {
        for (std::size_t i = 0; i < n; ++i) out[i] = encode_8bit(in[i], display);
        return;
    }
    // The scalar steps as selects: a value that is not above 0 (NaN too) gives 0; the rest are
    // exposed, clamped to 1 and rounded exactly as there.
    const bool exposed = display.exposure != 0;
    const float scale = std::exp2(display.exposure);
    for (std::size_t i = 0; i < n; ++i) {
        const float v = in[i];
        float x = exposed ? v * scale : v;
        x = x < 1.0f ? x : 1.0f;
        x = v > 0 ? x : 0.0f;
        out[i] = static_cast<std::uint8_t>(static_cast<int>(x * 255.0f + 0.5f));
    }
}

}  // namespace glint
