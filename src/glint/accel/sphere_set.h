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

/// Up to 16 rays in structure-of-arrays form, for the packet queries. Lanes past the rays in use
/// must hold t_max 0 (pad() does it): no hit lies in [kRayTMin, 0).
struct alignas(64) RayPacket {
    static constexpr int kSize = SphereSoa::kGroup;
    float ox[kSize], oy[kSize], oz[kSize], dx[kSize], dy[kSize], dz[kSize], t_max[kSize];
    void set(int lane, const Ray& r) {
        ox[lane] = r.origin.x, oy[lane] = r.origin.y, oz[lane] = r.origin.z;
        dx[lane] = r.direction.x, dy[lane] = r.direction.y, dz[lane] = r.direction.z;
        t_max[lane] = r.t_max;
    }
    /// Fills lanes [n, kSize) with rays that hit nothing.
    void pad(int n) {
        for (int k = n; k < kSize; ++k) ox[k] = oy[k] = oz[k] = dx[k] = dy[k] = dz[k] = t_max[k] = 0;
    }
};

/// A packet's nearest hits: t (the ray's t_max where nothing was hit) and the sphere's index as a
/// float (exact below 2^24), -1 for none.
struct alignas(64) PacketHits {
    float t[RayPacket::kSize];
    float index[RayPacket::kSize];
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
    /// The nearest hit of each of the packet's first n rays (n <= 16; lanes up to the next
    /// multiple of the kernel's width are computed too, so they must be padded).
    void closest(const RayPacket& p, int n, PacketHits& out) const;
    /// Bit k set when ray k of the first n is blocked by a sphere.
    std::uint32_t any(const RayPacket& p, int n) const;

private:
    SphereSoa soa_;
    SimdIsa isa_ = SimdIsa::kSse4;
};

#define GLINT_SPHERE_KERNEL_DECLARE(isa)                                                               \
    bool spheres_closest_##isa(const SphereSoa& s, const Ray& ray, float& t, std::uint32_t& index); \
    bool spheres_any_##isa(const SphereSoa& s, const Ray& ray);                                         \
    void spheres_closest_packet_##isa(const SphereSoa& s, const RayPacket& p, int n, PacketHits& out); \
    std::uint32_t spheres_any_packet_##isa(const SphereSoa& s, const RayPacket& p, int n);
GLINT_SPHERE_KERNEL_DECLARE(sse4)
GLINT_SPHERE_KERNEL_DECLARE(avx2)
GLINT_SPHERE_KERNEL_DECLARE(avx512)
#undef GLINT_SPHERE_KERNEL_DECLARE

}  // namespace glint
