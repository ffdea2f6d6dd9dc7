#pragma once
// The function space of RGB upsampling (Jakob and Hanika, "A Low-Dimensional Function Space for
// Efficient Spectral Upsampling", 2019): a reflectance s(lambda) = S(c0 t^2 + c1 t + c2), with
// S(x) = 1/2 + x / (2 sqrt(1 + x^2)) a sigmoid onto (0, 1) and t = (lambda - 360) / 470 the
// wavelength mapped onto [0, 1]. Smooth, bounded, three numbers per colour.
//
// The coefficients for every RGB colour are tabulated by glint's own optimiser at build time
// (rgb2spec_gen.cpp) and looked up by rgb_spectrum.cpp. The table: for each channel that is the
// largest (l = 0, 1, 2), a res^3 grid over z = that channel's value (spaced densely near 0 and
// 1) and x, y = the next two channels (l+1, l+2 mod 3) divided by z, three floats per node.
#include <cmath>

namespace glint::rgb_model {

constexpr int kRes = 64;
constexpr int kTableFloats = 3 * kRes * kRes * kRes * 3;

inline float sigmoid(float x) {
    if (std::isinf(x)) return x > 0 ? 1.0f : 0.0f;
    return 0.5f + x / (2 * std::sqrt(1 + x * x));
}

inline float wavelength_t(float lambda) { return (lambda - 360.0f) / 470.0f; }

inline float evaluate(const float c[3], float lambda) {
    const float t = wavelength_t(lambda);
    return sigmoid((c[0] * t + c[1]) * t + c[2]);
}

/// The z value of grid row k: smoothstep(smoothstep(k / (res - 1))).
inline float z_node(int k) {
    const auto smoothstep = [](double x) { return x * x * (3 - 2 * x); };
    return float(smoothstep(smoothstep(double(k) / (kRes - 1))));
}

/// The x (or y) value of grid column i: uniform (a denser spacing towards 1 or 0 was tried and
/// moved the interpolation error elsewhere: docs/spectral.md).
inline float x_node(int i) { return float(i) / (kRes - 1); }

/// Index of coefficient 0 of node (l, k (z), j (y), i (x)).
inline int node(int l, int k, int j, int i) { return (((l * kRes + k) * kRes + j) * kRes + i) * 3; }

}  // namespace glint::rgb_model
