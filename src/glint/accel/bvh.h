#pragma once
// glint's own bounding volume hierarchy: a W-wide BVH (W = 4 or 8), built top-down with a binned
// surface area heuristic (Wald 2007) directly into W-wide nodes (each node splits its primitives
// up to W - 1 times, always splitting the child with the largest area, as in Embree's builders),
// in parallel with oneTBB below the top levels; optionally with spatial splits (SBVH). The
// 4-wide traversal here tests the four child boxes of a node at once with SSE (x86-64-v2, the
// project's baseline ISA) and visits hit children nearest first; the 8-wide trees of meshes are
// traversed with AVX2 or AVX-512 where the CPU has them (mesh_bvh_kernels.h).
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
    /// Leaves are tested `block_size` primitives at a time (MeshBvh: packets of four triangles):
    /// the SAH counts a leaf of n primitives as ceil(n / block_size) tests.
    int block_size = 1;
    /// Spatial splits (Stich, Friedrich and Dietrich 2009, "SBVH"): where the best object split
    /// leaves children that overlap by more than `split_alpha` of the root's area, also try
    /// splitting the node's space with a plane, clipping the primitives that straddle it (a
    /// primitive may then sit in several leaves). Needs a clipper (Bvh::build's third argument).
    bool spatial_splits = false;
    float split_alpha = 1e-4f;  ///< Stich et al. suggest 1e-5; 1e-4 builds twice as fast (docs/benchmarks.md)
    float max_duplication = 1.0f;  ///< at most (1 + this) x n references in all
    /// Per primitive id (empty: none), whether it must have a leaf of its own, however large
    /// max_leaf_size: the scene's top level keeps a mesh instance alone, so that its box is
    /// tested before its transform and traversal set-up are paid, while the lone shapes around
    /// it share leaves. Honoured by the object-split builder (not with spatial splits).
    std::span<const std::uint8_t> alone;
};

/// Clips primitive `prim`, whose part in the node is bounded by `box`, by the plane
/// x[axis] = pos: the bounds of its parts on either side (each within `box`).
using BvhClipper = void (*)(const void* context, std::uint32_t prim, const Bounds3& box, int axis,
                            float pos, Bounds3& left, Bounds3& right);

/// A node of a W-wide BVH: the children's boxes, one SIMD lane per child (empty lanes have
/// lo = +inf, hi = -inf), then the children's references.
template <int W>
struct alignas(W * 4) BvhNode {
    float lo_x[W], hi_x[W], lo_y[W], hi_y[W], lo_z[W], hi_z[W];
    std::uint32_t child[W];  ///< an inner node index, or a leaf (kLeaf bit set)

    static constexpr std::uint32_t kLeaf = 0x80000000u;
    static constexpr std::uint32_t kEmpty = 0xffffffffu;  ///< a leaf with no primitives
    static constexpr int kCountBits = 4;                 ///< leaf: count in the low bits
    static std::uint32_t make_leaf(std::uint32_t first, std::uint32_t count) {
        return kLeaf | first << kCountBits | count;
    }
    static std::uint32_t leaf_first(std::uint32_t c) { return (c & ~kLeaf) >> kCountBits; }
    static std::uint32_t leaf_count(std::uint32_t c) { return c & ((1u << kCountBits) - 1); }
};
using Bvh4Node = BvhNode<4>;
using Bvh8Node = BvhNode<8>;
static_assert(sizeof(Bvh4Node) == 112 && sizeof(Bvh8Node) == 224);

namespace bvh_detail {
/// 1 + 2 gamma(3): far slab distances are widened by it, so that round-off never culls a box
/// the ray meets (pbrt-v4's robust ray-box test).
inline constexpr float kWiden = 1 + 2 * 3 * 0.5f * std::numeric_limits<float>::epsilon() /
                                        (1 - 3 * 0.5f * std::numeric_limits<float>::epsilon());
}  // namespace bvh_detail

