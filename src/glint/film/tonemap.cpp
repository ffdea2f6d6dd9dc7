#include "glint/film/tonemap.h"

#include <algorithm>
#include <cmath>

namespace glint {

float srgb_encode(float v) {
    return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
}

std::uint8_t encode_8bit(float v, Encoding encoding) {
    if (!(v > 0)) return 0;  // also catches NaN
    v = std::min(v, 1.0f);
    if (encoding == Encoding::kSrgb) v = srgb_encode(v);
    return static_cast<std::uint8_t>(v * 255.0f + 0.5f);  // v in [0, 1]: round half up
}

}  // namespace glint
