#pragma once
// The bottom level: one BVH per mesh, in the mesh's object space, shared by all its instances.
// The tree is 8-wide where the CPU has AVX2 (traversed with AVX2, or with AVX-512 where present)
// and 4-wide with SSE otherwise, chosen when the BVH is built (SimdIsa). Leaves hold packets of
// four triangles (their vertices copied in leaf order, one SIMD lane per triangle), tested at once
// with the watertight test of shapes/triangle.h, lane for lane the same arithmetic, so every ISA
// gives the same hits bit for bit.
#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "glint/accel/bvh.h"
#include "glint/shapes/mesh.h"
#include "glint/shapes/triangle.h"

namespace glint {

struct MeshHit {
    TriangleHit hit;
    std::uint32_t prim;
    /// The hit triangle's vertices where the traversal found them: &packet.p[0][0][lane] of the
    /// packet it tested (vertex i, axis a at [12 i + 4 a]), still in cache when the hit is shaded.
    const float* vertices = nullptr;
};

/// Four triangles, structure of arrays: p[vertex][axis][lane]. A leaf's last packet repeats its
/// last triangle in the unused lanes (a repeated triangle gives the same hit, so it changes
/// nothing).
struct alignas(16) TrianglePacket {
    float p[3][3][4];
    std::uint32_t prim[4];
};
static_assert(sizeof(TrianglePacket) == 160);
static_assert(sizeof(TrianglePacket::p[0]) == 12 * sizeof(float));  // packet_triangle's stride

/// The triangle of one lane of a packet, from &packet.p[0][0][lane] (as MeshHit::vertices
/// holds it): vertex i, axis a at [12 i + 4 a].
inline std::array<Point3, 3> packet_triangle(const float* lane) {
    const auto vertex = [&](int v) { return Point3{lane[12 * v], lane[12 * v + 4], lane[12 * v + 8]}; };
    return {vertex(0), vertex(1), vertex(2)};
}

/// The instruction sets the mesh traversal has kernels for.
enum class SimdIsa { kSse4, kAvx2, kAvx512 };
const char* simd_isa_name(SimdIsa isa);
/// The best kernel this CPU runs (AVX-512 needs F, VL, BW and DQ; AVX2 needs FMA and BMI2 too),
/// lowered by the environment variable GLINT_ISA (sse4, avx2 or avx512) when set; an unknown
/// value throws std::runtime_error, one above the CPU's is lowered to the CPU's.
SimdIsa default_simd_isa();
bool cpu_supports(SimdIsa isa);

/// An any-hit filter (alpha cut-outs): called for every candidate hit in [kRayTMin, t_max)
/// with its triangle and barycentrics; a hit it refuses is not there. Without one (nullptr)
/// the kernels run as they always did.
struct HitFilter {
    bool (*keep)(const void* context, std::uint32_t prim, float b1, float b2);
    const void* context;
};

/// What a traversal kernel reads: the nodes (Bvh4Node for SSE, Bvh8Node otherwise), the root
/// reference and the packets; leaf references count packets.
struct MeshTraversal {
    const void* nodes;
    std::uint32_t root;
    const TrianglePacket* packets;
    const HitFilter* filter = nullptr;
};

class MeshBvh {
public:
    void build(const TriangleMesh& mesh, const BvhBuildOptions& options = {},
               SimdIsa isa = default_simd_isa());

    /// Nearest triangle in [kRayTMin, ray.t_max) along an object-space ray (any direction
    /// length; t is in the ray's own parametrisation).
    std::optional<MeshHit> closest(const Ray& ray, const HitFilter* filter = nullptr) const;
    bool any(const Ray& ray, const HitFilter* filter = nullptr) const;

    Bounds3 bounds() const { return width_ == 8 ? bvh8_.bounds() : bvh4_.bounds(); }
    int depth() const { return width_ == 8 ? bvh8_.depth() : bvh4_.depth(); }
    int width() const { return width_; }
    SimdIsa isa() const { return isa_; }
    /// Triangle references in the leaves (more than the triangles with spatial splits).
    std::size_t references() const { return width_ == 8 ? bvh8_.order().size() : bvh4_.order().size(); }
    double sah_cost() const { return width_ == 8 ? bvh8_.sah_cost() : bvh4_.sah_cost(); }
    std::size_t memory_bytes() const {
        return bvh4_.memory_bytes() + bvh8_.memory_bytes() + packets_.size() * sizeof(TrianglePacket);
    }

private:
    MeshTraversal view() const;
    Bvh4 bvh4_;
    Bvh8 bvh8_;
    std::vector<TrianglePacket> packets_;
    SimdIsa isa_ = SimdIsa::kSse4;
    int width_ = 4;
};

}  // namespace glint
