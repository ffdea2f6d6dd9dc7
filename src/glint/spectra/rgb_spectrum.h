#pragma once
// RGB values of a scene as spectra, where a spectral path reads them (issue 36): by Jakob and
// Hanika's sigmoid polynomials (rgb_spectrum_model.h), as pbrt-v4 upsamples.
//  - reflectance: an albedo in [0, 1] (clamped), s(lambda) with the colour under D65 = rgb;
//  - unbounded: any non-negative value (media coefficients, a metal's eta given as RGB):
//    m s(lambda) with m = 2 max(rgb) and s the reflectance of rgb / m;
//  - illuminant: a light's RGB, the unbounded spectrum times D65 (normalised to Y = 1), so that
//    a light of RGB (1, 1, 1) shines D65 and a white surface under it images as (1, 1, 1).
#include "glint/math/color.h"
#include "glint/spectra/spectrum.h"

namespace glint {

/// The sigmoid polynomial of a colour (coefficients over t = (lambda - 360) / 470).
struct RgbSigmoid {
    float c[3]{0, 0, 0};
    float operator()(float lambda) const;
};
/// The coefficients for a reflectance rgb (components clamped to [0, 1]).
RgbSigmoid rgb_sigmoid(Color rgb);

/// A reflectance rgb made ready to be read at any wavelengths: RgbReflectance(rgb).at(wl) is
/// upsample_reflectance(rgb, wl) bit for bit. The table lookup (rgb_sigmoid) is the costly part;
/// the scene keeps one of these per constant texture (Scene::commit), so a hit pays for the
/// polynomial alone.
class RgbReflectance {
public:
    RgbReflectance() = default;
    explicit RgbReflectance(Color rgb);
    Color at(const Wavelengths& wl) const;

private:
    RgbSigmoid sigmoid_;
    float grey_ = -1;  ///< a grey's value (its own at every wavelength); -1 for a colour
};

/// A light's RGB made ready to be read at any wavelengths: RgbIlluminant(rgb).at(wl) is
/// upsample_illuminant(rgb, wl) bit for bit, with the table lookup paid once (the path
/// integrator keeps the last one per thread, so a path meeting the lamp pays the polynomial).
class RgbIlluminant {
public:
    RgbIlluminant() = default;
    explicit RgbIlluminant(Color rgb);
    Color at(const Wavelengths& wl) const;

private:
    RgbReflectance shape_;  ///< the reflectance of rgb / scale_
    float scale_ = 0;       ///< 2 max(rgb); 0 for a light with no positive channel
};

Color upsample_reflectance(Color rgb, const Wavelengths& wl);
Color upsample_unbounded(Color rgb, const Wavelengths& wl);
Color upsample_illuminant(Color rgb, const Wavelengths& wl);

/// How an RGB value is read in spectral mode.
enum class SpectrumKind : std::uint8_t { kReflectance, kUnbounded, kIlluminant };
inline Color upsample(Color rgb, SpectrumKind kind, const Wavelengths& wl) {
    switch (kind) {
        case SpectrumKind::kReflectance: return upsample_reflectance(rgb, wl);
        case SpectrumKind::kUnbounded: return upsample_unbounded(rgb, wl);
        default: return upsample_illuminant(rgb, wl);
    }
}

}  // namespace glint
