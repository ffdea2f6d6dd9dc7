#pragma once
// Axis-aligned bounding boxes.
#include <algorithm>
#include <limits>

#include "glint/math/vector.h"

namespace glint {

struct Bounds3 {
    Point3 lo{std::numeric_limits<Float>::infinity(), std::numeric_limits<Float>::infinity(),
              std::numeric_limits<Float>::infinity()};
    Point3 hi{-std::numeric_limits<Float>::infinity(), -std::numeric_limits<Float>::infinity(),
              -std::numeric_limits<Float>::infinity()};

    bool empty() const { return lo.x > hi.x || lo.y > hi.y || lo.z > hi.z; }
    void extend(Point3 p) {
        lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
        hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
    }

    /// Whether the ray from `origin` meets the box within [0, t_max]: the slab test, with the reciprocal
    /// direction given (±infinity for zero components). A NaN from 0 * infinity (an origin on a
    /// slab plane of an axis the ray runs parallel to) fails its comparison and so leaves that
    /// slab unconstrained. The far distance is widened by 3 ulps so that round-off cannot reject
    /// a ray that grazes the box (pbrt's robust slab test).
    bool hit(Point3 origin, Vector3 inv_dir, Float t_max) const {
        Float t0 = 0, t1 = t_max;
        for (int a = 0; a < 3; ++a) {
            Float t_near = (lo[a] - origin[a]) * inv_dir[a];
            Float t_far = (hi[a] - origin[a]) * inv_dir[a];
            if (t_near > t_far) std::swap(t_near, t_far);
            t_far *= 1 + 3 * std::numeric_limits<Float>::epsilon();
            if (t_near > t0) t0 = t_near;
            if (t_far < t1) t1 = t_far;
            if (t0 > t1) return false;
        }
        return true;
    }
};

inline Vector3 reciprocal(Vector3 d) { return {1 / d.x, 1 / d.y, 1 / d.z}; }

}  // namespace glint
