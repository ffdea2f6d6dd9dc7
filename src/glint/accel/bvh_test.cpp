// The BVH (both levels) against brute force, watertightness through the traversal, instances
// and their normals, degenerate input; Embree against brute force when built in.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <random>

#include <tbb/task_arena.h>

#include "glint/scene.h"
#include "glint/shapes/polygon.h"
#include "testing.h"

namespace glint {
namespace {

std::mt19937 rng(std::uint32_t seed) { return std::mt19937(seed); }

float uniform(std::mt19937& g, float lo, float hi) {
    return std::uniform_real_distribution<float>(lo, hi)(g);
}

Point3 random_point(std::mt19937& g, float r) { return {uniform(g, -r, r), uniform(g, -r, r), uniform(g, -r, r)}; }

Vector3 random_direction(std::mt19937& g) {
    for (;;) {
        const Vector3 v{uniform(g, -1, 1), uniform(g, -1, 1), uniform(g, -1, 1)};
        const float l = length(v);
        if (l > 0.1f && l <= 1) return v / l;
    }
}

// A soup of small triangles in a ball: the mesh the instances below place.
TriangleMesh random_soup(std::mt19937& g, int n) {
    TriangleMesh m;
    for (int i = 0; i < n; ++i) {
        const Point3 c = random_point(g, 1);
        for (int k = 0; k < 3; ++k) m.positions.push_back(c + to_vector(random_point(g, 0.15f)));
        m.indices.insert(m.indices.end(), {3u * i, 3u * i + 1, 3u * i + 2});
    }
    return m;
}

// A few large triangles across a cloud of small ones (as walls among furniture): the large
// ones' boxes cover every small one's, which object splits cannot undo; what spatial splits are
// for.
TriangleMesh large_among_small(std::mt19937& g, int small, int large) {
    TriangleMesh m;
    const auto add = [&](Point3 a, Point3 b, Point3 c) {
        const auto i = static_cast<std::uint32_t>(m.positions.size());
        m.positions.insert(m.positions.end(), {a, b, c});
        m.indices.insert(m.indices.end(), {i, i + 1, i + 2});
    };
    for (int i = 0; i < large; ++i)
        add(Point3{} + random_direction(g) * 2.0f, Point3{} + random_direction(g) * 2.0f,
            Point3{} + random_direction(g) * 2.0f);
    for (int i = 0; i < small; ++i) {
        const Point3 c = random_point(g, 2);
        add(c + to_vector(random_point(g, 0.05f)), c + to_vector(random_point(g, 0.05f)),
            c + to_vector(random_point(g, 0.05f)));
    }
    return m;
}

// Every kind of bounded shape, and five instances of two meshes under rotations, non-uniform
// scales and a mirror.
// With `alpha`: three instances cut out, by a 3D checker mask (half of each surface gone) and
// by a stochastic mask of 0.5 (half the rays pass).
Scene mixed_scene(AccelKind accel, std::optional<SimdIsa> isa = std::nullopt, bool alpha = false) {
    auto g = rng(7);
    Scene s;
    s.materials.push_back(DiffuseMaterial{0});
    s.textures.push_back(ConstantTexture{Color{0.5f}});
    for (int i = 0; i < 40; ++i) s.spheres.push_back({random_point(g, 5), uniform(g, 0.05f, 0.5f), 0});
    for (int i = 0; i < 20; ++i)
        s.quads.push_back(Quad::make(random_point(g, 5), to_vector(random_point(g, 0.6f)),
                                     to_vector(random_point(g, 0.6f)), 0));
    for (int i = 0; i < 20; ++i)
        s.disks.push_back({random_point(g, 5), Normal3(random_direction(g)), uniform(g, 0.1f, 0.6f), 0});
    for (int i = 0; i < 300; ++i) {
        const Point3 c = random_point(g, 5);
        s.triangles.push_back({c + to_vector(random_point(g, 0.4f)), c + to_vector(random_point(g, 0.4f)),
                               c + to_vector(random_point(g, 0.4f)), 0});
    }
    s.meshes.push_back(random_soup(g, 2000));
    s.meshes.push_back(random_soup(g, 500));
    s.meshes.push_back(large_among_small(g, 1000, 20));
    s.instances.push_back({2, Transform::translate({1, -3, 1}), std::nullopt});
    s.instances.push_back({0, Transform{}, std::nullopt});
    s.instances.push_back({0, Transform::translate({3, 1, -2}) * Transform::rotate(40, {1, 2, 3}) *
                                  Transform::scale({0.5f, 2, 1}), std::nullopt});
    s.instances.push_back({1, Transform::translate({-3, -2, 2}) * Transform::scale({-1, 1, 1}), std::nullopt});
    s.instances.push_back({1, Transform::rotate(-75, {0, 1, 0}) * Transform::translate({2, 2, 2}), std::nullopt});
    s.instances.push_back({0, Transform::translate({-2, 3, -3}) * Transform::scale({2, 2, 2}), std::nullopt});
    if (alpha) {
        s.textures.push_back(CheckerTexture{0.3f, Color{1}, Color{0}});
        s.textures.push_back(ConstantTexture{Color{0.5f}});
        s.alpha_masks = {{1, 0.5f, false}, {2, 0, true}};
        s.instances[1].alpha = 0;
        s.instances[2].alpha = 1;
        s.instances[4].alpha = 0;
    }
    s.accel = accel;
    s.mesh_isa = isa;
    s.commit();
    return s;
}

// glint's backends: with and without spatial splits, with every mesh traversal kernel.
struct Backend {
    AccelKind accel;
    SimdIsa isa;
};
std::string backend_name(const ::testing::TestParamInfo<Backend>& p) {
    return std::string(accel_name(p.param.accel)) + "_" + simd_isa_name(p.param.isa);
}
class BvhBackends : public ::testing::TestWithParam<Backend> {
protected:
    void SetUp() override {
        if (!cpu_supports(GetParam().isa)) GTEST_SKIP() << "this CPU has no " << simd_isa_name(GetParam().isa);
    }
};
INSTANTIATE_TEST_SUITE_P(All, BvhBackends,
                         ::testing::Values(Backend{AccelKind::kBvh, SimdIsa::kSse4}, Backend{AccelKind::kBvh, SimdIsa::kAvx2},
                                         Backend{AccelKind::kBvh, SimdIsa::kAvx512},
                                         Backend{AccelKind::kSbvh, SimdIsa::kSse4},
                                         Backend{AccelKind::kSbvh, SimdIsa::kAvx2},
                                         Backend{AccelKind::kSbvh, SimdIsa::kAvx512}),
                         backend_name);

std::vector<Ray> random_rays(int n) {
    auto g = rng(11);
    std::vector<Ray> rays;
    for (int i = 0; i < n; ++i) {
        Ray r{random_point(g, 7), random_direction(g)};
        if (i % 3 == 0) r.t_max = uniform(g, 0.5f, 6);  // shadow-ray-like segments
        if (i % 10 == 1) r.direction = {0, 0, r.direction.z > 0 ? 1.0f : -1.0f};  // axis-parallel
        rays.push_back(r);
    }
    return rays;
}

TEST_P(BvhBackends, ClosestAndAnyHitAgreeWithBruteForceOnEveryShapeKind) {
    const Scene s = mixed_scene(GetParam().accel, GetParam().isa);
    int hits = 0, mesh_hits = 0;
    std::array<int, 6> kinds{};
    for (const Ray& r : random_rays(testing::scaled(10000))) {
        const auto a = s.intersect(r), b = s.intersect_brute_force(r);
        ASSERT_EQ(a.has_value(), b.has_value());
        ASSERT_EQ(s.occluded(r), b.has_value());
        ASSERT_EQ(s.occluded_brute_force(r), b.has_value());
        if (!a) continue;
        ++hits;
        ++kinds[static_cast<int>(a->kind)];
        // The same primitive tests run in both, so the answers are identical, not close.
        EXPECT_EQ(a->t, b->t);
        EXPECT_EQ(a->kind, b->kind);
        EXPECT_EQ(a->index, b->index);
        EXPECT_EQ(a->prim, b->prim);
        EXPECT_EQ(a->b1, b->b1);
        if (a->kind == ShapeKind::kMesh) {
            // The traversal hands on the hit triangle's vertices from its packet (shading reads
            // them there): exactly the mesh's vertices of that triangle, in the mesh's order.
            ++mesh_hits;
            ASSERT_NE(a->vertices, nullptr);
            const auto v = s.meshes[s.instances[a->index].mesh].vertices(a->prim);
            for (int i = 0; i < 3; ++i)
                for (int axis = 0; axis < 3; ++axis) EXPECT_EQ(a->vertices[12 * i + 4 * axis], v[i][axis]);
        }
    }
    EXPECT_GT(mesh_hits, testing::scaled(20));
    EXPECT_GT(hits, testing::scaled(1000));
    for (ShapeKind k : {ShapeKind::kSphere, ShapeKind::kQuad, ShapeKind::kDisk, ShapeKind::kTriangle,
                        ShapeKind::kMesh})
        EXPECT_GT(kinds[static_cast<int>(k)], testing::scaled(20)) << "kind " << static_cast<int>(k);
}

// Alpha cut-outs are an any-hit filter inside the traversal: every kernel must agree with brute
// force (which applies the same mask to each triangle), and the masks must remove hits.
TEST_P(BvhBackends, AlphaMasksAgreeWithBruteForce) {
    const Scene opaque = mixed_scene(GetParam().accel, GetParam().isa);
    const Scene s = mixed_scene(GetParam().accel, GetParam().isa, true);
    int hits = 0, opaque_hits = 0, masked_mesh_hits = 0, passed = 0;
    for (const Ray& r : random_rays(testing::scaled(10000))) {
        const auto a = s.intersect(r), b = s.intersect_brute_force(r);
        ASSERT_EQ(a.has_value(), b.has_value());
        ASSERT_EQ(s.occluded(r), b.has_value());
        ASSERT_EQ(s.occluded_brute_force(r), b.has_value());
        const auto o = opaque.intersect(r);
        opaque_hits += o.has_value();
        ASSERT_FALSE(a && !o);  // a mask only removes surface
        if (o && o->kind == ShapeKind::kMesh && s.instances[o->index].alpha >= 0 &&
            !(a && a->kind == o->kind && a->index == o->index && a->prim == o->prim))
            ++passed;  // went through the cut-out (to something behind, or nothing)
        if (!a) continue;
        ++hits;
        EXPECT_EQ(a->t, b->t);
        EXPECT_EQ(a->index, b->index);
        EXPECT_EQ(a->prim, b->prim);
        if (a->kind == ShapeKind::kMesh && s.instances[a->index].alpha >= 0) {
            ++masked_mesh_hits;
            EXPECT_TRUE(s.alpha_keeps(a->index, a->prim, a->b1, a->b2, r));
        }
    }
    EXPECT_LT(hits, opaque_hits);
    EXPECT_GT(passed, testing::scaled(50));            // the cut-outs let rays through (139 of 10000 rays)
    EXPECT_GT(masked_mesh_hits, testing::scaled(200));  // and keep the rest
}

TEST(Sbvh, SplitsLargeTrianglesAndLowersTheSahCost) {
    auto g = rng(21);
    const TriangleMesh m = large_among_small(g, 4000, 40);
    BvhBuildOptions spatial;
    spatial.spatial_splits = true;
    for (SimdIsa isa : {SimdIsa::kSse4, SimdIsa::kAvx2}) {
        if (!cpu_supports(isa)) continue;
        MeshBvh plain, split;
        plain.build(m, {}, isa);
        split.build(m, spatial, isa);
        EXPECT_EQ(plain.references(), m.triangle_count());
        // The large triangles are cut into many references, within the duplication budget.
        EXPECT_GT(split.references(), m.triangle_count() + 40 * 4);
        EXPECT_LE(split.references(), m.triangle_count() * 2 + 4000);
        // The expected cost of a random ray (the SAH, summed over the built tree) drops.
        EXPECT_LT(split.sah_cost(), 0.8 * plain.sah_cost()) << simd_isa_name(isa);
        EXPECT_EQ(plain.bounds().lo.x, split.bounds().lo.x);
    }
}

TEST(Sbvh, TheTreeIsTheSameForAnyThreadCount) {
    // With a small duplication budget that runs out, the tree must not depend on which subtree
    // a thread builds first (images are bit-identical for any thread count).
    auto g = rng(22);
    const TriangleMesh m = large_among_small(g, 20000, 200);
    BvhBuildOptions spatial;
    spatial.spatial_splits = true;
    spatial.max_duplication = 0.02f;
    const auto build_on = [&](int threads) {
        MeshBvh b;
        tbb::task_arena(threads).execute([&] { b.build(m, spatial); });
        return b;
    };
    const MeshBvh one = build_on(1), two = build_on(2);
    EXPECT_GT(one.references(), m.triangle_count());
    EXPECT_LE(one.references(), m.triangle_count() * 102 / 100);  // within the budget
    EXPECT_EQ(one.references(), two.references());
    EXPECT_EQ(one.sah_cost(), two.sah_cost());
    for (const Ray& r : random_rays(2000)) {
        const auto a = one.closest(r), b = two.closest(r);
        ASSERT_EQ(a.has_value(), b.has_value());
        if (a) {
            EXPECT_EQ(a->prim, b->prim);
        }
    }
}

// n boxes at random in a cube of half-size 10, each spanning a corner and a point within `size`
// of it.
std::vector<Bounds3> random_boxes(std::mt19937& g, std::size_t n, float size) {
    std::vector<Bounds3> boxes(n);
    for (auto& b : boxes) {
        const Point3 c = random_point(g, 10);
        b.extend(c);
        b.extend(c + to_vector(random_point(g, size)));
    }
    return boxes;
}

TEST(Bvh, TreeInvariants) {
    auto g = rng(3);
    std::vector<Bounds3> boxes = random_boxes(g, 5000, 0.5f);
    // Bad input is left out, not a crash: a NaN and an infinite box.
    boxes[10].lo.x = std::numeric_limits<float>::quiet_NaN();
    boxes[20].hi.y = std::numeric_limits<float>::infinity();
    Bvh4 bvh;
    bvh.build(boxes);
    EXPECT_EQ(bvh.skipped(), 2u);
    EXPECT_EQ(bvh.order().size(), boxes.size() - 2);
    // Every primitive appears once, and every child box holds what is below it.
    std::vector<int> seen(boxes.size(), 0);
    for (std::uint32_t p : bvh.order()) ++seen[p];
    for (std::size_t i = 0; i < boxes.size(); ++i) EXPECT_EQ(seen[i], i == 10 || i == 20 ? 0 : 1);
    const auto contains = [](const Bvh4Node& n, int i, const Bounds3& b) {
        return n.lo_x[i] <= b.lo.x && n.lo_y[i] <= b.lo.y && n.lo_z[i] <= b.lo.z && n.hi_x[i] >= b.hi.x &&
               n.hi_y[i] >= b.hi.y && n.hi_z[i] >= b.hi.z;
    };
    std::function<Bounds3(std::uint32_t)> check = [&](std::uint32_t ref) -> Bounds3 {
        Bounds3 all;
        if (ref & Bvh4Node::kLeaf) {
            EXPECT_LE(Bvh4Node::leaf_count(ref), 8u);
            for (std::uint32_t i = 0; i < Bvh4Node::leaf_count(ref); ++i) {
                const Bounds3& b = boxes[bvh.order()[Bvh4Node::leaf_first(ref) + i]];
                all.extend(b.lo);
                all.extend(b.hi);
            }
            return all;
        }
        const Bvh4Node& n = bvh.nodes()[ref];
        for (int i = 0; i < 4; ++i) {
            if (n.child[i] == Bvh4Node::kEmpty) continue;
            const Bounds3 b = check(n.child[i]);
            EXPECT_TRUE(contains(n, i, b));
            all.extend(b.lo);
            all.extend(b.hi);
        }
        return all;
    };
    check(0);
    EXPECT_LT(bvh.depth(), 20);
}

// BvhBuildOptions::alone (the scene's top level keeps each mesh instance in a leaf of its own):
// every marked primitive sits alone in its leaf, the others still share leaves, and without
// the marks the same boxes put marked ones in shared leaves (so the marks are what holds).
TEST(Bvh, PrimitivesMarkedAloneHaveLeavesOfTheirOwn) {
    auto g = rng(11);
    const std::vector<Bounds3> boxes = random_boxes(g, 600, 0.5f);
    std::vector<std::uint8_t> alone(boxes.size());
    for (std::size_t i = 0; i < alone.size(); i += 7) alone[i] = 1;
    const auto leaves = [&](bool marked) {
        BvhBuildOptions options;
        options.max_leaf_size = 4;
        options.traversal_cost = 4;  // so that leaves of several are worth it
        if (marked) options.alone = alone;
        Bvh4 bvh;
        bvh.build(boxes, options);
        int shared_marked = 0, shared_leaves = 0;
        std::vector<int> seen(boxes.size());
        std::function<void(std::uint32_t)> walk = [&](std::uint32_t ref) {
            if (ref & Bvh4Node::kLeaf) {
                const std::uint32_t count = Bvh4Node::leaf_count(ref);
                shared_leaves += count > 1;
                for (std::uint32_t i = 0; i < count; ++i) {
                    const std::uint32_t p = bvh.order()[Bvh4Node::leaf_first(ref) + i];
                    ++seen[p];
                    shared_marked += count > 1 && alone[p];
                }
                return;
            }
            for (std::uint32_t c : bvh.nodes()[ref].child)
                if (c != Bvh4Node::kEmpty) walk(c);
        };
        walk(bvh.root());
        for (int n : seen) EXPECT_EQ(n, 1);
        return std::pair{shared_marked, shared_leaves};
    };
    const auto [marked_shared, marked_leaves] = leaves(true);
    EXPECT_EQ(marked_shared, 0);
    EXPECT_GT(marked_leaves, 20);
    const auto [unmarked_shared, unmarked_leaves] = leaves(false);
    EXPECT_GT(unmarked_shared, 10);
}

// The nodes lie as a traversal meets them (bvh.cpp, lay_out_nodes): each node's inner children
// side by side, and every subtree below a node in one stretch, also when two threads built the
// tree (whose builders number nodes as they make them, the two halves interleaved).
TEST(Bvh, NodesLieInTraversalOrder) {
    auto g = rng(41);
    const std::vector<Bounds3> boxes = random_boxes(g, 100000, 0.05f);
    Bvh8 bvh;
    tbb::task_arena(2).execute([&] { bvh.build(boxes); });
    ASSERT_EQ(bvh.root(), 0u);
    std::vector<int> placed(bvh.nodes().size(), 0);
    placed[0] = 1;
    // The indices of the nodes below ref (ref itself not included): checked to be one stretch.
    std::function<std::pair<std::uint32_t, std::uint32_t>(std::uint32_t)> below =
        [&](std::uint32_t ref) -> std::pair<std::uint32_t, std::uint32_t> {
        std::uint32_t lo = UINT32_MAX, hi = 0, count = 0, previous = 0;
        const Bvh8Node& n = bvh.nodes()[ref];
        for (const std::uint32_t c : n.child) {
            if (c & Bvh8Node::kLeaf) continue;
            if (count > 0) EXPECT_EQ(c, previous + 1) << "children of node " << ref;
            EXPECT_GT(c, ref);
            ++placed[c];
            previous = c;
            lo = std::min(lo, c), hi = std::max(hi, c), ++count;
        }
        for (const std::uint32_t c : n.child) {
            if (c & Bvh8Node::kLeaf) continue;
            const auto [l, h] = below(c);
            if (l > h) continue;  // c has no inner children
            const std::uint32_t size = h - l + 1;
            lo = std::min(lo, l), hi = std::max(hi, h), count += size;
        }
        if (count > 0) EXPECT_EQ(hi - lo + 1, count) << "the nodes below node " << ref << " are not one stretch";
        return {lo, count > 0 ? hi : 0};
    };
    below(0);
    EXPECT_GT(bvh.nodes().size(), 1000u);
    for (std::size_t i = 0; i < placed.size(); ++i) EXPECT_EQ(placed[i], 1) << "node " << i;
}

TEST_P(BvhBackends, RaysAtSharedVerticesAndEdgesNeverSlipThrough) {
    // A 32 x 32 grid of quads (two triangles each) with jittered interior vertices, tilted by an
    // instance transform: rays aimed at every vertex and every edge midpoint must hit.
    auto g = rng(5);
    const int n = 32;
    TriangleMesh m;
    for (int y = 0; y <= n; ++y)
        for (int x = 0; x <= n; ++x) {
            const bool inner = x > 0 && y > 0 && x < n && y < n;
            m.positions.push_back({x + (inner ? uniform(g, -0.3f, 0.3f) : 0), y + (inner ? uniform(g, -0.3f, 0.3f) : 0),
                                   inner ? uniform(g, -0.2f, 0.2f) : 0});
        }
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            const std::uint32_t a = y * (n + 1) + x, b = a + 1, c = a + n + 1, d = c + 1;
            m.indices.insert(m.indices.end(), {a, b, d, a, d, c});
        }
    Scene s;
    s.materials.push_back(DiffuseMaterial{0});
    s.textures.push_back(ConstantTexture{Color{0.5f}});
    s.meshes.push_back(m);
    const Transform place = Transform::rotate(33, {1, 0.5f, 0.2f}) * Transform::translate({-16, -16, 0});
    s.instances.push_back({0, place, std::nullopt});
    s.accel = GetParam().accel;
    s.mesh_isa = GetParam().isa;
    s.commit();
    // Only targets inside the grid: past a border vertex or edge, a miss is correct.
    const auto on_border = [n](std::uint32_t v) {
        const std::uint32_t x = v % (n + 1), y = v / (n + 1);
        return x == 0 || y == 0 || x == static_cast<std::uint32_t>(n) || y == static_cast<std::uint32_t>(n);
    };
    int rays = 0, misses = 0;
    const auto shoot = [&](Point3 target) {
        for (int o = 0; o < 2; ++o) {
            const Point3 origin{uniform(g, -30, 30), uniform(g, -30, 30), o ? 40.0f : -40.0f};
            ++rays;
            if (!s.intersect(Ray{origin, normalize(target - origin)})) ++misses;
        }
    };
    for (const std::uint32_t* tri = m.indices.data(); tri < m.indices.data() + m.indices.size(); tri += 3) {
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t a = tri[k], b = tri[(k + 1) % 3];
            const Point3 p = place.point(m.positions[a]), q = place.point(m.positions[b]);
            if (!on_border(a)) shoot(p);
            if (!on_border(a) || !on_border(b)) shoot(p + (q - p) * 0.5f);
        }
    }
    EXPECT_GT(rays, 20000);
    EXPECT_EQ(misses, 0);
}

