#include "glint/shapes/plane.h"

#include <cmath>

namespace glint {

Point3 Plane::project(Point3 p) const {
    // For an axis-aligned normal this sets that coordinate to the plane's exactly: p.y + (k - p.y)
    // is exact when p.y is within a factor of two of k (Sterbenz).
    Point3 q = p;
    for (int axis = 0; axis < 3; ++axis) {
        if (std::abs(normal[axis]) == 1) {
            q[axis] = point[axis];
            return q;
        }
    }
    return p + to_vector(normal) * dot(normal, point - p);
}

}  // namespace glint
