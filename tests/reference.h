#pragma once
// Independent double-precision references for the end-to-end tests: the article's camera and
// ray-sphere formulas written out again, textbook-style, to check the renderer against.
#include <array>
#include <cmath>
#include <optional>

namespace glint::reference {

using V = std::array<double, 3>;
inline V add(V a, V b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
inline V sub(V a, V b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
inline V mul(V a, double s) { return {a[0] * s, a[1] * s, a[2] * s}; }
inline double dot(V a, V b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline V unit(V a) { return mul(a, 1 / std::sqrt(dot(a, a))); }
inline V cross(V a, V b) {
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

/// The article's ray direction for pixel (col, row)'s centre: H = up x V, U = V x H,
/// B = -w/2 H - h/2 U, A = B + w x/Sw H + h y/Sh U + z V with x = col + 1/2 and
/// y = Sh - (row + 1/2) (y up from the bottom-left corner).
inline V camera_dir(V v, double w, double h, double z, int sw, int sh, int col, int row) {
    v = unit(v);
    const V H = unit(cross({0, 1, 0}, v));
    const V U = cross(v, H);
    const double x = col + 0.5, y = sh - (row + 0.5);
    V a = add(mul(H, -w / 2), mul(U, -h / 2));
    a = add(a, mul(H, w * x / sw));
    a = add(a, mul(U, h * y / sh));
    a = add(a, mul(v, z));
    return unit(a);
}

/// Nearest t > 1e-9 of the textbook quadratic t^2 + 2bt + c = 0 (unit d), if any.
inline std::optional<double> hit_sphere(V o, V d, V center, double r) {
    const V f = sub(o, center);
    const double b = dot(f, d), c = dot(f, f) - r * r;
    const double disc = b * b - c;
    if (disc < 0) return std::nullopt;
    const double t0 = -b - std::sqrt(disc), t1 = -b + std::sqrt(disc);
    if (t0 > 1e-9) return t0;
    if (t1 > 1e-9) return t1;
    return std::nullopt;
}

/// The article's sky: t = (d.y + 1)/2, (1-t)(1,1,1) + t(0.5,0.7,1).
inline V sky(V d) {
    const double t = 0.5 * (d[1] + 1);
    return {1 - t + t * 0.5, 1 - t + t * 0.7, 1.0};
}

}  // namespace glint::reference
