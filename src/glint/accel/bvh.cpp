#include "glint/accel/bvh.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <type_traits>

namespace glint {

namespace {

constexpr int kBins = 32;
constexpr std::uint32_t kParallelThreshold = 4096;  // primitives below which a subtree is serial

float half_area(const Bounds3& b) {
    if (b.empty()) return 0;
    const Vector3 d = b.hi - b.lo;
    return d.x * d.y + d.y * d.z + d.z * d.x;
}

Bounds3 merge(Bounds3 a, const Bounds3& b) {
    if (b.empty()) return a;
    a.extend(b.lo);
    a.extend(b.hi);
    return a;
}

Bounds3 intersection(const Bounds3& a, const Bounds3& b) {
    Bounds3 r;
    for (int i = 0; i < 3; ++i) {
        r.lo[i] = std::max(a.lo[i], b.lo[i]);
        r.hi[i] = std::min(a.hi[i], b.hi[i]);
    }
    return r;
}

// Halves first: hi - lo overflows to infinity for a box near float max (a sphere of radius 1e38).
Point3 centre(const Bounds3& b) {
    return {b.lo.x * 0.5f + b.hi.x * 0.5f, b.lo.y * 0.5f + b.hi.y * 0.5f, b.lo.z * 0.5f + b.hi.z * 0.5f};
}

/// Which of kBins equal bins over [lo, lo + extent] holds x, in double: a float extent or
/// scale overflows for boxes near float max, and a NaN or out-of-range bin would index outside
/// the bins. Always in 0 … kBins-1.
int bin_index(float x, float lo, double extent) {
    const double t = (static_cast<double>(x) - lo) * (kBins / extent);
    return t >= kBins - 1 ? kBins - 1 : t > 0 ? static_cast<int>(t) : 0;
}

/// The extent of an axis of a box, in double (finite for every finite box).
double extent_of(const Bounds3& b, int axis) { return static_cast<double>(b.hi[axis]) - b.lo[axis]; }

void max_into(std::atomic<int>& m, int d) {
    int cur = m.load();
    while (d > cur && !m.compare_exchange_weak(cur, d)) {
    }
}

/// The best binned-SAH object split of a set of `count` primitives whose centroids span
/// `centroids`; `each(f)` calls f(centroid, box) for every primitive of the set.
struct ObjectSplit {
    int axis = -1, bin = 0;
    float cost = std::numeric_limits<float>::infinity();  ///< A_L N_L + A_R N_R
    Bounds3 left, right;
    /// Whether a primitive with this centroid goes left.
    bool goes_left(Point3 c, const Bounds3& centroids) const {
        return bin_index(c[axis], centroids.lo[axis], extent_of(centroids, axis)) < bin;
    }
};

/// The SAH weight of n primitives tested `block` at a time.
float blocks(std::uint32_t n, int block) { return static_cast<float>((n + block - 1) / block); }

template <typename ForEach>
ObjectSplit find_object_split(const Bounds3& centroids, std::uint32_t count, int block, ForEach&& each) {
    struct Bin {
        Bounds3 b;
        std::uint32_t n = 0;
    };
    ObjectSplit best;
    for (int axis = 0; axis < 3; ++axis) {
        const float lo = centroids.lo[axis];
        const double extent = extent_of(centroids, axis);
        if (!(extent > 0) || !std::isfinite(extent)) continue;
        std::array<Bin, kBins> bins{};
        each([&](Point3 c, const Bounds3& box) {
            const int b = bin_index(c[axis], lo, extent);
            bins[b].b = merge(bins[b].b, box);
            ++bins[b].n;
        });
        // Sweep from the right, then from the left.
        std::array<float, kBins> right_cost{};
        std::array<Bounds3, kBins> right_box{};
        Bounds3 acc;
        std::uint32_t acc_n = 0;
        for (int b = kBins - 1; b > 0; --b) {
            acc = merge(acc, bins[b].b);
            acc_n += bins[b].n;
            right_cost[b] = half_area(acc) * blocks(acc_n, block);
            right_box[b] = acc;
        }
        acc = Bounds3{};
        acc_n = 0;
        for (int b = 0; b < kBins - 1; ++b) {
            acc = merge(acc, bins[b].b);
            acc_n += bins[b].n;
            if (acc_n == 0 || acc_n == count) continue;
            const float cost = half_area(acc) * blocks(acc_n, block) + right_cost[b + 1];
            if (cost < best.cost) best = {axis, b + 1, cost, acc, right_box[b + 1]};
        }
    }
    return best;
}

/// Splits the child with the largest area until there are W children or none can be split;
/// `split(set)` returns the two halves or nullopt (a leaf). Returns the number of children.
template <int W, typename Set, typename Split>
int split_into_children(std::array<Set, W>& child, std::array<bool, W>& final, Split&& split) {
    int n = 1;
    while (n < W) {
        int pick = -1;
        float best_area = -1;
        for (int i = 0; i < n; ++i) {
            if (final[i] || child[i].count() < 2) continue;
            const float a = half_area(child[i].bounds);
            if (a > best_area) best_area = a, pick = i;
        }
        if (pick < 0) break;
        auto s = split(child[pick]);
        if (!s) {
            final[pick] = true;
            continue;
        }
        child[pick] = std::move(s->first);
        child[n++] = std::move(s->second);
    }
    return n;
}

template <int W, typename Set>
void write_boxes(BvhNode<W>& node, const std::array<Set, W>& child, int n) {
    for (int i = 0; i < W; ++i) {
        const Bounds3 b = i < n ? child[i].bounds : Bounds3{};
        node.lo_x[i] = b.lo.x, node.hi_x[i] = b.hi.x;
        node.lo_y[i] = b.lo.y, node.hi_y[i] = b.hi.y;
        node.lo_z[i] = b.lo.z, node.hi_z[i] = b.hi.z;
        node.child[i] = BvhNode<W>::kEmpty;
    }
}

/// Whether the SAH prefers a leaf over a split of cost `split_cost` (A_L N_L + A_R N_R, N in
/// blocks).
bool leaf_is_cheaper(float split_cost, const Bounds3& bounds, std::uint32_t count, const BvhBuildOptions& o) {
    const float parent = half_area(bounds);
    const float leaf = blocks(count, o.block_size);
    const float sah = o.traversal_cost + (parent > 0 ? split_cost / parent : leaf);
    return sah >= leaf;
}

// ---------------------------------------------------------------------------------------------
// Object splits only: ranges of one id array, partitioned in place (the default builder).

struct Range {
    std::uint32_t begin = 0, end = 0;
    Bounds3 bounds, centroids;
    std::uint32_t count() const { return end - begin; }
};

template <int W>
class Builder {
public:
    using Node = BvhNode<W>;
    Builder(std::span<const Bounds3> bounds, const BvhBuildOptions& options,
            std::vector<std::uint32_t>& order, std::span<Node> nodes)
        : bounds_(bounds), options_(options), order_(order), nodes_(nodes) {
        centroid_.resize(bounds.size());
        for (std::size_t i = 0; i < bounds.size(); ++i) centroid_[i] = centre(bounds[i]);
    }

