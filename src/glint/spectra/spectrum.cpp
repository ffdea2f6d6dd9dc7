#include "glint/spectra/spectrum.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace glint {

namespace {

#include "glint/spectra/cie_tables.inc"

struct NamedSpectrumData {
    std::string_view name;
    std::span<const float> pairs;
    bool illuminant;
};

#include "glint/spectra/named_spectra.inc"

constexpr int kCieSamples = 471;

// The visible density and its inverse CDF in closed form: p(l) = A / cosh^2(B (l - 538)) over
// [360, 830]; A normalises it (A = B / (tanh(B 292) + tanh(B 178))).
constexpr double kB = 0.0072;
const double kTanhLo = std::tanh(kB * (kLambdaMin - 538)), kTanhHi = std::tanh(kB * (kLambdaMax - 538));

struct NamedTable {
    std::vector<PiecewiseLinearSpectrum> spectra;
    NamedTable() {
        for (const NamedSpectrumData& d : kNamedSpectra)
            spectra.push_back(PiecewiseLinearSpectrum::interleaved(d.pairs, d.illuminant));
    }
};
const NamedTable& named_table() {
    static const NamedTable table;
    return table;
}

}  // namespace

float visible_wavelength_pdf(float lambda) {
    if (lambda < kLambdaMin || lambda > kLambdaMax) return 0;
    const double c = std::cosh(kB * (lambda - 538));
    return float(kB / (kTanhHi - kTanhLo) / (c * c));
}

Wavelengths sample_wavelengths(float u) {
    // lambda = 538 + atanh(t) / B with t uniform over [tanh lo, tanh hi]; then
    // cosh^-2(B (lambda - 538)) = 1 - t^2, so the density needs no cosh, and atanh is one log.
    constexpr float kHalfOverB = float(0.5 / kB);
    const float lo = float(kTanhLo), span = float(kTanhHi - kTanhLo), a = float(kB / (kTanhHi - kTanhLo));
    Wavelengths wl;
    for (int i = 0; i < 3; ++i) {
        float ui = u + float(i) * (1.0f / 3);
        if (ui >= 1) ui -= 1;
        const float t = lo + ui * span;
        const float lambda = 538 + std::log((1 + t) / (1 - t)) * kHalfOverB;
        wl.lambda[i] = std::clamp(lambda, kLambdaMin, kLambdaMax);
        wl.pdf[i] = wl.lambda[i] == lambda ? a * (1 - t * t) : visible_wavelength_pdf(wl.lambda[i]);
    }
    return wl;
}

void terminate_secondary(Wavelengths& wl) {
    if (wl.secondary_terminated) return;
    wl.secondary_terminated = true;
    wl.pdf[0] /= 3;
    wl.pdf[1] = wl.pdf[2] = 0;
}

Xyz cie_xyz(float lambda) {
    const float x = lambda - kLambdaMin;
    if (!(x >= 0) || x > kCieSamples - 1) return {};
    const int i = std::min(int(x), kCieSamples - 2);
    const float t = x - float(i);
    const auto lerp = [&](const float* f) { return f[i] + t * (f[i + 1] - f[i]); };
    return {lerp(kCieX), lerp(kCieY), lerp(kCieZ)};
}

float cie_y_integral() {
    static const float sum = float(std::accumulate(kCieY, kCieY + kCieSamples, 0.0));
    return sum;
}

// XYZ to linear sRGB (D65), IEC 61966-2-1's matrix.
constexpr double kSrgbFromXyz[3][3] = {{3.2404542, -1.5371385, -0.4985314},
                                       {-0.9692660, 1.8760108, 0.0415560},
                                       {0.0556434, -0.2040259, 1.0572252}};

Color xyz_to_linear_srgb(Xyz c) {
    const auto row = [&](int i) {
        return float(kSrgbFromXyz[i][0]) * c.x + float(kSrgbFromXyz[i][1]) * c.y + float(kSrgbFromXyz[i][2]) * c.z;
    };
    return {row(0), row(1), row(2)};
}

Xyz daylight_white(float kelvin) {
    const double t = double(kelvin) * 1.4388 / 1.4380;  // the CCT on today's value of c2
    double x, y;
    if (t < 4000) {
        const Xyz c = spectrum_to_xyz(Spectrum::blackbody(float(t)));
        x = c.x / (c.x + c.y + c.z), y = c.y / (c.x + c.y + c.z);
    } else {
        // CIE 15's daylight locus.
        x = t <= 7000 ? -4.6070e9 / (t * t * t) + 2.9678e6 / (t * t) + 0.09911e3 / t + 0.244063
                      : -2.0064e9 / (t * t * t) + 1.9018e6 / (t * t) + 0.24748e3 / t + 0.237040;
        y = -3 * x * x + 2.870 * x - 0.275;
    }
    return {float(x / y), 1, float((1 - x - y) / y)};
}

