#pragma once
// Warps from the unit square to shapes, for sampling points uniformly by area. Each maps
// uniform (u1, u2) in [0,1)^2 to a uniform point of its domain.
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

}  // namespace glint