/// What a 4-wide traversal derives from the ray once.
struct BvhRay {
    __m128 o[3], inv[3];
    /// inv times 1 + 2 gamma(3): the far distances' robust widening (pbrt's), folded into the
    /// reciprocal once a ray instead of a multiply per slab and node (one step shorter a chain).
    __m128 inv_far[3];
    /// Per axis, where the near and the far planes' four floats start in a node (lo_a or hi_a,
    /// by the sign of the direction), so that the box test needs no branch.
    int near_offset[3], far_offset[3];
    explicit BvhRay(const Ray& ray) {
        // The three reciprocals as one vector division (correctly rounded per lane, so the same
        // floats as three scalar ones, at a third of the latency), widened as one product, and
        // the three signs as one mask (the offsets were a compare and two selects per axis).
        const __m128 r = _mm_div_ps(_mm_set1_ps(1), _mm_setr_ps(ray.direction.x, ray.direction.y, ray.direction.z, 1));
        const __m128 r_far = _mm_mul_ps(r, _mm_set1_ps(bvh_detail::kWiden));
        inv[0] = _mm_shuffle_ps(r, r, 0x00);
        inv[1] = _mm_shuffle_ps(r, r, 0x55);
        inv[2] = _mm_shuffle_ps(r, r, 0xaa);
        inv_far[0] = _mm_shuffle_ps(r_far, r_far, 0x00);
        inv_far[1] = _mm_shuffle_ps(r_far, r_far, 0x55);
        inv_far[2] = _mm_shuffle_ps(r_far, r_far, 0xaa);
        const int negative = _mm_movemask_ps(r);  // bit a: the sign of 1 / d_a
        for (int a = 0; a < 3; ++a) {
            o[a] = _mm_set1_ps(ray.origin[a]);
            near_offset[a] = 8 * a + 4 * ((negative >> a) & 1);
            far_offset[a] = near_offset[a] ^ 4;  // the other half of the axis' eight floats
        }
    }
};

/// A W-wide BVH over boxes. The 4-wide tree has its traversal here (SSE, the baseline ISA); the
/// 8-wide one is traversed by the AVX2 and AVX-512 kernels in mesh_bvh_kernels.h.
template <int W>
class Bvh {
public:
    using Node = BvhNode<W>;

    /// Builds over `bounds` (one box per primitive, ids 0..n-1). Primitives with empty or
    /// non-finite boxes are left out; `skipped()` counts them. Throws std::length_error past
    /// 2^27 - 16 primitives (what a leaf reference can address). With
    /// `options.spatial_splits` and a clipper, order() may name a primitive more than once.
    void build(std::span<const Bounds3> bounds, const BvhBuildOptions& options = {},
               BvhClipper clipper = nullptr, const void* clip_context = nullptr);

    /// Primitive ids in leaf order: leaf (first, count) holds order()[first .. first + count).
    const std::vector<std::uint32_t>& order() const { return order_; }
    const std::vector<Node>& nodes() const { return nodes_; }
    std::uint32_t root() const { return root_; }
    Bounds3 bounds() const { return bounds_; }
    std::size_t skipped() const { return skipped_; }
    int depth() const { return depth_; }
    bool empty() const { return root_ == Node::kEmpty; }
    std::size_t memory_bytes() const {
        return nodes_.size() * sizeof(Node) + order_.size() * sizeof(std::uint32_t);
    }
    /// Replaces every leaf reference (first, count) by f(first, count) (another leaf reference):
    /// for owners that repack the leaves' primitives (MeshBvh's triangle packets).
    template <typename F>
    void remap_leaves(F&& f) {
        if (root_ != Node::kEmpty && (root_ & Node::kLeaf))
            root_ = f(Node::leaf_first(root_), Node::leaf_count(root_));
        for (Node& n : nodes_)
            for (std::uint32_t& c : n.child)
                if ((c & Node::kLeaf) && c != Node::kEmpty) c = f(Node::leaf_first(c), Node::leaf_count(c));
    }
    /// The expected cost of a random ray by the surface area heuristic: inner nodes weigh
    /// `traversal_cost`, leaves their primitive count, each by its area over the root's.
    double sah_cost(float traversal_cost = 1) const;

    /// Closest-hit traversal (W = 4): calls `leaf(first, count)` for every leaf whose box the
    /// ray meets within (0, t_max], nearest box first; the callback tests its primitives and
    /// lowers t_max (a reference it shares with the caller) when it finds a hit.
    template <typename Leaf>
    void closest(const BvhRay& r, const float& t_max, Leaf&& leaf) const;
    /// Any-hit traversal (W = 4): stops as soon as `leaf(first, count)` returns true.
    template <typename Leaf>
    bool any(const BvhRay& r, float t_max, Leaf&& leaf) const;

private:
    std::vector<Node> nodes_;
    std::vector<std::uint32_t> order_;
    std::uint32_t root_ = Node::kEmpty;
    Bounds3 bounds_;
    std::size_t skipped_ = 0;
    int depth_ = 0;
};
using Bvh4 = Bvh<4>;
using Bvh8 = Bvh<8>;
extern template class Bvh<4>;
extern template class Bvh<8>;