ColorMatrix white_balance(float kelvin) {
    // Bradford's cone response (Lam 1985) and its inverse, computed.
    const double b[3][3] = {{0.8951, 0.2664, -0.1614}, {-0.7502, 1.7135, 0.0367}, {0.0389, -0.0685, 1.0296}};
    const auto inverse = [](const double a[3][3], double out[3][3]) {
        const double det = a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
                           a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
                           a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) {
                const int i1 = (j + 1) % 3, i2 = (j + 2) % 3, j1 = (i + 1) % 3, j2 = (i + 2) % 3;
                out[i][j] = (a[i1][j1] * a[i2][j2] - a[i1][j2] * a[i2][j1]) / det;
            }
    };
    const auto mul = [](const double a[3][3], const double c[3][3], double out[3][3]) {
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) out[i][j] = a[i][0] * c[0][j] + a[i][1] * c[1][j] + a[i][2] * c[2][j];
    };
    // linear sRGB <-> XYZ (the film's matrix and its inverse)
    const auto& to_rgb = kSrgbFromXyz;
    double to_xyz[3][3], b_inv[3][3];
    inverse(to_rgb, to_xyz);
    inverse(b, b_inv);
    const Xyz src = daylight_white(kelvin);
    // The target: the white of linear sRGB itself (D65 as the matrix has it), so that the balanced
    // white is (1, 1, 1) to the last digit.
    const double dst_y = to_xyz[1][0] + to_xyz[1][1] + to_xyz[1][2];
    const double dst_x = (to_xyz[0][0] + to_xyz[0][1] + to_xyz[0][2]) / dst_y,
                 dst_z = (to_xyz[2][0] + to_xyz[2][1] + to_xyz[2][2]) / dst_y;
    double scale[3][3]{};
    for (int i = 0; i < 3; ++i) {
        const double s = b[i][0] * src.x + b[i][1] * src.y + b[i][2] * src.z;
        const double d = b[i][0] * dst_x + b[i][1] * 1 + b[i][2] * dst_z;
        scale[i][i] = d / s;
    }
    double t1[3][3], t2[3][3], t3[3][3], t4[3][3];
    mul(scale, b, t1);       // diag * B
    mul(b_inv, t1, t2);      // B^-1 diag B  (on XYZ)
    mul(t2, to_xyz, t3);     // from linear sRGB
    mul(to_rgb, t3, t4);     // back to linear sRGB
    ColorMatrix m;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) m.m[i][j] = float(t4[i][j]);
    return m;
}

Color film_rgb(Color radiance, const Wavelengths& wl) {
    Xyz sum;
    for (int i = 0; i < 3; ++i) {
        const float v = radiance[i];
        if (v == 0 || !(wl.pdf[i] > 0)) continue;
        const Xyz c = cie_xyz(wl.lambda[i]);
        const float w = v / wl.pdf[i];
        sum.x += c.x * w, sum.y += c.y * w, sum.z += c.z * w;
    }
    const float n = 1 / (3 * cie_y_integral());
    return xyz_to_linear_srgb({sum.x * n, sum.y * n, sum.z * n});
}

PiecewiseLinearSpectrum::PiecewiseLinearSpectrum(std::vector<float> lambda, std::vector<float> value)
    : lambda_(std::move(lambda)), value_(std::move(value)) {}

PiecewiseLinearSpectrum PiecewiseLinearSpectrum::interleaved(std::span<const float> pairs, bool normalise) {
    std::vector<float> l, v;
    for (std::size_t i = 0; i + 1 < pairs.size(); i += 2) l.push_back(pairs[i]), v.push_back(pairs[i + 1]);
    PiecewiseLinearSpectrum s(std::move(l), std::move(v));
    if (normalise) {
        const float y = spectrum_to_xyz(s).y;
        if (y > 0) s.scale(1 / y);
    }
    return s;
}

float PiecewiseLinearSpectrum::operator()(float lambda) const {
    if (lambda_.empty()) return 0;
    if (lambda <= lambda_.front()) return value_.front();
    if (lambda >= lambda_.back()) return value_.back();
    const auto it = std::upper_bound(lambda_.begin(), lambda_.end(), lambda);
    const std::size_t i = std::size_t(it - lambda_.begin()) - 1;
    const float t = (lambda - lambda_[i]) / (lambda_[i + 1] - lambda_[i]);
    return value_[i] + t * (value_[i + 1] - value_[i]);
}

void PiecewiseLinearSpectrum::scale(float s) {
    for (float& v : value_) v *= s;
}

double planck(float lambda_nm, float kelvin) {
    if (!(kelvin > 0)) return 0;
    constexpr double c = 299792458.0, h = 6.62606957e-34, kb = 1.3806488e-23;
    const double l = lambda_nm * 1e-9;
    return 2 * h * c * c / (l * l * l * l * l * (std::exp(h * c / (l * kb * kelvin)) - 1));
}

