#pragma once
// Light as a function of wavelength (issue 36). In spectral mode a path carries radiance at three
// wavelengths, one per channel of a Color: every BSDF, medium and light term is a per-channel
// product already, so the lobes run unchanged on wavelength samples. The conversions are at the
// edges: RGB values of the scene become spectra where a path reads them (spectra/rgb_spectrum.h),
// and a path's three values become XYZ, then linear sRGB, before the film (film_rgb below).
//
// Conventions: wavelengths in nanometres over [kLambdaMin, kLambdaMax]; XYZ normalised so that a
// spectrum of constant value 1 has Y = 1 (the CIE integrals divided by the integral of y-bar).
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "glint/math/color.h"

namespace glint {

constexpr float kLambdaMin = 360, kLambdaMax = 830;

/// The three wavelengths a path carries (one per Color channel) and the density each was drawn
/// with. lambda[0] is the hero: a dispersive surface keeps it alone (see terminate_secondary).
struct Wavelengths {
    float lambda[3]{};
    float pdf[3]{};
    bool secondary_terminated = false;
};

/// Three wavelengths from one number: u, u + 1/3 and u + 2/3 (mod 1) through the inverse of
/// the visible density below, so that each is distributed by it and together they stratify it.
Wavelengths sample_wavelengths(float u);
/// The sampling density over [360, 830] nm, proportional to 1 / cosh^2(0.0072 (lambda - 538))
/// (pbrt-v4's visible-wavelength density, which follows the eye's sensitivity).
float visible_wavelength_pdf(float lambda);
/// After a dispersive event only the hero wavelength stays (pbrt-v4's TerminateSecondary): the
/// others' densities become 0, so the film leaves them out, and the hero's is divided by 3, so
/// that it alone is the estimate of the spectrum. The path's values are not touched (the media's
/// spectral MIS still weighs every channel).
void terminate_secondary(Wavelengths& wl);

struct Xyz {
    float x = 0, y = 0, z = 0;
};
/// The white of a sensor white-balanced for `kelvin`, as pbrt-v4's film takes it: CIE daylight's
/// chromaticity at that temperature (the locus formula, at T * 1.4388 / 1.4380, from 4000 K on), a
/// black body's below 4000 K. Y = 1.
Xyz daylight_white(float kelvin);
/// A 3x3 matrix on linear sRGB colours.
struct ColorMatrix {
    float m[3][3]{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    Color operator()(Color c) const {
        return {m[0][0] * c.r + m[0][1] * c.g + m[0][2] * c.b, m[1][0] * c.r + m[1][1] * c.g + m[1][2] * c.b,
                m[2][0] * c.r + m[2][1] * c.g + m[2][2] * c.b};
    }
};
/// White balance for `kelvin` (pbrt-v4's "whitebalance"): von Kries scaling in Bradford's cone
/// space that takes daylight_white(kelvin) to sRGB's white (D65), as a matrix on linear sRGB.
ColorMatrix white_balance(float kelvin);
/// The CIE 1931 2-degree matching functions at lambda (1 nm table, linear between entries).
Xyz cie_xyz(float lambda);
/// The integral of y-bar over 360-830 nm (in nm).
float cie_y_integral();
/// XYZ to linear sRGB (Rec.709 primaries, D65 white), the colour space of glint's images.
Color xyz_to_linear_srgb(Xyz c);
/// The film's value of one path: radiance at the three wavelengths to an estimate of linear sRGB,
/// (1/3) sum L(lambda_i) cmf(lambda_i) / pdf(lambda_i), divided by the y-bar integral.
Color film_rgb(Color radiance, const Wavelengths& wl);

/// A spectrum given at increasing wavelengths, linear between them and constant beyond the ends.
class PiecewiseLinearSpectrum {
public:
    PiecewiseLinearSpectrum() = default;
    PiecewiseLinearSpectrum(std::vector<float> lambda, std::vector<float> value);
    /// From (lambda, value) pairs; `normalise`: scaled to Y = 1 (what pbrt does to illuminants).
    static PiecewiseLinearSpectrum interleaved(std::span<const float> pairs, bool normalise);
    float operator()(float lambda) const;
    Color at(const Wavelengths& wl) const { return {(*this)(wl.lambda[0]), (*this)(wl.lambda[1]), (*this)(wl.lambda[2])}; }
    void scale(float s);
    bool empty() const { return lambda_.empty(); }
    const std::vector<float>& lambda() const { return lambda_; }
    const std::vector<float>& value() const { return value_; }

private:
    std::vector<float> lambda_, value_;
};

/// The CIE XYZ of a spectrum (integrated at 1 nm over 360-830).
template <class F>
Xyz spectrum_to_xyz(const F& s) {
    double x = 0, y = 0, z = 0;
    for (int l = 360; l <= 830; ++l) {
        const Xyz c = cie_xyz(float(l));
        const double v = s(float(l));
        x += v * c.x, y += v * c.y, z += v * c.z;
    }
    const double n = cie_y_integral();
    return {float(x / n), float(y / n), float(z / n)};
}

/// Planck's law: the spectral radiance of a black body at temperature T (kelvin), in W / (m^2 sr
/// m), at lambda nanometres. 0 for T <= 0.
double planck(float lambda_nm, float kelvin);
/// A black body's spectrum scaled to a peak of 1 (pbrt's "blackbody" spectra): Planck's law over
/// its value at Wien's peak wavelength.
float blackbody_normalised(float lambda_nm, float kelvin);

/// A spectrum as a scene gives one: a table (named or inline), a black body (normalised to a peak
/// of 1), or a dielectric's index of refraction by Sellmeier's equation
///   n^2(lambda) = 1 + sum_i B_i lambda^2 / (lambda^2 - C_i)   (lambda in micrometres, C in um^2)
/// or by Cauchy's n = A + B / lambda^2 (lambda in nm; from an Abbe number, see from_abbe).
class Spectrum {
public:
    enum class Kind : std::uint8_t { kTabulated, kBlackbody, kSellmeier, kCauchy };
    static Spectrum tabulated(PiecewiseLinearSpectrum table);
    static Spectrum blackbody(float kelvin);
    static Spectrum sellmeier(const float b[3], const float c[3]);
    /// Cauchy's two terms through n_d at 587.56 nm with Abbe number V_d = (n_d - 1) / (n_F - n_C)
    /// (F: 486.13 nm, C: 656.27 nm).
    static Spectrum from_abbe(float n_d, float v_d);
    float operator()(float lambda) const;
    Color at(const Wavelengths& wl) const { return {(*this)(wl.lambda[0]), (*this)(wl.lambda[1]), (*this)(wl.lambda[2])}; }
    /// Whether the value is the same at every wavelength (a dielectric then does not disperse).
    bool constant() const;
    /// An emitter's spectrum: this one scaled to Y = 1, so that an emitter's strength is the
    /// luminance of its RGB stand-in (as pbrt-v4 divides a light's spectrum by its photometric
    /// value). Its RGB stand-in is emission_rgb.
    Spectrum normalised_emission() const;
    /// The linear sRGB colour of this spectrum as an emitter (RGB mode's stand-in, and its power),
    /// normalised to luminance 1; a channel out of the gamut (negative) is 0.
    Color emission_rgb() const;
    /// The colour the film records for this spectrum seen directly (its XYZ at 1 nm in linear
    /// sRGB): the expectation of film_rgb over the sampled wavelengths. Kept by
    /// normalised_emission, so that an emitter's costs nothing to read.
    Color film_colour() const { return has_film_colour_ ? film_colour_ : xyz_to_linear_srgb(spectrum_to_xyz(*this)); }
    Kind kind() const { return kind_; }
    float kelvin() const { return p_[0]; }
    /// The parameters: Sellmeier's B1..B3, C1..C3; Cauchy's A, B.
    const float* parameters() const { return p_; }
    /// The name a tabulated spectrum was found under ("glass-BK7"), or empty.
    const std::string& name() const { return name_; }
    void set_name(std::string name) { name_ = std::move(name); }
    const PiecewiseLinearSpectrum& table() const { return table_; }

private:
    Kind kind_ = Kind::kTabulated;
    PiecewiseLinearSpectrum table_;
    float p_[6]{};
    float scale_ = 1;
    bool has_film_colour_ = false;
    Color film_colour_{0};
    std::string name_;
};

/// pbrt-v4's named spectra: standard illuminants ("stdillum-D65", "stdillum-A", F1-F12, D50;
/// normalised to Y = 1), measured metals ("metal-Au-eta", "metal-Au-k", ...) and glasses
/// ("glass-BK7", "glass-F11", ...). nullptr for a name not known.
const PiecewiseLinearSpectrum* named_spectrum(std::string_view name);
/// Every name named_spectrum knows, for error messages.
std::vector<std::string_view> named_spectrum_names();
/// The CIE D65 illuminant normalised to Y = 1 (the white of sRGB; lights given as RGB shine it).
const PiecewiseLinearSpectrum& d65();
/// D65 at the path's wavelengths from a 1 nm table (no search: it is read at every light sample).
Color d65_at(const Wavelengths& wl);
/// A reflectance spectrum's colour: its linear sRGB under D65 (RGB mode's stand-in for it).
template <class F>
Color reflectance_rgb(const F& s) {
    return xyz_to_linear_srgb(spectrum_to_xyz([&](float l) { return s(l) * d65()(l); }));
}

}  // namespace glint
