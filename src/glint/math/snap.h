#pragma once
#include <cmath>

#include "glint/math/vector.h"

namespace glint {

/// p moved onto the plane through `origin` with unit normal n. O + tD lands within round-off of
/// a flat shape, on either side; a 3D checkerboard evaluated on the plane z = k would then
/// flicker between floor(k) and floor(k) - 1 from pixel to pixel. For an axis-aligned normal the
/// coordinate is set to the plane's exactly; otherwise p is projected (the checker's cell
/// boundaries then cross the plane, and round-off cannot flip a whole cell).
[[gnu::always_inline]] inline Point3 snap_to_plane(Point3 p, Point3 origin, Normal3 n) {
    for (int axis = 0; axis < 3; ++axis) {
        if (std::abs(n[axis]) == 1) {
            p[axis] = origin[axis];
            return p;
        }
    }
    return p + to_vector(n) * dot(n, origin - p);
}

}  // namespace glint