TEST(Bvh, InstanceNormalsTransformByTheInverseTranspose) {
    // A triangle in the plane x + z = 0 (normal (1, 0, 1)/sqrt 2 by its winding), with vertex
    // normals along the same direction, scaled by (2, 1, 1): by hand, the world normal is
    // M^-T n = (1/2, 0, 1) normalised, while the scaled edges' cross product agrees.
    TriangleMesh m;
    m.positions = {{-1, -1, 1}, {1, -1, -1}, {0, 1, 0}};
    m.indices = {0, 1, 2};
    const Normal3 vn = normalize(Normal3{1, 0, 1});
    m.normals = {vn, vn, vn};
    Scene s;
    s.materials.push_back(DiffuseMaterial{0});
    s.textures.push_back(ConstantTexture{Color{0.5f}});
    s.meshes.push_back(m);
    s.instances.push_back({0, Transform::scale({2, 1, 1}), std::nullopt});
    s.commit();
    const Ray r{{5, 0, 5}, normalize(Vector3{-1, 0, -1})};
    const auto hit = s.intersect(r);
    ASSERT_TRUE(hit);
    const SurfaceInteraction si = s.interaction(r, *hit);
    const float k = 1 / std::sqrt(1.25f);
    EXPECT_NEAR(si.ns.x, 0.5f * k, 1e-5f);
    EXPECT_NEAR(si.ns.y, 0, 1e-5f);
    EXPECT_NEAR(si.ns.z, k, 1e-5f);
    EXPECT_NEAR(si.n.x, 0.5f * k, 1e-5f);
    EXPECT_NEAR(si.n.z, k, 1e-5f);
    // The hit point is on the scaled plane x/2 + z = 0.
    EXPECT_NEAR(si.p.x / 2 + si.p.z, 0, 1e-5f);
}

