#pragma once
// A scene of spheres alone (the article's scenes: a handful of spheres beside planes) needs no
// BVH: testing every sphere at once, W at a time in SIMD lanes (4 with SSE, 8 with AVX2, 16 with
// AVX-512, chosen at run time like the mesh kernels), is cheaper than a traversal for up to a few
// dozen. Each lane computes exactly what Sphere::intersect computes, in the same order with the
// same operations (no fused multiply-add), so the t of every hit is the scalar code's to the bit.
// The nearest valid root over all spheres wins; among equal t the lowest index.
#include <cstdint>
#include <vector>

#include "glint/accel/mesh_bvh.h"
#include "glint/ray.h"
#include "glint/shapes/sphere.h"

namespace glint {

/// The spheres in structure-of-arrays groups of 16 (padded with spheres no ray can hit), so that
/// every kernel width reads whole aligned groups.
struct SphereSoa {
    static constexpr int kGroup = 16;
    struct alignas(64) Group {
        float cx[kGroup], cy[kGroup], cz[kGroup], r[kGroup], r2[kGroup];
    };
    std::vector<Group> groups;
    std::uint32_t count = 0;
};

class SphereSet {
public:
    /// Scenes with at most this many spheres (and no other bounded shape) use the set.
    static constexpr std::size_t kMaxSpheres = 64;

    void build(const std::vector<Sphere>& spheres, SimdIsa isa);
    bool empty() const { return soa_.count == 0; }
    SimdIsa isa() const { return isa_; }
    std::size_t memory_bytes() const { return soa_.groups.size() * sizeof(SphereSoa::Group); }
    /// The nearest sphere hit in [kRayTMin, ray.t_max): its t and index, or false.
    bool closest(const Ray& ray, float& t, std::uint32_t& index) const;
    /// Whether any sphere lies in [kRayTMin, ray.t_max).
    bool any(const Ray& ray) const;

private:
    SphereSoa soa_;
    SimdIsa isa_ = SimdIsa::kSse4;
};

#define GLINT_SPHERE_KERNEL_DECLARE(isa)                                                               \
    bool spheres_closest_##isa(const SphereSoa& s, const Ray& ray, float& t, std::uint32_t& index); \
    bool spheres_any_##isa(const SphereSoa& s, const Ray& ray);
GLINT_SPHERE_KERNEL_DECLARE(sse4)
GLINT_SPHERE_KERNEL_DECLARE(avx2)
GLINT_SPHERE_KERNEL_DECLARE(avx512)
#undef GLINT_SPHERE_KERNEL_DECLARE

}  // namespace glint
