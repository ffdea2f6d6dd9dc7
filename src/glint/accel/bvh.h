#pragma once
// glint's own bounding volume hierarchy: a 4-wide BVH, built top-down with a binned surface area
// heuristic (Wald 2007) directly into 4-wide nodes (each node splits its primitives up to three
// times, always splitting the child with the largest area, as in Embree's BVH4 builder), in
// parallel with oneTBB below the top levels. Traversal tests the four child boxes of a node at
// once with SSE (x86-64-v2, the project's baseline ISA) and visits hit children nearest first.
//
// The structure knows only boxes: it orders an array of primitive ids so that every leaf is a
// contiguous range, and hands ranges to a callback, so one class serves both levels of the scene
// (instances and shapes at the top, a mesh's triangles at the bottom).
//
// Robustness: the box test is pbrt's (far distance widened by 2 gamma(3), NaN from 0 * inf
// never narrows the interval), so no ray that hits a primitive misses its box through round-off.
// Primitives whose bounds are not finite are left out of the tree (reported by the builder's
// caller); a NaN ray direction hits nothing.
#include <smmintrin.h>
#include <xmmintrin.h>

#include <cmath>

#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "glint/math/bounds.h"
#include "glint/ray.h"

namespace glint {

struct BvhBuildOptions {
    int max_leaf_size = 8;      ///< primitives per leaf at most
    float traversal_cost = 1;   ///< SAH cost of visiting a node, relative to one primitive test
    bool parallel = true;       ///< build subtrees on oneTBB tasks
};

struct alignas(16) Bvh4Node {
    // The four children's boxes, one SIMD lane per child: empty lanes have lo = +inf, hi = -inf.
    float lo_x[4], hi_x[4], lo_y[4], hi_y[4], lo_z[4], hi_z[4];
    std::uint32_t child[4];  ///< an inner node index, or a leaf (kLeaf bit set)

    static constexpr std::uint32_t kLeaf = 0x80000000u;
    static constexpr std::uint32_t kEmpty = 0xffffffffu;  ///< a leaf with no primitives
    static constexpr int kCountBits = 4;                 ///< leaf: count in the low bits
    static std::uint32_t make_leaf(std::uint32_t first, std::uint32_t count) {
        return kLeaf | first << kCountBits | count;
    }
    static std::uint32_t leaf_first(std::uint32_t c) { return (c & ~kLeaf) >> kCountBits; }
    static std::uint32_t leaf_count(std::uint32_t c) { return c & ((1u << kCountBits) - 1); }
};
static_assert(sizeof(Bvh4Node) == 112);

/// What a traversal derives from the ray once.
struct BvhRay {
    __m128 o[3], inv[3];
    /// Per axis, where the near and the far planes' four floats start in a node (lo_a or hi_a,
    /// by the sign of the direction), so that the box test needs no branch.
    int near_offset[3], far_offset[3];
    explicit BvhRay(const Ray& ray) {
        for (int a = 0; a < 3; ++a) {
            o[a] = _mm_set1_ps(ray.origin[a]);
            const float inv_d = 1 / ray.direction[a];
            inv[a] = _mm_set1_ps(inv_d);
            const bool negative = std::signbit(inv_d);
            near_offset[a] = 8 * a + (negative ? 4 : 0);
            far_offset[a] = 8 * a + (negative ? 0 : 4);
        }
    }
};

class Bvh4 {
public:
    /// Builds over `bounds` (one box per primitive, ids 0..n-1). Primitives with empty or
    /// non-finite boxes are left out; `skipped()` counts them. Throws std::length_error past
    /// 2^27 - 16 primitives (what a leaf reference can address).
    void build(std::span<const Bounds3> bounds, const BvhBuildOptions& options = {});

    /// Primitive ids in leaf order: leaf (first, count) holds order()[first .. first + count).
    const std::vector<std::uint32_t>& order() const { return order_; }
    const std::vector<Bvh4Node>& nodes() const { return nodes_; }
    Bounds3 bounds() const { return bounds_; }
    std::size_t skipped() const { return skipped_; }
    int depth() const { return depth_; }
    bool empty() const { return root_ == Bvh4Node::kEmpty; }
    std::size_t memory_bytes() const {
        return nodes_.size() * sizeof(Bvh4Node) + order_.size() * sizeof(std::uint32_t);
    }

