#include "glint/accel/bvh.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <optional>
#include <stdexcept>

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

bool finite_box(const Bounds3& b) {
    for (int a = 0; a < 3; ++a)
        if (!std::isfinite(b.lo[a]) || !std::isfinite(b.hi[a]) || b.lo[a] > b.hi[a]) return false;
    return true;
}

struct Range {
    std::uint32_t begin = 0, end = 0;
    Bounds3 bounds, centroids;
    std::uint32_t count() const { return end - begin; }
};

class Builder {
public:
    Builder(std::span<const Bounds3> bounds, const BvhBuildOptions& options,
            std::vector<std::uint32_t>& order, std::vector<Bvh4Node>& nodes)
        : bounds_(bounds), options_(options), order_(order), nodes_(nodes) {
        centroid_.resize(bounds.size());
        for (std::size_t i = 0; i < bounds.size(); ++i)
            centroid_[i] = bounds[i].lo + (bounds[i].hi - bounds[i].lo) * 0.5f;
    }

    std::uint32_t build(const Range& r, int depth) {
        max_depth_seen(depth);
        std::array<Range, 4> child{r};
        std::array<bool, 4> final{};
        int n = 1;
        while (n < 4) {
            int pick = -1;
            float best_area = -1;
            for (int i = 0; i < n; ++i) {
                if (final[i] || child[i].count() < 2) continue;
                const float a = half_area(child[i].bounds);
                if (a > best_area) best_area = a, pick = i;
            }
            if (pick < 0) break;
            const auto s = split(child[pick], depth);
            if (!s) {
                final[pick] = true;
                continue;
            }
            child[pick] = s->first;
            child[n++] = s->second;
        }
        if (n == 1) return Bvh4Node::make_leaf(r.begin, r.count());

        const std::uint32_t index = next_node_.fetch_add(1);
        Bvh4Node& node = nodes_[index];
        for (int i = 0; i < 4; ++i) {
            const Bounds3 b = i < n ? child[i].bounds : Bounds3{};
            node.lo_x[i] = b.lo.x, node.hi_x[i] = b.hi.x;
            node.lo_y[i] = b.lo.y, node.hi_y[i] = b.hi.y;
            node.lo_z[i] = b.lo.z, node.hi_z[i] = b.hi.z;
            node.child[i] = Bvh4Node::kEmpty;
        }
        const auto make_child = [&](int i) {
            nodes_[index].child[i] =
                final[i] || child[i].count() == 1
                    ? Bvh4Node::make_leaf(child[i].begin, child[i].count())
                    : build(child[i], depth + 1);
        };
        if (options_.parallel && r.count() > kParallelThreshold)
            tbb::parallel_for(0, n, make_child);
        else
            for (int i = 0; i < n; ++i) make_child(i);
        return index;
    }

    std::uint32_t node_count() const { return next_node_.load(); }
    int depth() const { return depth_.load(); }

private:
    void max_depth_seen(int d) {
        int cur = depth_.load();
        while (d > cur && !depth_.compare_exchange_weak(cur, d)) {
        }
    }

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
        const bool must_split = count > static_cast<std::uint32_t>(options_.max_leaf_size);
        if (depth < bvh_detail::kMaxDepth - 20) {
            struct Bin {
                Bounds3 b;
                std::uint32_t n = 0;
            };
            float best_cost = std::numeric_limits<float>::infinity();
            int best_axis = -1, best_split = 0;
            for (int axis = 0; axis < 3; ++axis) {
                const float lo = r.centroids.lo[axis], extent = r.centroids.hi[axis] - lo;
                if (!(extent > 0)) continue;
                const float scale = kBins / extent;
                std::array<Bin, kBins> bins{};
                for (std::uint32_t i = r.begin; i < r.end; ++i) {
                    const std::uint32_t p = order_[i];
                    const int b = std::min(kBins - 1, static_cast<int>((centroid_[p][axis] - lo) * scale));
                    bins[b].b = merge(bins[b].b, bounds_[p]);
                    ++bins[b].n;
                }
                // Sweep from the right, then from the left.
                std::array<float, kBins> right_cost{};
                Bounds3 acc;
                std::uint32_t acc_n = 0;
                for (int b = kBins - 1; b > 0; --b) {
                    acc = merge(acc, bins[b].b);
                    acc_n += bins[b].n;
                    right_cost[b] = half_area(acc) * acc_n;
                }
                acc = Bounds3{};
                acc_n = 0;
                for (int b = 0; b < kBins - 1; ++b) {
                    acc = merge(acc, bins[b].b);
                    acc_n += bins[b].n;
                    if (acc_n == 0 || acc_n == count) continue;
                    const float cost = half_area(acc) * acc_n + right_cost[b + 1];
                    if (cost < best_cost) best_cost = cost, best_axis = axis, best_split = b + 1;
                }
            }
            if (best_axis >= 0) {
                const float parent = half_area(r.bounds);
                const float sah = options_.traversal_cost + (parent > 0 ? best_cost / parent : count);
                if (!must_split && sah >= static_cast<float>(count)) return std::nullopt;
                const float lo = r.centroids.lo[best_axis];
                const float scale = kBins / (r.centroids.hi[best_axis] - lo);
                const auto mid = std::partition(
                    order_.begin() + r.begin, order_.begin() + r.end, [&](std::uint32_t p) {
                        return std::min(kBins - 1,
                                        static_cast<int>((centroid_[p][best_axis] - lo) * scale)) <
                               best_split;
                    });
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

public:
    Range root_range(std::uint32_t n) const { return make_range(0, n); }

private:
    std::span<const Bounds3> bounds_;
    const BvhBuildOptions& options_;
    std::vector<std::uint32_t>& order_;
    std::vector<Bvh4Node>& nodes_;
    std::vector<Point3> centroid_;
    std::atomic<std::uint32_t> next_node_{0};
    std::atomic<int> depth_{0};
};

}  // namespace

void Bvh4::build(std::span<const Bounds3> bounds, const BvhBuildOptions& options_in) {
    BvhBuildOptions options = options_in;
    options.max_leaf_size = std::clamp(options.max_leaf_size, 1, (1 << Bvh4Node::kCountBits) - 1);
    order_.clear();
    nodes_.clear();
    root_ = Bvh4Node::kEmpty;
    bounds_ = Bounds3{};
    depth_ = 0;
    order_.reserve(bounds.size());
    for (std::uint32_t i = 0; i < bounds.size(); ++i)
        if (finite_box(bounds[i])) order_.push_back(i);
    skipped_ = bounds.size() - order_.size();
    if (order_.empty()) return;
    // Leaves address primitives with 27 bits (Bvh4Node::make_leaf).
    if (order_.size() >= (std::size_t(1) << (32 - 1 - Bvh4Node::kCountBits)) - 16)
        throw std::length_error("too many primitives for one BVH (at most 134 million)");
    nodes_.resize(order_.size());  // a 4-wide tree over n leaves-worth of primitives has < n nodes
    Builder builder(bounds, options, order_, nodes_);
    const Range root = builder.root_range(static_cast<std::uint32_t>(order_.size()));
    bounds_ = root.bounds;
    root_ = builder.build(root, 0);
    nodes_.resize(builder.node_count());
    nodes_.shrink_to_fit();
    depth_ = builder.depth() + 1;
}

}  // namespace glint
