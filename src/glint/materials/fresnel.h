#pragma once
// Fresnel reflectance. Conventions: cos_i is the cosine between the incident direction and the
// normal on the side the light arrives from when positive; eta is the relative index
// n_transmitted / n_incident seen from the positive side of the normal.
#include <algorithm>
#include <cmath>
#include <complex>

#include "glint/math/color.h"
#include "glint/math/vector.h"

namespace glint {

constexpr float sqr(float v) { return v * v; }

/// Unpolarised reflectance of a smooth dielectric interface. A negative cos_i means the light
/// arrives from the other side, where the relative index is 1 / eta. Total internal reflection
/// gives 1.
inline float fresnel_dielectric(float cos_i, float eta) {
    cos_i = std::clamp(cos_i, -1.0f, 1.0f);
    if (cos_i < 0) {
        eta = 1 / eta;
        cos_i = -cos_i;
    }
    const float sin2_i = 1 - cos_i * cos_i;
    const float sin2_t = sin2_i / (eta * eta);
    if (sin2_t >= 1) return 1;
    const float cos_t = std::sqrt(std::max(0.0f, 1 - sin2_t));
    const float r_par = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    const float r_perp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    return 0.5f * (r_par * r_par + r_perp * r_perp);
}

/// Reflectance of a conductor with complex index eta + i k (relative to the outside medium),
/// for one wavelength: the dielectric formula with complex arithmetic.
inline float fresnel_complex(float cos_i, std::complex<float> eta) {
    using C = std::complex<float>;
    cos_i = std::clamp(cos_i, 0.0f, 1.0f);
    const float sin2_i = 1 - cos_i * cos_i;
    const C sin2_t = C(sin2_i) / (eta * eta);
    const C cos_t = std::sqrt(C(1) - sin2_t);
    const C r_par = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    const C r_perp = (C(cos_i) - eta * cos_t) / (C(cos_i) + eta * cos_t);
    return 0.5f * (std::norm(r_par) + std::norm(r_perp));
}

inline Color fresnel_conductor(float cos_i, Color eta, Color k) {
    return {fresnel_complex(cos_i, {eta.r, k.r}), fresnel_complex(cos_i, {eta.g, k.g}),
            fresnel_complex(cos_i, {eta.b, k.b})};
}

/// Schlick's approximation with normal-incidence reflectance f0 (glTF's metals).
inline Color fresnel_schlick(float cos_i, Color f0) {
    const float m = std::clamp(1 - cos_i, 0.0f, 1.0f);
    const float m5 = (m * m) * (m * m) * m;
    return f0 + (Color{1} - f0) * m5;
}

/// The direction refracted through a surface with normal +z (local frame) and relative index
/// eta (n_inside / n_outside); wi may be on either side. False on total internal reflection.
/// `eta_rel` receives the index ratio actually crossed (eta or 1 / eta).
inline bool refract(Vector3 wi, Vector3 n, float eta, Vector3& wt, float& eta_rel) {
    float cos_i = dot(n, wi);
    if (cos_i < 0) {
        eta = 1 / eta;
        cos_i = -cos_i;
        n = -n;
    }
    const float sin2_i = std::max(0.0f, 1 - cos_i * cos_i);
    const float sin2_t = sin2_i / (eta * eta);
    if (sin2_t >= 1) return false;
    const float cos_t = std::sqrt(1 - sin2_t);
    wt = -wi / eta + n * (cos_i / eta - cos_t);
    eta_rel = eta;
    return true;
}

}  // namespace glint
