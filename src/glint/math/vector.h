#pragma once
// Vectors, points and normals: three distinct types so that the compiler catches mixing them
// (a point minus a point is a vector; a point plus a point is a bug).
//
// Frame convention (the article's, and POV-Ray's and pbrt's): +y is up, the default camera looks
// along +z and +x points to the image's right. That is a left-handed frame: cross products are
// the ordinary formula, and with up=(0,1,0), V=(0,0,1) the camera's right is up x V = (1,0,0).
#include <algorithm>
#include <cmath>

namespace glint {

using Float = float;

/// A 2D point: texture coordinates (u, v) or a point of a 2D domain.
struct Point2 {
    Float x = 0, y = 0;
};

template <typename Derived>
struct Tuple3 {
    Float x = 0, y = 0, z = 0;
    constexpr Tuple3() = default;
    constexpr Tuple3(Float x_, Float y_, Float z_) : x(x_), y(y_), z(z_) {}
    constexpr Float operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
    constexpr Float& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }
    constexpr bool operator==(const Tuple3&) const = default;
};

struct Vector3 : Tuple3<Vector3> {
    using Tuple3::Tuple3;
    constexpr Vector3 operator+(Vector3 o) const { return {x + o.x, y + o.y, z + o.z}; }
    constexpr Vector3 operator-(Vector3 o) const { return {x - o.x, y - o.y, z - o.z}; }
    constexpr Vector3 operator-() const { return {-x, -y, -z}; }
    constexpr Vector3 operator*(Float s) const { return {x * s, y * s, z * s}; }
    constexpr Vector3 operator/(Float s) const { return *this * (Float(1) / s); }
    constexpr Vector3& operator+=(Vector3 o) { return *this = *this + o; }
};
constexpr Vector3 operator*(Float s, Vector3 v) { return v * s; }

struct Point3 : Tuple3<Point3> {
    using Tuple3::Tuple3;
    constexpr Point3 operator+(Vector3 v) const { return {x + v.x, y + v.y, z + v.z}; }
    constexpr Point3 operator-(Vector3 v) const { return {x - v.x, y - v.y, z - v.z}; }
    constexpr Vector3 operator-(Point3 p) const { return {x - p.x, y - p.y, z - p.z}; }
};

struct Normal3 : Tuple3<Normal3> {
    using Tuple3::Tuple3;
    constexpr explicit Normal3(Vector3 v) : Tuple3(v.x, v.y, v.z) {}
    constexpr Normal3 operator-() const { return {-x, -y, -z}; }
    constexpr Normal3 operator*(Float s) const { return {x * s, y * s, z * s}; }
};

constexpr Vector3 to_vector(Normal3 n) { return {n.x, n.y, n.z}; }
constexpr Vector3 to_vector(Point3 p) { return {p.x, p.y, p.z}; }

template <typename A, typename B>
constexpr Float dot(const Tuple3<A>& a, const Tuple3<B>& b) {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}
constexpr Vector3 cross(Vector3 a, Vector3 b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
template <typename T>
Float length(const Tuple3<T>& v) {
    return std::sqrt(dot(v, v));
}
inline Vector3 normalize(Vector3 v) { return v / length(v); }
inline Normal3 normalize(Normal3 n) { return n * (Float(1) / length(n)); }
template <typename T>
bool is_finite(const Tuple3<T>& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}
template <typename T>
Float max_abs_component(const Tuple3<T>& v) {
    return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
}

/// Mirror reflection of an incoming direction d about the normal n (the article's
/// R = D - 2(N.D)N). Works for either orientation of n.
inline Vector3 reflect(Vector3 d, Normal3 n) { return d - to_vector(n) * (2 * dot(n, d)); }

/// n flipped, if needed, to lie in the hemisphere opposite the incoming direction d.
inline Normal3 face_forward(Normal3 n, Vector3 d) { return dot(n, d) > 0 ? -n : n; }

/// v read float by float (three 4-byte loads), for a vector that a callee has just stored in
/// pieces that straddle it: an 8-byte load across two of those stores cannot take its data from
/// them and waits for the cache (a failed store forward; docs/performance.md, step 20).
inline Vector3 reload(const Vector3& v) {
    const volatile Float &x = v.x, &y = v.y, &z = v.z;
    return {x, y, z};
}

}  // namespace glint
