#pragma once
// Affine transforms: a 3x4 matrix (rotation/scale/shear in the 3x3 part, translation in the last
// column) together with its inverse, so that normals (by the inverse transpose) and rays (into
// object space, by the inverse) cost no inversion at render time. Column-vector convention:
// p' = M p; `a * b` applies b first, then a (scene files list transforms in the order applied).
#include <array>
#include <cmath>
#include <numbers>
#include <optional>

#include "glint/math/bounds.h"
#include "glint/math/vector.h"

namespace glint {

struct Matrix34 {
    std::array<std::array<Float, 4>, 3> m{{{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}}};

    Point3 apply(Point3 p) const {
        return {m[0][0] * p.x + m[0][1] * p.y + m[0][2] * p.z + m[0][3],
                m[1][0] * p.x + m[1][1] * p.y + m[1][2] * p.z + m[1][3],
                m[2][0] * p.x + m[2][1] * p.y + m[2][2] * p.z + m[2][3]};
    }
    Vector3 apply(Vector3 v) const {
        return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z,
                m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
                m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
    }
    /// By the transpose of the 3x3 part (used with the inverse: normals).
    Vector3 apply_transposed(Vector3 v) const {
        return {m[0][0] * v.x + m[1][0] * v.y + m[2][0] * v.z,
                m[0][1] * v.x + m[1][1] * v.y + m[2][1] * v.z,
                m[0][2] * v.x + m[1][2] * v.y + m[2][2] * v.z};
    }
    Matrix34 operator*(const Matrix34& b) const {
        Matrix34 r;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 4; ++j) {
                double s = j == 3 ? m[i][3] : 0;
                for (int k = 0; k < 3; ++k) s += double(m[i][k]) * b.m[k][j];
                r.m[i][j] = static_cast<Float>(s);
            }
        return r;
    }
    double determinant() const {
        return double(m[0][0]) * (double(m[1][1]) * m[2][2] - double(m[1][2]) * m[2][1]) -
               double(m[0][1]) * (double(m[1][0]) * m[2][2] - double(m[1][2]) * m[2][0]) +
               double(m[0][2]) * (double(m[1][0]) * m[2][1] - double(m[1][1]) * m[2][0]);
    }
    /// The inverse, in double; nullopt when the 3x3 part is singular (or not finite).
    std::optional<Matrix34> inverse() const;
    bool operator==(const Matrix34&) const = default;
};

inline std::optional<Matrix34> Matrix34::inverse() const {
    const double det = determinant();
    if (!(std::abs(det) > 1e-30) || !std::isfinite(det)) return std::nullopt;
    const auto a = [this](int i, int j) { return double(m[i][j]); };
    double inv[3][3];
    inv[0][0] = (a(1, 1) * a(2, 2) - a(1, 2) * a(2, 1)) / det;
    inv[0][1] = (a(0, 2) * a(2, 1) - a(0, 1) * a(2, 2)) / det;
    inv[0][2] = (a(0, 1) * a(1, 2) - a(0, 2) * a(1, 1)) / det;
    inv[1][0] = (a(1, 2) * a(2, 0) - a(1, 0) * a(2, 2)) / det;
    inv[1][1] = (a(0, 0) * a(2, 2) - a(0, 2) * a(2, 0)) / det;
    inv[1][2] = (a(0, 2) * a(1, 0) - a(0, 0) * a(1, 2)) / det;
    inv[2][0] = (a(1, 0) * a(2, 1) - a(1, 1) * a(2, 0)) / det;
    inv[2][1] = (a(0, 1) * a(2, 0) - a(0, 0) * a(2, 1)) / det;
    inv[2][2] = (a(0, 0) * a(1, 1) - a(0, 1) * a(1, 0)) / det;
    Matrix34 r;
    for (int i = 0; i < 3; ++i) {
        double t = 0;
        for (int k = 0; k < 3; ++k) {
            r.m[i][k] = static_cast<Float>(inv[i][k]);
            t -= inv[i][k] * a(k, 3);
        }
        r.m[i][3] = static_cast<Float>(t);
    }
    return r;
}

