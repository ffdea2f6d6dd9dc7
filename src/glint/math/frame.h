#pragma once
// Orthonormal frames.
#include <cmath>

#include "glint/math/vector.h"

namespace glint {

/// Two unit vectors t, b completing the unit normal n to an orthonormal frame, continuous in n
/// except at n.z = 0 crossings of the sign, and with no division by a small number (Duff et al.,
/// "Building an Orthonormal Basis, Revisited", JCGT 2017).
inline void orthonormal_basis(Vector3 n, Vector3& t, Vector3& b) {
    const Float sign = std::copysign(Float(1), n.z);
    const Float a = -1 / (sign + n.z);
    const Float c = n.x * n.y * a;
    t = {1 + sign * n.x * n.x * a, sign * c, -sign * n.x};
    b = {c, sign + n.y * n.y * a, -n.y};
}

}  // namespace glint
