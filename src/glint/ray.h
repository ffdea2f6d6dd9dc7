#pragma once
#include <limits>

#include "glint/math/vector.h"

namespace glint {

/// A ray O + tD. The direction is unit length for every ray glint traces (camera, shadow and
/// reflection rays are normalized at creation), which the shape tests rely on (a = D.D = 1).
struct Ray {
    Point3 origin;
    Vector3 direction;
    Float t_max = std::numeric_limits<Float>::infinity();

    constexpr Point3 at(Float t) const { return origin + direction * t; }
};

/// Hits closer than this are ignored, the "small epsilon" of every intersection test. Secondary
/// rays are also spawned off the surface (spawn_ray), so this only has to catch round-off.
inline constexpr Float kRayTMin = 1e-5f;

/// A ray leaving surface point p with unit direction d, its origin pushed off the surface along
/// the geometric normal n (to the side d points to) by an amount that grows with |p|, so that
/// the new ray cannot re-hit the surface it leaves through round-off. t_max, if given, is a
/// distance along d measured from p (for shadow rays towards a point light).
inline Ray spawn_ray(Point3 p, Normal3 n, Vector3 d,
                     Float t_max = std::numeric_limits<Float>::infinity()) {
    Float offset = 1e-4f * std::max(Float(1), max_abs_component(p));
    Vector3 push = to_vector(n) * (dot(n, d) >= 0 ? offset : -offset);
    return Ray{p + push, d, t_max};
}

}  // namespace glint
