#include "glint/shapes/triangle.h"

#include <cmath>
#include <utility>

namespace glint {

WatertightRay::WatertightRay(const Ray& ray) : origin(ray.origin), t_max(ray.t_max) {
    const Vector3 d = ray.direction;
    // The dimension where the direction is largest becomes z; x and y follow cyclically and
    // swap when d.z < 0 to keep the triangle's winding.
    kz = 0;
    if (std::abs(d.y) > std::abs(d[kz])) kz = 1;
    if (std::abs(d.z) > std::abs(d[kz])) kz = 2;
    kx = kz + 1 == 3 ? 0 : kz + 1;
    ky = kx + 1 == 3 ? 0 : kx + 1;
    if (d[kz] < 0) std::swap(kx, ky);
    sx = d[kx] / d[kz];
    sy = d[ky] / d[kz];
    sz = 1 / d[kz];
}

}  // namespace glint
