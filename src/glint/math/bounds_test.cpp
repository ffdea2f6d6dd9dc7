#include "glint/math/bounds.h"

#include <gtest/gtest.h>

#include "glint/samplers/hash.h"
#include "glint/shapes/sphere.h"

namespace glint {
namespace {

const Bounds3 kUnit{{-1, -1, -1}, {1, 1, 1}};

bool hits(Point3 o, Vector3 d, Float t_max = std::numeric_limits<Float>::infinity()) {
    const Ray r{o, normalize(d), t_max};
    return kUnit.hit(r.origin, reciprocal(r.direction), r.t_max);
}

TEST(Bounds, SlabTestHandValues) {
    EXPECT_TRUE(hits({0, 0, -5}, {0, 0, 1}));
    EXPECT_FALSE(hits({0, 0, -5}, {0, 0, -1}));     // behind
    EXPECT_FALSE(hits({0, 2, -5}, {0, 0, 1}));      // beside, parallel to two axes
    EXPECT_TRUE(hits({0, 0, 0}, {1, 2, 3}));        // from inside
    EXPECT_FALSE(hits({0, 0, -5}, {0, 0, 1}, 3.9f));  // stops short of the box
    EXPECT_TRUE(hits({0, 0, -5}, {0, 0, 1}, 4.1f));
    EXPECT_TRUE(hits({-5, -5, -5}, {1, 1, 1}));     // through the corners
}

TEST(Bounds, OriginOnASlabPlaneWhileParallelToItIsNotRejected) {
    // 0 * infinity = NaN in that slab; it must leave the slab unconstrained, not reject.
    EXPECT_TRUE(hits({1, 0, -5}, {0, 0, 1}));   // grazing the x = 1 face
    EXPECT_TRUE(hits({-1, 1, -5}, {0, 0, 1}));  // along an edge
}

TEST(Bounds, NeverRejectsARayThatHitsAnEnclosedSphere) {
    // Property: the box around spheres is conservative for the sphere test itself.
    std::uint32_t n = 0;
    auto u = [&n] { return to_unit_float(mix32(n++ * 0x9e3779b9U + 5)); };
    const Sphere s{{0.25f, -0.5f, 3}, 1.5f};
    Bounds3 b;
    b.extend(s.center - Vector3{1.5f, 1.5f, 1.5f});
    b.extend(s.center + Vector3{1.5f, 1.5f, 1.5f});
    int hit_count = 0;
    for (int i = 0; i < 50000; ++i) {
        const Point3 o{u() * 10 - 5, u() * 10 - 5, u() * 10 - 5};
        const Ray r{o, normalize(s.center - o + Vector3{u() - 0.5f, u() - 0.5f, u() - 0.5f} * 4)};
        if (s.intersect(r)) {
            ++hit_count;
            ASSERT_TRUE(b.hit(r.origin, reciprocal(r.direction), r.t_max)) << i;
        }
    }
    EXPECT_GT(hit_count, 10000);
}

}  // namespace
}  // namespace glint