    std::uint32_t build(const Range& r, int depth) {
        max_into(depth_, depth);
        std::array<Range, W> child{r};
        std::array<bool, W> final{};
        const int n = split_into_children<W>(child, final, [&](const Range& c) { return split(c, depth); });
        if (n == 1) return Node::make_leaf(r.begin, r.count());

        const std::uint32_t index = next_node_.fetch_add(1);
        write_boxes<W>(nodes_[index], child, n);
        const auto make_child = [&](int i) {
            nodes_[index].child[i] = final[i] || child[i].count() == 1
                                         ? Node::make_leaf(child[i].begin, child[i].count())
                                         : build(child[i], depth + 1);
        };
        if (options_.parallel && r.count() > kParallelThreshold)
            tbb::parallel_for(0, n, make_child);
        else
            for (int i = 0; i < n; ++i) make_child(i);
        return index;
    }

    Range root_range(std::uint32_t n) const { return make_range(0, n); }
    std::uint32_t node_count() const { return next_node_.load(); }
    int depth() const { return depth_.load(); }

private:
    Range make_range(std::uint32_t begin, std::uint32_t end) const {
        Range r{begin, end, {}, {}};
        for (std::uint32_t i = begin; i < end; ++i) {
            r.bounds = merge(r.bounds, bounds_[order_[i]]);
            r.centroids.extend(centroid_[order_[i]]);
        }
        return r;
    }