    /// Closest-hit traversal: calls `leaf(first, count)` for every leaf whose box the ray meets
    /// within (0, t_max], nearest box first; the callback tests its primitives and lowers t_max
    /// (a reference it shares with the caller) when it finds a hit.
    template <typename Leaf>
    void closest(const BvhRay& r, const float& t_max, Leaf&& leaf) const;
    /// Any-hit traversal: stops as soon as `leaf(first, count)` returns true.
    template <typename Leaf>
    bool any(const BvhRay& r, float t_max, Leaf&& leaf) const;

private:
    std::vector<Bvh4Node> nodes_;
    std::vector<std::uint32_t> order_;
    std::uint32_t root_ = Bvh4Node::kEmpty;
    Bounds3 bounds_;
    std::size_t skipped_ = 0;
    int depth_ = 0;
};

namespace bvh_detail {

inline constexpr int kStackSize = 256;  // the builder keeps the depth under kMaxDepth
inline constexpr int kMaxDepth = 80;

/// Which of the node's four boxes the ray meets, as a 4-bit mask; tnear per lane.
inline int hit_boxes(const Bvh4Node& n, const BvhRay& r, __m128 t_max, __m128& tnear) {
    const float* base = n.lo_x;  // lo_x hi_x lo_y hi_y lo_z hi_z, four floats each
    __m128 t0 = _mm_setzero_ps(), t1 = t_max;
    // Far distances widened by 1 + 2 gamma(3) (pbrt's robust slab test).
    const __m128 widen = _mm_set1_ps(1 + 2 * 3 * 0.5f * std::numeric_limits<float>::epsilon() /
                                             (1 - 3 * 0.5f * std::numeric_limits<float>::epsilon()));
    for (int a = 0; a < 3; ++a) {
        const __m128 near_plane = _mm_load_ps(base + r.near_offset[a]);
        const __m128 far_plane = _mm_load_ps(base + r.far_offset[a]);
        const __m128 tn = _mm_mul_ps(_mm_sub_ps(near_plane, r.o[a]), r.inv[a]);
        const __m128 tf = _mm_mul_ps(_mm_mul_ps(_mm_sub_ps(far_plane, r.o[a]), r.inv[a]), widen);
        // maxps/minps return the second operand when either is NaN: the running bound is second,
        // so a NaN slab distance leaves it unchanged.
        t0 = _mm_max_ps(tn, t0);
        t1 = _mm_min_ps(tf, t1);
    }
    tnear = t0;
    return _mm_movemask_ps(_mm_cmple_ps(t0, t1));
}

}  // namespace bvh_detail

template <typename Leaf>
void Bvh4::closest(const BvhRay& r, const float& t_max, Leaf&& leaf) const {
    if (root_ == Bvh4Node::kEmpty) return;
    struct Entry {
        std::uint32_t ref;
        float t;
    };
    Entry stack[bvh_detail::kStackSize];
    int top = 0;
    stack[top++] = {root_, 0};
    while (top > 0) {
        const Entry e = stack[--top];
        if (e.t > t_max) continue;  // a nearer hit was found after this entry was pushed
        if (e.ref & Bvh4Node::kLeaf) {
            if (e.ref != Bvh4Node::kEmpty) leaf(Bvh4Node::leaf_first(e.ref), Bvh4Node::leaf_count(e.ref));
            continue;
        }
        const Bvh4Node& n = nodes_[e.ref];
        __m128 tnear;
        int mask = bvh_detail::hit_boxes(n, r, _mm_set1_ps(t_max), tnear);
        if (mask == 0) continue;
        alignas(16) float tn[4];
        _mm_store_ps(tn, tnear);
        // Push hit children farthest first (insertion into the stack's top, at most four).
        const int base = top;
        while (mask) {
            const int i = __builtin_ctz(mask);
            mask &= mask - 1;
            Entry c{n.child[i], tn[i]};
            if (!(c.ref & Bvh4Node::kLeaf)) _mm_prefetch(reinterpret_cast<const char*>(&nodes_[c.ref]), _MM_HINT_T0);
            int j = top++;
            while (j > base && stack[j - 1].t < c.t) {
                stack[j] = stack[j - 1];
                --j;
            }
            stack[j] = c;
        }
    }
}

template <typename Leaf>
bool Bvh4::any(const BvhRay& r, float t_max, Leaf&& leaf) const {
    if (root_ == Bvh4Node::kEmpty) return false;
    std::uint32_t stack[bvh_detail::kStackSize];
    int top = 0;
    stack[top++] = root_;
    const __m128 tm = _mm_set1_ps(t_max);
    while (top > 0) {
        const std::uint32_t ref = stack[--top];
        if (ref & Bvh4Node::kLeaf) {
            if (ref != Bvh4Node::kEmpty &&
                leaf(Bvh4Node::leaf_first(ref), Bvh4Node::leaf_count(ref)))
                return true;
            continue;
        }
        const Bvh4Node& n = nodes_[ref];
        __m128 tnear;
        int mask = bvh_detail::hit_boxes(n, r, tm, tnear);
        while (mask) {
            const int i = __builtin_ctz(mask);
            mask &= mask - 1;
            stack[top++] = n.child[i];
        }
    }
    return false;
}

}  // namespace glint
