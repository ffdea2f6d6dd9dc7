#include "glint/accel/sphere_set.h"

namespace glint {

void SphereSet::build(const std::vector<Sphere>& spheres, SimdIsa isa) {
    isa_ = isa;
    soa_.count = static_cast<std::uint32_t>(spheres.size());
    soa_.groups.assign((spheres.size() + SphereSoa::kGroup - 1) / SphereSoa::kGroup, SphereSoa::Group{});
    for (auto& g : soa_.groups) {
        // Padding: radius 0 and r2 -1 (disc = -1 - |perp|^2 < 0 for every ray: never a hit).
        for (int k = 0; k < SphereSoa::kGroup; ++k) g.cx[k] = g.cy[k] = g.cz[k] = 0, g.r[k] = 0, g.r2[k] = -1;
    }
    for (std::size_t i = 0; i < spheres.size(); ++i) {
        SphereSoa::Group& g = soa_.groups[i / SphereSoa::kGroup];
        const std::size_t k = i % SphereSoa::kGroup;
        g.cx[k] = spheres[i].center.x, g.cy[k] = spheres[i].center.y, g.cz[k] = spheres[i].center.z;
        g.r[k] = spheres[i].radius;
        g.r2[k] = spheres[i].radius * spheres[i].radius;
    }
}

bool SphereSet::closest(const Ray& ray, float& t, std::uint32_t& index) const {
    switch (isa_) {
        case SimdIsa::kAvx512: return spheres_closest_avx512(soa_, ray, t, index);
        case SimdIsa::kAvx2: return spheres_closest_avx2(soa_, ray, t, index);
        case SimdIsa::kSse4: break;
    }
    return spheres_closest_sse4(soa_, ray, t, index);
}

bool SphereSet::any(const Ray& ray) const {
    switch (isa_) {
        case SimdIsa::kAvx512: return spheres_any_avx512(soa_, ray);
        case SimdIsa::kAvx2: return spheres_any_avx2(soa_, ray);
        case SimdIsa::kSse4: break;
    }
    return spheres_any_sse4(soa_, ray);
}

void SphereSet::closest(const RayPacket& p, int n, PacketHits& out) const {
    switch (isa_) {
        case SimdIsa::kAvx512: return spheres_closest_packet_avx512(soa_, p, n, out);
        case SimdIsa::kAvx2: return spheres_closest_packet_avx2(soa_, p, n, out);
        case SimdIsa::kSse4: break;
    }
    spheres_closest_packet_sse4(soa_, p, n, out);
}

std::uint32_t SphereSet::any(const RayPacket& p, int n) const {
    switch (isa_) {
        case SimdIsa::kAvx512: return spheres_any_packet_avx512(soa_, p, n);
        case SimdIsa::kAvx2: return spheres_any_packet_avx2(soa_, p, n);
        case SimdIsa::kSse4: break;
    }
    return spheres_any_packet_sse4(soa_, p, n);
}

}  // namespace glint
