#pragma once
// Warps from the unit square to shapes, for sampling points uniformly by area. Each maps
// uniform (u1, u2) in [0,1)^2 to a uniform point of its domain.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "glint/math/vector.h"
#include "glint/samplers/stratified.h"

namespace glint {

/// Uniform on the unit disk, Shirley and Chiu's concentric map: squares to rings, so that
/// stratification of the square carries over (unlike r = sqrt(u1), phi = 2 pi u2).
inline Point2 sample_uniform_disk_concentric(Sample2 u) {
    const float a = 2 * u.x - 1, b = 2 * u.y - 1;
    if (a == 0 && b == 0) return {0, 0};
    constexpr float kPi4 = std::numbers::pi_v<float> / 4, kPi2 = std::numbers::pi_v<float> / 2;
    float r, phi;
    if (std::abs(a) > std::abs(b)) {
        r = a;
        phi = kPi4 * (b / a);
    } else {
        r = b;
        phi = kPi2 - kPi4 * (a / b);
    }
    return {r * std::cos(phi), r * std::sin(phi)};
}

/// Barycentric coordinates (b0, b1) of a uniform point of a triangle (b2 = 1 - b0 - b1):
/// b0 = 1 - sqrt(u1), b1 = u2 sqrt(u1).
inline Point2 sample_uniform_triangle(Sample2 u) {
    const float s = std::sqrt(u.x);
    return {1 - s, u.y * s};
}

/// Cosine-weighted direction about +z (Malley's method: a uniform disk point lifted onto the
/// hemisphere); density cos(theta) / pi.
inline Vector3 sample_cosine_hemisphere(Sample2 u) {
    const Point2 d = sample_uniform_disk_concentric(u);
    const float z = std::sqrt(std::max(0.0f, 1 - d.x * d.x - d.y * d.y));
    return {d.x, d.y, z};
}
inline float cosine_hemisphere_pdf(float cos_theta) {
    return cos_theta > 0 ? cos_theta * std::numbers::inv_pi_v<float> : 0;
}

/// Uniform direction on the unit sphere; density 1 / (4 pi).
inline Vector3 sample_uniform_sphere(Sample2 u) {
    const float z = 1 - 2 * u.x;
    const float r = std::sqrt(std::max(0.0f, 1 - z * z));
    const float phi = 2 * std::numbers::pi_v<float> * u.y;
    return {r * std::cos(phi), r * std::sin(phi), z};
}
inline constexpr float kUniformSpherePdf = 0.25f * std::numbers::inv_pi_v<float>;

/// Uniform direction in the cone of directions within angle theta_max of +z, given
/// one_minus_cos = 1 - cos(theta_max) > 0 (pass 2 sin^2(theta_max / 2): exact for a small sun);
/// density 1 / (2 pi one_minus_cos).
inline Vector3 sample_uniform_cone(Sample2 u, float one_minus_cos) {
    const float one_minus_z = u.x * one_minus_cos;
    const float r = std::sqrt(std::max(0.0f, one_minus_z * (2 - one_minus_z)));
    const float phi = 2 * std::numbers::pi_v<float> * u.y;
    return {r * std::cos(phi), r * std::sin(phi), 1 - one_minus_z};
}
inline float uniform_cone_pdf(float one_minus_cos) {
    return 1 / (2 * std::numbers::pi_v<float> * one_minus_cos);
}

/// Veach's power heuristic with beta = 2: the weight of a sample of density pdf_a against a
/// second strategy of density pdf_b at the same point (1 when pdf_a is infinite: a delta).
inline float power_heuristic(float pdf_a, float pdf_b) {
    const float a = pdf_a * pdf_a, b = pdf_b * pdf_b;
    if (std::isinf(a)) return 1;
    return a + b > 0 ? a / (a + b) : 0;
}

}  // namespace glint
