#pragma once
#include <cmath>
#include <optional>

#include "glint/interaction.h"
#include "glint/math/bounds.h"
#include "glint/ray.h"
#include "glint/samplers/stratified.h"
#include "glint/shapes/area_sample.h"

namespace glint {

/// A parallelogram: corner + a edge1 + b edge2 for a, b in [0, 1]. Its front faces along
/// edge1 x edge2. Build it with make(), which precomputes what intersect() reads.
struct Quad {
    Point3 corner;
    Vector3 edge1, edge2;
    Vector3 n_raw;     ///< edge1 x edge2
    Float inv_len2;    ///< 1 / |edge1 x edge2|^2
    MaterialId material = 0;

    /// Requires non-parallel, non-zero edges (the scene parser checks).
    static Quad make(Point3 corner, Vector3 edge1, Vector3 edge2, MaterialId material = 0) {
        const Vector3 n = cross(edge1, edge2);
        return {corner, edge1, edge2, n, 1 / dot(n, n), material};
    }

    /// The plane's t, then the hit point's coordinates (a, b) along the edges:
    /// a = ((w x edge2) . n) / |n|^2, b = ((edge1 x w) . n) / |n|^2 with w = p - corner.
    std::optional<Float> intersect(const Ray& ray) const {
        const Float denom = dot(n_raw, ray.direction);
        if (std::abs(denom) < Float(1e-12) * std::sqrt(dot(n_raw, n_raw))) return std::nullopt;
        const Float t = dot(n_raw, corner - ray.origin) / denom;
        if (!(t >= kRayTMin && t < ray.t_max)) return std::nullopt;
        const Vector3 w = ray.at(t) - corner;
        const Float a = dot(cross(w, edge2), n_raw) * inv_len2;
        const Float b = dot(cross(edge1, w), n_raw) * inv_len2;
        if (a < 0 || a > 1 || b < 0 || b > 1) return std::nullopt;
        return t;
    }

    /// (a, b): the point's coordinates along edge1 and edge2, each in [0, 1].
    Point2 uv_at(Point3 p) const {
        const Vector3 w = p - corner;
        return {dot(cross(w, edge2), n_raw) * inv_len2, dot(cross(edge1, w), n_raw) * inv_len2};
    }

    /// The box of the four corners (a tree pads it: padded_for_rounding).
    Bounds3 bounds() const {
        Bounds3 b;
        for (const Point3 p : {corner, corner + edge1, corner + edge2, corner + edge1 + edge2}) b.extend(p);
        return b;
    }

    Normal3 normal() const { return Normal3(n_raw * std::sqrt(inv_len2)); }
    Float area() const { return 1 / std::sqrt(inv_len2); }
    AreaSample sample_area(Sample2 u) const {
        return {corner + edge1 * u.x + edge2 * u.y, normal()};
    }
};

}  // namespace glint
