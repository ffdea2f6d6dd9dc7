// The SIMD sphere set against the scalar Sphere::intersect, lane for lane: the same t to the bit
// and the same sphere, for every kernel this CPU can run, on rays from everywhere (outside,
// inside, grazing, and with t_max cutting through).
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <random>

#include "glint/accel/sphere_set.h"

namespace glint {
namespace {

TEST(SphereSet, EveryKernelFindsTheScalarHitToTheBit) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(-1, 1);
    for (const std::size_t count : {std::size_t{1}, std::size_t{9}, std::size_t{17}, std::size_t{40}}) {
        std::vector<Sphere> spheres;
        for (std::size_t i = 0; i < count; ++i)
            spheres.push_back({{3 * u(rng), 3 * u(rng), 3 * u(rng) + 4}, 0.2f + std::abs(u(rng)), 0});
        spheres.push_back(spheres.front());  // an exact twin: the lower index must win the tie
        for (const SimdIsa isa : {SimdIsa::kSse4, SimdIsa::kAvx2, SimdIsa::kAvx512}) {
            if (!cpu_supports(isa)) continue;
            SCOPED_TRACE(simd_isa_name(isa));
            SphereSet set;
            set.build(spheres, isa);
            std::vector<Ray> packet_rays;
            std::vector<int> packet_best;
            std::vector<float> packet_t;
            for (int n = 0; n < 20000; ++n) {
                Ray ray;
                const Sphere& target = spheres[static_cast<std::size_t>(n) % spheres.size()];
                // Half the rays start near or inside a sphere, half far away aiming at one.
                ray.origin = n % 2 ? target.center + Vector3{u(rng), u(rng), u(rng)} * target.radius * 1.2f
                                   : Point3{4 * u(rng), 4 * u(rng), -5 + u(rng)};
                ray.direction = normalize((target.center + Vector3{u(rng), u(rng), u(rng)} * target.radius) - ray.origin);
                ray.t_max = n % 3 == 0 ? 2 + 6 * std::abs(u(rng)) : std::numeric_limits<Float>::infinity();
                // The scalar reference: every sphere in index order, nearest strictly first.
                std::optional<Float> best;
                std::uint32_t best_i = 0;
                for (std::uint32_t i = 0; i < spheres.size(); ++i) {
                    if (const auto t = spheres[i].intersect(ray); t && (!best || *t < *best)) best = t, best_i = i;
                }
                packet_rays.push_back(ray);
                packet_best.push_back(best ? static_cast<int>(best_i) : -1);
                packet_t.push_back(best ? *best : ray.t_max);
                float t = -1;
                std::uint32_t index = 0;
                const bool hit = set.closest(ray, t, index);
                ASSERT_EQ(hit, best.has_value()) << n;
                EXPECT_EQ(set.any(ray), best.has_value()) << n;
                if (hit) {
                    ASSERT_EQ(t, *best) << n;
                    ASSERT_EQ(index, best_i) << n;
                }
            }
            // The packet kernels on the same rays, in packets of 1 to 16 (padded as required).
            for (std::size_t first = 0, n = 1; first < packet_rays.size(); first += n, n = n % 16 + 1) {
                const int count = static_cast<int>(std::min(n, packet_rays.size() - first));
                RayPacket p;
                for (int k = 0; k < count; ++k) p.set(k, packet_rays[first + static_cast<std::size_t>(k)]);
                p.pad(count);
                PacketHits hits;
                set.closest(p, count, hits);
                const std::uint32_t blocked = set.any(p, count);
                for (int k = 0; k < count; ++k) {
                    const std::size_t r = first + static_cast<std::size_t>(k);
                    ASSERT_EQ(static_cast<int>(hits.index[k]), packet_best[r]) << r;
                    ASSERT_EQ(hits.t[k], packet_t[r]) << r;
                    ASSERT_EQ((blocked >> k) & 1u, packet_best[r] >= 0 ? 1u : 0u) << r;
                }
                ASSERT_EQ(blocked >> count, 0u);  // the padding lanes hit nothing
            }
        }
    }
}

}  // namespace
}  // namespace glint
