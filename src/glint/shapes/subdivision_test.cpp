// Loop subdivision against hand-computed points: one step of the regular octahedron (every
// vertex of valence 4) and of a single triangle (all boundary); the limit surface against
// pbrt-v4's masks worked by hand, against the limit that many plain steps converge to, and
// flat meshes keeping their plane's normal at every kind of boundary vertex.
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
    const SubdividedMesh m = loop_subdivide(p, f, 1, false);
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
    const SubdividedMesh m = loop_subdivide({{0, 0, 0}, {4, 0, 0}, {0, 4, 0}}, {0, 1, 2}, 1, false);
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

const std::vector<std::uint32_t> kOctahedronFaces{0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5};

TEST(LoopSubdivision, LimitPositionsFollowPbrtMasks) {
    // No subdivision, only the push: valence 4, beta = 3/32, gamma = 1 / (4 + 3 / (8 beta)) = 1/8,
    // so (1, 0, 0) goes to (1 - 4/8) (1, 0, 0) + 1/8 (sum of its ring = 0) = (0.5, 0, 0).
    const std::vector<Point3> p{{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    const SubdividedMesh m = loop_subdivide(p, kOctahedronFaces, 0);
    expect_point(m.positions[0], {0.5f, 0, 0});
    EXPECT_NEAR(m.normals[0].x, 1, 1e-6f);
    // A lone triangle: each corner is a boundary vertex, 3/5 v + 1/5 of its two neighbours.
    const SubdividedMesh t = loop_subdivide({{0, 0, 0}, {5, 0, 0}, {0, 5, 0}}, {0, 1, 2}, 0);
    expect_point(t.positions[0], {1, 1, 0});
    expect_point(t.positions[1], {3, 1, 0});
}

TEST(LoopSubdivision, LimitIsWhereManyPlainStepsConverge) {
    // A lopsided octahedron; its six vertices keep their indices through every step, and plain
    // subdivision moves each towards its limit point geometrically (by 3/8 per step at valence 4).
    const std::vector<Point3> p{{1.3f, 0.1f, 0}, {-0.8f, 0, 0.2f}, {0, 1.1f, -0.1f}, {0.2f, -0.7f, 0}, {0, 0.3f, 1.6f}, {-0.1f, 0, -0.9f}};
    const SubdividedMesh limit = loop_subdivide(p, kOctahedronFaces, 1);
    const SubdividedMesh fine = loop_subdivide(p, kOctahedronFaces, 8, false);
    for (std::size_t v = 0; v < p.size(); ++v) {
        EXPECT_NEAR(limit.positions[v].x, fine.positions[v].x, 2e-3f) << "vertex " << v;
        EXPECT_NEAR(limit.positions[v].y, fine.positions[v].y, 2e-3f) << "vertex " << v;
        EXPECT_NEAR(limit.positions[v].z, fine.positions[v].z, 2e-3f) << "vertex " << v;
        // The limit normal against the fine mesh's (its faces around the vertex are tiny).
        const Normal3 a = limit.normals[v], b = fine.normals[v];
        EXPECT_GT(a.x * b.x + a.y * b.y + a.z * b.z, std::cos(2 * 3.14159265f / 180)) << "vertex " << v;
    }
    // And the push moved them: the control points are far from it.
    const SubdividedMesh control = loop_subdivide(p, kOctahedronFaces, 1, false);
    EXPECT_GT(std::abs(control.positions[0].x - limit.positions[0].x), 0.05f);
}

TEST(LoopSubdivision, FlatMeshesKeepTheirPlaneNormalAtEveryBoundaryValence) {
    // A fan of k triangles around the origin in the plane z = 0 (open: boundary vertices of ring
    // sizes 2, 3 and k + 1 at the centre), subdivided twice: every limit normal is +z.
    for (const int k : {1, 2, 3, 4, 5, 7}) {
        std::vector<Point3> p{{0, 0, 0}};
        std::vector<std::uint32_t> f;
        for (int i = 0; i <= k; ++i) {
            const float a = 2.5f * float(i) / float(k);  // less than a full turn: open
            p.push_back({std::cos(a), std::sin(a), 0});
        }
        for (int i = 0; i < k; ++i) f.insert(f.end(), {0, std::uint32_t(i + 1), std::uint32_t(i + 2)});
        const SubdividedMesh m = loop_subdivide(p, f, 2);
        for (std::size_t v = 0; v < m.positions.size(); ++v) {
            EXPECT_NEAR(m.positions[v].z, 0, 1e-6f);
            EXPECT_NEAR(m.normals[v].z, 1, 1e-5f) << "fan of " << k << ", vertex " << v;
        }
    }
}

}  // namespace
}  // namespace glint
