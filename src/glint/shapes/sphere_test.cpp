#include "glint/shapes/sphere.h"

#include <gtest/gtest.h>

#include <cmath>

namespace glint {
namespace {

Ray ray(Point3 o, Vector3 d) { return Ray{o, normalize(d)}; }

TEST(Sphere, RayPassingBesideMisses) {
    const Sphere s{{0, 0, 0}, 1};
    EXPECT_FALSE(s.intersect(ray({0, 1.01f, -5}, {0, 0, 1})));
    EXPECT_FALSE(s.intersect(ray({0, 0, -5}, {0, 1, 0})));
}

TEST(Sphere, TangentRayTouchesOnce) {
    // f = (0,1,-5), b = -5, f - bD = (0,1,0): discriminant 1 - 1 = 0, t = 5.
    const Sphere s{{0, 0, 0}, 1};
    const auto t = s.intersect(ray({0, 1, -5}, {0, 0, 1}));
    ASSERT_TRUE(t);
    EXPECT_FLOAT_EQ(*t, 5);
}

TEST(Sphere, RayThroughCentreReturnsTheNearHit) {
    const Sphere s{{0, 0, 1}, 1};
    const auto t = s.intersect(ray({0, 0, -1}, {0, 0, 1}));
    ASSERT_TRUE(t);
    EXPECT_FLOAT_EQ(*t, 1);  // enters at z = 0; the far hit is at t = 3
}

TEST(Sphere, TwoHitsOffAxisMatchHandValues) {
    // O = (0,0.6,-5), D = (0,0,1), r = 1: chord half-length sqrt(1 - 0.36) = 0.8, t = 5 - 0.8.
    const Sphere s{{0, 0, 0}, 1};
    const auto t = s.intersect(ray({0, 0.6f, -5}, {0, 0, 1}));
    ASSERT_TRUE(t);
    EXPECT_NEAR(*t, 4.2f, 1e-6);
}

TEST(Sphere, SphereBehindTheRayIsNotHit) {
    const Sphere s{{0, 0, -3}, 1};
    EXPECT_FALSE(s.intersect(ray({0, 0, 0}, {0, 0, 1})));
}

TEST(Sphere, RayFromInsideHitsFarSide) {
    const Sphere s{{0, 0, 0}, 2};
    auto t = s.intersect(ray({0, 0, 0}, {0, 0, 1}));
    ASSERT_TRUE(t);
    EXPECT_FLOAT_EQ(*t, 2);
    t = s.intersect(ray({0, 0, 0.5f}, {0, 0, -1}));
    ASSERT_TRUE(t);
    EXPECT_FLOAT_EQ(*t, 2.5f);
}

TEST(Sphere, RespectsTMax) {
    const Sphere s{{0, 0, 5}, 1};
    Ray r = ray({0, 0, 0}, {0, 0, 1});
    r.t_max = 3.99f;
    EXPECT_FALSE(s.intersect(r));
    r.t_max = 4.01f;
    EXPECT_TRUE(s.intersect(r));
}

TEST(Sphere, FarAwaySphereIsHitAccurately) {
    // Unit sphere 10^5 away; the ray passes 0.5 from its centre: t = 1e5 - sqrt(0.75).
    // The textbook discriminant b^2 - c subtracts two numbers near 10^10 in float (spacing 1024)
    // and loses the 0.75 entirely.
    const Sphere s{{0, 0, 1e5f}, 1};
    const auto t = s.intersect(ray({0, 0.5f, 0}, {0, 0, 1}));
    ASSERT_TRUE(t);
    EXPECT_NEAR(*t, 1e5 - std::sqrt(0.75), 0.02);
    // Grazing: 0.999 from the centre still hits, 1.001 misses.
    EXPECT_TRUE(s.intersect(ray({0, 0.999f, 0}, {0, 0, 1})));
    EXPECT_FALSE(s.intersect(ray({0, 1.001f, 0}, {0, 0, 1})));
}

TEST(Sphere, HugeSphereNearItsSurfaceIsHitAccurately) {
    // A ground "plane" made of a sphere of radius 10^6 whose top is at y = 0.
    const Sphere s{{0, -1e6f, 0}, 1e6f};
    auto t = s.intersect(ray({0, 1, 0}, {0, -1, 0}));
    ASSERT_TRUE(t);
    EXPECT_FLOAT_EQ(*t, 1);
    // Slanted at 45 degrees: the surface at x = u lies at y = sqrt(1e12 - u^2) - 1e6 ~ -u^2/2e6,
    // so t = sqrt(2) * u with u (1 + u/2e6... ) = 1: t = sqrt(2) to within 1e-6 relative.
    t = s.intersect(ray({0, 1, 0}, {1, -1, 0}));
    ASSERT_TRUE(t);
    EXPECT_NEAR(*t, std::sqrt(2.0), 1e-5);
}

TEST(Sphere, NormalPointsOutward) {
    const Sphere s{{1, 2, 3}, 2};
    const Normal3 n = s.normal_at({1, 2, 5});
    EXPECT_FLOAT_EQ(n.x, 0);
    EXPECT_FLOAT_EQ(n.y, 0);
    EXPECT_FLOAT_EQ(n.z, 1);
}

TEST(Sphere, RandomRaysHitPointsLieOnTheSurface) {
    // Seeded property test: for rays from many directions the hit point is on the sphere.
    const Sphere s{{0.3f, -0.2f, 4}, 1.5f};
    std::uint32_t state = 12345;
    auto next = [&state] {
        state = state * 1664525u + 1013904223u;
        return static_cast<float>(state >> 8) / 16777216.0f;
    };
    int hits = 0;
    for (int i = 0; i < 2000; ++i) {
        const Point3 o{next() * 4 - 2, next() * 4 - 2, next() * 2 - 2};
        const Ray r = ray(o, s.center - o + Vector3{next() - 0.5f, next() - 0.5f, next() - 0.5f} * 3);
        if (const auto t = s.intersect(r)) {
            ++hits;
            EXPECT_NEAR(length(r.at(*t) - s.center), s.radius, 1e-5f);
        }
    }
    EXPECT_GT(hits, 500);
}

}  // namespace
}  // namespace glint
