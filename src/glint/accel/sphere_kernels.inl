// The sphere-set kernels (sphere_set.h), one instruction set per including file: GLINT_KERNEL_ISA
// names it and GLINT_KERNEL_WIDTH gives the lanes. As in mesh_bvh_kernels.inl, everything here
// is internal to the file except the two entry points.
#include <immintrin.h>

#include <bit>
#include <cstdint>

#include "glint/accel/sphere_set.h"

#define GLINT_CAT2(a, b) a##b
#define GLINT_CAT(a, b) GLINT_CAT2(a, b)

namespace glint {
namespace {

#if GLINT_KERNEL_WIDTH == 16
using V = __m512;
using M = __mmask16;
inline V set1(float x) { return _mm512_set1_ps(x); }
inline V load(const float* p) { return _mm512_load_ps(p); }
inline V add(V a, V b) { return _mm512_add_ps(a, b); }
inline V sub(V a, V b) { return _mm512_sub_ps(a, b); }
inline V mul(V a, V b) { return _mm512_mul_ps(a, b); }
inline V div(V a, V b) { return _mm512_div_ps(a, b); }
inline V sqrt(V a) { return _mm512_sqrt_ps(a); }
inline V neg(V a) { return _mm512_castsi512_ps(_mm512_xor_si512(_mm512_castps_si512(a), _mm512_set1_epi32(INT32_MIN))); }
inline M gt(V a, V b) { return _mm512_cmp_ps_mask(a, b, _CMP_GT_OQ); }
inline M ge(V a, V b) { return _mm512_cmp_ps_mask(a, b, _CMP_GE_OQ); }
inline M lt(V a, V b) { return _mm512_cmp_ps_mask(a, b, _CMP_LT_OQ); }
inline M neq(V a, V b) { return _mm512_cmp_ps_mask(a, b, _CMP_NEQ_UQ); }
inline M mand(M a, M b) { return static_cast<M>(a & b); }
inline M mor(M a, M b) { return static_cast<M>(a | b); }
inline M mandnot(M a, M b) { return static_cast<M>(~a & b); }  // b and not a
inline V select(M m, V a, V b) { return _mm512_mask_blend_ps(m, b, a); }  // m ? a : b
inline unsigned bits(M m) { return m; }
#elif GLINT_KERNEL_WIDTH == 8
using V = __m256;
using M = __m256;
inline V set1(float x) { return _mm256_set1_ps(x); }
inline V load(const float* p) { return _mm256_load_ps(p); }
inline V add(V a, V b) { return _mm256_add_ps(a, b); }
inline V sub(V a, V b) { return _mm256_sub_ps(a, b); }
inline V mul(V a, V b) { return _mm256_mul_ps(a, b); }
inline V div(V a, V b) { return _mm256_div_ps(a, b); }
inline V sqrt(V a) { return _mm256_sqrt_ps(a); }
inline V neg(V a) { return _mm256_xor_ps(a, _mm256_set1_ps(-0.0f)); }
inline M gt(V a, V b) { return _mm256_cmp_ps(a, b, _CMP_GT_OQ); }
inline M ge(V a, V b) { return _mm256_cmp_ps(a, b, _CMP_GE_OQ); }
inline M lt(V a, V b) { return _mm256_cmp_ps(a, b, _CMP_LT_OQ); }
inline M neq(V a, V b) { return _mm256_cmp_ps(a, b, _CMP_NEQ_UQ); }
inline M mand(M a, M b) { return _mm256_and_ps(a, b); }
inline M mor(M a, M b) { return _mm256_or_ps(a, b); }
inline M mandnot(M a, M b) { return _mm256_andnot_ps(a, b); }
inline V select(M m, V a, V b) { return _mm256_blendv_ps(b, a, m); }
inline unsigned bits(M m) { return static_cast<unsigned>(_mm256_movemask_ps(m)); }
#else
using V = __m128;
using M = __m128;
inline V set1(float x) { return _mm_set1_ps(x); }
inline V load(const float* p) { return _mm_load_ps(p); }
inline V add(V a, V b) { return _mm_add_ps(a, b); }
inline V sub(V a, V b) { return _mm_sub_ps(a, b); }
inline V mul(V a, V b) { return _mm_mul_ps(a, b); }
inline V div(V a, V b) { return _mm_div_ps(a, b); }
inline V sqrt(V a) { return _mm_sqrt_ps(a); }
inline V neg(V a) { return _mm_xor_ps(a, _mm_set1_ps(-0.0f)); }
inline M gt(V a, V b) { return _mm_cmpgt_ps(a, b); }
inline M ge(V a, V b) { return _mm_cmpge_ps(a, b); }
inline M lt(V a, V b) { return _mm_cmplt_ps(a, b); }
inline M neq(V a, V b) { return _mm_cmpneq_ps(a, b); }
inline M mand(M a, M b) { return _mm_and_ps(a, b); }
inline M mor(M a, M b) { return _mm_or_ps(a, b); }
inline M mandnot(M a, M b) { return _mm_andnot_ps(a, b); }
inline V select(M m, V a, V b) { return _mm_blendv_ps(b, a, m); }
inline unsigned bits(M m) { return static_cast<unsigned>(_mm_movemask_ps(m)); }
#endif

constexpr int kW = GLINT_KERNEL_WIDTH;

struct RayW {
    V ox, oy, oz, dx, dy, dz, t_min, t_max;
};

// Sphere::intersect on W spheres: the valid lanes and their t. Line for line the scalar code's
// arithmetic (see shapes/sphere.h for the why of each step).
// The lanes hold W spheres against one ray (broadcast), or one sphere (broadcast) against W rays.
inline M test(V cx, V cy, V cz, V radius, V r2, const RayW& r, V& t_out) {
    const V fx = sub(r.ox, cx), fy = sub(r.oy, cy), fz = sub(r.oz, cz);
    const V b = add(add(mul(fx, r.dx), mul(fy, r.dy)), mul(fz, r.dz));
    const V ff = add(add(mul(fx, fx), mul(fy, fy)), mul(fz, fz));
    const V zero = set1(0.0f);
    M miss = mand(gt(b, zero), gt(ff, r2));
    const V px = sub(fx, mul(r.dx, b)), py = sub(fy, mul(r.dy, b)), pz = sub(fz, mul(r.dz, b));
    const V disc = sub(r2, add(add(mul(px, px), mul(py, py)), mul(pz, pz)));
    miss = mor(miss, lt(disc, zero));
    const V root = sqrt(disc);
    const V nb = neg(b);
    const V near = sub(nb, root);
    const V q = select(gt(b, zero), near, add(nb, root));
    miss = mor(miss, ge(near, r.t_max));
    const V dist = sqrt(ff);
    const V c = mul(sub(dist, radius), add(dist, radius));
    const V t0 = select(neq(q, zero), div(c, q), zero);
    const M swap = gt(t0, q);
    const V lo = select(swap, q, t0), hi = select(swap, t0, q);
    const M v0 = mand(ge(lo, r.t_min), lt(lo, r.t_max));
    const M v1 = mand(ge(hi, r.t_min), lt(hi, r.t_max));
    t_out = select(v0, lo, hi);
    return mandnot(miss, mor(v0, v1));
}

inline M test(const SphereSoa::Group& g, int lane0, const RayW& r, V& t_out) {
    return test(load(g.cx + lane0), load(g.cy + lane0), load(g.cz + lane0), load(g.r + lane0),
                load(g.r2 + lane0), r, t_out);
}

inline RayW lanes(const RayPacket& p, int lane0) {
    return {load(p.ox + lane0), load(p.oy + lane0), load(p.oz + lane0), load(p.dx + lane0),
            load(p.dy + lane0), load(p.dz + lane0), set1(kRayTMin), load(p.t_max + lane0)};
}

inline void store(float* p, V v) {
#if GLINT_KERNEL_WIDTH == 16
    _mm512_store_ps(p, v);
#elif GLINT_KERNEL_WIDTH == 8
    _mm256_store_ps(p, v);
#else
    _mm_store_ps(p, v);
#endif
}

inline RayW wide(const Ray& ray) {
    return {set1(ray.origin.x), set1(ray.origin.y), set1(ray.origin.z), set1(ray.direction.x),
            set1(ray.direction.y), set1(ray.direction.z), set1(kRayTMin), set1(ray.t_max)};
}

}  // namespace

bool GLINT_CAT(spheres_closest_, GLINT_KERNEL_ISA)(const SphereSoa& s, const Ray& ray, float& t, std::uint32_t& index) {
    const RayW r = wide(ray);
    float best = ray.t_max;
    bool found = false;
    alignas(64) float ts[kW];
    for (std::size_t gi = 0; gi < s.groups.size(); ++gi) {
        for (int lane0 = 0; lane0 < SphereSoa::kGroup; lane0 += kW) {
            V tv;
            unsigned m = bits(test(s.groups[gi], lane0, r, tv));
            if (!m) continue;
            store(ts, tv);
            for (; m; m &= m - 1) {  // lanes in index order: the lowest index wins a tie
                const int k = std::countr_zero(m);
                if (ts[k] < best) {
                    best = ts[k];
                    index = static_cast<std::uint32_t>(gi * SphereSoa::kGroup + static_cast<std::size_t>(lane0 + k));
                    found = true;
                }
            }
        }
    }
    if (found) t = best;
    return found;
}

bool GLINT_CAT(spheres_any_, GLINT_KERNEL_ISA)(const SphereSoa& s, const Ray& ray) {
    const RayW r = wide(ray);
    for (const SphereSoa::Group& g : s.groups) {
        for (int lane0 = 0; lane0 < SphereSoa::kGroup; lane0 += kW) {
            V tv;
            if (bits(test(g, lane0, r, tv))) return true;
        }
    }
    return false;
}

// Packets: one sphere at a time against W rays. Spheres in index order and a strict "nearer"
// test, so the lowest index wins a tie, as above.
void GLINT_CAT(spheres_closest_packet_, GLINT_KERNEL_ISA)(const SphereSoa& s, const RayPacket& p, int n,
                                                         PacketHits& out) {
    for (int lane0 = 0; lane0 < n; lane0 += kW) {
        const RayW r = lanes(p, lane0);
        V best = r.t_max, index = set1(-1.0f);
        for (std::uint32_t i = 0; i < s.count; ++i) {
            const SphereSoa::Group& g = s.groups[i / SphereSoa::kGroup];
            const std::uint32_t k = i % SphereSoa::kGroup;
            V t;
            const M valid = test(set1(g.cx[k]), set1(g.cy[k]), set1(g.cz[k]), set1(g.r[k]), set1(g.r2[k]), r, t);
            const M nearer = mand(valid, lt(t, best));
            best = select(nearer, t, best);
            index = select(nearer, set1(static_cast<float>(i)), index);
        }
        store(out.t + lane0, best);
        store(out.index + lane0, index);
    }
}

std::uint32_t GLINT_CAT(spheres_any_packet_, GLINT_KERNEL_ISA)(const SphereSoa& s, const RayPacket& p, int n) {
    std::uint32_t hits = 0;
    for (int lane0 = 0; lane0 < n; lane0 += kW) {
        const RayW r = lanes(p, lane0);
        const unsigned all = (1u << kW) - 1;
        unsigned hit = 0;
        for (std::uint32_t i = 0; i < s.count && hit != all; ++i) {
            const SphereSoa::Group& g = s.groups[i / SphereSoa::kGroup];
            const std::uint32_t k = i % SphereSoa::kGroup;
            V t;
            hit |= bits(test(set1(g.cx[k]), set1(g.cy[k]), set1(g.cz[k]), set1(g.r[k]), set1(g.r2[k]), r, t));
        }
        hits |= static_cast<std::uint32_t>(hit) << lane0;
    }
    return hits;
}

}  // namespace glint
