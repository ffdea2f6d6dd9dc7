#pragma once
// What `glint info` and `glint bench` measure: scene statistics, and per acceleration backend
// the build time, memory and ray throughput (primary rays through every pixel centre, and one
// cosine-distributed diffuse bounce from each primary hit, both closest-hit).
#include <cstdint>
#include <string>
#include <vector>

#include "glint/cameras/camera.h"
#include "glint/scene.h"

namespace glint {

struct SceneInfo {
    std::uint64_t triangles = 0;         ///< as rendered: every instance counted
    std::uint64_t unique_triangles = 0;  ///< stored: each mesh once
    std::uint64_t meshes = 0, instances = 0, analytic_shapes = 0, vertices = 0;
    std::uint64_t mesh_bytes = 0;   ///< vertex and index arrays
    std::uint64_t accel_bytes = 0;  ///< the committed backend's structures
    int bvh_depth = 0;              ///< the deepest mesh BVH (our backends)
    std::uint64_t bvh_references = 0;  ///< triangle references in the mesh BVHs' leaves
    int bvh_width = 0;                 ///< children per node of the mesh BVHs
    std::string bvh_isa;               ///< their traversal kernel
    Bounds3 bounds;
};

SceneInfo scene_info(const Scene& scene);

struct BenchResult {
    std::string backend;
    double build_seconds = 0;  ///< median over the runs
    std::uint64_t accel_bytes = 0;
    double primary_mrays = 0, diffuse_mrays = 0;  ///< medians, million rays per second
    std::uint64_t primary_rays = 0, diffuse_rays = 0;
    std::uint64_t primary_hits = 0, diffuse_hits = 0;  ///< equal across backends up to float noise
};

/// The rays every backend traces: the camera's width x height pixel-centre rays, and from each
/// of their hits (found with the scene as committed) one cosine-distributed bounce chosen by a
/// fixed hash. Made once, so that the backends trace exactly the same rays.
struct BenchRays {
    std::vector<Ray> primary, diffuse;
};
BenchRays bench_rays(const Scene& scene, const Camera& camera, int width, int height);

/// `runs` rounds; in each, every backend in turn commits `scene` (timed) and traces both ray sets
/// on `threads` threads (closest hit). The backends take turns round by round, in reversed order
/// every other round, so that the machine's drift over the minutes of a run falls on all of
/// them alike and their ratios are measured seconds apart, not minutes. One result per backend.
std::vector<BenchResult> bench_backends(Scene& scene, const std::vector<AccelKind>& accels, const BenchRays& rays,
                                        int threads, int runs);

}  // namespace glint