namespace bvh_detail {

inline constexpr int kStackSize = 256;  // the builder keeps the depth under kMaxDepth
inline constexpr int kMaxDepth = 80;

/// Which of the node's four boxes the ray meets, as a 4-bit mask; tnear per lane.
inline int hit_boxes(const Bvh4Node& n, const BvhRay& r, __m128 t_max, __m128& tnear) {
    const float* base = n.lo_x;  // lo_x hi_x lo_y hi_y lo_z hi_z, four floats each
    __m128 t0 = _mm_setzero_ps(), t1 = t_max;
    // Far distances widened by 1 + 2 gamma(3) (pbrt's robust slab test), through inv_far.
    for (int a = 0; a < 3; ++a) {
        const __m128 near_plane = _mm_load_ps(base + r.near_offset[a]);
        const __m128 far_plane = _mm_load_ps(base + r.far_offset[a]);
        const __m128 tn = _mm_mul_ps(_mm_sub_ps(near_plane, r.o[a]), r.inv[a]);
        const __m128 tf = _mm_mul_ps(_mm_sub_ps(far_plane, r.o[a]), r.inv_far[a]);
        // maxps/minps return the second operand when either is NaN: the running bound is second,
        // so a NaN slab distance leaves it unchanged.
        t0 = _mm_max_ps(tn, t0);
        t1 = _mm_min_ps(tf, t1);
    }
    tnear = t0;
    return _mm_movemask_ps(_mm_cmple_ps(t0, t1));
}

}  // namespace bvh_detail

template <int W>
template <typename Leaf>
void Bvh<W>::closest(const BvhRay& r, const float& t_max, Leaf&& leaf) const {
    static_assert(W == 4, "the 8-wide tree is traversed by the kernels in mesh_bvh_kernels.h");
    if (root_ == Bvh4Node::kEmpty) return;
    // As the mesh kernels (mesh_bvh_kernels.inl): down to the nearest hit child without the
    // stack; the others pushed farthest first, references and distances in two arrays so that
    // a pop reads back exactly what a push wrote (no store-forwarding stall).
    std::uint32_t stack_ref[bvh_detail::kStackSize];
    float stack_t[bvh_detail::kStackSize];
    int top = 0;
    std::uint32_t cur = root_;
    for (;;) {
        while (!(cur & Bvh4Node::kLeaf)) {
            const Bvh4Node& n = nodes_[cur];
            __m128 tnear;
            unsigned mask = static_cast<unsigned>(bvh_detail::hit_boxes(n, r, _mm_set1_ps(t_max), tnear));
            if (mask == 0) {
                cur = Bvh4Node::kEmpty;
                break;
            }
            int i = __builtin_ctz(mask);
            mask &= mask - 1;
            if (mask == 0) {
                cur = n.child[i];
                continue;
            }
            alignas(16) float tn[4];
            _mm_store_ps(tn, tnear);
            const int base = top;
            for (;;) {
                const std::uint32_t ref = n.child[i];
                const float t = tn[i];
                if (!(ref & Bvh4Node::kLeaf)) _mm_prefetch(reinterpret_cast<const char*>(&nodes_[ref]), _MM_HINT_T0);
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
            cur = stack_ref[--top];
        }
        if (cur != Bvh4Node::kEmpty) leaf(Bvh4Node::leaf_first(cur), Bvh4Node::leaf_count(cur));
        for (;;) {  // the next entry nearer than the nearest hit so far
            if (top == 0) return;
            --top;
            if (stack_t[top] <= t_max) break;
        }
        cur = stack_ref[top];
    }
}

template <int W>
template <typename Leaf>
bool Bvh<W>::any(const BvhRay& r, float t_max, Leaf&& leaf) const {
    static_assert(W == 4, "the 8-wide tree is traversed by the kernels in mesh_bvh_kernels.h");
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
