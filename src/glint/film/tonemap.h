#pragma once
// From linear film values to 8-bit display codes: exposure, a tone curve, the clamp to [0, 1],
// then the transfer encoding. EXR output skips all of this: it stores the linear values.
#include <cstddef>
#include <cstdint>

namespace glint {

enum class Encoding {
    kSrgb,  ///< the sRGB transfer curve (the default for PNG/PPM)
    kRaw,   ///< no curve: the article's display values are written as they are
};

enum class ToneCurve {
    kClamp,     ///< none: values above 1 clip (the default; the article's figures)
    kReinhard,  ///< v / (1 + v) per channel: never clips, compresses highlights
    kAces,      ///< Narkowicz's fit of the ACES filmic curve (RRT + ODT), pre-exposed: 1 -> 0.80
};

struct DisplaySettings {
    Encoding encoding = Encoding::kSrgb;
    ToneCurve curve = ToneCurve::kClamp;
    float exposure = 0;  ///< in stops: values are multiplied by 2^exposure before the curve
};

/// The sRGB opto-electronic transfer function (IEC 61966-2-1), for v in [0, 1].
float srgb_encode(float v);

/// The tone curve alone, for v >= 0 (results in [0, 1] except for kClamp, which clamps later).
float tone_curve(float v, ToneCurve curve);

/// A linear value to an 8-bit code: exposure, curve, clamp to [0, 1], encoding, x255, round to
/// nearest. NaN encodes as 0.
std::uint8_t encode_8bit(float v, const DisplaySettings& display);

/// encode_8bit on n values, to the same codes: the article's settings (raw, clamp) take a
/// branch-free loop the compiler vectorises; the rest go value by value.
void encode_8bit(const float* in, std::size_t n, std::uint8_t* out, const DisplaySettings& display);

}  // namespace glint
