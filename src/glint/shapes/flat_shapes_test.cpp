// Quads, disks and triangles: hand-computed hits and misses, watertightness, and area sampling
// (points on the shape, uniform by area, density 1/area).
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <limits>
#include <numbers>
#include <utility>
#include <vector>

#include "glint/samplers/hash.h"
#include "glint/shapes/disk.h"
#include "glint/shapes/plane.h"
#include "glint/shapes/quad.h"
#include "glint/shapes/sphere.h"
#include "glint/shapes/triangle.h"
#include "glint/shapes/triangle_sse.h"
#include "stats.h"

namespace glint {
namespace {

Ray ray(Point3 o, Vector3 d) { return Ray{o, normalize(d)}; }
Sample2 uniform(std::uint32_t i) {
    return {to_unit_float(mix32(2 * i + 77)), to_unit_float(mix32(2 * i + 78))};
}

// The Cornell box light: 343..213 in x, 227..332 in z at y = 548.7. Edge order (z, then -x):
// (0,0,105) x (-130,0,0) = (0*0 - 105*0, 105*(-130) - 0*0, 0*0 - 0*(-130)) = (0, -13650, 0),
// so it faces down, into the box.
const Quad kLight = Quad::make({343, 548.7f, 227}, {0, 0, 105}, {-130, 0, 0});

TEST(Quad, HitsInsideMissesOutside) {
    auto t = kLight.intersect(ray({278, 0, 280}, {0, 1, 0}));
    ASSERT_TRUE(t);
    EXPECT_NEAR(*t, 548.7f, 1e-3);
    EXPECT_FALSE(kLight.intersect(ray({200, 0, 280}, {0, 1, 0})));  // x outside 213..343
    EXPECT_FALSE(kLight.intersect(ray({278, 0, 340}, {0, 1, 0})));  // z outside 227..332
    EXPECT_FALSE(kLight.intersect(ray({278, 0, 280}, {1, 0, 0})));  // parallel
    EXPECT_FALSE(kLight.intersect(ray({278, 600, 280}, {0, 1, 0})));  // behind
}

TEST(Quad, NormalIsEdge1CrossEdge2AndAreaIsTheParallelogram) {
    EXPECT_NEAR(kLight.normal().y, -1, 1e-6);
    EXPECT_NEAR(kLight.area(), 130.0f * 105.0f, 1e-2);
    const Quad skew = Quad::make({0, 0, 0}, {2, 0, 0}, {1, 3, 0});
    EXPECT_NEAR(skew.area(), 6, 1e-5);  // base 2, height 3
    EXPECT_TRUE(skew.intersect(ray({2.9f, 2.9f, -1}, {0, 0, 1})));   // inside the slanted side
    EXPECT_FALSE(skew.intersect(ray({0.5f, 2.9f, -1}, {0, 0, 1})));  // left of it
}

TEST(Disk, HitsWithinTheRadius) {
    const Disk d{{0, 0, 5}, {0, 0, -1}, 2};
    auto t = d.intersect(ray({1.9f, 0, 0}, {0, 0, 1}));
    ASSERT_TRUE(t);
    EXPECT_FLOAT_EQ(*t, 5);
    EXPECT_FALSE(d.intersect(ray({1.5f, 1.5f, 0}, {0, 0, 1})));  // |(1.5,1.5)| = 2.12 > 2
    EXPECT_NEAR(d.area(), 4 * std::numbers::pi, 1e-5);
}

TEST(Triangle, HitsAtHandValuesAndMissesOutside) {
    const Triangle tri{{0, 0, 5}, {2, 0, 5}, {0, 2, 5}};
    auto t = tri.intersect(ray({0.5f, 0.5f, 0}, {0, 0, 1}));
    ASSERT_TRUE(t);
    EXPECT_FLOAT_EQ(*t, 5);
    EXPECT_FALSE(tri.intersect(ray({1.5f, 1.5f, 0}, {0, 0, 1})));  // beyond the hypotenuse
    EXPECT_FALSE(tri.intersect(ray({0.5f, 0.5f, 6}, {0, 0, 1})));  // behind
    // Slanted ray: from (0,0,0) towards (1, 0.5, 5), t = |(1, 0.5, 5)|.
    t = tri.intersect(ray({0, 0, 0}, {1, 0.5f, 5}));
    ASSERT_TRUE(t);
    EXPECT_NEAR(*t, std::sqrt(1 + 0.25 + 25), 1e-5);
    EXPECT_NEAR(tri.area(), 2, 1e-6);
    EXPECT_NEAR(tri.normal().z, 1, 1e-6);  // (2,0,0) x (0,2,0) = (0,0,4)
}

TEST(Triangle, TheWatertightAxesFollowTheLargestComponentAndTheSign) {
    // Woop et al.'s rule written out plainly: z is the first axis of largest |d|, x and y follow
    // it cyclically and swap when d points down z. Over the axes, both signs, ties and zeros.
    const float values[] = {-2.0f, -1.0f, -0.5f, -0.0f, 0.0f, 0.5f, 1.0f, 2.0f};
    for (const float x : values) {
        for (const float y : values) {
            for (const float z : values) {
                if (x == 0 && y == 0 && z == 0) continue;
                const float c[3] = {x, y, z};
                int kz = 0;
                for (int k = 1; k < 3; ++k)
                    if (std::abs(c[k]) > std::abs(c[kz])) kz = k;
                int kx = (kz + 1) % 3, ky = (kz + 2) % 3;
                if (c[kz] < 0) std::swap(kx, ky);
                const WatertightRay w(Ray{{0, 0, 0}, Vector3{x, y, z}});
                EXPECT_EQ(w.kz, kz) << x << " " << y << " " << z;
                EXPECT_EQ(w.kx, kx) << x << " " << y << " " << z;
                EXPECT_EQ(w.ky, ky) << x << " " << y << " " << z;
                EXPECT_EQ(w.sx, c[kx] / c[kz]);
                EXPECT_EQ(w.sy, c[ky] / c[kz]);
                EXPECT_EQ(w.sz, 1 / c[kz]);
            }
        }
    }
}

TEST(Triangle, RaysThroughSharedEdgesAndVerticesNeverSlipThrough) {
    // A fan of 8 triangles around a centre vertex, all in the plane z = 3 with awkward
    // coordinates. Rays aimed exactly at the shared vertex, at points on the shared edges and at
    // the fan's edge midpoints must hit at least one triangle.
    const Point3 c{0.1f, -0.3f, 3};
    std::vector<Point3> rim;
    for (int i = 0; i < 8; ++i) {
        const float a = static_cast<float>(i) * std::numbers::pi_v<float> / 4 + 0.1f;
        rim.push_back({c.x + 1.7f * std::cos(a), c.y + 1.3f * std::sin(a), 3});
    }
    std::vector<Triangle> fan;
    for (int i = 0; i < 8; ++i) fan.push_back({c, rim[static_cast<std::size_t>(i)], rim[static_cast<std::size_t>((i + 1) % 8)]});
    auto hit_any = [&](Point3 origin, Point3 target) {
        const Ray r = ray(origin, target - origin);
        for (const Triangle& t : fan)
            if (t.intersect(r)) return true;
        return false;
    };
    int aimed = 0;
    for (Point3 origin : {Point3{0, 0, 0}, Point3{-2.3f, 1.1f, -4}, Point3{0.37f, 5, 0.5f}}) {
        EXPECT_TRUE(hit_any(origin, c));
        ++aimed;
        for (int i = 0; i < 8; ++i) {
            const Point3 v = rim[static_cast<std::size_t>(i)];
            for (float f : {0.1f, 0.333f, 0.5f, 0.77f, 0.999f}) {
                EXPECT_TRUE(hit_any(origin, c + (v - c) * f)) << i << " " << f;
                ++aimed;
            }
        }
    }
    EXPECT_EQ(aimed, 3 * (1 + 8 * 5));
}

// The textbook Moller-Trumbore test, in float: the control that shows the watertightness test
// below can fail.
bool moller_trumbore(const Triangle& tr, const Ray& r) {
    const Vector3 e1 = tr.p1 - tr.p0, e2 = tr.p2 - tr.p0, p = cross(r.direction, e2);
    const float det = dot(e1, p);
    if (std::abs(det) < 1e-12f) return false;
    const float inv = 1 / det;
    const Vector3 s = r.origin - tr.p0;
    const float u = dot(s, p) * inv;
    if (u < 0 || u > 1) return false;
    const Vector3 q = cross(s, e1);
    const float v = dot(r.direction, q) * inv;
    if (v < 0 || u + v > 1) return false;
    return dot(e2, q) * inv > kRayTMin;
}

TEST(Triangle, RaysAtRandomSharedEdgesNeverSlipThrough) {
    // Pairs of triangles sharing a random edge a-b, and rays from random origins aimed at random
    // points of that edge: at least one of the two must report a hit. Moller-Trumbore, run on
    // the same rays, lets a few percent through (it computes each triangle's edge test
    // differently); the watertight test must let none through.
    int mt_cracks = 0, cracks = 0;
    const int n = 50000;
    for (std::uint32_t k = 0; k < n; ++k) {
        auto u = [k](std::uint32_t j) { return to_unit_float(mix32(k * 16 + j)); };
        const Point3 a{u(0) * 4 - 2, u(1) * 4 - 2, 3 + u(2)}, b{u(3) * 4 - 2, u(4) * 4 - 2, 3 + u(5)};
        const Point3 c{u(6) * 4 - 2, u(7) * 4 - 2, 3};
        const Point3 mid = a + (b - a) * 0.5f;
        const Point3 d = mid + (mid - c);  // across the edge from c
        const Triangle t1{a, b, c}, t2{b, a, d};
        const Point3 target = a + (b - a) * u(8);
        const Point3 o{u(9) * 10 - 5, u(10) * 10 - 5, -5 - u(11) * 5};
        const Ray r = ray(o, target - o);
        cracks += !t1.intersect(r) && !t2.intersect(r);
        mt_cracks += !moller_trumbore(t1, r) && !moller_trumbore(t2, r);
    }
    EXPECT_EQ(cracks, 0);
    EXPECT_GT(mt_cracks, n / 100);  // the rays really are hard
}

TEST(Triangle, SseOrdersAreTheScalarAxes) {
    // WatertightRaySse's byte order (read from kWatertightOrders) against WatertightRay's axes,
    // which the test above checks against the rule: lane i of the order holds bytes 4 k_i .. 4 k_i + 3.
    const float values[] = {-2.0f, -1.0f, -0.5f, -0.0f, 0.0f, 0.5f, 1.0f, 2.0f};
    int seen[6] = {};
    for (const float x : values)
        for (const float y : values)
            for (const float z : values) {
                if (x == 0 && y == 0 && z == 0) continue;
                const Ray r{{0, 0, 0}, Vector3{x, y, z}};
                const WatertightRay w(r);
                const WatertightRaySse sse(r);
                alignas(16) std::uint32_t lanes[4];
                _mm_store_si128(reinterpret_cast<__m128i*>(lanes), sse.order);
                const int k[4] = {w.kx, w.ky, w.kz, 3};
                for (int i = 0; i < 4; ++i)
                    EXPECT_EQ(lanes[i], 0x03020100u + 0x04040404u * static_cast<std::uint32_t>(k[i]))
                        << x << " " << y << " " << z << " lane " << i;
                ++seen[2 * w.kz + (w.kx != (w.kz + 1) % 3)];
            }
    for (int i = 0; i < 6; ++i) EXPECT_GT(seen[i], 0) << "order " << i << " never chosen";
}

TEST(Triangle, TheSseTestGivesTheScalarTestsBits) {
    // intersect_triangle_sse (the scene's lone triangles) against intersect_triangle, the
    // reference it replaces: the same hit or miss, t and barycentrics to the bit, for random
    // triangles and rays in every direction (so every axis permutation and sign), t_max cut
    // before, at and after the hit, rays aimed exactly at vertices and along shared edges (where
    // an edge function is zero and the scalar test decides in double), and a triangle seen
    // edge-on.
    const auto bits = [](float f) { return std::bit_cast<std::uint32_t>(f); };
    constexpr float kInfinity = std::numeric_limits<float>::infinity();
    int hits = 0, edge_on = 0, checked = 0;
    const auto check = [&](const Triangle& t, const Ray& r, float t_max) {
        WatertightRay w(r);
        w.t_max = t_max;
        const WatertightRaySse sse(r);
        const auto a = intersect_triangle(t, w);
        const auto b = intersect_triangle_sse(t, sse, t_max);
        ++checked;
        ASSERT_EQ(a.has_value(), b.has_value()) << checked;
        if (!a) return;
        ++hits;
        ASSERT_EQ(bits(a->t), bits(b->t)) << checked;
        ASSERT_EQ(bits(a->b1), bits(b->b1)) << checked;
        ASSERT_EQ(bits(a->b2), bits(b->b2)) << checked;
    };
    for (std::uint32_t k = 0; k < 40000; ++k) {
        auto u = [k](std::uint32_t j) { return to_unit_float(mix32(k * 32 + j)); };
        const Triangle t{{u(0) * 4 - 2, u(1) * 4 - 2, u(2) * 4 - 2},
                         {u(3) * 4 - 2, u(4) * 4 - 2, u(5) * 4 - 2},
                         {u(6) * 4 - 2, u(7) * 4 - 2, u(8) * 4 - 2}};
        const Point3 o{u(9) * 12 - 6, u(10) * 12 - 6, u(11) * 12 - 6};
        // Aimed inside the triangle, at a vertex, or at a point of an edge.
        const float b1 = u(12), b2 = u(13) * (1 - b1);
        Point3 target = t.p0 + (t.p1 - t.p0) * b1 + (t.p2 - t.p0) * b2;
        if (k % 4 == 1) target = t.p1;
        if (k % 4 == 2) target = t.p0 + (t.p2 - t.p0) * u(14);
        const Ray r = ray(o, target - o);
        const float hit_t = intersect_triangle(t, WatertightRay(r)).value_or(TriangleHit{1, 0, 0}).t;
        for (const float t_max : {kInfinity, hit_t, std::nextafter(hit_t, kInfinity), hit_t * 0.5f})
            check(t, Ray{r.origin, r.direction, t_max}, t_max);
        // The same ray in the reverse direction (a miss behind the origin).
        check(t, Ray{r.origin, -r.direction}, kInfinity);
    }
    // Edge-on: rays in the triangle's own plane, and rays through an axis-aligned triangle's
    // edge along the axes (edge functions of exactly zero).
    const Triangle flat{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    for (const Ray& r : {Ray{{-1, 0.25f, 0}, {1, 0, 0}}, Ray{{0.5f, 0, -1}, {0, 0, 1}}, Ray{{0, 0, -1}, {0, 0, 1}},
                         Ray{{0.25f, 0.25f, -1}, {0, 0, 1}}, Ray{{0.5f, 0.5f, 2}, {0, 0, -1}}}) {
        check(flat, r, kInfinity);
        ++edge_on;
    }
    EXPECT_EQ(checked, 40000 * 5 + edge_on);
    EXPECT_GT(hits, 40000);  // the rays really meet the triangles
}

// Samples must lie on the shape, and their mean must be its centroid (a uniform density by
// area). For the disk and triangle the warps' uniformity is checked by chi-square in
// warp_test.cpp; here we check the placement in space.
template <typename Shape>
void check_area_samples(const Shape& shape, Point3 centroid, auto on_shape) {
    double sx = 0, sy = 0, sz = 0;
    const int n = 40000;
    for (int i = 0; i < n; ++i) {
        const AreaSample s = shape.sample_area(uniform(static_cast<std::uint32_t>(i)));
        ASSERT_TRUE(on_shape(s.p)) << s.p.x << "," << s.p.y << "," << s.p.z;
        sx += s.p.x, sy += s.p.y, sz += s.p.z;
    }
    const double scale = std::sqrt(shape.area());
    EXPECT_NEAR(sx / n, centroid.x, 0.01 * scale);
    EXPECT_NEAR(sy / n, centroid.y, 0.01 * scale);
    EXPECT_NEAR(sz / n, centroid.z, 0.01 * scale);
}

TEST(AreaSampling, QuadSamplesLieOnTheQuadAroundItsCentroid) {
    const Quad q = Quad::make({1, 2, 3}, {2, 0, 1}, {0, 3, 0});
    check_area_samples(q, Point3{2, 3.5f, 3.5f}, [&](Point3 p) {
        const Vector3 w = p - q.corner;
        const double a = dot(cross(w, q.edge2), q.n_raw) * q.inv_len2;
        const double b = dot(cross(q.edge1, w), q.n_raw) * q.inv_len2;
        return std::abs(dot(q.normal(), w)) < 1e-4 && a > -1e-5 && a < 1 + 1e-5 && b > -1e-5 &&
               b < 1 + 1e-5;
    });
}

TEST(AreaSampling, DiskSamplesLieOnTheDisk) {
    const Disk d{{1, -2, 0.5f}, Normal3(normalize(Vector3{1, 2, -2})), 1.5f};
    check_area_samples(d, d.center, [&](Point3 p) {
        const Vector3 w = p - d.center;
        return std::abs(dot(d.normal, w)) < 1e-4 && dot(w, w) <= 1.5 * 1.5 + 1e-4;
    });
}

TEST(AreaSampling, TriangleSamplesLieOnTheTriangleAroundItsCentroid) {
    const Triangle t{{0, 0, 0}, {3, 0, 1}, {0, 2, 2}};
    check_area_samples(t, Point3{1, 2.0f / 3, 1}, [&](Point3 p) {
        return static_cast<bool>(
            t.intersect(Ray{p + to_vector(t.normal()) * 0.01f, -to_vector(t.normal())}));
    });
}

TEST(AreaSampling, SphereSamplesAreUniformOverTheSphere) {
    // Archimedes: equal-height slabs of a sphere have equal area. 16 slabs x 16 sectors.
    const Sphere s{{1, 2, 3}, 2};
    const int slabs = 16, sectors = 16, n = 128000;
    std::vector<double> observed(slabs * sectors, 0), expected(slabs * sectors, double(n) / (slabs * sectors));
    for (int i = 0; i < n; ++i) {
        const AreaSample a = s.sample_area(uniform(static_cast<std::uint32_t>(i)));
        ASSERT_NEAR(length(a.p - s.center), 2, 1e-5);
        ASSERT_NEAR(dot(a.n, (a.p - s.center) / 2), 1, 1e-5);
        const double z = (a.p.z - s.center.z) / 2;
        const int slab = std::min(slabs - 1, static_cast<int>((z + 1) / 2 * slabs));
        double phi = std::atan2(a.p.y - s.center.y, a.p.x - s.center.x);
        if (phi < 0) phi += 2 * std::numbers::pi;
        const int sector = std::min(sectors - 1, static_cast<int>(phi / (2 * std::numbers::pi) * sectors));
        observed[static_cast<std::size_t>(slab * sectors + sector)] += 1;
    }
    EXPECT_LT(testing::chi_square(observed, expected),
              testing::chi_square_critical_1e4(slabs * sectors - 1));
    EXPECT_NEAR(s.area(), 16 * std::numbers::pi, 1e-4);
}

}  // namespace
}  // namespace glint

namespace glint {
namespace {

TEST(Uv, EachShapesConvention) {
    const Sphere s{{0, 0, 5}, 2};
    auto uv = s.uv_at({0, 0, 3});  // facing the default camera
    EXPECT_NEAR(uv.x, 0.5, 1e-6);
    EXPECT_NEAR(uv.y, 0.5, 1e-6);
    EXPECT_NEAR(s.uv_at({0, 2, 5}).y, 1, 1e-6);   // top pole
    EXPECT_NEAR(s.uv_at({0, -2, 5}).y, 0, 1e-6);  // bottom pole
    EXPECT_NEAR(s.uv_at({2, 0, 5}).x, 0.75, 1e-6);  // a quarter turn to the right
    const Quad q = Quad::make({1, 1, 1}, {2, 0, 0}, {0, 4, 0});
    uv = q.uv_at({2, 4, 1});
    EXPECT_NEAR(uv.x, 0.5, 1e-6);
    EXPECT_NEAR(uv.y, 0.75, 1e-6);
    const Disk d{{0, 0, 0}, {0, 1, 0}, 2};
    uv = d.uv_at({0, 0, 0});
    EXPECT_NEAR(uv.x, 0.5, 1e-6);
    EXPECT_NEAR(uv.y, 0.5, 1e-6);
    const Triangle t{{0, 0, 0}, {4, 0, 0}, {0, 2, 1}};
    EXPECT_NEAR(t.uv_at({4, 0, 0}).x, 1, 1e-6);
    EXPECT_NEAR(t.uv_at({0, 2, 1}).y, 1, 1e-6);
    uv = t.uv_at({1, 0.5f, 0.25f});  // p0 + 1/4 e1 + 1/4 e2
    EXPECT_NEAR(uv.x, 0.25, 1e-6);
    EXPECT_NEAR(uv.y, 0.25, 1e-6);
    const Plane pl{{1, 0, 2}, {0, 1, 0}};
    uv = pl.uv_at({3, 0, 5});  // u = x - 1, v = 2 - z for the +y normal
    EXPECT_NEAR(uv.x, 2, 1e-6);
    EXPECT_NEAR(uv.y, -3, 1e-6);
}

}  // namespace
}  // namespace glint

#include "glint/scene.h"

namespace glint {
namespace {

TEST(FlatShapes, HitPointsAreSnappedOntoAxisAlignedPlanes) {
    // A quad, a disk and a triangle in the plane z = 0 (where a 3D checker's floor(z) would
    // otherwise flicker between 0 and -1): every interaction point has z == 0 exactly.
    Scene scene;
    scene.quads.push_back(Quad::make({-1, -1, 0}, {2, 0, 0}, {0, 2, 0}));
    scene.disks.push_back(Disk{{3, 0, 0}, {0, 0, -1}, 1});
    scene.triangles.push_back(Triangle{{-3, -1, 0}, {-2, 1, 0}, {-4, 1, 0}});
    scene.commit();
    int hits = 0;
    for (std::uint32_t i = 0; i < 3000; ++i) {
        const Point3 target{to_unit_float(mix32(i)) * 8 - 4, to_unit_float(mix32(i + 99999)) * 2 - 1, 0};
        const Ray r = ray({0.3f, 0.2f, -2.7f}, target - Point3{0.3f, 0.2f, -2.7f});
        if (const auto h = scene.intersect(r)) {
            ++hits;
            ASSERT_EQ(scene.interaction(r, *h).p.z, 0.0f) << i;
        }
    }
    EXPECT_GT(hits, 1000);
}

// A lone triangle's normal is kept at commit (Scene::triangle_normals_): each hit's interaction
// carries its own triangle's normal(), bit for bit. The triangles all face different ways, so a
// normal read for the wrong triangle fails.
TEST(FlatShapes, EachLoneTriangleHitCarriesItsOwnNormal) {
    Scene scene;
    for (int k = 0; k < 12; ++k) {
        const float x = 3.0f * static_cast<float>(k % 4) - 4.5f, y = 3.0f * static_cast<float>(k / 4) - 3;
        const float tilt = 0.1f * static_cast<float>(k) - 0.55f;
        scene.triangles.push_back(Triangle{{x - 1, y - 1, tilt}, {x + 1, y - 1, -tilt}, {x, y + 1, 0.3f * tilt}});
    }
    scene.commit();
    std::vector<int> hits(scene.triangles.size());
    for (std::uint32_t i = 0; i < 6000; ++i) {
        const Point3 target{to_unit_float(mix32(i)) * 12 - 6, to_unit_float(mix32(i + 99999)) * 9 - 4.5f, 0};
        const Ray r = ray({0.1f, 0.2f, -9.0f}, target - Point3{0.1f, 0.2f, -9.0f});
        const auto h = scene.intersect(r);
        if (!h) continue;
        ASSERT_EQ(h->kind, ShapeKind::kTriangle);
        ++hits[h->index];
        const Normal3 n = scene.interaction(r, *h).n, want = scene.triangles[h->index].normal();
        ASSERT_EQ(std::bit_cast<std::uint32_t>(n.x), std::bit_cast<std::uint32_t>(want.x)) << i;
        ASSERT_EQ(std::bit_cast<std::uint32_t>(n.y), std::bit_cast<std::uint32_t>(want.y)) << i;
        ASSERT_EQ(std::bit_cast<std::uint32_t>(n.z), std::bit_cast<std::uint32_t>(want.z)) << i;
    }
    for (int c : hits) EXPECT_GT(c, 20);
}

}  // namespace
}  // namespace glint
