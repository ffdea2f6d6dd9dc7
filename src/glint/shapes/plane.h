#pragma once
#include <cmath>
#include <optional>

#include "glint/interaction.h"
#include "glint/math/snap.h"
#include "glint/ray.h"

namespace glint {

/// An infinite plane through `point` with unit normal `normal` (which also fixes its
/// orientation: the side the normal points to is the front).
struct Plane {
    Point3 point;
    Normal3 normal;
    MaterialId material = 0;

    /// t = (P0 - O).N / (D.N); rays parallel to the plane (|D.N| tiny) miss.
    std::optional<Float> intersect(const Ray& ray) const {
        const Float denom = dot(normal, ray.direction);
        if (std::abs(denom) < Float(1e-9)) return std::nullopt;
        const Float t = dot(normal, point - ray.origin) / denom;
        if (t >= kRayTMin && t < ray.t_max) return t;
        return std::nullopt;
    }

    /// The hit point moved exactly onto the plane (snap_to_plane).
    Point3 project(Point3 p) const { return snap_to_plane(p, point, normal); }

    /// Coordinates along the frame orthonormal_basis(normal) gives, from `point`, in scene units
    /// (for the normal +y: u = x - point.x, v = point.z - z). Unbounded: textures repeat.
    Point2 uv_at(Point3 p) const;
};

}  // namespace glint
