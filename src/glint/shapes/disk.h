#pragma once
#include <numbers>
#include <optional>

#include "glint/interaction.h"
#include "glint/math/frame.h"
#include "glint/ray.h"
#include "glint/shapes/plane.h"
#include "glint/samplers/warp.h"
#include "glint/shapes/area_sample.h"

namespace glint {

/// A flat disk of `radius` around `center`, facing along the unit `normal`.
struct Disk {
    Point3 center;
    Normal3 normal;
    Float radius;
    MaterialId material = 0;

    std::optional<Float> intersect(const Ray& ray) const {
        const auto t = intersect_plane(ray, center, normal);
        if (!t) return std::nullopt;
        const Vector3 w = ray.at(*t) - center;
        if (dot(w, w) > radius * radius) return std::nullopt;
        return t;
    }

    /// The disk's bounding square mapped to [0,1]^2 along the frame orthonormal_basis(normal)
    /// gives: u = 1/2 + (w.t) / 2r, v = 1/2 + (w.b) / 2r, w = p - center.
    Point2 uv_at(Point3 p) const {
        Vector3 t, b;
        orthonormal_basis(to_vector(normal), t, b);
        const Vector3 w = p - center;
        return {Float(0.5) + dot(w, t) / (2 * radius), Float(0.5) + dot(w, b) / (2 * radius)};
    }

    Float area() const { return std::numbers::pi_v<Float> * radius * radius; }
    /// Concentric mapping onto the disk's plane.
    AreaSample sample_area(Sample2 u) const {
        Vector3 t, b;
        orthonormal_basis(to_vector(normal), t, b);
        const Point2 d = sample_uniform_disk_concentric(u);
        return {center + (t * d.x + b * d.y) * radius, normal};
    }
};

}  // namespace glint
