#pragma once
// Warps from the unit square to shapes, for sampling points uniformly by area. Each maps
// uniform (u1, u2) in [0,1)^2 to a uniform point of its domain.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <numbers>

#include "glint/math/vector.h"
#include "glint/samplers/stratified.h"

namespace glint {

/// sin and cos of pi/4 t for t in [-1, 1] (an angle within pi/4 of 0), as polynomials in t:
/// sin by t (c0 + c1 t^2 + c2 t^4 + c3 t^6), cos by degree 4 in t^2. The coefficients are a
/// near-minimax fit on [-1, 1] (iteratively reweighted least squares in double, rounded to float);
/// their own error is below 2.5e-9 (sin) and 5e-11 (cos), and evaluated in float below 1e-7,
/// about one float ulp at 1 (warp_test.cpp checks against double-precision sin and cos). Shorter
/// than the Taylor series to the same accuracy, so fewer dependent steps.
struct SinCos {
    float sin, cos;
};
inline SinCos sin_cos_quarter_pi(float t) {
    const float t2 = t * t;
    const float s = t * (0.78539818525f + t2 * (-0.080745436251f + t2 * (0.0024900070857f + t2 * -3.5954508348e-05f)));
    const float c =
        1 + t2 * (-0.30842512846f + t2 * (0.015854325145f + t2 * (-0.00032593862852f + t2 * 3.5298112380e-06f)));
    return {s, c};
}

/// Uniform on the unit disk, Shirley and Chiu's concentric map: squares to rings, so that
/// stratification of the square carries over (unlike r = sqrt(u1), phi = 2 pi u2).
inline Point2 sample_uniform_disk_concentric(Sample2 u) {
    const float a = 2 * u.x - 1, b = 2 * u.y - 1;
    if (a == 0 && b == 0) return {0, 0};
    // The wedge |b| < |a| has r = a, phi = pi/4 (b/a); the other r = b, phi = pi/2 - pi/4 (a/b),
    // whose cosine and sine are the sine and cosine of pi/4 (a/b). So both need cos and sin of
    // pi/4 t for one ratio t in [-1, 1], and the wedge only picks which goes where: selects, not
    // a branch that mispredicts on half the samples, and polynomials, not a libm call
    // (performance.md, step 7).
    const bool steep = std::abs(a) <= std::abs(b);
    const float r = steep ? b : a;
    const float t = (steep ? a : b) / r;
    const SinCos sc = sin_cos_quarter_pi(t);
    // The swap by masks: GCC turns a ternary here back into the branch.
    const std::uint32_t mask = 0u - static_cast<std::uint32_t>(steep);
    const auto s = std::bit_cast<std::uint32_t>(sc.sin), c = std::bit_cast<std::uint32_t>(sc.cos);
    return {r * std::bit_cast<float>((s & mask) | (c & ~mask)), r * std::bit_cast<float>((c & mask) | (s & ~mask))};
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