TEST(Mesh, NormalMapsTiltTheShadingNormalInTheUvFrame) {
    // A square in z = 0 facing -z (toward the ray), u along +x and v along +y; a constant
    // normal-map texel (0.5 + 0.5 sin a, 0.5, 0.5 + 0.5 cos a) tilts the normal by a toward the
    // tangent +x: n' = sin a (+x) + cos a n. Green tilts it toward +v (+y) alike. Mirrored uvs
    // flip the tangent or the bitangent.
    for (const int mirror : {0, 1, 2}) {  // none, u, v
        const bool mirrored_u = mirror == 1, mirrored_v = mirror == 2;
        TriangleMesh m;
        m.positions = {{0, 0, 0}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0}};
        m.indices = {0, 1, 2, 0, 2, 3};  // (p1 - p0) x (p2 - p0) = -z
        m.uvs = {{0, 0}, {0, 1}, {1, 1}, {1, 0}};
        for (Point2& uv : m.uvs) {
            if (mirrored_u) uv.x = 1 - uv.x;
            if (mirrored_v) uv.y = 1 - uv.y;
        }
        Scene s;
        s.materials.push_back(DiffuseMaterial{0});
        const float a = 0.3f;
        s.textures.push_back(ConstantTexture{Color{0.5f + 0.5f * std::sin(a), 0.5f, 0.5f + 0.5f * std::cos(a)}});
        s.textures.push_back(ConstantTexture{Color{0.5f, 0.5f + 0.5f * std::sin(a), 0.5f + 0.5f * std::cos(a)}});
        s.materials.push_back(DiffuseMaterial{0});
        s.normal_maps = {NormalMap{0, 1}, NormalMap{1, 1}};
        s.meshes.push_back(m);
        s.instances.push_back({0, Transform{}, std::nullopt});
        s.commit();
        const Ray r{{0.3f, 0.6f, -2}, {0, 0, 1}};
        const auto hit = s.intersect(r);
        ASSERT_TRUE(hit);
        const SurfaceInteraction si = s.interaction(r, *hit);
        EXPECT_NEAR(si.n.z, -1, 1e-6f);
        const float tx = mirrored_u ? -1.0f : 1.0f;
        EXPECT_NEAR(si.ns.x, tx * std::sin(a), 1e-4f) << mirror;
        EXPECT_NEAR(si.ns.y, 0, 1e-4f);
        EXPECT_NEAR(si.ns.z, -std::cos(a), 1e-4f);
        // The green map on the same square (material 1): toward +v.
        Scene& ms = s;
        ms.instances[0].material = 1;
        ms.commit();
        const SurfaceInteraction sg = ms.interaction(r, *ms.intersect(r));
        const float ty = mirrored_v ? -1.0f : 1.0f;
        EXPECT_NEAR(sg.ns.x, 0, 1e-4f) << mirror;
        EXPECT_NEAR(sg.ns.y, ty * std::sin(a), 1e-4f) << mirror;
        EXPECT_NEAR(sg.ns.z, -std::cos(a), 1e-4f);
    }
}