    /// The binned-SAH split of r, or nullopt when a leaf is cheaper (and allowed).
    std::optional<std::pair<Range, Range>> split(const Range& r, int depth) {
        const std::uint32_t count = r.count();
        const bool must_split = count > static_cast<std::uint32_t>(options_.max_leaf_size) ||
                                (count > 1 && holds_one_alone(r));
        if (depth < bvh_detail::kMaxDepth - 20) {
            const ObjectSplit s = find_object_split(r.centroids, count, options_.block_size, [&](auto&& f) {
                for (std::uint32_t i = r.begin; i < r.end; ++i) f(centroid_[order_[i]], bounds_[order_[i]]);
            });
            if (s.axis >= 0) {
                if (!must_split && leaf_is_cheaper(s.cost, r.bounds, count, options_))
                    return std::nullopt;
                const auto mid = std::partition(order_.begin() + r.begin, order_.begin() + r.end,
                                                [&](std::uint32_t p) { return s.goes_left(centroid_[p], r.centroids); });
                const auto m = static_cast<std::uint32_t>(mid - order_.begin());
                if (m > r.begin && m < r.end) return std::pair{make_range(r.begin, m), make_range(m, r.end)};
            }
        }
        if (!must_split) return std::nullopt;
        // No usable SAH split (all centroids equal, or the tree is getting deep): halve by the
        // centroids' median on the widest axis, which bounds the depth by log2 of the count.
        const Vector3 ext = r.centroids.hi - r.centroids.lo;
        const int axis = ext.x >= ext.y && ext.x >= ext.z ? 0 : (ext.y >= ext.z ? 1 : 2);
        const std::uint32_t m = r.begin + count / 2;
        std::nth_element(order_.begin() + r.begin, order_.begin() + m, order_.begin() + r.end,
                         [&](std::uint32_t a, std::uint32_t b) {
                             return centroid_[a][axis] < centroid_[b][axis] ||
                                    (centroid_[a][axis] == centroid_[b][axis] && a < b);
                         });
        return std::pair{make_range(r.begin, m), make_range(m, r.end)};
    }

    /// Whether r holds a primitive that must have a leaf of its own (BvhBuildOptions::alone).
    bool holds_one_alone(const Range& r) const {
        if (options_.alone.empty()) return false;
        for (std::uint32_t i = r.begin; i < r.end; ++i)
            if (order_[i] < options_.alone.size() && options_.alone[order_[i]]) return true;
        return false;
    }

    std::span<const Bounds3> bounds_;
    const BvhBuildOptions& options_;
    std::vector<std::uint32_t>& order_;
    std::span<Node> nodes_;
    std::vector<Point3> centroid_;
    std::atomic<std::uint32_t> next_node_{0};
    std::atomic<int> depth_{0};
};

// ---------------------------------------------------------------------------------------------
// With spatial splits: sets of references (a primitive and the box of its part in the set),
// which a split may clip in two.

struct Ref {
    Bounds3 box;
    std::uint32_t prim;
};

struct RefSet {
    std::vector<Ref> refs;
    Bounds3 bounds, centroids;
    /// How many more references spatial splits in this subtree may make. Each split hands what
    /// is left to its two halves in proportion to their sizes (as Embree does), so the tree
    /// does not depend on which subtree a thread happens to build first.
    std::int64_t budget = 0;
    std::uint32_t count() const { return static_cast<std::uint32_t>(refs.size()); }
    static RefSet of(std::vector<Ref>&& refs, std::int64_t budget) {
        RefSet s{std::move(refs), {}, {}, budget};
        for (const Ref& r : s.refs) {
            s.bounds = merge(s.bounds, r.box);
            s.centroids.extend(centre(r.box));
        }
        return s;
    }
    /// The two halves of a split of a set whose remaining budget is `budget`.
    static std::pair<RefSet, RefSet> halves(std::vector<Ref>&& left, std::vector<Ref>&& right, std::int64_t budget) {
        budget = std::max<std::int64_t>(budget, 0);
        const auto nl = static_cast<std::int64_t>(left.size()), nr = static_cast<std::int64_t>(right.size());
        const std::int64_t bl = budget * nl / (nl + nr);
        return {of(std::move(left), bl), of(std::move(right), budget - bl)};
    }
};

template <int W>
class SpatialBuilder {
public:
    using Node = BvhNode<W>;
    SpatialBuilder(const BvhBuildOptions& options, BvhClipper clip, const void* context,
                   std::span<Node> nodes, float root_area)
        : options_(options), clip_(clip), context_(context), nodes_(nodes), min_overlap_(options.split_alpha * root_area) {}

