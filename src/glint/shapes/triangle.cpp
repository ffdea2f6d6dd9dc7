#include "glint/shapes/triangle.h"

#include <immintrin.h>

#include <cmath>

namespace glint {

WatertightRay::WatertightRay(const Ray& ray) : origin(ray.origin), t_max(ray.t_max) {
    const Vector3 d = ray.direction;
    // (An array, not Vector3::operator[], whose ?: chain would bring branches back.)
    const float c[3] = {d.x, d.y, d.z};
    watertight_axes(std::abs(c[0]), std::abs(c[1]), std::abs(c[2]), (c[0] < 0) | (c[1] < 0) << 1 | (c[2] < 0) << 2,
                    kx, ky, kz);
    // The three divisions as one vector division: IEEE division is correctly rounded in every
    // lane, so each quotient is the scalar one to the bit, at a third of the latency.
    alignas(16) float s[4];
    _mm_store_ps(s, _mm_div_ps(_mm_setr_ps(c[kx], c[ky], 1, 1), _mm_set1_ps(c[kz])));
    sx = s[0];
    sy = s[1];
    sz = s[2];
}

}  // namespace glint
