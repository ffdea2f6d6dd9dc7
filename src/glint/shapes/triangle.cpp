#include "glint/shapes/triangle.h"

#include <immintrin.h>

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
    // The three divisions as one vector division: IEEE division is correctly rounded in every
    // lane, so each quotient is the scalar one to the bit, at a third of the latency.
    alignas(16) float s[4];
    _mm_store_ps(s, _mm_div_ps(_mm_setr_ps(d[kx], d[ky], 1, 1), _mm_set1_ps(d[kz])));
    sx = s[0];
    sy = s[1];
    sz = s[2];
}

}  // namespace glint
