#pragma once
// The watertight test of one stored triangle (shapes/triangle.h) with SSE: the three vertices
// moved to the ray's frame as three vectors, the edge functions as one. Every lane is the scalar
// code's operation on the same operands, in the same order (no fused multiply-adds: the baseline
// ISA has none, and intrinsics are never contracted), so the hit is intersect_triangle's to the
// bit (`Triangle.TheSseTestGivesTheScalarTestsBits` in flat_shapes_test.cpp checks that on random
// and on edge-on rays). Where an edge function is exactly zero, the scalar test decides, as it
// does (in double).
//
// For the baseline build only: not to be included by the per-ISA kernels (accel/*_kernels.inl),
// whose copies of these inline functions would be compiled for another ISA under the same name.
#include <emmintrin.h>
#include <smmintrin.h>
#include <tmmintrin.h>

#include <cmath>
#include <cstdint>
#include <optional>

#include "glint/shapes/triangle.h"

namespace glint {

/// WatertightRay's set-up as SSE vectors: the ray's origin, its axis permutation as a byte
/// shuffle, its shear, computed from the ray with the same choice of axes and the same
/// divisions (so the same bits), without WatertightRay's round trip through memory.
/// pshufb masks for (kx, ky, kz, 3), indexed by 2 kz + (d[kz] < 0), as watertight_axes chooses
/// them: kx and ky are kz's next two axes, swapped when d[kz] is negative. Byte j of lane i is
/// 4 k_i + j. (Test: Triangle.SseOrdersAreTheScalarAxes.)
alignas(16) inline constexpr std::uint32_t kWatertightOrders[6][4] = {
    {0x07060504, 0x0b0a0908, 0x03020100, 0x0f0e0d0c}, {0x0b0a0908, 0x07060504, 0x03020100, 0x0f0e0d0c},
    {0x0b0a0908, 0x03020100, 0x07060504, 0x0f0e0d0c}, {0x03020100, 0x0b0a0908, 0x07060504, 0x0f0e0d0c},
    {0x03020100, 0x07060504, 0x0b0a0908, 0x0f0e0d0c}, {0x07060504, 0x03020100, 0x0b0a0908, 0x0f0e0d0c},
};

struct WatertightRaySse {
    __m128 origin;  ///< (ox, oy, oz, *): the fourth lane is never read
    __m128i order;  ///< lane i of a permuted vector is lane k[i] of the original: kx, ky, kz, 3
    __m128 sx, sy, sz;
    const Ray* ray;  ///< for the edge-on case (the scalar test), which builds its WatertightRay from it
    WatertightRaySse() = default;  ///< unusable until assigned (for scenes with no lone triangles)
    /// `r` must outlive this.
    explicit WatertightRaySse(const Ray& r) : ray(&r) {
        const __m128 d = _mm_setr_ps(r.direction.x, r.direction.y, r.direction.z, 0);
        // watertight_axes' choice (kz the largest |d|, kx and ky the next two, swapped where
        // d[kz] < 0) as one of six byte orders, read from a table rather than built lane by lane.
        const int kz = watertight_kz(std::abs(r.direction.x), std::abs(r.direction.y), std::abs(r.direction.z));
        const int flip = (_mm_movemask_ps(_mm_cmplt_ps(d, _mm_setzero_ps())) >> kz) & 1;
        order = _mm_load_si128(reinterpret_cast<const __m128i*>(kWatertightOrders[2 * kz + flip]));
        origin = _mm_loadu_ps(&r.origin.x);
        // (d[kx], d[ky], 1, 1) / d[kz]: the three divisions as one, each correctly rounded.
        const __m128 permuted = _mm_castsi128_ps(_mm_shuffle_epi8(_mm_castps_si128(d), order));
        const __m128 q = _mm_div_ps(_mm_blend_ps(permuted, _mm_set1_ps(1), 0xc),
                                    _mm_shuffle_ps(permuted, permuted, _MM_SHUFFLE(2, 2, 2, 2)));
        sx = _mm_shuffle_ps(q, q, _MM_SHUFFLE(0, 0, 0, 0));
        sy = _mm_shuffle_ps(q, q, _MM_SHUFFLE(1, 1, 1, 1));
        sz = _mm_shuffle_ps(q, q, _MM_SHUFFLE(2, 2, 2, 2));
    }
};

static_assert(sizeof(Ray) >= 16, "WatertightRaySse reads 16 bytes at the origin");
static_assert(sizeof(Triangle) >= 40, "intersect_triangle_sse reads 16 bytes at p2");

/// intersect_triangle(t, r) with r.t_max = t_max, the same bits.
inline std::optional<TriangleHit> intersect_triangle_sse(const Triangle& t, const WatertightRaySse& r, Float t_max) {
    // Each vertex less the origin (the fourth lane is the next field's, never read), permuted.
    const auto vertex = [&](const Point3& p) {
        const __m128 d = _mm_sub_ps(_mm_loadu_ps(&p.x), r.origin);
        return _mm_castsi128_ps(_mm_shuffle_epi8(_mm_castps_si128(d), r.order));
    };
    const __m128 a = vertex(t.p0), b = vertex(t.p1), c = vertex(t.p2);
    // Transposed: x, y and z of (a, b, c).
    const __m128 ab_lo = _mm_unpacklo_ps(a, b), ab_hi = _mm_unpackhi_ps(a, b);  // ax bx ay by; az bz
    const __m128 x = _mm_movelh_ps(ab_lo, c);                                   // ax bx cx
    const __m128 y = _mm_shuffle_ps(ab_lo, c, _MM_SHUFFLE(1, 1, 3, 2));         // ay by cy
    const __m128 z = _mm_shuffle_ps(ab_hi, c, _MM_SHUFFLE(2, 2, 1, 0));         // az bz cz
    // Sheared: ax = a.x - sx a.z, ay = a.y - sy a.z, and so on.
    const __m128 sxv = _mm_sub_ps(x, _mm_mul_ps(r.sx, z));
    const __m128 syv = _mm_sub_ps(y, _mm_mul_ps(r.sy, z));
    // (u, v, w) = (cx by - cy bx, ax cy - ay cx, bx ay - by ax).
    const __m128 x201 = _mm_shuffle_ps(sxv, sxv, _MM_SHUFFLE(3, 1, 0, 2));  // cx ax bx
    const __m128 x120 = _mm_shuffle_ps(sxv, sxv, _MM_SHUFFLE(3, 0, 2, 1));  // bx cx ax
    const __m128 y120 = _mm_shuffle_ps(syv, syv, _MM_SHUFFLE(3, 0, 2, 1));  // by cy ay
    const __m128 y201 = _mm_shuffle_ps(syv, syv, _MM_SHUFFLE(3, 1, 0, 2));  // cy ay by
    const __m128 uvw = _mm_sub_ps(_mm_mul_ps(x201, y120), _mm_mul_ps(y201, x120));
    const __m128 zero = _mm_setzero_ps();
    if (_mm_movemask_ps(_mm_cmpeq_ps(uvw, zero)) & 7) {  // on an edge in float: the scalar test
        WatertightRay w(*r.ray);
        w.t_max = t_max;
        return intersect_triangle(t, w);
    }
    const int negative = _mm_movemask_ps(_mm_cmplt_ps(uvw, zero)) & 7;
    const int positive = _mm_movemask_ps(_mm_cmpgt_ps(uvw, zero)) & 7;
    if (negative && positive) return std::nullopt;
    alignas(16) float e[4], z_sheared[4];
    _mm_store_ps(e, uvw);
    _mm_store_ps(z_sheared, _mm_mul_ps(r.sz, z));  // az = sz a.z, bz, cz
    return triangle_detail::hit_from_edges(e[0], e[1], e[2], z_sheared[0], z_sheared[1], z_sheared[2], t_max);
}

}  // namespace glint
