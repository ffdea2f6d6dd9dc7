#include "glint/shapes/plane.h"

#include <gtest/gtest.h>

namespace glint {
namespace {

const Plane kFloor{{0, -1, 0}, {0, 1, 0}};

TEST(Plane, RayTowardsPlaneHitsAtHandValue) {
    const auto t = kFloor.intersect(Ray{{0, 1, 0}, {0, -1, 0}});
    ASSERT_TRUE(t);
    EXPECT_FLOAT_EQ(*t, 2);
    // 45 degrees down from height 1 above the plane at y = -1: t = 2 sqrt(2).
    const auto t2 = kFloor.intersect(Ray{{0, 1, 0}, normalize(Vector3{1, -1, 0})});
    ASSERT_TRUE(t2);
    EXPECT_NEAR(*t2, 2 * std::sqrt(2.0f), 1e-6);
}

TEST(Plane, ParallelRaysMiss) {
    EXPECT_FALSE(kFloor.intersect(Ray{{0, 1, 0}, {1, 0, 0}}));
    EXPECT_FALSE(kFloor.intersect(Ray{{0, -1, 0}, {0, 0, 1}}));  // lying in the plane
}

TEST(Plane, PlaneBehindTheRayIsNotHit) {
    EXPECT_FALSE(kFloor.intersect(Ray{{0, 1, 0}, {0, 1, 0}}));
}

TEST(Plane, RayFromBelowHitsTheBack) {
    const auto t = kFloor.intersect(Ray{{0, -3, 0}, {0, 1, 0}});
    ASSERT_TRUE(t);
    EXPECT_FLOAT_EQ(*t, 2);
}

TEST(Plane, ProjectSnapsOntoAnAxisAlignedPlaneExactly) {
    const Ray r{{0.1f, 1.6f, -1.5f}, normalize(Vector3{0.37f, -0.5f, 1.1f})};
    const auto t = kFloor.intersect(r);
    ASSERT_TRUE(t);
    const Point3 p = kFloor.project(r.at(*t));
    EXPECT_EQ(p.y, -1.0f);
    EXPECT_NEAR(p.x, r.at(*t).x, 1e-6);
}

TEST(Plane, ProjectMovesOntoATiltedPlane) {
    const Plane p{{0, 0, 0}, Normal3(normalize(Vector3{1, 1, 0}))};
    const Point3 q = p.project({1, 1, 5});
    EXPECT_NEAR(q.x, 0, 1e-6);
    EXPECT_NEAR(q.y, 0, 1e-6);
    EXPECT_NEAR(q.z, 5, 1e-6);
}

}  // namespace
}  // namespace glint
