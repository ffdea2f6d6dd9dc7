// Loop subdivision against hand-computed points: one step of the regular octahedron (every
// vertex of valence 4) and of a single triangle (all boundary).
#include <gtest/gtest.h>

#include "glint/shapes/subdivision.h"

namespace glint {
namespace {

void expect_point(Point3 a, Point3 b) {
    EXPECT_NEAR(a.x, b.x, 1e-6f);
    EXPECT_NEAR(a.y, b.y, 1e-6f);
    EXPECT_NEAR(a.z, b.z, 1e-6f);
}

bool has_point(const SubdividedMesh& m, Point3 p) {
    for (const Point3& q : m.positions)
        if (std::abs(q.x - p.x) < 1e-6f && std::abs(q.y - p.y) < 1e-6f && std::abs(q.z - p.z) < 1e-6f) return true;
    return false;
}

TEST(LoopSubdivision, OctahedronOneLevelByHand) {
    const std::vector<Point3> p{{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    // Eight faces, wound outwards.
    const std::vector<std::uint32_t> f{0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5};
    const SubdividedMesh m = loop_subdivide(p, f, 1);
    EXPECT_EQ(m.indices.size(), 8u * 4 * 3);
    EXPECT_EQ(m.positions.size(), 6u + 12u);  // V + E
    // Valence 4: beta = 3/32; the four neighbours sum to 0, so v moves to (1 - 12/32) v.
    expect_point(m.positions[0], {0.625f, 0, 0});
    // The edge (1,0,0)-(0,1,0): 3/8 of its ends + 1/8 of (0,0,1) and (0,0,-1).
    EXPECT_TRUE(has_point(m, {0.375f, 0.375f, 0}));
    // Normals point outwards.
    EXPECT_GT(m.normals[0].x, 0.99f);
}

TEST(LoopSubdivision, LoneTriangleKeepsCornersAndSplitsEdgesAtMidpoints) {
    const SubdividedMesh m = loop_subdivide({{0, 0, 0}, {4, 0, 0}, {0, 4, 0}}, {0, 1, 2}, 1);
    EXPECT_EQ(m.indices.size(), 12u);
    // Every vertex is on the boundary: 3/4 v + 1/8 (its two neighbours).
    expect_point(m.positions[0], {0.5f, 0.5f, 0});
    expect_point(m.positions[1], {3, 0.5f, 0});
    EXPECT_TRUE(has_point(m, {2, 0, 0}));
    EXPECT_TRUE(has_point(m, {2, 2, 0}));
    EXPECT_TRUE(has_point(m, {0, 2, 0}));
    const SubdividedMesh two = loop_subdivide({{0, 0, 0}, {4, 0, 0}, {0, 4, 0}}, {0, 1, 2}, 2);
    EXPECT_EQ(two.indices.size(), 48u);
}

}  // namespace
}  // namespace glint
