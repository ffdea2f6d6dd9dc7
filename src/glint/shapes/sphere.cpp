#include "glint/shapes/sphere.h"

#include <cmath>
#include <utility>

namespace glint {

std::optional<Float> Sphere::intersect(const Ray& ray) const {
    const Vector3 f = ray.origin - center;
    const Float b = dot(f, ray.direction);
    const Vector3 perp = f - ray.direction * b;  // f minus its projection on D
    const Float disc = radius * radius - dot(perp, perp);
    if (disc < 0) return std::nullopt;
    const Float dist = length(f);
    const Float c = (dist - radius) * (dist + radius);
    const Float root = std::sqrt(disc);
    const Float q = b > 0 ? -b - root : -b + root;
    Float t0 = q, t1 = q;
    if (q != 0) {
        t0 = c / q;
    } else {
        // b == 0 and disc == 0: the ray starts exactly on the tangent line's contact point.
        t0 = 0;
    }
    if (t0 > t1) std::swap(t0, t1);
    if (t0 >= kRayTMin && t0 < ray.t_max) return t0;
    if (t1 >= kRayTMin && t1 < ray.t_max) return t1;
    return std::nullopt;
}

}  // namespace glint
