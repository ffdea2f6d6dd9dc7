#pragma once
#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <utility>

#include "glint/interaction.h"
#include "glint/ray.h"
#include "glint/samplers/stratified.h"
#include "glint/shapes/area_sample.h"

namespace glint {

/// The article's sphere |S - C|^2 = r^2. The normal is (I - C)/r, pointing outward.
struct Sphere {
    Point3 center;
    Float radius;
    MaterialId material = 0;

    /// Nearest t in [kRayTMin, t_max) where the (unit-direction) ray meets the sphere, if any.
    ///
    /// Solves the article's quadratic t^2 + 2bt + c = 0 (a = D.D = 1) in a form that avoids the
    /// two catastrophic cancellations of the textbook formula (Haines et al., "Precision
    /// Improvements for Ray/Sphere Intersection", Ray Tracing Gems ch. 7):
    ///  - the discriminant b^2 - c is computed as r^2 - |f - (f.D)D|^2 (f = O - C), the squared
    ///    distance of the line from the centre, which stays accurate for far-away spheres where
    ///    b^2 and c are both huge and nearly equal;
    ///  - c = |f|^2 - r^2 is computed as (|f| - r)(|f| + r), accurate when the origin is near the
    ///    surface of a huge sphere;
    ///  - the two roots are q and c/q with q = -b - sign(b) sqrt(disc), so neither is the
    ///    difference of two nearly equal numbers.
    /// From inside (c < 0) the roots have opposite signs and the far one is returned.
    std::optional<Float> intersect(const Ray& ray) const {
        const Vector3 f = ray.origin - center;
        const Float b = dot(f, ray.direction);
        const Float r2 = radius * radius;
        // Outside and moving away: both roots are negative. (Near the surface the sign test
        // may go either way; both roots are then below kRayTMin, a miss either way.)
        if (b > 0 && dot(f, f) > r2) return std::nullopt;
        const Vector3 perp = f - ray.direction * b;  // f minus its projection on D
        const Float disc = r2 - dot(perp, perp);
        if (disc < 0) return std::nullopt;
        const Float root = std::sqrt(disc);
        const Float q = b > 0 ? -b - root : -b + root;
        // The near root is at least -b - root; skip the rest when even that is beyond t_max.
        if (-b - root >= ray.t_max) return std::nullopt;
        const Float dist = std::sqrt(dot(f, f));
        const Float c = (dist - radius) * (dist + radius);
        Float t0 = q != 0 ? c / q : 0;  // q == 0 only for a tangent ray starting at the contact
        Float t1 = q;
        if (t0 > t1) std::swap(t0, t1);
        if (t0 >= kRayTMin && t0 < ray.t_max) return t0;
        if (t1 >= kRayTMin && t1 < ray.t_max) return t1;
        return std::nullopt;
    }

    Normal3 normal_at(Point3 p) const { return Normal3((p - center) / radius); }

    /// u = 1/2 + atan2(n.x, -n.z) / 2pi: 1/2 where the sphere faces -z (the default camera),
    /// growing to the right; v = 1 - acos(n.y) / pi: 0 at the bottom pole, 1 at the top. An
    /// equirectangular image wraps the sphere upright, its top row at the north pole.
    Point2 uv_at(Point3 p) const {
        const Vector3 n = (p - center) / radius;
        const Float u = Float(0.5) + std::atan2(n.x, -n.z) / (2 * std::numbers::pi_v<Float>);
        const Float v =
            1 - std::acos(std::clamp(n.y, Float(-1), Float(1))) / std::numbers::pi_v<Float>;
        return {u, v};
    }

    Float area() const { return 4 * std::numbers::pi_v<Float> * radius * radius; }
    /// Uniform by area: z = 1 - 2 u1 is uniform on [-1, 1] (Archimedes), phi = 2 pi u2.
    AreaSample sample_area(Sample2 u) const {
        const Float z = 1 - 2 * u.x;
        const Float r = std::sqrt(std::max(Float(0), 1 - z * z));
        const Float phi = 2 * std::numbers::pi_v<Float> * u.y;
        const Normal3 n{r * std::cos(phi), r * std::sin(phi), z};
        return {center + to_vector(n) * radius, n};
    }
};

}  // namespace glint
