#pragma once
// The bottom level: one BVH per mesh, in the mesh's object space, shared by all its instances.
// The triangles' vertices are copied into leaf order (36 bytes each) so that a leaf's triangles
// are contiguous in memory and the traversal never goes through the index buffer.
#include <array>
#include <cstdint>
#include <vector>

#include "glint/accel/bvh.h"
#include "glint/shapes/mesh.h"
#include "glint/shapes/triangle.h"

namespace glint {

struct MeshHit {
    TriangleHit hit;
    std::uint32_t prim;
};

class MeshBvh {
public:
    void build(const TriangleMesh& mesh, const BvhBuildOptions& options = {});

    /// Nearest triangle in [kRayTMin, ray.t_max) along an object-space ray (any direction
    /// length; t is in the ray's own parametrisation).
    std::optional<MeshHit> closest(const Ray& ray) const {
        const BvhRay br(ray);
        WatertightRay wr(ray);
        std::optional<MeshHit> best;
        bvh_.closest(br, wr.t_max, [&](std::uint32_t first, std::uint32_t count) {
            for (std::uint32_t i = first; i < first + count; ++i) {
                const auto& v = vertices_[i];
                if (const auto h = intersect_triangle(v[0], v[1], v[2], wr)) {
                    wr.t_max = h->t;
                    best = MeshHit{*h, bvh_.order()[i]};
                }
            }
        });
        return best;
    }
    bool any(const Ray& ray) const {
        const BvhRay br(ray);
        const WatertightRay wr(ray);
        return bvh_.any(br, ray.t_max, [&](std::uint32_t first, std::uint32_t count) {
            for (std::uint32_t i = first; i < first + count; ++i) {
                const auto& v = vertices_[i];
                if (intersect_triangle(v[0], v[1], v[2], wr)) return true;
            }
            return false;
        });
    }

    Bounds3 bounds() const { return bvh_.bounds(); }
    const Bvh4& bvh() const { return bvh_; }
    std::size_t memory_bytes() const {
        return bvh_.memory_bytes() + vertices_.size() * sizeof(vertices_[0]);
    }

private:
    Bvh4 bvh_;
    std::vector<std::array<Point3, 3>> vertices_;  ///< leaf order
};

}  // namespace glint
