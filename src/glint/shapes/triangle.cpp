#include "glint/shapes/triangle.h"

#include <cmath>
#include <utility>

namespace glint {

std::optional<Float> Triangle::intersect(const Ray& ray) const {
    const Vector3 d = ray.direction;
    // The dimension where the direction is largest becomes z; x and y follow cyclically and
    // swap when d.z < 0 to keep the triangle's winding.
    int kz = 0;
    if (std::abs(d.y) > std::abs(d[kz])) kz = 1;
    if (std::abs(d.z) > std::abs(d[kz])) kz = 2;
    int kx = kz + 1 == 3 ? 0 : kz + 1;
    int ky = kx + 1 == 3 ? 0 : kx + 1;
    if (d[kz] < 0) std::swap(kx, ky);
    const Float sx = d[kx] / d[kz], sy = d[ky] / d[kz], sz = 1 / d[kz];

    const Vector3 a = p0 - ray.origin, b = p1 - ray.origin, c = p2 - ray.origin;
    const Float ax = a[kx] - sx * a[kz], ay = a[ky] - sy * a[kz];
    const Float bx = b[kx] - sx * b[kz], by = b[ky] - sy * b[kz];
    const Float cx = c[kx] - sx * c[kz], cy = c[ky] - sy * c[kz];

    Float u = cx * by - cy * bx;
    Float v = ax * cy - ay * cx;
    Float w = bx * ay - by * ax;
    if (u == 0 || v == 0 || w == 0) {  // on an edge in float: decide in double
        u = static_cast<Float>(static_cast<double>(cx) * by - static_cast<double>(cy) * bx);
        v = static_cast<Float>(static_cast<double>(ax) * cy - static_cast<double>(ay) * cx);
        w = static_cast<Float>(static_cast<double>(bx) * ay - static_cast<double>(by) * ax);
    }
    if ((u < 0 || v < 0 || w < 0) && (u > 0 || v > 0 || w > 0)) return std::nullopt;
    const Float det = u + v + w;
    if (det == 0) return std::nullopt;

    const Float az = sz * a[kz], bz = sz * b[kz], cz = sz * c[kz];
    const Float t_scaled = u * az + v * bz + w * cz;  // t * det
    const Float t = t_scaled / det;
    if (!(t >= kRayTMin && t < ray.t_max)) return std::nullopt;
    return t;
}

}  // namespace glint
