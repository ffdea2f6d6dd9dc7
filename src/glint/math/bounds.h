#pragma once
// Axis-aligned bounding boxes.
#include <algorithm>
#include <cmath>
#include <limits>

#include "glint/math/vector.h"

namespace glint {

struct Bounds3 {
    Point3 lo{std::numeric_limits<Float>::infinity(), std::numeric_limits<Float>::infinity(),
              std::numeric_limits<Float>::infinity()};
    Point3 hi{-std::numeric_limits<Float>::infinity(), -std::numeric_limits<Float>::infinity(),
              -std::numeric_limits<Float>::infinity()};

    bool empty() const { return lo.x > hi.x || lo.y > hi.y || lo.z > hi.z; }
    /// Finite and not empty: what a BVH builds over (it skips every other box).
    bool finite() const {
        for (int a = 0; a < 3; ++a)
            if (!std::isfinite(lo[a]) || !std::isfinite(hi[a]) || lo[a] > hi[a]) return false;
        return true;
    }
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

/// The box grown on every side by 2e-5 of its largest coordinate magnitude (clamped to the float
/// range): what the trees use for a shape whose own test accepts a hit from a rounded hit point
/// (a quad's edge coordinates, a disk's radius, a sphere's discriminant), which can lie a rounding
/// error outside the shape's exact box. The BVH's slab test is exact about the box, so without
/// the margin it could cull a hit the shape's test accepts (a ray from the ceiling grazing the
/// Cornell box light's edge met the wall behind through the tree). 2e-5 is 170 to 340 ulps of the
/// largest coordinate, several times the tests' error. The scene's extent keeps the exact boxes.
inline Bounds3 padded_for_rounding(Bounds3 b) {
    Float size = 0;
    for (int a = 0; a < 3; ++a) size = std::max({size, std::abs(b.lo[a]), std::abs(b.hi[a])});
    const Float m = size * Float(2e-5);
    for (int a = 0; a < 3; ++a) {  // a NaN or empty box stays non-finite (the trees skip it)
        b.lo[a] = std::max(b.lo[a] - m, std::numeric_limits<Float>::lowest());
        b.hi[a] = std::min(b.hi[a] + m, std::numeric_limits<Float>::max());
    }
    return b;
}

/// The box of the ball of radius r at c: a sphere's, or a disk's (a disk lies in its ball).
inline Bounds3 ball_bounds(Point3 c, Float r) {
    Bounds3 b;
    b.extend(c - Vector3{r, r, r});
    b.extend(c + Vector3{r, r, r});
    return b;
}

}  // namespace glint