    std::uint32_t build(RefSet&& r, int depth) {
        max_into(depth_, depth);
        const std::uint32_t total = r.count();
        std::array<RefSet, W> child{std::move(r)};
        std::array<bool, W> final{};
        const int n = split_into_children<W>(child, final, [&](RefSet& c) { return split(c, depth); });
        if (n == 1) return leaf(child[0]);

        const std::uint32_t index = next_node_.fetch_add(1);
        if (index >= nodes_.size()) throw std::length_error("BVH node pool exhausted");
        write_boxes<W>(nodes_[index], child, n);
        const auto make_child = [&](int i) {
            nodes_[index].child[i] = final[i] || child[i].count() == 1 ? leaf(child[i])
                                                                       : build(std::move(child[i]), depth + 1);
        };
        if (options_.parallel && total > kParallelThreshold)
            tbb::parallel_for(0, n, make_child);
        else
            for (int i = 0; i < n; ++i) make_child(i);
        return index;
    }

    /// Leaf references made during the build name an entry of leaves_; this gives them their
    /// place in `order`, visiting the tree depth first so that the result is the same for any
    /// scheduling of the build.
    std::uint32_t place_leaves(std::uint32_t ref, std::vector<std::uint32_t>& order) {
        if (ref & Node::kLeaf) {
            const auto& l = leaves_[ref & ~Node::kLeaf];
            const auto first = static_cast<std::uint32_t>(order.size());
            if (first + l.size() >= (std::size_t(1) << (32 - 1 - Node::kCountBits)) - 16)
                throw std::length_error("too many primitive references for one BVH (at most 134 million)");
            order.insert(order.end(), l.begin(), l.end());
            return Node::make_leaf(first, static_cast<std::uint32_t>(l.size()));
        }
        for (std::uint32_t& c : nodes_[ref].child)
            if (c != Node::kEmpty) c = place_leaves(c, order);
        return ref;
    }

    std::uint32_t node_count() const { return next_node_.load(); }
    int depth() const { return depth_.load(); }

private:
    std::uint32_t leaf(const RefSet& s) {
        std::vector<std::uint32_t> prims(s.refs.size());
        for (std::size_t i = 0; i < prims.size(); ++i) prims[i] = s.refs[i].prim;
        const std::lock_guard lock(mutex_);
        leaves_.push_back(std::move(prims));
        return Node::kLeaf | static_cast<std::uint32_t>(leaves_.size() - 1);
    }

    struct SpatialSplit {
        int axis = -1;
        float pos = 0, cost = std::numeric_limits<float>::infinity();
    };

    /// The bin boundary b (1..kBins-1) on axis a of the set's bounds.
    static float plane(const Bounds3& bounds, int a, int b) {
        return static_cast<float>(bounds.lo[a] + extent_of(bounds, a) * (static_cast<double>(b) / kBins));
    }

