#include "glint/accel/mesh_bvh.h"

#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <string>

#include "glint/accel/mesh_bvh_kernels.h"

namespace glint {

const char* simd_isa_name(SimdIsa isa) {
    switch (isa) {
        case SimdIsa::kSse4: return "sse4";
        case SimdIsa::kAvx2: return "avx2";
        case SimdIsa::kAvx512: return "avx512";
    }
    return "?";
}

bool cpu_supports(SimdIsa isa) {
    __builtin_cpu_init();
    switch (isa) {
        case SimdIsa::kSse4: return __builtin_cpu_supports("sse4.2");
        case SimdIsa::kAvx2:
            return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") &&
                   __builtin_cpu_supports("bmi2");
        case SimdIsa::kAvx512:
            return cpu_supports(SimdIsa::kAvx2) && __builtin_cpu_supports("avx512f") &&
                   __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512bw") &&
                   __builtin_cpu_supports("avx512dq");
    }
    return false;
}

SimdIsa default_simd_isa() {
    SimdIsa best = cpu_supports(SimdIsa::kAvx512) ? SimdIsa::kAvx512
                   : cpu_supports(SimdIsa::kAvx2) ? SimdIsa::kAvx2
                                                  : SimdIsa::kSse4;
    if (const char* env = std::getenv("GLINT_ISA"); env && *env) {
        const std::string s = env;
        SimdIsa wanted;
        if (s == "sse4")
            wanted = SimdIsa::kSse4;
        else if (s == "avx2")
            wanted = SimdIsa::kAvx2;
        else if (s == "avx512")
            wanted = SimdIsa::kAvx512;
        else
            throw std::runtime_error("GLINT_ISA=" + s + ": expected sse4, avx2 or avx512");
        if (static_cast<int>(wanted) < static_cast<int>(best)) best = wanted;
    }
    return best;
}

bool intersect_packet_lane(const TrianglePacket& p, int lane, const WatertightRay& ray, TriangleHit& out) {
    const auto [p0, p1, p2] = packet_triangle(&p.p[0][0][lane]);
    const auto h = intersect_triangle(p0, p1, p2, ray);
    if (h) out = *h;
    return h.has_value();
}

namespace {

/// The bounds of the parts of triangle `prim` on either side of the plane x[axis] = pos, each
/// within `box` (the part of the triangle the reference stands for). The points where edges
/// cross the plane are padded by 2^-20 of their coordinates' magnitude, more than their
/// round-off, so that no point of the real triangle is left outside both boxes.
void clip_triangle(const void* context, std::uint32_t prim, const Bounds3& box, int axis, float pos,
                   Bounds3& left, Bounds3& right) {
    const auto& mesh = *static_cast<const TriangleMesh*>(context);
    const auto [p0, p1, p2] = mesh.vertices(prim);
    const Point3 v[3] = {p0, p1, p2};
    left = right = Bounds3{};
    for (int i = 0; i < 3; ++i) {
        const Point3 a = v[i], b = v[(i + 1) % 3];
        if (a[axis] <= pos) left.extend(a);
        if (a[axis] >= pos) right.extend(a);
        if ((a[axis] < pos && b[axis] > pos) || (a[axis] > pos && b[axis] < pos)) {
            const float t = (pos - a[axis]) / (b[axis] - a[axis]);
            Point3 lo, hi;
            for (int k = 0; k < 3; ++k) {
                const float q = a[k] + t * (b[k] - a[k]);
                const float pad = (std::abs(a[k]) + std::abs(b[k])) * 0x1p-20f;
                lo[k] = q - pad;
                hi[k] = q + pad;
            }
            lo[axis] = hi[axis] = pos;
            left.extend(lo), left.extend(hi);
            right.extend(lo), right.extend(hi);
        }
    }
    const auto clamp_to_box = [&](Bounds3& b) {
        if (b.empty()) return;
        for (int k = 0; k < 3; ++k) {
            b.lo[k] = std::max(b.lo[k], box.lo[k]);
            b.hi[k] = std::min(b.hi[k], box.hi[k]);
        }
        if (b.empty()) b = Bounds3{};
    };
    clamp_to_box(left);
    clamp_to_box(right);
    if (!left.empty()) left.hi[axis] = std::min(left.hi[axis], pos);
    if (!right.empty()) right.lo[axis] = std::max(right.lo[axis], pos);
}

/// Repacks the tree's leaves (ranges of order) as packets of four triangles.
template <int W>
void pack_leaves(Bvh<W>& bvh, const TriangleMesh& mesh, std::vector<TrianglePacket>& packets) {
    using Node = BvhNode<W>;
    // Counted first, so that the vector is allocated once at its size (no copy to shrink it).
    std::size_t total = 0;
    bvh.remap_leaves([&](std::uint32_t first, std::uint32_t count) {
        total += (count + 3) / 4;
        return Node::make_leaf(first, count);
    });
    packets = std::vector<TrianglePacket>();  // no capacity left from an earlier build
    packets.reserve(total);
    const auto& order = bvh.order();
    bvh.remap_leaves([&](std::uint32_t first, std::uint32_t count) {
        const auto p0 = static_cast<std::uint32_t>(packets.size());
        for (std::uint32_t k = 0; k < count; k += 4) {
            TrianglePacket& p = packets.emplace_back();
            for (int lane = 0; lane < 4; ++lane) {
                const std::uint32_t prim = order[first + std::min(k + lane, count - 1)];
                const auto [a, b, c] = mesh.vertices(prim);
                const Point3 v[3] = {a, b, c};
                for (int i = 0; i < 3; ++i)
                    for (int axis = 0; axis < 3; ++axis) p.p[i][axis][lane] = v[i][axis];
                p.prim[lane] = prim;
            }
        }
        return Node::make_leaf(p0, static_cast<std::uint32_t>(packets.size()) - p0);
    });
}

}  // namespace

void MeshBvh::build(const TriangleMesh& mesh, const BvhBuildOptions& options_in, SimdIsa isa) {
    BvhBuildOptions options = options_in;
    options.block_size = 4;  // the leaves' packets
    const std::uint32_t n = mesh.triangle_count();
    std::vector<Bounds3> boxes(n);
    for (std::uint32_t t = 0; t < n; ++t) {
        const auto [p0, p1, p2] = mesh.vertices(t);
        boxes[t].extend(p0);
        boxes[t].extend(p1);
        boxes[t].extend(p2);
    }
    if (!cpu_supports(isa)) throw std::runtime_error(std::string("this CPU cannot run the ") + simd_isa_name(isa) + " kernel");
    isa_ = isa;
    width_ = isa == SimdIsa::kSse4 ? 4 : 8;
    bvh4_ = Bvh4{};
    bvh8_ = Bvh8{};
    if (width_ == 8) {
        bvh8_.build(boxes, options, clip_triangle, &mesh);
        pack_leaves(bvh8_, mesh, packets_);
    } else {
        bvh4_.build(boxes, options, clip_triangle, &mesh);
        pack_leaves(bvh4_, mesh, packets_);
    }
}

MeshTraversal MeshBvh::view() const {
    if (width_ == 8) return {bvh8_.nodes().data(), bvh8_.root(), packets_.data()};
    return {bvh4_.nodes().data(), bvh4_.root(), packets_.data()};
}

std::optional<MeshHit> MeshBvh::closest(const Ray& ray, const HitFilter* filter) const {
    MeshTraversal v = view();
    v.filter = filter;
    MeshHit h;
    bool found = false;
    switch (isa_) {
        case SimdIsa::kSse4: found = mesh_closest_sse4(v, ray, h); break;
        case SimdIsa::kAvx2: found = mesh_closest_avx2(v, ray, h); break;
        case SimdIsa::kAvx512: found = mesh_closest_avx512(v, ray, h); break;
    }
    return found ? std::optional<MeshHit>(h) : std::nullopt;
}

bool MeshBvh::any(const Ray& ray, const HitFilter* filter) const {
    MeshTraversal v = view();
    v.filter = filter;
    switch (isa_) {
        case SimdIsa::kSse4: return mesh_any_sse4(v, ray);
        case SimdIsa::kAvx2: return mesh_any_avx2(v, ray);
        case SimdIsa::kAvx512: return mesh_any_avx512(v, ray);
    }
    return false;
}

}  // namespace glint
