#include "glint/shapes/plane.h"

#include <cmath>

#include "glint/math/frame.h"
#include "glint/math/snap.h"

namespace glint {

Point2 Plane::uv_at(Point3 p) const {
    Vector3 t, b;
    orthonormal_basis(to_vector(normal), t, b);
    const Vector3 w = p - point;
    return {dot(w, t), dot(w, b)};
}

}  // namespace glint
