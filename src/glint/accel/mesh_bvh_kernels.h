#pragma once
// The mesh traversal kernels, one per instruction set, each compiled in its own file with its
// own -march (mesh_bvh_sse4.cpp, mesh_bvh_avx2.cpp, mesh_bvh_avx512.cpp) from the same source,
// mesh_bvh_kernels.inl. Only these entry points have external linkage: everything else in a
// kernel file is internal to it, so no inline function compiled for AVX2 can be picked by the
// linker for code that must run on an SSE-only CPU.
#include "glint/accel/mesh_bvh.h"

namespace glint {

#define GLINT_MESH_KERNEL_DECLARE(isa)                                                 \
    bool mesh_closest_##isa(const MeshTraversal& m, const Ray& ray, MeshHit& out); \
    bool mesh_any_##isa(const MeshTraversal& m, const Ray& ray);
GLINT_MESH_KERNEL_DECLARE(sse4)
GLINT_MESH_KERNEL_DECLARE(avx2)
GLINT_MESH_KERNEL_DECLARE(avx512)
#undef GLINT_MESH_KERNEL_DECLARE

/// The scalar watertight test (shapes/triangle.h) on lane `lane` of a packet, out of line and
/// compiled for the baseline ISA: the kernels' path for the rare rays where an edge function is
/// exactly zero in float.
bool intersect_packet_lane(const TrianglePacket& p, int lane, const WatertightRay& ray, TriangleHit& out);

}  // namespace glint