    SpatialSplit find_spatial_split(const RefSet& s) const {
        SpatialSplit best;
        for (int a = 0; a < 3; ++a) {
            const float lo = s.bounds.lo[a];
            const double extent = extent_of(s.bounds, a);
            if (!(extent > 0) || !std::isfinite(extent)) continue;
            std::array<Bounds3, kBins> box{};
            std::array<std::uint32_t, kBins> enter{}, exit{};
            const auto bin_of = [&](float x) { return bin_index(x, lo, extent); };
            for (const Ref& r : s.refs) {
                const int b0 = bin_of(r.box.lo[a]), b1 = bin_of(r.box.hi[a]);
                ++enter[b0];
                ++exit[b1];
                Bounds3 rest = r.box;
                for (int b = b0; b < b1; ++b) {  // chop the reference at each boundary it crosses
                    Bounds3 left, right;
                    clip_(context_, r.prim, rest, a, plane(s.bounds, a, b + 1), left, right);
                    box[b] = merge(box[b], left);
                    rest = right;
                }
                box[b1] = merge(box[b1], rest);
            }
            std::array<float, kBins> right_cost{};
            Bounds3 acc;
            std::uint32_t acc_n = 0;
            for (int b = kBins - 1; b > 0; --b) {
                acc = merge(acc, box[b]);
                acc_n += exit[b];
                right_cost[b] = half_area(acc) * blocks(acc_n, options_.block_size);
            }
            acc = Bounds3{};
            acc_n = 0;
            for (int b = 0; b < kBins - 1; ++b) {
                acc = merge(acc, box[b]);
                acc_n += enter[b];
                if (acc_n == 0 || right_cost[b + 1] == 0) continue;
                const float cost = half_area(acc) * blocks(acc_n, options_.block_size) + right_cost[b + 1];
                if (cost < best.cost) best = {a, plane(s.bounds, a, b + 1), cost};
            }
        }
        return best;
    }

    /// Splits at the plane, clipping references that straddle it, unless moving one whole to a
    /// side is cheaper ("reference unsplitting").
    std::optional<std::pair<RefSet, RefSet>> apply_spatial_split(const RefSet& s, const SpatialSplit& sp) {
        const int a = sp.axis;
        std::vector<Ref> left, right, straddle;
        Bounds3 lb, rb;
        for (const Ref& r : s.refs) {
            if (r.box.hi[a] <= sp.pos) {
                left.push_back(r);
                lb = merge(lb, r.box);
            } else if (r.box.lo[a] >= sp.pos) {
                right.push_back(r);
                rb = merge(rb, r.box);
            } else {
                straddle.push_back(r);
            }
        }
        // (Unsplitting weighs primitives one by one, as in Stich et al.)
        float nl = static_cast<float>(left.size() + straddle.size());
        float nr = static_cast<float>(right.size() + straddle.size());
        std::int64_t duplicates = 0;
        for (const Ref& r : straddle) {
            Bounds3 l, rr;
            clip_(context_, r.prim, r.box, a, sp.pos, l, rr);
            const float c_split = half_area(merge(lb, l)) * nl + half_area(merge(rb, rr)) * nr;
            const float c_left = half_area(merge(lb, r.box)) * nl + half_area(rb) * (nr - 1);
            const float c_right = half_area(lb) * (nl - 1) + half_area(merge(rb, r.box)) * nr;
            // Out of budget, a straddling reference goes whole to its cheaper side.
            const bool may_split = duplicates < s.budget;
            if (rr.empty() || ((c_left < c_split || !may_split) && c_left <= c_right)) {
                left.push_back(r);
                lb = merge(lb, r.box);
                nr -= 1;
            } else if (l.empty() || c_right < c_split || !may_split) {
                right.push_back(r);
                rb = merge(rb, r.box);
                nl -= 1;
            } else {
                left.push_back({l, r.prim});
                right.push_back({rr, r.prim});
                lb = merge(lb, l);
                rb = merge(rb, rr);
                ++duplicates;
            }
        }
        if (left.empty() || right.empty()) return std::nullopt;
        return RefSet::halves(std::move(left), std::move(right), s.budget - duplicates);
    }