TEST(Bvh, InstancesShareTheirMeshAndItsTree) {
    auto g = rng(9);
    Scene s;
    s.materials.push_back(DiffuseMaterial{0});
    s.textures.push_back(ConstantTexture{Color{0.5f}});
    s.meshes.push_back(random_soup(g, 10000));
    s.instances.push_back({0, Transform{}, std::nullopt});
    s.commit();
    const std::size_t one = s.accel_memory_bytes();
    for (int i = 1; i < 100; ++i) s.instances.push_back({0, Transform::translate({3.0f * i, 0, 0}), std::nullopt});
    s.commit();
    EXPECT_EQ(s.mesh_bvhs().size(), 1u);
    // 99 more instances cost their top-level share only (well under one mesh's tree each).
    EXPECT_LT(s.accel_memory_bytes() - one, one / 10);
    const Ray r{{3.0f * 57, 0, -10}, {0, 0, 1}};
    const auto hit = s.intersect(r);
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->index, 57u);
}

TEST(Mesh, DegenerateAndNonFiniteTrianglesAreDroppedAndCounted) {
    TriangleMesh m;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {2, 0, 0}, {nan, 0, 0}};
    m.indices = {0, 1, 2, 0, 1, 3, 0, 0, 2, 0, 1, 4, 2, 1, 0};  // good, collinear, repeated, NaN, good
    EXPECT_EQ(validate_and_drop_degenerate(m), 3u);
    EXPECT_EQ(m.indices, (std::vector<std::uint32_t>{0, 1, 2, 2, 1, 0}));
    TriangleMesh bad;
    bad.positions = {{0, 0, 0}};
    bad.indices = {0, 0, 1};
    EXPECT_THROW(validate_and_drop_degenerate(bad), std::invalid_argument);
}

