#include "glint/spectra/rgb_spectrum.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <xmmintrin.h>

#include "glint/spectra/rgb_spectrum_model.h"

// The table glint_rgb2spec wrote at build time, assembled into the library (rgb_spectrum_table.S).
extern "C" const float glint_rgb_spectrum_table[];

namespace glint {

namespace {

using namespace rgb_model;

struct ZNodes {
    std::array<float, kRes> z;
    ZNodes() {
        for (int k = 0; k < kRes; ++k) z[std::size_t(k)] = z_node(k);
    }
};
const ZNodes& z_nodes() {
    static const ZNodes nodes;
    return nodes;
}

}  // namespace

float RgbSigmoid::operator()(float lambda) const { return evaluate(c, lambda); }

RgbSigmoid rgb_sigmoid(Color rgb) {
    // Into [0, 1]; NaN to 0 (no index is computed from a NaN).
    const auto unit = [](float x) { return x > 0 ? (x < 1 ? x : 1.0f) : 0.0f; };
    const float v[3] = {unit(rgb.r), unit(rgb.g), unit(rgb.b)};
    RgbSigmoid s;
    if (v[0] == v[1] && v[1] == v[2]) {
        // A grey is a constant: the sigmoid's inverse at it (infinite at 0 and 1).
        const float g = v[0];
        s.c[2] = g <= 0 ? -INFINITY : g >= 1 ? INFINITY : (g - 0.5f) / std::sqrt(g * (1 - g));
        return s;
    }
    const int l = v[0] >= v[1] ? (v[0] >= v[2] ? 0 : 2) : (v[1] >= v[2] ? 1 : 2);
    const float z = v[l];
    const float x = v[(l + 1) % 3] / z * (kRes - 1), y = v[(l + 2) % 3] / z * (kRes - 1);
    const int xi = std::min(int(x), kRes - 2), yi = std::min(int(y), kRes - 2);
    const auto& zs = z_nodes().z;
    const int zi = std::clamp(int(std::upper_bound(zs.begin(), zs.end(), z) - zs.begin()) - 1, 0, kRes - 2);
    const float dx = x - float(xi), dy = y - float(yi);
    const float dz = (z - zs[std::size_t(zi)]) / (zs[std::size_t(zi) + 1] - zs[std::size_t(zi)]);
    const float* t = glint_rgb_spectrum_table;
    for (int a = 0; a < 3; ++a) {
        const auto at = [&](int k, int j, int i) { return t[node(l, k, j, i) + a]; };
        const auto lerp = [](float u, float p, float q) { return p + u * (q - p); };
        s.c[a] = lerp(dz,
                      lerp(dy, lerp(dx, at(zi, yi, xi), at(zi, yi, xi + 1)), lerp(dx, at(zi, yi + 1, xi), at(zi, yi + 1, xi + 1))),
                      lerp(dy, lerp(dx, at(zi + 1, yi, xi), at(zi + 1, yi, xi + 1)),
                           lerp(dx, at(zi + 1, yi + 1, xi), at(zi + 1, yi + 1, xi + 1))));
    }
    return s;
}

RgbReflectance::RgbReflectance(Color rgb) {
    // A grey is its own value at every wavelength (its sigmoid is a constant).
    if (rgb.r == rgb.g && rgb.g == rgb.b)
        grey_ = rgb.r > 0 ? (rgb.r < 1 ? rgb.r : 1.0f) : 0.0f;
    else
        sigmoid_ = rgb_sigmoid(rgb);
}

Color RgbReflectance::at(const Wavelengths& wl) const {
    if (grey_ >= 0) return Color{grey_};
    const RgbSigmoid& s = sigmoid_;
    // The three sigmoids at once (four lanes, one spare): the polynomial, then
    // 1/2 + x / (2 sqrt(1 + x^2)) with one square root and one division for all.
    const auto t = [&](int i) { return wavelength_t(wl.lambda[i]); };
    const __m128 tv = _mm_setr_ps(t(0), t(1), t(2), 0);
    const __m128 x = _mm_add_ps(_mm_mul_ps(_mm_add_ps(_mm_mul_ps(_mm_set1_ps(s.c[0]), tv), _mm_set1_ps(s.c[1])), tv),
                                _mm_set1_ps(s.c[2]));
    const __m128 root = _mm_sqrt_ps(_mm_add_ps(_mm_set1_ps(1), _mm_mul_ps(x, x)));
    const __m128 half = _mm_set1_ps(0.5f);
    alignas(16) float v[4];
    _mm_store_ps(v, _mm_add_ps(half, _mm_div_ps(_mm_mul_ps(half, x), root)));
    return {v[0], v[1], v[2]};
}

Color upsample_reflectance(Color rgb, const Wavelengths& wl) { return RgbReflectance(rgb).at(wl); }

namespace {

// An unbounded value as scale times a reflectance: scale = 2 max(rgb) (0 when no channel is
// positive, and then nothing is upsampled), shape = rgb / scale.
struct UnboundedSplit {
    float scale = 0;
    Color shape{0};
};
UnboundedSplit split_unbounded(Color rgb) {
    const float m = std::max({rgb.r, rgb.g, rgb.b});
    if (!(m > 0)) return {};
    const float scale = 2 * m;
    return {scale, rgb / scale};
}

}  // namespace

Color upsample_unbounded(Color rgb, const Wavelengths& wl) {
    const UnboundedSplit u = split_unbounded(rgb);
    if (!(u.scale > 0)) return Color{0};
    return upsample_reflectance(u.shape, wl) * u.scale;
}

RgbIlluminant::RgbIlluminant(Color rgb) {
    // upsample_unbounded's split, its table lookup done here.
    const UnboundedSplit u = split_unbounded(rgb);
    scale_ = u.scale;
    if (scale_ > 0) shape_ = RgbReflectance(u.shape);
}

Color RgbIlluminant::at(const Wavelengths& wl) const {
    if (!(scale_ > 0)) return Color{0};
    const Color s = shape_.at(wl) * scale_;
    if (s.is_black()) return s;
    return s * d65_at(wl);
}

Color upsample_illuminant(Color rgb, const Wavelengths& wl) { return RgbIlluminant(rgb).at(wl); }

}  // namespace glint
