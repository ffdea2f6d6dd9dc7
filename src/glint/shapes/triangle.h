#pragma once
#include <optional>

#include "glint/interaction.h"
#include "glint/ray.h"
#include "glint/samplers/warp.h"
#include "glint/shapes/area_sample.h"

namespace glint {

/// A triangle p0 p1 p2, facing along (p1 - p0) x (p2 - p0).
struct Triangle {
    Point3 p0, p1, p2;
    MaterialId material = 0;

    /// Watertight ray-triangle intersection (Woop, Benthin and Wald, JCGT 2013): the triangle is
    /// moved into a frame where the ray runs along +z from the origin, and the hit is decided by
    /// the signs of three 2D edge functions, recomputed in double when one is exactly zero. Rays
    /// through a shared edge or vertex hit at least one of the triangles that share it.
    std::optional<Float> intersect(const Ray& ray) const;

    /// The barycentric coordinates (b1, b2) of p: p = p0 + b1 (p1 - p0) + b2 (p2 - p0). (Meshes
    /// with per-vertex UVs come with the mesh importers.)
    Point2 uv_at(Point3 p) const {
        const Vector3 e1 = p1 - p0, e2 = p2 - p0, w = p - p0;
        const Float d11 = dot(e1, e1), d12 = dot(e1, e2), d22 = dot(e2, e2);
        const Float w1 = dot(w, e1), w2 = dot(w, e2);
        const Float inv = 1 / (d11 * d22 - d12 * d12);
        return {(d22 * w1 - d12 * w2) * inv, (d11 * w2 - d12 * w1) * inv};
    }

    Normal3 normal() const { return Normal3(normalize(cross(p1 - p0, p2 - p0))); }
    Float area() const { return Float(0.5) * length(cross(p1 - p0, p2 - p0)); }
    AreaSample sample_area(Sample2 u) const {
        const Point2 b = sample_uniform_triangle(u);
        const Vector3 e1 = p1 - p0, e2 = p2 - p0;
        // p = b0 p0 + b1 p1 + b2 p2 = p0 + b1 e1 + b2 e2
        return {p0 + e1 * b.y + e2 * (1 - b.x - b.y), normal()};
    }
};

}  // namespace glint