TEST(Mesh, ConvexPolygonsTriangulateAsFans) {
    // A convex quad (a unit square), a two-corner face (skipped) and a triangle.
    const std::vector<Point3> p{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 0},
                                {1, 0, 0}, {0, 0, 1}, {1, 0, 1}, {0, 1, 1}};
    std::vector<std::uint32_t> tris, face_of;
    EXPECT_EQ(triangulate_faces({4, 2, 3}, {0, 1, 2, 3, 4, 5, 6, 7, 8}, p, tris, &face_of), 1u);
    EXPECT_EQ(tris, (std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3, 6, 7, 8}));
    EXPECT_EQ(face_of, (std::vector<std::uint32_t>{0, 0, 2}));
    EXPECT_THROW(triangulate_faces({5}, {0, 1, 2}, p, tris), std::invalid_argument);
}

TEST(Bvh, NanRaysHitNothing) {
    const Scene s = mixed_scene(AccelKind::kBvh);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    EXPECT_FALSE(s.intersect(Ray{{0, 0, 0}, {nan, nan, nan}}));
    EXPECT_FALSE(s.occluded(Ray{{nan, 0, 0}, {0, 0, 1}}));
}

TEST(Transform, InverseRotationAndLookAt) {
    const Transform t = Transform::translate({1, 2, 3}) * Transform::rotate(90, {0, 1, 0}) *
                        Transform::scale({2, 3, 4});
    const Point3 p{0.3f, -0.7f, 1.1f};
    const Point3 back = Transform{t.to_object, t.to_world}.point(t.point(p));
    EXPECT_NEAR(back.x, p.x, 1e-5f);
    EXPECT_NEAR(back.y, p.y, 1e-5f);
    EXPECT_NEAR(back.z, p.z, 1e-5f);
    // Rotating +x by 90 degrees about +y gives -z (the right-hand rule, as pbrt's Rotate).
    const Vector3 x = Transform::rotate(90, {0, 1, 0}).vector({1, 0, 0});
    EXPECT_NEAR(x.x, 0, 1e-6f);
    EXPECT_NEAR(x.z, -1, 1e-6f);
    const auto la = Transform::look_at({1, 1, 1}, {1, 1, 5}, {0, 1, 0});
    ASSERT_TRUE(la);
    const Vector3 z = la->vector({0, 0, 1});
    EXPECT_NEAR(z.z, 1, 1e-6f);
    EXPECT_FALSE(Transform::look_at({0, 0, 0}, {0, 1, 0}, {0, 1, 0}));  // up along the view
    EXPECT_FALSE(Transform::from(Matrix34{{{{1, 0, 0, 0}, {0, 0, 0, 0}, {0, 0, 1, 0}}}}));  // singular
    EXPECT_TRUE(Transform::scale({-1, 1, 1}).flips());
}