    std::optional<std::pair<RefSet, RefSet>> split(const RefSet& s, int depth) {
        const std::uint32_t count = s.count();
        const bool must_split = count > static_cast<std::uint32_t>(options_.max_leaf_size);
        if (depth < bvh_detail::kMaxDepth - 20) {
            const ObjectSplit o = find_object_split(s.centroids, count, options_.block_size, [&](auto&& f) {
                for (const Ref& r : s.refs) f(centre(r.box), r.box);
            });
            SpatialSplit sp;
            if (s.budget > 0 && (o.axis < 0 || half_area(intersection(o.left, o.right)) > min_overlap_))
                sp = find_spatial_split(s);
            const float best = std::min(o.cost, sp.cost);
            if (best < std::numeric_limits<float>::infinity() && !must_split &&
                leaf_is_cheaper(best, s.bounds, count, options_))
                return std::nullopt;
            if (sp.cost < o.cost)
                if (auto r = apply_spatial_split(s, sp)) return r;
            if (o.axis >= 0) {
                std::vector<Ref> left, right;
                for (const Ref& r : s.refs) (o.goes_left(centre(r.box), s.centroids) ? left : right).push_back(r);
                if (!left.empty() && !right.empty()) return RefSet::halves(std::move(left), std::move(right), s.budget);
            }
        }
        if (!must_split) return std::nullopt;
        // As in the object builder: halve by the centroids' median on the widest axis.
        const Vector3 ext = s.centroids.hi - s.centroids.lo;
        const int axis = ext.x >= ext.y && ext.x >= ext.z ? 0 : (ext.y >= ext.z ? 1 : 2);
        std::vector<Ref> refs = s.refs;
        const auto m = refs.begin() + count / 2;
        std::nth_element(refs.begin(), m, refs.end(), [&](const Ref& x, const Ref& y) {
            const float cx = centre(x.box)[axis], cy = centre(y.box)[axis];
            return cx < cy || (cx == cy && x.prim < y.prim);
        });
        std::vector<Ref> right(m, refs.end());
        refs.erase(m, refs.end());
        return RefSet::halves(std::move(refs), std::move(right), s.budget);
    }

