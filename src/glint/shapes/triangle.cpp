#include "glint/shapes/triangle.h"

#include <immintrin.h>

#include <algorithm>
#include <cmath>

namespace glint {

WatertightRay::WatertightRay(const Ray& ray) : origin(ray.origin), t_max(ray.t_max) {
    const Vector3 d = ray.direction;
    // The dimension where the direction is largest becomes z (the first of equals); x and y
    // follow cyclically and swap when d.z < 0 to keep the triangle's winding. Selects, not
    // branches: a diffuse bounce's direction is random, and the branches here mispredicted
    // their way to 6 % of a Cornell box render.
    // (An array, not Vector3::operator[], whose ?: chain would bring the branches back.)
    const float c[3] = {d.x, d.y, d.z};
    const float ax = std::abs(c[0]), ay = std::abs(c[1]), az = std::abs(c[2]);
    const int y_wins = ay > ax, z_wins = az > std::max(ax, ay);  // std::max(ax, ay): ay > ax ? ay : ax
    kz = y_wins + z_wins * (2 - y_wins);
    const int next = kz == 2 ? 0 : kz + 1, after = 3 - kz - next;
    const int swap = (next ^ after) & -static_cast<int>(c[kz] < 0);  // next ^ after, or 0
    kx = next ^ swap;
    ky = after ^ swap;
    // The three divisions as one vector division: IEEE division is correctly rounded in every
    // lane, so each quotient is the scalar one to the bit, at a third of the latency.
    alignas(16) float s[4];
    _mm_store_ps(s, _mm_div_ps(_mm_setr_ps(c[kx], c[ky], 1, 1), _mm_set1_ps(c[kz])));
    sx = s[0];
    sy = s[1];
    sz = s[2];
}

}  // namespace glint
