#pragma once
// Encoding linear film values for 8-bit output.
#include <cstdint>

namespace glint {

enum class Encoding {
    kSrgb,  ///< clamp to [0,1], then the sRGB transfer curve (the default for PNG/PPM)
    kRaw,   ///< the article's display values: clamp to [0,1], no curve
};

/// The sRGB opto-electronic transfer function (IEC 61966-2-1), for v in [0, 1].
float srgb_encode(float v);

/// A linear value to an 8-bit code: clamp to [0,1], apply the encoding, x255, round to nearest.
/// NaN encodes as 0.
std::uint8_t encode_8bit(float v, Encoding encoding);

}  // namespace glint