/// A transform and its inverse.
struct Transform {
    Matrix34 to_world;   ///< object -> world
    Matrix34 to_object;  ///< world -> object

    /// nullopt when m is singular.
    static std::optional<Transform> from(const Matrix34& m) {
        const auto inv = m.inverse();
        if (!inv) return std::nullopt;
        return Transform{m, *inv};
    }
    static Transform translate(Vector3 d) {
        Transform t;
        for (int i = 0; i < 3; ++i) {
            t.to_world.m[i][3] = d[i];
            t.to_object.m[i][3] = -d[i];
        }
        return t;
    }
    /// Non-zero scale factors.
    static Transform scale(Vector3 s) {
        Transform t;
        for (int i = 0; i < 3; ++i) {
            t.to_world.m[i][i] = s[i];
            t.to_object.m[i][i] = 1 / s[i];
        }
        return t;
    }
    /// Rotation by `degrees` about `axis` (any length but zero), right-hand rule in a
    /// right-handed frame; in glint's left-handed frame, counter-clockwise seen from the axis'
    /// tip looking back is clockwise. (Same formula as pbrt's Rotate.)
    static Transform rotate(Float degrees, Vector3 axis) {
        const Vector3 a = normalize(axis);
        const double th = double(degrees) * std::numbers::pi / 180;
        const double s = std::sin(th), c = std::cos(th);
        Transform t;
        auto& m = t.to_world.m;
        m[0][0] = Float(a.x * a.x + (1 - a.x * a.x) * c);
        m[0][1] = Float(a.x * a.y * (1 - c) - a.z * s);
        m[0][2] = Float(a.x * a.z * (1 - c) + a.y * s);
        m[1][0] = Float(a.x * a.y * (1 - c) + a.z * s);
        m[1][1] = Float(a.y * a.y + (1 - a.y * a.y) * c);
        m[1][2] = Float(a.y * a.z * (1 - c) - a.x * s);
        m[2][0] = Float(a.x * a.z * (1 - c) - a.y * s);
        m[2][1] = Float(a.y * a.z * (1 - c) + a.x * s);
        m[2][2] = Float(a.z * a.z + (1 - a.z * a.z) * c);
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) t.to_object.m[i][j] = m[j][i];  // orthonormal
        return t;
    }
    /// Places an object at `from`, its +z axis towards `to`, its +y axis as close to `up` as
    /// possible (nullopt when from == to or up is parallel to the view direction).
    static std::optional<Transform> look_at(Point3 eye, Point3 to, Vector3 up) {
        const Vector3 d = to - eye;
        if (!(length(d) > 0)) return std::nullopt;
        const Vector3 z = normalize(d);
        const Vector3 xx = cross(up, z);
        if (!(length(xx) > 1e-6f * length(up))) return std::nullopt;
        const Vector3 x = normalize(xx);
        const Vector3 y = cross(z, x);
        Matrix34 m;
        for (int i = 0; i < 3; ++i) {
            m.m[i][0] = x[i];
            m.m[i][1] = y[i];
            m.m[i][2] = z[i];
            m.m[i][3] = eye[i];
        }
        return from(m);
    }

    Transform operator*(const Transform& b) const {
        return {to_world * b.to_world, b.to_object * to_object};
    }
    Point3 point(Point3 p) const { return to_world.apply(p); }
    Vector3 vector(Vector3 v) const { return to_world.apply(v); }
    /// Normals by the inverse transpose; not normalised.
    Normal3 normal(Normal3 n) const { return Normal3(to_object.apply_transposed(to_vector(n))); }
    bool is_identity() const { return to_world == Matrix34{}; }
    /// Whether the transform flips handedness (a mirror): the cross product of transformed edges
    /// then points against the transformed normal.
    bool flips() const { return to_world.determinant() < 0; }
    Bounds3 bounds(const Bounds3& b) const {
        Bounds3 r;
        for (int c = 0; c < 8; ++c)
            r.extend(point({c & 1 ? b.hi.x : b.lo.x, c & 2 ? b.hi.y : b.lo.y, c & 4 ? b.hi.z : b.lo.z}));
        return r;
    }
};

}  // namespace glint
