#pragma once
#include <algorithm>
#include <cmath>
#include <limits>

#include "glint/math/transform.h"
#include "glint/math/vector.h"

namespace glint {

/// A ray O + tD. The direction is unit length for every ray glint traces (camera, shadow and
/// reflection rays are normalized at creation), which the shape tests rely on (a = D.D = 1).
struct Ray {
    Point3 origin;
    Vector3 direction;
    Float t_max = std::numeric_limits<Float>::infinity();
    /// When the ray is traced, in [0, 1] across the camera's shutter (math/motion.h): moving
    /// shapes are met where they are at that time. Rays spawned from a hit keep their path's.
    Float time = 0;

    constexpr Point3 at(Float t) const { return origin + direction * t; }
};

/// Where the line from_p + t dir (from_p relative to p) meets the plane through p with normal n,
/// relative to p; false where the line runs parallel to the plane. (The pixel footprint's model
/// and a path's offset rays both meet a hit's tangent plane this way.)
inline bool meet_plane(Vector3 from_p, Vector3 dir, Normal3 n, Vector3& out) {
    const Float denom = dot(dir, n);
    if (!(std::abs(denom) > 1e-8f * length(dir))) return false;
    const Float t = -dot(from_p, n) / denom;
    out = from_p + dir * t;
    return true;
}

/// The rays beside a path's own that pass one pixel to the right and one pixel up (scaled as the
/// pixel footprint is, cameras/camera.h), carried through perfectly specular reflections and
/// refractions (Igehy's ray differentials, which pbrt-v4 carries the same way), so that a texture
/// or the environment seen in a mirror or through glass is read over what the pixel covers there.
/// Each offset ray is kept as a line, a point on it and a direction of any length, not as
/// derivatives: at a specular surface it is itself reflected or refracted where it meets the
/// tangent plane, about the shading normal there (integrators/differentials.h).
struct RayDifferential {
    Point3 ox, oy;   ///< a point on each offset ray
    Vector3 dx, dy;  ///< their directions (any length)

    /// Where the offset rays meet the plane through p with normal n, relative to p; false (and
    /// nothing written) where one runs parallel to the plane or the point is not finite.
    bool at(Point3 p, Normal3 n, Vector3& dpdx, Vector3& dpdy) const {
        const auto meet = [&](Point3 o, Vector3 d, Vector3& out) {
            return meet_plane(o - p, d, n, out) && is_finite(out);
        };
        Vector3 x, y;
        if (!meet(ox, dx, x) || !meet(oy, dy, y)) return false;
        dpdx = x;
        dpdy = y;
        return true;
    }
    /// How far the offset rays' directions turn from unit direction d: the larger chord between
    /// the unit directions, about the angle in radians for the small angles of a pixel.
    Float spread(Vector3 d) const {
        const Float lx = length(dx), ly = length(dy);
        if (!(lx > 0) || !(ly > 0)) return 0;
        const Float s = std::max(length(dx / lx - d), length(dy / ly - d));
        return std::isfinite(s) ? s : 0;
    }
};

/// A world ray in the object space of `t`, its direction not renormalised, so that t means the
/// same point in both spaces.
inline Ray object_ray(const Transform& t, const Ray& r) {
    return {t.to_object.apply(r.origin), t.to_object.apply(r.direction), r.t_max, r.time};
}

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

/// The rest of `ray` after it crossed a surface at p (normal n) that it passes through (a medium
/// interface, a transparent shadow blocker): the origin is pushed off the surface as spawn_ray's
/// is, and a segment with an end is aimed at that end again, as pbrt-v4's SpawnRayTo is at each
/// crossing. (Keeping the remaining length t_max - t moved the end forward by the push, which
/// grows with |p|; keeping the direction instead shifts the segment sideways by the push. Either
/// way a segment that ended just short of a light, pushed off it by its own smaller amount,
/// could end inside the light, which then blocked its own shadow ray.)
inline Ray continue_ray(const Ray& ray, Point3 p, Normal3 n) {
    Ray next = spawn_ray(p, n, ray.direction, ray.t_max);
    next.time = ray.time;
    if (std::isinf(ray.t_max)) return next;
    const Vector3 to_end = ray.at(ray.t_max) - next.origin;
    const Float dist = length(to_end);
    if (!(dist > 0) || dot(to_end, ray.direction) <= 0) {
        next.t_max = 0;  // the crossing was at the end: nothing is left
        return next;
    }
    next.direction = to_end / dist;
    next.t_max = dist;
    return next;
}

/// A shadow ray from surface point p (normal n) to point q on a light's surface (normal n_q):
/// both ends are pushed off their surfaces, towards each other, by the same amount as
/// spawn_ray's, and the ray ends just before q. (Ending at a fraction of the distance from p
/// instead is not enough: the push at p alone can bring the origin closer to q than the margin,
/// and the light then blocks its own shadow ray.)
inline Ray spawn_ray_to(Point3 p, Normal3 n, Point3 q, Normal3 n_q) {
    const Vector3 towards = q - p;
    const Float offset_p = 1e-4f * std::max(Float(1), max_abs_component(p));
    const Float offset_q = 1e-4f * std::max(Float(1), max_abs_component(q));
    const Point3 o = p + to_vector(n) * (dot(n, towards) >= 0 ? offset_p : -offset_p);
    const Point3 end = q + to_vector(n_q) * (dot(n_q, towards) <= 0 ? offset_q : -offset_q);
    const Vector3 d = end - o;
    const Float dist = length(d);
    return Ray{o, d / dist, dist * (1 - 1e-5f)};
}

}  // namespace glint