float blackbody_normalised(float lambda_nm, float kelvin) {
    if (!(kelvin > 0)) return 0;
    const float peak = float(2.8977721e-3 / kelvin * 1e9);  // Wien's displacement law, in nm
    return float(planck(lambda_nm, kelvin) / planck(peak, kelvin));
}

Spectrum Spectrum::tabulated(PiecewiseLinearSpectrum table) {
    Spectrum s;
    s.kind_ = Kind::kTabulated;
    s.table_ = std::move(table);
    return s;
}

Spectrum Spectrum::blackbody(float kelvin) {
    Spectrum s;
    s.kind_ = Kind::kBlackbody;
    s.p_[0] = kelvin;
    return s;
}

Spectrum Spectrum::sellmeier(const float b[3], const float c[3]) {
    Spectrum s;
    s.kind_ = Kind::kSellmeier;
    for (int i = 0; i < 3; ++i) s.p_[i] = b[i], s.p_[3 + i] = c[i];
    return s;
}

Spectrum Spectrum::from_abbe(float n_d, float v_d) {
    constexpr double l_d = 587.56, l_f = 486.13, l_c = 656.27;
    Spectrum s;
    s.kind_ = Kind::kCauchy;
    const double b = (n_d - 1) / v_d / (1 / (l_f * l_f) - 1 / (l_c * l_c));
    s.p_[0] = float(n_d - b / (l_d * l_d));
    s.p_[1] = float(b);
    return s;
}

Spectrum Spectrum::normalised_emission() const {
    Spectrum s = *this;
    const float y = spectrum_to_xyz(s).y;
    if (y > 0) s.scale_ /= y;
    s.film_colour_ = s.film_colour();
    s.has_film_colour_ = true;
    return s;
}

Color Spectrum::emission_rgb() const {
    // Out of the sRGB gamut (a narrow band, a deep red black body) a channel is negative: no
    // emitter gives negative light, so that channel is 0 and the luminance is made 1 again.
    Color c = xyz_to_linear_srgb(spectrum_to_xyz(*this));
    c = {std::max(c.r, 0.0f), std::max(c.g, 0.0f), std::max(c.b, 0.0f)};
    const float y = luminance(c);
    return y > 0 ? c / y : c;
}

float Spectrum::operator()(float lambda) const {
    switch (kind_) {
        case Kind::kTabulated: return scale_ * table_(lambda);
        case Kind::kBlackbody: return scale_ * blackbody_normalised(lambda, p_[0]);
        case Kind::kSellmeier: {
            const double l2 = double(lambda) * lambda * 1e-6;  // micrometres squared
            double n2 = 1;
            for (int i = 0; i < 3; ++i) n2 += p_[i] * l2 / (l2 - p_[3 + i]);
            return float(std::sqrt(std::max(n2, 0.0)));
        }
        case Kind::kCauchy: return p_[0] + p_[1] / (lambda * lambda);
    }
    return 0;
}

bool Spectrum::constant() const {
    switch (kind_) {
        case Kind::kTabulated:
            return std::all_of(table_.value().begin(), table_.value().end(),
                               [&](float v) { return v == table_.value().front(); });
        case Kind::kBlackbody: return false;
        case Kind::kSellmeier: return p_[0] == 0 && p_[1] == 0 && p_[2] == 0;
        case Kind::kCauchy: return p_[1] == 0;
    }
    return true;
}

const PiecewiseLinearSpectrum* named_spectrum(std::string_view name) {
    const auto& t = named_table();
    for (std::size_t i = 0; i < std::size(kNamedSpectra); ++i)
        if (kNamedSpectra[i].name == name) return &t.spectra[i];
    return nullptr;
}

std::vector<std::string_view> named_spectrum_names() {
    std::vector<std::string_view> names;
    for (const NamedSpectrumData& d : kNamedSpectra) names.push_back(d.name);
    return names;
}

Color d65_at(const Wavelengths& wl) {
    static const std::vector<float> table = [] {
        std::vector<float> t(kCieSamples);
        for (int i = 0; i < kCieSamples; ++i) t[std::size_t(i)] = d65()(kLambdaMin + float(i));
        return t;
    }();
    const auto at = [&](float lambda) {
        const float x = std::clamp(lambda - kLambdaMin, 0.0f, float(kCieSamples - 1));
        const int i = std::min(int(x), kCieSamples - 2);
        const float t = x - float(i);
        return table[std::size_t(i)] + t * (table[std::size_t(i) + 1] - table[std::size_t(i)]);
    };
    return {at(wl.lambda[0]), at(wl.lambda[1]), at(wl.lambda[2])};
}

const PiecewiseLinearSpectrum& d65() {
    static const PiecewiseLinearSpectrum& s = *named_spectrum("stdillum-D65");
    return s;
}

}  // namespace glint
