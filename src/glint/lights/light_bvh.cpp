#include "glint/lights/light_bvh.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

namespace glint {

namespace {

constexpr float kPi = std::numbers::pi_v<float>;
constexpr float kOneMinusEpsilon = 0x1.fffffep-1f;

float safe_acos(float c) { return std::acos(std::clamp(c, -1.0f, 1.0f)); }
float sin_of(float c) { return std::sqrt(std::max(0.0f, 1 - c * c)); }

// (cos, sin) of max(0, a - b) for angles a, b in [0, pi] given by their cosines and sines.
struct CosSin {
    float c, s;
};
CosSin minus_clamped(CosSin a, CosSin b) {
    if (a.c >= b.c) return {1, 0};  // a <= b
    return {a.c * b.c + a.s * b.s, a.s * b.c - a.c * b.s};
}

// v rotated by `angle` about the unit `axis` (Rodrigues).
Vector3 rotate(Vector3 v, Vector3 axis, float angle) {
    const float c = std::cos(angle), s = std::sin(angle);
    return v * c + cross(axis, v) * s + axis * (dot(axis, v) * (1 - c));
}

Bounds3 unite(const Bounds3& a, const Bounds3& b) {
    Bounds3 r = a;
    if (!b.empty()) {
        r.extend(b.lo);
        r.extend(b.hi);
    }
    return r;
}

Point3 box_centre(const Bounds3& b) { return b.lo + (b.hi - b.lo) * 0.5f; }

// Half the surface area of the box, each side widened by `pad` so that flat and point-like
// clusters still compare by their extent in the other axes.
float half_area(const Bounds3& b, float pad) {
    const Vector3 e = b.hi - b.lo + Vector3{pad, pad, pad};
    return e.x * e.y + e.y * e.z + e.z * e.x;
}

}  // namespace

LightBounds unite(const LightBounds& a, const LightBounds& b) {
    if (!(a.phi > 0)) return b;
    if (!(b.phi > 0)) return a;
    LightBounds r;
    r.box = unite(a.box, b.box);
    r.phi = a.phi + b.phi;
    r.cos_e = std::min(a.cos_e, b.cos_e);
    r.two_sided = a.two_sided || b.two_sided;
    // The bounding cone of the two cones.
    const float theta_a = safe_acos(a.cos_o), theta_b = safe_acos(b.cos_o);
    const float theta_d = safe_acos(dot(a.w, b.w));
    if (std::min(theta_d + theta_b, kPi) <= theta_a) {
        r.w = a.w, r.cos_o = a.cos_o;
    } else if (std::min(theta_d + theta_a, kPi) <= theta_b) {
        r.w = b.w, r.cos_o = b.cos_o;
    } else {
        const float theta_o = 0.5f * (theta_a + theta_d + theta_b);
        const Vector3 axis = cross(a.w, b.w);
        const float len = length(axis);
        if (theta_o >= kPi || !(len > 1e-7f)) {
            r.w = a.w, r.cos_o = -1;  // every direction
        } else {
            r.w = normalize(rotate(a.w, axis / len, theta_o - theta_a));
            r.cos_o = std::cos(theta_o);
        }
    }
    return r;
}

PackedLightBounds PackedLightBounds::from(const LightBounds& b) {
    PackedLightBounds r;
    r.centre = box_centre(b.box);
    r.radius = 0.5f * length(b.box.hi - b.box.lo);
    r.w = b.w;
    r.phi = b.phi;
    r.cos_o = b.cos_o;
    r.sin_o = sin_of(b.cos_o);
    r.cos_e = b.cos_e;
    r.two_sided = b.two_sided;
    return r;
}

float importance(const LightBounds& b, Point3 p, Normal3 n) { return importance(PackedLightBounds::from(b), p, n); }

namespace {

// importance(PackedLightBounds), inlined into the traversal so that the two children's
// computations interleave.
[[gnu::always_inline]] inline float importance_inline(const PackedLightBounds& b, Point3 p, Normal3 n) {
    const Vector3 d = p - b.centre;  // from the lights towards p
    const float d2 = dot(d, d);
    const float r2 = b.radius * b.radius;
    const float inv_d = d2 > 0 ? 1 / std::sqrt(d2) : 0;
    // The cone of directions from p that holds the box's bounding sphere: everything when p is
    // inside.
    CosSin bound{-1, 0};
    if (d2 > r2) {
        const float sin_b = std::min(b.radius * inv_d, 1.0f);
        bound = {std::sqrt(1 - sin_b * sin_b), sin_b};
    }
    float emitted = 1;
    if (b.cos_o > -1) {  // not every direction: how far outside the cone is p?
        float cos_w = std::clamp(dot(b.w, d) * inv_d, -1.0f, 1.0f);
        if (b.two_sided) cos_w = std::abs(cos_w);
        emitted = minus_clamped(minus_clamped({cos_w, sin_of(cos_w)}, {b.cos_o, b.sin_o}), bound).c;
        if (emitted < b.cos_e) return 0;
    }
    float cos_i = 1;
    if (n.x != 0 || n.y != 0 || n.z != 0) {
        const float ci = std::min(std::abs(dot(n, d)) * inv_d, 1.0f);
        cos_i = minus_clamped({ci, sin_of(ci)}, bound).c;
    }
    // Nearer than the box's own size the inverse square says nothing: clamp, and keep finite.
    const float dist2 = std::max({d2, r2, std::numeric_limits<float>::min()});
    return std::min(b.phi * emitted * cos_i / dist2, std::numeric_limits<float>::max());
}

}  // namespace

float importance(const PackedLightBounds& b, Point3 p, Normal3 n) { return importance_inline(b, p, n); }

float orientation_measure(float cos_o, float cos_e) {
    const float theta_o = safe_acos(cos_o);
    const float theta_w = std::min(theta_o + safe_acos(cos_e), kPi);
    const float sin_o = sin_of(cos_o);
    return 2 * kPi * (1 - cos_o) +
           0.5f * kPi * (2 * theta_w * sin_o - std::cos(theta_o - 2 * theta_w) - 2 * theta_o * sin_o + cos_o);
}

void LightBvh::build(const std::vector<LightBounds>& bounds) {
    nodes_.clear();
    trail_.assign(bounds.size(), 0);
    depth_.assign(bounds.size(), 0xff);
    std::vector<Item> items;
    for (std::uint32_t i = 0; i < bounds.size(); ++i) {
        if (bounds[i].phi > 0 && std::isfinite(bounds[i].phi) && !bounds[i].box.empty())
            items.push_back({bounds[i], box_centre(bounds[i].box), i});
    }
    if (items.empty()) return;
    nodes_.reserve(2 * items.size() - 1);
    build_node(items, 0, items.size(), 0, 0);
}

// Splits by the surface area orientation heuristic over 12 buckets per axis: a side's cost is
// its phi times its cone's orientation measure times its box's area, an axis's divided by how
// long it is against the longest (Conty Estevez and Kulla's regularisation).
void LightBvh::build_node(std::vector<Item>& items, std::size_t begin, std::size_t end, int depth,
                          std::uint64_t trail) {
    const std::uint32_t me = static_cast<std::uint32_t>(nodes_.size());
    nodes_.emplace_back();
    LightBounds all;
    Bounds3 centroids;
    for (std::size_t i = begin; i < end; ++i) {
        all = unite(all, items[i].bounds);
        centroids.extend(items[i].centroid);
    }
    nodes_[me].bounds = PackedLightBounds::from(all);
    if (end - begin == 1) {
        nodes_[me].leaf = true;
        nodes_[me].index = items[begin].light;
        trail_[items[begin].light] = trail;
        depth_[items[begin].light] = static_cast<std::uint8_t>(depth);
        return;
    }
    constexpr int kBuckets = 12;
    const Vector3 extent = centroids.hi - centroids.lo;
    const float longest = std::max({extent.x, extent.y, extent.z});
    const float pad = 1e-3f * std::max(longest, max_abs_component(all.box.hi - all.box.lo));
    std::size_t mid = begin + (end - begin) / 2;
    // Without extent, and past depth 30 (the trail has 64 bits; halving 2^32 lights takes 32
    // more): halves by count.
    if (depth < 30 && longest > 0) {
        float best = std::numeric_limits<float>::infinity();
        int best_axis = -1, best_split = 0;
        const auto bucket_of = [&](const Item& it, int axis) {
            const int b = static_cast<int>(kBuckets * (it.centroid[axis] - centroids.lo[axis]) / extent[axis]);
            return std::clamp(b, 0, kBuckets - 1);
        };
        for (int axis = 0; axis < 3; ++axis) {
            if (!(extent[axis] > 0)) continue;
            std::array<LightBounds, kBuckets> bucket{};
            for (std::size_t i = begin; i < end; ++i) {
                LightBounds& b = bucket[static_cast<std::size_t>(bucket_of(items[i], axis))];
                b = unite(b, items[i].bounds);
            }
            const auto cost = [&](const LightBounds& b) {
                return b.phi > 0 ? b.phi * orientation_measure(b.cos_o, b.cos_e) * half_area(b.box, pad) : 0.0f;
            };
            // Costs of the right sides, from the right.
            std::array<float, kBuckets> right{};
            LightBounds acc;
            for (int s = kBuckets - 1; s > 0; --s) {
                acc = unite(acc, bucket[static_cast<std::size_t>(s)]);
                right[static_cast<std::size_t>(s)] = cost(acc);
            }
            acc = LightBounds{};
            const float regularise = longest / extent[axis];
            for (int s = 1; s < kBuckets; ++s) {
                acc = unite(acc, bucket[static_cast<std::size_t>(s - 1)]);
                const float c = (cost(acc) + right[static_cast<std::size_t>(s)]) * regularise;
                if (c < best) best = c, best_axis = axis, best_split = s;
            }
        }
        if (best_axis >= 0) {
            const auto first_end = std::partition(
                items.begin() + static_cast<std::ptrdiff_t>(begin), items.begin() + static_cast<std::ptrdiff_t>(end),
                [&](const Item& it) { return bucket_of(it, best_axis) < best_split; });
            const auto m = static_cast<std::size_t>(first_end - items.begin());
            if (m > begin && m < end) mid = m;
        }
    }
    build_node(items, begin, mid, depth + 1, trail);
    nodes_[me].index = static_cast<std::uint32_t>(nodes_.size());
    build_node(items, mid, end, depth + 1, trail | (std::uint64_t{1} << depth));
}

namespace {

// The probability of an inner node's first child (the ratio in double: two importances near
// float's maximum do not overflow their sum). Callers handle both being 0 first.
double first_share(float a, float b) { return static_cast<double>(a) / (static_cast<double>(a) + b); }

}  // namespace

std::uint32_t LightBvh::sample(Point3 p, Normal3 n, float u, float* pmf) const {
    *pmf = 0;
    if (nodes_.empty()) return kNoBvhLight;
    float prob = 1;
    std::uint32_t i = 0;
    while (!nodes_[i].leaf) {
        const std::uint32_t a = i + 1, b = nodes_[i].index;
        const float ia = importance_inline(nodes_[a].bounds, p, n), ib = importance_inline(nodes_[b].bounds, p, n);
        if (!(ia > 0 || ib > 0)) return kNoBvhLight;
        const float pa = static_cast<float>(first_share(ia, ib));
        if (u < pa) {
            u = std::min(u / pa, kOneMinusEpsilon);
            prob *= pa;
            i = a;
        } else {
            u = std::min((u - pa) / (1 - pa), kOneMinusEpsilon);
            prob *= 1 - pa;
            i = b;
        }
    }
    *pmf = prob;
    return nodes_[i].index;
}

float LightBvh::pmf(Point3 p, Normal3 n, std::uint32_t light) const {
    if (light >= depth_.size() || depth_[light] == 0xff) return 0;
    const std::uint64_t trail = trail_[light];
    float prob = 1;
    std::uint32_t i = 0;
    for (int k = 0; k < depth_[light]; ++k) {
        const std::uint32_t a = i + 1, b = nodes_[i].index;
        const float ia = importance_inline(nodes_[a].bounds, p, n), ib = importance_inline(nodes_[b].bounds, p, n);
        if (!(ia > 0 || ib > 0)) return 0;
        const float pa = static_cast<float>(first_share(ia, ib));
        if ((trail >> k) & 1) {
            prob *= 1 - pa;
            i = b;
        } else {
            prob *= pa;
            i = a;
        }
    }
    return prob;
}

}  // namespace glint
