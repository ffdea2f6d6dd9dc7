#pragma once
#include <cmath>
#include <optional>

#include "glint/interaction.h"
#include "glint/math/snap.h"
#include "glint/ray.h"

namespace glint {

/// The t in [kRayTMin, ray.t_max) where the ray meets the plane through `point` with unit normal
/// n: (P0 - O).N / (D.N); rays parallel to the plane (|D.N| tiny) miss. Shared by every flat
/// shape whose plane is given by a point and a unit normal.
inline std::optional<Float> intersect_plane(const Ray& ray, Point3 point, Normal3 n) {
    const Float denom = dot(n, ray.direction);
    if (std::abs(denom) < Float(1e-9)) return std::nullopt;
    const Float num = dot(n, point - ray.origin);
    // t = num / denom is positive only when the two have the same sign: skip the division for the
    // rays that move away from the plane (half the sky rays of the article's scenes). t is 0 or
    // negative exactly when this test fails, so no hit changes.
    if ((num > 0) != (denom > 0) || num == 0) return std::nullopt;
    const Float t = num / denom;
    if (t >= kRayTMin && t < ray.t_max) return t;
    return std::nullopt;
}

/// An infinite plane through `point` with unit normal `normal` (which also fixes its
/// orientation: the side the normal points to is the front).
struct Plane {
    Point3 point;
    Normal3 normal;
    MaterialId material = 0;

    /// t = (P0 - O).N / (D.N); rays parallel to the plane (|D.N| tiny) miss.
    std::optional<Float> intersect(const Ray& ray) const { return intersect_plane(ray, point, normal); }

    /// The hit point moved exactly onto the plane (snap_to_plane).
    Point3 project(Point3 p) const { return snap_to_plane(p, point, normal); }

    /// Coordinates along the frame orthonormal_basis(normal) gives, from `point`, in scene units
    /// (for the normal +y: u = x - point.x, v = point.z - z). Unbounded: textures repeat.
    Point2 uv_at(Point3 p) const;
};

}  // namespace glint
