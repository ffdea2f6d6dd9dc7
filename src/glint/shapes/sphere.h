#pragma once
#include <optional>

#include "glint/interaction.h"
#include "glint/ray.h"

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
    std::optional<Float> intersect(const Ray& ray) const;

    Normal3 normal_at(Point3 p) const { return Normal3((p - center) / radius); }
};

}  // namespace glint