// A quad's own test accepts a hit whose rounded point lies a rounding error outside the quad's
// flat box; the tree must not cull it there (a ray grazing the Cornell box light's edge once met
// the wall behind through the tree and the light by brute force). Rays from inside a box of quads
// at the Cornell box's scale, aimed at points on the quads' edges and just either side of them.
TEST(Bvh, QuadHitsAtTheirEdgesAreTheBruteForceHits) {
    auto g = rng(23);
    Scene s;
    s.materials.push_back(DiffuseMaterial{0});
    s.textures.push_back(ConstantTexture{Color{0.5f}});
    s.quads.push_back(Quad::make({343, 548.7f, 227}, {0, 0, 105}, {-130, 0, 0}));  // the light
    s.quads.push_back(Quad::make({0, 0, 0}, {556, 0, 0}, {0, 0, 559.2f}));          // floor
    s.quads.push_back(Quad::make({0, 548.8f, 0}, {0, 0, 559.2f}, {556, 0, 0}));     // ceiling
    s.quads.push_back(Quad::make({0, 0, 559.2f}, {556, 0, 0}, {0, 548.8f, 0}));     // back
    for (int i = 0; i < 12; ++i) {  // axis-aligned and tilted quads inside
        const Point3 c{uniform(g, 50, 450), uniform(g, 50, 450), uniform(g, 50, 450)};
        const bool flat = i % 2 == 0;
        const Vector3 e1 = flat ? Vector3{uniform(g, 20, 120), 0, 0} : to_vector(random_point(g, 100));
        const Vector3 e2 = flat ? Vector3{0, 0, uniform(g, 20, 120)} : to_vector(random_point(g, 100));
        s.quads.push_back(Quad::make(c, e1, e2));
    }
    s.accel = AccelKind::kBvh;
    s.commit();
    int hits = 0, quad_edge_hits = 0;
    for (int i = 0; i < testing::scaled(200000); ++i) {
        const Quad& q = s.quads[static_cast<std::size_t>(i) % s.quads.size()];
        float a = uniform(g, 0, 1), b = uniform(g, 0, 1);
        const float edge = (i / 3) % 2 == 0 ? 0.0f : 1.0f;
        ((i / 7) % 2 == 0 ? a : b) = edge + ((i % 3) - 1) * uniform(g, 0, 1e-6f);  // on, inside, outside
        const Point3 target = q.corner + q.edge1 * a + q.edge2 * b;
        // Half the rays start far away, half a short way off the quad's plane (as from the
        // ceiling 0.1 above the light), where the box test's relative widening is tiny.
        const Point3 origin = i % 2 == 0 ? Point3{uniform(g, 10, 540), uniform(g, 10, 540), uniform(g, -700, 540)}
                                         : target + to_vector(q.normal()) * uniform(g, -0.5f, 0.5f) +
                                               to_vector(random_point(g, 2));
        const Vector3 d = target - origin;
        if (length(d) < 1e-3f) continue;
        const Ray r{origin, normalize(d)};
        const auto x = s.intersect(r), y = s.intersect_brute_force(r);
        ASSERT_EQ(x.has_value(), y.has_value()) << i;
        ASSERT_EQ(s.occluded(r), y.has_value()) << i;
        if (!x) continue;
        ++hits;
        if (x->index == y->index) {
            ASSERT_EQ(x->t, y->t) << i;
        } else {  // two quads meeting at an edge: either may hold the nearest hit, an ulp apart
            ASSERT_NEAR(x->t, y->t, 1e-5f * y->t) << i << ": quad " << x->index << " against " << y->index;
            ASSERT_EQ(s.quads[x->index].intersect(r), std::optional<Float>(x->t)) << i;
        }
        quad_edge_hits += &s.quads[x->index] == &q;
    }
    EXPECT_GT(hits, testing::scaled(150000));
    EXPECT_GT(quad_edge_hits, testing::scaled(50000));
    // The padding is the tree's alone: the scene's extent (which sizes distant and environment
    // lights) is the exact box of the corners.
    Scene light;
    light.materials = s.materials;
    light.textures = s.textures;
    light.quads.push_back(s.quads[0]);
    light.commit();
    EXPECT_EQ(light.bounds().lo, (Point3{213, 548.7f, 227}));
    EXPECT_EQ(light.bounds().hi, (Point3{343, 548.7f, 332}));
}

