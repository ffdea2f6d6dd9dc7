#include "glint/media/medium.h"

#include <type_traits>

#include "glint/spectra/rgb_spectrum.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace glint {

MediumPoint GridMedium::at(Point3 p, const SpectralMedium* sm) const {
    const float d = density.lookup(p);
    MediumPoint mp = sm ? MediumPoint{sm->sigma_a * d, sm->sigma_s * d, Color{0}} : MediumPoint{sigma_a * d, sigma_s * d, Color{0}};
    switch (emission_kind) {
        case EmissionKind::kNone: break;
        case EmissionKind::kGrid: mp.Le = (sm ? sm->Le : emission_color) * (emission.lookup(p) * emission_scale); break;
        case EmissionKind::kTemperature: {
            const float kelvin = emission.lookup(p) * temperature_scale;
            if (!sm) {
                mp.Le = blackbody_rgb(kelvin) * emission_scale;
            } else {
                for (int i = 0; i < 3; ++i)
                    (i == 0 ? mp.Le.r : i == 1 ? mp.Le.g : mp.Le.b) = blackbody_normalised(sm->wl->lambda[i], kelvin) * emission_scale;
            }
            break;
        }
    }
    return mp;
}

SpectralMedium spectral_medium(const Medium& m, const Wavelengths& wl) {
    return std::visit(
        [&](const auto& x) {
            using T = std::decay_t<decltype(x)>;
            Color le;
            if constexpr (std::is_same_v<T, HomogeneousMedium>) le = x.Le;
            else le = x.emission_color;
            return SpectralMedium{upsample_unbounded(x.sigma_a, wl), upsample_unbounded(x.sigma_s, wl),
                                  upsample_illuminant(le, wl), &wl};
        },
        m);
}

namespace {

// The CIE 1931 2-degree colour matching functions as Wyman, Sloan and Shirley's multi-lobe
// Gaussian fit ("Simple Analytic Approximations to the CIE XYZ Color Matching Functions", JCGT
// 2013), nanometres.
double lobe(double l, double mu, double s1, double s2) {
    const double t = (l - mu) / (l < mu ? s1 : s2);
    return std::exp(-0.5 * t * t);
}
double cie_x(double l) {
    return 1.056 * lobe(l, 599.8, 37.9, 31.0) + 0.362 * lobe(l, 442.0, 16.0, 26.7) -
           0.065 * lobe(l, 501.1, 20.4, 26.2);
}
double cie_y(double l) { return 0.821 * lobe(l, 568.8, 46.9, 40.5) + 0.286 * lobe(l, 530.9, 16.3, 31.1); }
double cie_z(double l) { return 1.217 * lobe(l, 437.0, 11.8, 36.0) + 0.681 * lobe(l, 459.0, 26.0, 13.8); }

// Planck's law, spectral radiance at wavelength l (nm) and temperature t (K), in W / (m^2 sr m).
double planck(double l_nm, double t) {
    constexpr double c = 299792458.0, h = 6.62606957e-34, kb = 1.3806488e-23;
    const double l = l_nm * 1e-9;
    return 2 * h * c * c / (l * l * l * l * l * std::expm1(h * c / (l * kb * t)));
}

Color blackbody_exact(double t) {
    if (!(t > 0)) return Color{0};
    const double peak = planck(2.8977721e-3 / t * 1e9, t);  // Wien's displacement law
    double x = 0, y = 0, z = 0, y_integral = 0;
    for (int l = 360; l <= 830; ++l) {
        const double b = planck(l, t) / peak;
        x += b * cie_x(l);
        y += b * cie_y(l);
        z += b * cie_z(l);
        y_integral += cie_y(l);
    }
    x /= y_integral, y /= y_integral, z /= y_integral;
    // XYZ to linear sRGB (Rec. 709 primaries, D65 white).
    const auto pos = [](double v) { return static_cast<float>(std::max(v, 0.0)); };  // out of gamut: clipped
    return Color{pos(3.2404542 * x - 1.5371385 * y - 0.4985314 * z),
                 pos(-0.9692660 * x + 1.8760108 * y + 0.0415560 * z),
                 pos(0.0556434 * x - 0.2040259 * y + 1.0572252 * z)};
}

constexpr float kTableStep = 25.0f;
constexpr int kTableSize = 1601;  // 0 .. 40000 K

const std::vector<Color>& blackbody_table() {
    static const std::vector<Color> table = [] {
        std::vector<Color> t(kTableSize);
        for (int i = 0; i < kTableSize; ++i) t[std::size_t(i)] = blackbody_exact(double(i) * kTableStep);
        return t;
    }();
    return table;
}

}  // namespace

Color blackbody_rgb(float kelvin) {
    if (!(kelvin > 0)) return Color{0};
    const auto& table = blackbody_table();
    const float x = std::min(kelvin / kTableStep, float(kTableSize - 1));
    const int i = std::min(int(x), kTableSize - 2);
    const float f = x - float(i);
    const Color a = table[std::size_t(i)], b = table[std::size_t(i) + 1];
    return a * (1 - f) + b * f;
}

}  // namespace glint
