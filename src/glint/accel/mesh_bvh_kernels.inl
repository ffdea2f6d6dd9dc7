// One mesh traversal kernel: included by mesh_bvh_sse4.cpp, mesh_bvh_avx2.cpp and
// mesh_bvh_avx512.cpp with GLINT_KERNEL_ISA (the entry points' suffix) and GLINT_KERNEL_WIDTH
// (4 or 8 children per node) defined. Everything but the two entry points is in an anonymous
// namespace, and the code calls no inline function with external linkage (only intrinsics and
// plain field reads), so nothing compiled here for a wider ISA can stand in for baseline code.
//
// The arithmetic is that of the scalar code, operation for operation and in the same order
// (the files are compiled with -ffp-contract=off so that no multiply-add is fused): box tests as
// bvh_detail::hit_boxes, triangle tests as intersect_triangle in shapes/triangle.h.
#include <immintrin.h>

#include <cstdint>
#include <limits>

#include "glint/accel/mesh_bvh_kernels.h"

#define GLINT_CAT2(a, b) a##b
#define GLINT_CAT(a, b) GLINT_CAT2(a, b)

namespace glint {
namespace {

constexpr int W = GLINT_KERNEL_WIDTH;
using Node = BvhNode<W>;
constexpr int kStack = 256;
constexpr float kInf = std::numeric_limits<float>::infinity();
inline std::uint32_t leaf_first(std::uint32_t c) { return (c & ~Node::kLeaf) >> Node::kCountBits; }
inline std::uint32_t leaf_count(std::uint32_t c) { return c & ((1u << Node::kCountBits) - 1); }

// The node's box test, W lanes at once.
#if GLINT_KERNEL_WIDTH == 8
using VecW = __m256;
inline VecW set1(float x) { return _mm256_set1_ps(x); }
inline VecW load(const float* p) { return _mm256_load_ps(p); }
inline VecW sub(VecW a, VecW b) { return _mm256_sub_ps(a, b); }
inline VecW mul(VecW a, VecW b) { return _mm256_mul_ps(a, b); }
inline VecW vmax(VecW a, VecW b) { return _mm256_max_ps(a, b); }
inline VecW vmin(VecW a, VecW b) { return _mm256_min_ps(a, b); }
inline void store(float* p, VecW a) { _mm256_store_ps(p, a); }
#if defined(__AVX512VL__)
inline unsigned le_mask(VecW a, VecW b) { return _mm256_cmp_ps_mask(a, b, _CMP_LE_OQ); }
#else
inline unsigned le_mask(VecW a, VecW b) {
    return static_cast<unsigned>(_mm256_movemask_ps(_mm256_cmp_ps(a, b, _CMP_LE_OQ)));
}
#endif
#else
using VecW = __m128;
inline VecW set1(float x) { return _mm_set1_ps(x); }
inline VecW load(const float* p) { return _mm_load_ps(p); }
inline VecW sub(VecW a, VecW b) { return _mm_sub_ps(a, b); }
inline VecW mul(VecW a, VecW b) { return _mm_mul_ps(a, b); }
inline VecW vmax(VecW a, VecW b) { return _mm_max_ps(a, b); }
inline VecW vmin(VecW a, VecW b) { return _mm_min_ps(a, b); }
inline void store(float* p, VecW a) { _mm_store_ps(p, a); }
inline unsigned le_mask(VecW a, VecW b) { return static_cast<unsigned>(_mm_movemask_ps(_mm_cmple_ps(a, b))); }
#endif

/// Prefetches all of a child about to be pushed: a node's box planes and references span four
/// cache lines (8-wide) or two; a leaf's first packet three.
inline void prefetch(const MeshTraversal& m, const Node* nodes, std::uint32_t ref) {
    const char* p;
    int bytes;
    if (ref & Node::kLeaf) {
        if (ref == Node::kEmpty) return;
        p = reinterpret_cast<const char*>(m.packets + leaf_first(ref));
        bytes = sizeof(TrianglePacket);
    } else {
        p = reinterpret_cast<const char*>(nodes + ref);
        bytes = sizeof(Node);
    }
    for (int off = 0; off < bytes; off += 64) _mm_prefetch(p + off, _MM_HINT_T0);
}

constexpr float kWiden = bvh_detail::kWiden;  // the far slabs' robust widening (accel/bvh.h)

struct BoxRay {
    VecW o[3], inv[3];
    VecW inv_far[3];  ///< inv times kWiden: the far planes' robust widening, made once a ray
    int near_offset[3], far_offset[3];
};

// The watertight test on a packet of four triangles: the ray's frame and shear, as
// WatertightRay's (the same choice of axes, the same divisions).
struct TriRay {
    int kx, ky, kz;
    float ox, oy, oz;  // the origin's permuted coordinates
    __m128 sx, sy, sz;
    const Ray* ray;    // for the scalar fallback, which builds its WatertightRay from it
};

/// Both set-ups at once, the six divisions as two vector divisions (IEEE division is correctly
/// rounded in every lane, so each quotient is the scalar one bit for bit).
inline void make_rays(const Ray& ray, BoxRay& br, TriRay& tr) {
    const float o[3] = {ray.origin.x, ray.origin.y, ray.origin.z};
    const float d[3] = {ray.direction.x, ray.direction.y, ray.direction.z};
    alignas(16) float inv[4], inv_far[4];
    const __m128 r = _mm_div_ps(_mm_set1_ps(1), _mm_setr_ps(d[0], d[1], d[2], 1));
    _mm_store_ps(inv, r);
    _mm_store_ps(inv_far, _mm_mul_ps(r, _mm_set1_ps(kWiden)));
    const int negative = _mm_movemask_ps(r);  // bit a: the sign of 1 / d_a
    for (int a = 0; a < 3; ++a) {
        br.o[a] = set1(o[a]);
        br.inv[a] = set1(inv[a]);
        br.inv_far[a] = set1(inv_far[a]);
        br.near_offset[a] = 2 * W * a + W * ((negative >> a) & 1);
        br.far_offset[a] = br.near_offset[a] ^ W;  // the other half of the axis' 2W floats
    }
    // As WatertightRay::WatertightRay: the largest direction component becomes z.
    int kz = 0;
    if (__builtin_fabsf(d[1]) > __builtin_fabsf(d[kz])) kz = 1;
    if (__builtin_fabsf(d[2]) > __builtin_fabsf(d[kz])) kz = 2;
    int kx = kz + 1 == 3 ? 0 : kz + 1;
    int ky = kx + 1 == 3 ? 0 : kx + 1;
    if (d[kz] < 0) {
        const int k = kx;
        kx = ky;
        ky = k;
    }
    alignas(16) float s[4];
    _mm_store_ps(s, _mm_div_ps(_mm_setr_ps(d[kx], d[ky], 1, 1), _mm_set1_ps(d[kz])));
    tr.kx = kx;
    tr.ky = ky;
    tr.kz = kz;
    tr.ox = o[kx];
    tr.oy = o[ky];
    tr.oz = o[kz];
    tr.sx = _mm_set1_ps(s[0]);
    tr.sy = _mm_set1_ps(s[1]);
    tr.sz = _mm_set1_ps(s[2]);
    tr.ray = &ray;
}

inline unsigned hit_boxes(const Node& n, const BoxRay& r, float t_max, float* tnear) {
    const float* base = n.lo_x;
    VecW t0 = set1(0), t1 = set1(t_max);
    for (int a = 0; a < 3; ++a) {
        const VecW tn = mul(sub(load(base + r.near_offset[a]), r.o[a]), r.inv[a]);
        const VecW tf = mul(sub(load(base + r.far_offset[a]), r.o[a]), r.inv_far[a]);
        t0 = vmax(tn, t0);  // a NaN slab distance leaves the running bound (second operand)
        t1 = vmin(tf, t1);
    }
    store(tnear, t0);
    return le_mask(t0, t1);
}

struct PacketResult {
    __m128 t, b1, b2;
    unsigned hit;  ///< lanes with a hit in [kRayTMin, t_max)
    bool exact;    ///< an edge function was zero in some lane: the caller redoes the packet in scalar
};

inline PacketResult test_packet(const TrianglePacket& p, const TriRay& r, float t_max, bool need_uv) {
    PacketResult res{};
    const __m128 ox = _mm_set1_ps(r.ox), oy = _mm_set1_ps(r.oy), oz = _mm_set1_ps(r.oz);
    // Vertices relative to the origin in the permuted frame, then sheared.
    __m128 vx[3], vy[3], vz[3];
    for (int v = 0; v < 3; ++v) {
        const __m128 x = _mm_sub_ps(_mm_load_ps(p.p[v][r.kx]), ox);
        const __m128 y = _mm_sub_ps(_mm_load_ps(p.p[v][r.ky]), oy);
        vz[v] = _mm_sub_ps(_mm_load_ps(p.p[v][r.kz]), oz);
        vx[v] = _mm_sub_ps(x, _mm_mul_ps(r.sx, vz[v]));
        vy[v] = _mm_sub_ps(y, _mm_mul_ps(r.sy, vz[v]));
    }
    const __m128 u = _mm_sub_ps(_mm_mul_ps(vx[2], vy[1]), _mm_mul_ps(vy[2], vx[1]));
    const __m128 v = _mm_sub_ps(_mm_mul_ps(vx[0], vy[2]), _mm_mul_ps(vy[0], vx[2]));
    const __m128 w = _mm_sub_ps(_mm_mul_ps(vx[1], vy[0]), _mm_mul_ps(vy[1], vx[0]));
    const __m128 zero = _mm_setzero_ps();
    if (_mm_movemask_ps(_mm_or_ps(_mm_or_ps(_mm_cmpeq_ps(u, zero), _mm_cmpeq_ps(v, zero)), _mm_cmpeq_ps(w, zero)))) {
        res.exact = true;
        return res;
    }
    const __m128 neg = _mm_or_ps(_mm_or_ps(_mm_cmplt_ps(u, zero), _mm_cmplt_ps(v, zero)), _mm_cmplt_ps(w, zero));
    const __m128 pos = _mm_or_ps(_mm_or_ps(_mm_cmpgt_ps(u, zero), _mm_cmpgt_ps(v, zero)), _mm_cmpgt_ps(w, zero));
    __m128 ok = _mm_andnot_ps(_mm_and_ps(neg, pos), _mm_castsi128_ps(_mm_set1_epi32(-1)));
    const __m128 det = _mm_add_ps(_mm_add_ps(u, v), w);
    ok = _mm_and_ps(ok, _mm_cmpneq_ps(det, zero));
    if (!_mm_movemask_ps(ok)) return res;
    const __m128 t_scaled = _mm_add_ps(
        _mm_add_ps(_mm_mul_ps(u, _mm_mul_ps(r.sz, vz[0])), _mm_mul_ps(v, _mm_mul_ps(r.sz, vz[1]))),
        _mm_mul_ps(w, _mm_mul_ps(r.sz, vz[2])));
    const __m128 tmin = _mm_set1_ps(kRayTMin), tmax = _mm_set1_ps(t_max);
    const __m128 lo = _mm_mul_ps(tmin, det), hi = _mm_mul_ps(tmax, det);
    const __m128 in_pos = _mm_and_ps(_mm_cmpge_ps(t_scaled, lo), _mm_cmplt_ps(t_scaled, hi));
    const __m128 in_neg = _mm_and_ps(_mm_cmple_ps(t_scaled, lo), _mm_cmpgt_ps(t_scaled, hi));
    ok = _mm_and_ps(ok, _mm_blendv_ps(in_neg, in_pos, _mm_cmpgt_ps(det, zero)));
    if (!_mm_movemask_ps(ok)) return res;
    res.t = _mm_div_ps(t_scaled, det);
    ok = _mm_and_ps(ok, _mm_and_ps(_mm_cmpge_ps(res.t, tmin), _mm_cmplt_ps(res.t, tmax)));
    res.hit = static_cast<unsigned>(_mm_movemask_ps(ok));
    if (res.hit && need_uv) {
        const __m128 inv_det = _mm_div_ps(_mm_set1_ps(1), det);
        res.b1 = _mm_mul_ps(v, inv_det);
        res.b2 = _mm_mul_ps(w, inv_det);
    }
    res.t = _mm_blendv_ps(_mm_set1_ps(kInf), res.t, ok);
    return res;
}

/// Tests a leaf's packets, lowering t_max and filling `out` at each nearer hit.
inline bool closest_in_leaf(const MeshTraversal& m, std::uint32_t ref, const TriRay& r, float& t_max,
                            MeshHit& out) {
    bool found = false;
    const std::uint32_t first = leaf_first(ref), count = leaf_count(ref);
    for (std::uint32_t k = first; k < first + count; ++k) {
        const TrianglePacket& p = m.packets[k];
        const PacketResult res = test_packet(p, r, t_max, true);
        if (res.exact) {  // lane by lane in scalar, as intersect_triangle would in leaf order
            WatertightRay wr(*r.ray);
            for (int lane = 0; lane < 4; ++lane) {
                wr.t_max = t_max;
                TriangleHit h;
                if (intersect_packet_lane(p, lane, wr, h) &&
                    (!m.filter || m.filter->keep(m.filter->context, p.prim[lane], h.b1, h.b2))) {
                    t_max = h.t;
                    out.hit = h;
                    out.prim = p.prim[lane];
                    out.vertices = &p.p[0][0][lane];
                    found = true;
                }
            }
            continue;
        }
        if (!res.hit) continue;
        // The nearest lane; the first of equal ones, as a scalar loop in lane order keeps.
        alignas(16) float t[4], b1[4], b2[4];
        _mm_store_ps(t, res.t);
        _mm_store_ps(b1, res.b1);
        _mm_store_ps(b2, res.b2);
        unsigned hit = res.hit;
        if (m.filter) {  // refused lanes drop out
            for (int lane = 0; lane < 4; ++lane)
                if ((hit >> lane & 1u) && !m.filter->keep(m.filter->context, p.prim[lane], b1[lane], b2[lane]))
                    hit &= ~(1u << lane), t[lane] = kInf;
            if (!hit) continue;
        }
        int best = __builtin_ctz(hit);
        for (int lane = best + 1; lane < 4; ++lane)
            if (t[lane] < t[best]) best = lane;
        t_max = t[best];
        out.hit = TriangleHit{t[best], b1[best], b2[best]};
        out.prim = p.prim[best];
        out.vertices = &p.p[0][0][best];
        found = true;
    }
    return found;
}

inline bool any_in_leaf(const MeshTraversal& m, std::uint32_t ref, const TriRay& r, float t_max) {
    const std::uint32_t first = leaf_first(ref), count = leaf_count(ref);
    for (std::uint32_t k = first; k < first + count; ++k) {
        const TrianglePacket& p = m.packets[k];
        const PacketResult res = test_packet(p, r, t_max, m.filter != nullptr);
        if (res.exact) {
            const WatertightRay wr(*r.ray);
            TriangleHit h;
            for (int lane = 0; lane < 4; ++lane)
                if (intersect_packet_lane(p, lane, wr, h) &&
                    (!m.filter || m.filter->keep(m.filter->context, p.prim[lane], h.b1, h.b2)))
                    return true;
            continue;
        }
        if (res.hit && m.filter) {
            alignas(16) float b1[4], b2[4];
            _mm_store_ps(b1, res.b1);
            _mm_store_ps(b2, res.b2);
            for (int lane = 0; lane < 4; ++lane)
                if ((res.hit >> lane & 1u) && m.filter->keep(m.filter->context, p.prim[lane], b1[lane], b2[lane]))
                    return true;
            continue;
        }
        if (res.hit) return true;
    }
    return false;
}

}  // namespace

bool GLINT_CAT(mesh_closest_, GLINT_KERNEL_ISA)(const MeshTraversal& m, const Ray& ray, MeshHit& out) {
    if (m.root == Node::kEmpty) return false;
    const Node* nodes = static_cast<const Node*>(m.nodes);
    BoxRay br;
    TriRay tr;
    make_rays(ray, br, tr);
    float t_max = ray.t_max;
    bool found = false;
    // The stack holds the hit children not yet visited, with their entry distances, in two
    // arrays (a pop reads what a push wrote, word for word, so loads forward from stores).
    std::uint32_t stack_ref[kStack];
    float stack_t[kStack];
    int top = 0;
    std::uint32_t cur = m.root;
    for (;;) {
        // Down the tree: the nearest hit child next, the others pushed farthest first.
        while (!(cur & Node::kLeaf)) {
            const Node& n = nodes[cur];
            alignas(W * 4) float tn[W];
            unsigned mask = hit_boxes(n, br, t_max, tn);
            if (mask == 0) {
                cur = Node::kEmpty;
                break;
            }
            int i = __builtin_ctz(mask);
            mask &= mask - 1;
            if (mask == 0) {  // one child: no stack traffic
                cur = n.child[i];
                continue;
            }
            const int base = top;
            for (;;) {  // insertion of child i into the stack's top, sorted by distance
                const std::uint32_t ref = n.child[i];
                const float t = tn[i];
                prefetch(m, nodes, ref);
                int j = top++;
                while (j > base && stack_t[j - 1] < t) {
                    stack_ref[j] = stack_ref[j - 1];
                    stack_t[j] = stack_t[j - 1];
                    --j;
                }
                stack_ref[j] = ref;
                stack_t[j] = t;
                if (mask == 0) break;
                i = __builtin_ctz(mask);
                mask &= mask - 1;
            }
            cur = stack_ref[--top];  // the nearest
        }
        if (cur != Node::kEmpty) found |= closest_in_leaf(m, cur, tr, t_max, out);
        // Up: the next entry nearer than the nearest hit so far.
        for (;;) {
            if (top == 0) return found;
            --top;
            if (stack_t[top] <= t_max) break;
        }
        cur = stack_ref[top];
    }
}

bool GLINT_CAT(mesh_any_, GLINT_KERNEL_ISA)(const MeshTraversal& m, const Ray& ray) {
    if (m.root == Node::kEmpty) return false;
    const Node* nodes = static_cast<const Node*>(m.nodes);
    BoxRay br;
    TriRay tr;
    make_rays(ray, br, tr);
    std::uint32_t stack[kStack];
    int top = 0;
    std::uint32_t cur = m.root;
    for (;;) {
        while (!(cur & Node::kLeaf)) {  // down: the first hit child next, the others pushed
            alignas(W * 4) float tn[W];
            unsigned mask = hit_boxes(nodes[cur], br, ray.t_max, tn);
            if (mask == 0) {
                cur = Node::kEmpty;
                break;
            }
            const Node& n = nodes[cur];
            cur = n.child[__builtin_ctz(mask)];
            mask &= mask - 1;
            while (mask) {
                stack[top++] = n.child[__builtin_ctz(mask)];
                mask &= mask - 1;
            }
        }
        if (cur != Node::kEmpty && any_in_leaf(m, cur, tr, ray.t_max)) return true;
        if (top == 0) return false;
        cur = stack[--top];
    }
}

}  // namespace glint

#undef GLINT_CAT
#undef GLINT_CAT2