#if GLINT_EMBREE
TEST(Embree, AgreesWithBruteForceWithinFloatNoise) {
  for (const bool alpha : {false, true}) {
    const Scene s = mixed_scene(AccelKind::kEmbree, std::nullopt, alpha);
    int compared = 0, differ = 0;
    for (const Ray& r : random_rays(testing::scaled(10000))) {
        const auto a = s.intersect(r), b = s.intersect_brute_force(r);
        const bool occluded = s.occluded(r);
        // Embree's triangle test is not watertight and its interval ends differ by an ulp:
        // allow a handful of grazing disagreements, no more.
        if (a.has_value() != b.has_value() || occluded != b.has_value()) {
            ++differ;
            continue;
        }
        if (!a) continue;
        ++compared;
        if (a->kind != b->kind || a->index != b->index || a->prim != b->prim ||
            std::abs(a->t - b->t) > 1e-4f * std::max(1.0f, b->t)) {
            ++differ;
            continue;
        }
        if (a->kind == ShapeKind::kMesh) {
            EXPECT_NEAR(a->b1, b->b1, 1e-3f);
            EXPECT_NEAR(a->b2, b->b2, 1e-3f);
        }
    }
    EXPECT_GT(compared, testing::scaled(1000));
    EXPECT_LE(differ, alpha ? 10 : 5) << "alpha " << alpha;  // a checker edge may fall either side too
    EXPECT_GT(s.accel_memory_bytes(), 0u);
  }
}
#endif

}  // namespace
}  // namespace glint
