#include "glint/accel/mesh_bvh.h"

namespace glint {

void MeshBvh::build(const TriangleMesh& mesh, const BvhBuildOptions& options) {
    const std::uint32_t n = mesh.triangle_count();
    std::vector<Bounds3> boxes(n);
    for (std::uint32_t t = 0; t < n; ++t) {
        const auto [p0, p1, p2] = mesh.vertices(t);
        boxes[t].extend(p0);
        boxes[t].extend(p1);
        boxes[t].extend(p2);
    }
    bvh_.build(boxes, options);
    vertices_.resize(bvh_.order().size());
    for (std::size_t i = 0; i < vertices_.size(); ++i) vertices_[i] = mesh.vertices(bvh_.order()[i]);
}

}  // namespace glint