    const BvhBuildOptions& options_;
    BvhClipper clip_;
    const void* context_;
    std::span<Node> nodes_;
    float min_overlap_;
    std::mutex mutex_;
    std::vector<std::vector<std::uint32_t>> leaves_;
    std::atomic<std::uint32_t> next_node_{0};
    std::atomic<int> depth_{0};
};

/// The built nodes copied out in the order a traversal meets them: depth first, each node's
/// inner children placed side by side when the node is reached (as Embree allocates them), so
/// that siblings share cache lines and pages and a subtree lies in one stretch of memory. The
/// builders number nodes as they make them, and with two threads the two halves of the tree
/// interleave. Only the node indices change: every box and every child order stays, so every
/// traversal visits the same boxes in the same order. Returns the new root reference.
template <int W>
std::uint32_t lay_out_nodes(const BvhNode<W>* pool, std::uint32_t count, std::uint32_t root,
                            std::vector<BvhNode<W>>& out) {
    using Node = BvhNode<W>;
    out.clear();
    if (root & Node::kLeaf) return root;
    out.reserve(count);
    out.push_back(pool[root]);
    std::vector<std::uint32_t> pending{0};  // placed nodes whose children still name pool nodes
    while (!pending.empty()) {
        const std::uint32_t at = pending.back();
        pending.pop_back();
        const auto first = static_cast<std::uint32_t>(out.size());
        for (int i = 0; i < W; ++i) {
            const std::uint32_t c = out[at].child[i];
            if (c & Node::kLeaf) continue;
            out[at].child[i] = static_cast<std::uint32_t>(out.size());
            out.push_back(pool[c]);
        }
        for (auto k = static_cast<std::uint32_t>(out.size()); k-- > first;) pending.push_back(k);  // first child first
    }
    return 0;
}

}  // namespace

template <int W>
void Bvh<W>::build(std::span<const Bounds3> bounds, const BvhBuildOptions& options_in, BvhClipper clipper,
                   const void* clip_context) {
    // The builders write nodes into a pool sized for the worst case (a node per primitive), of
    // which a mesh's tree uses a few percent (leaves hold several triangles: 56,985 nodes for a
    // lat-long sphere of 998,000 triangles at W = 8). The pool is left uninitialised (new[] of a
    // trivial type), so only the pages of the nodes written are ever touched; a vector resized to
    // the worst case zeroed all of it (224 MB for a million triangles at W = 8), and the build of
    // such a mesh took 1.8 times as long with one thread, 2.6 times with two (docs/benchmarks.md).
    static_assert(std::is_trivially_default_constructible_v<Node>);
    using NodePool = std::unique_ptr<Node[]>;
    BvhBuildOptions options = options_in;
    options.max_leaf_size = std::clamp(options.max_leaf_size, 1, (1 << Node::kCountBits) - 1);
    order_.clear();
    nodes_.clear();
    root_ = Node::kEmpty;
    bounds_ = Bounds3{};
    depth_ = 0;
    order_.reserve(bounds.size());
    for (std::uint32_t i = 0; i < bounds.size(); ++i)
        if (bounds[i].finite()) order_.push_back(i);
    skipped_ = bounds.size() - order_.size();
    if (order_.empty()) return;
    // Leaves address primitives with 27 bits (BvhNode::make_leaf).
    if (order_.size() >= (std::size_t(1) << (32 - 1 - Node::kCountBits)) - 16)
        throw std::length_error("too many primitives for one BVH (at most 134 million)");

    if (options.spatial_splits && clipper) {
        std::vector<Ref> refs(order_.size());
        for (std::size_t i = 0; i < refs.size(); ++i) refs[i] = {bounds[order_[i]], order_[i]};
        const auto budget = static_cast<std::int64_t>(std::max(0.0f, options.max_duplication) *
                                                      static_cast<double>(refs.size()));
        RefSet root = RefSet::of(std::move(refs), budget);
        bounds_ = root.bounds;
        // A W-wide tree over m references has fewer than m nodes, and m <= n + budget.
        const std::size_t capacity = order_.size() + static_cast<std::size_t>(budget) + 1;
        const NodePool pool(new Node[capacity]);
        SpatialBuilder<W> builder(options, clipper, clip_context, std::span<Node>(pool.get(), capacity),
                                  half_area(bounds_));
        const std::uint32_t root_ref = builder.build(std::move(root), 0);
        order_.clear();
        root_ = lay_out_nodes<W>(pool.get(), builder.node_count(), builder.place_leaves(root_ref, order_), nodes_);
        depth_ = builder.depth() + 1;
    } else {
        const std::size_t capacity = order_.size();  // a W-wide tree over n leaves-worth of primitives has < n nodes
        const NodePool pool(new Node[capacity]);
        Builder<W> builder(bounds, options, order_, std::span<Node>(pool.get(), capacity));
        const Range root = builder.root_range(static_cast<std::uint32_t>(order_.size()));
        bounds_ = root.bounds;
        root_ = lay_out_nodes<W>(pool.get(), builder.node_count(), builder.build(root, 0), nodes_);
        depth_ = builder.depth() + 1;
    }
    order_.shrink_to_fit();
}

template <int W>
double Bvh<W>::sah_cost(float traversal_cost) const {
    if (empty()) return 0;
    const double root = std::max(1e-30f, half_area(bounds_));
    double cost = 0;
    const auto leaf_cost = [&](std::uint32_t ref, double area) {
        if (ref != Node::kEmpty) cost += area / root * Node::leaf_count(ref);
    };
    if (root_ & Node::kLeaf) {
        leaf_cost(root_, root);
        return cost;
    }
    cost += traversal_cost;  // the root
    // Depth first from the root, so that the sum's order (and so its rounding) is the tree's,
    // not the node array's (whose order depends on the build's scheduling).
    std::vector<std::uint32_t> stack{root_};
    while (!stack.empty()) {
        const Node& n = nodes_[stack.back()];
        stack.pop_back();
        for (int i = 0; i < W; ++i) {
            if (n.child[i] == Node::kEmpty) continue;
            Bounds3 b;
            b.lo = {n.lo_x[i], n.lo_y[i], n.lo_z[i]};
            b.hi = {n.hi_x[i], n.hi_y[i], n.hi_z[i]};
            if (n.child[i] & Node::kLeaf) {
                leaf_cost(n.child[i], half_area(b));
            } else {
                cost += traversal_cost * half_area(b) / root;
                stack.push_back(n.child[i]);
            }
        }
    }
    return cost;
}

template class Bvh<4>;
template class Bvh<8>;

}  // namespace glint
