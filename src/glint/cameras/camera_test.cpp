#include "glint/cameras/camera.h"

#include <gtest/gtest.h>

#include <cmath>
#include <optional>

namespace glint {
namespace {

void expect_vec(Vector3 a, Vector3 b, float tol = 1e-6f) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}

TEST(Camera, ArticleExampleGivesRightAndUp) {
    // The article: V = (0,0,1) gives H = (1,0,0) and U = (0,1,0).
    const CameraBasis b = camera_basis({0, 0, 1}, {0, 1, 0});
    expect_vec(b.h, {1, 0, 0}, 0);
    expect_vec(b.u, {0, 1, 0}, 0);
}

TEST(Camera, BasisIsOrthonormalForATiltedView) {
    const Vector3 v = normalize(Vector3{0, -0.25f, 1});
    const CameraBasis b = camera_basis(v, {0, 1, 0});
    EXPECT_NEAR(length(b.h), 1, 1e-6);
    EXPECT_NEAR(length(b.u), 1, 1e-6);
    EXPECT_NEAR(dot(b.h, b.u), 0, 1e-6);
    EXPECT_NEAR(dot(b.h, v), 0, 1e-6);
    EXPECT_GT(b.u.y, 0);  // up stays up
    // By hand: H = (1,0,0), U = V x H = (0, 1, 0.25)/|(0,1,0.25)|.
    expect_vec(b.h, {1, 0, 0});
    expect_vec(b.u, Vector3{0, 1, 0.25f} / std::sqrt(1.0625f));
}

TEST(Camera, ViewParallelToUpUsesAnotherAxis) {
    for (Vector3 v : {Vector3{0, 1, 0}, Vector3{0, -1, 0}}) {
        const CameraBasis b = camera_basis(v, {0, 1, 0});
        EXPECT_TRUE(is_finite(b.h) && is_finite(b.u));
        EXPECT_NEAR(length(b.h), 1, 1e-6);
        EXPECT_NEAR(length(b.u), 1, 1e-6);
        EXPECT_NEAR(dot(b.h, v), 0, 1e-6);
        EXPECT_NEAR(dot(b.u, v), 0, 1e-6);
    }
}

TEST(Camera, PixelCentresMapToTheArticlesViewport) {
    // Sw=4, Sh=2, w=4, h=2, z=1 at the origin: B = (-2,-1), pixel (col,row) centre is
    // x = col + 0.5, y = Sh - (row + 0.5), A = (-2 + x, -1 + y, 1).
    const Camera cam({0, 0, 0}, {0, 0, 1}, {0, 1, 0}, 4, 2, 1, 4, 2);
    expect_vec(cam.generate_ray(0.5f, 0.5f).direction, normalize(Vector3{-1.5f, 0.5f, 1}));
    expect_vec(cam.generate_ray(3.5f, 1.5f).direction, normalize(Vector3{1.5f, -0.5f, 1}));
    // Row 0 is the top of the image: its rays point up; column 0 is the left: rays point to -x.
    EXPECT_GT(cam.generate_ray(2, 0.5f).direction.y, 0);
    EXPECT_LT(cam.generate_ray(0.5f, 1).direction.x, 0);
    // The image centre looks straight along V.
    expect_vec(cam.generate_ray(2, 1).direction, {0, 0, 1});
    EXPECT_EQ(cam.generate_ray(2, 1).origin, (Point3{0, 0, 0}));
}

TEST(Camera, LookAtBuildsTheSameCameraAsTheArticleForm) {
    // fov 90 degrees gives h = 2 tan(45) = 2 at z = 1, w = h * 16/9.
    const Camera a({0, 0, -1}, {0, 0, 1}, {0, 1, 0}, 2.0f * 16 / 9, 2, 1, 160, 90);
    const Camera b = Camera::look_at({0, 0, -1}, {0, 0, 1}, {0, 1, 0}, 90, 160, 90);
    for (float fx : {0.5f, 37.25f, 159.5f})
        for (float fy : {0.5f, 45.0f, 89.5f})
            expect_vec(a.generate_ray(fx, fy).direction, b.generate_ray(fx, fy).direction, 1e-6f);
}

TEST(Camera, OrthographicRaysLeaveTheFilmPointsParallelToTheView) {
    // From (1, 2, 3) along +z, a viewport 8 x 4 world units on a 200 x 100 film: H = (1, 0, 0),
    // U = (0, 1, 0), so film (0, 0) is P - 4H + 2U and film (200, 100) is P + 4H - 2U.
    Camera c({1, 2, 3}, {0, 0, 1}, {0, 1, 0}, 8, 4, 1, 200, 100);
    c.make_orthographic();
    const auto expect_ray = [&](float fx, float fy, Vector3 origin) {
        const Ray r = c.generate_ray(fx, fy);
        expect_vec(r.origin - Point3{0, 0, 0}, origin, 1e-5f);
        expect_vec(r.direction, {0, 0, 1}, 0);
    };
    expect_ray(0, 0, {-3, 4, 3});
    expect_ray(200, 100, {5, 0, 3});
    expect_ray(100, 50, {1, 2, 3});
    expect_ray(150, 25, {3, 3, 3});
}

TEST(Camera, AWindowShowsPartOfTheView) {
    // fov 90: the viewport at z = 1 spans [-1, 1]^2. The window [0, 1] x [0, 1] is its top-right
    // quarter: film (0, 0) looks through (0, 1, 1), film (100, 100) through (1, 0, 1).
    Camera c = Camera::look_at({0, 0, 0}, {0, 0, 1}, {0, 1, 0}, 90, 100, 100);
    const Camera whole = c;
    c.set_window(-1, 1, -1, 1, 100);  // the whole viewport: the same rays
    for (float f : {0.5f, 33.0f, 99.5f})
        expect_vec(c.generate_ray(f, 100 - f).direction, whole.generate_ray(f, 100 - f).direction, 1e-6f);
    c.set_window(0, 1, 0, 1, 100);
    expect_vec(c.generate_ray(0, 0).direction, normalize(Vector3{0, 1, 1}), 1e-6f);
    expect_vec(c.generate_ray(100, 100).direction, normalize(Vector3{1, 0, 1}), 1e-6f);
    expect_vec(c.generate_ray(50, 50).direction, normalize(Vector3{0.5f, 0.5f, 1}), 1e-6f);
}

// The automatic framing: boxes of every size (1e-3 to 1e4), up to 1000 sizes from the origin, flat or
// elongated, on wide and tall films: every corner lies inside the frame (checked from the camera's
// own position and basis, not the framing formula), and one touches the margin (no waste).
TEST(Camera, FrameBoxShowsEveryCornerTightly) {
    std::uint32_t state = 12345;
    const auto rnd = [&] {
        state = state * 1664525u + 1013904223u;
        return float(state >> 8) / 16777216.0f;
    };
    const Vector3 towards{0.35f, 0.35f, -1};
    for (int trial = 0; trial < 200; ++trial) {
        const float scale = std::pow(10.0f, -3 + 7 * rnd());
        const Vector3 size{scale * (0.01f + rnd()), scale * (0.01f + rnd()), scale * (trial % 7 == 0 ? 0 : 0.01f + rnd())};
        // Up to 1000 times its own size from the origin (float coordinates: farther, the box's
        // corners themselves would round).
        const float far = scale * (trial % 3 == 0 ? 1000.0f : 10.0f);
        const Point3 lo{(rnd() - 0.5f) * 2 * far, (rnd() - 0.5f) * 2 * far, (rnd() - 0.5f) * 2 * far};
        Bounds3 b;
        b.extend(lo);
        b.extend(lo + size);
        const int w = trial % 2 ? 800 : 300, h = trial % 2 ? 450 : 700;
        const Camera c = frame_box(b, towards, {0, 1, 0}, 40, w, h);
        const Point3 eye = c.generate_ray(w / 2.0f, h / 2.0f).origin;
        const Vector3 v = c.view_direction(), hh = c.basis().h, uu = c.basis().u;
        const double tan_v = std::tan(20 * M_PI / 180), tan_h = tan_v * w / h;
        double widest = 0;
        for (int i = 0; i < 8; ++i) {
            const Point3 p{(i & 1) ? b.hi.x : b.lo.x, (i & 2) ? b.hi.y : b.lo.y, (i & 4) ? b.hi.z : b.lo.z};
            const Vector3 q = p - eye;
            const double depth = dot(q, v);
            ASSERT_GT(depth, 0) << "trial " << trial << " corner " << i;
            const double fx = std::abs(dot(q, hh)) / depth / tan_h, fy = std::abs(dot(q, uu)) / depth / tan_v;
            EXPECT_LE(fx, 0.9 + 1e-3) << "trial " << trial;
            EXPECT_LE(fy, 0.9 + 1e-3) << "trial " << trial;
            widest = std::max({widest, fx, fy});
        }
        EXPECT_NEAR(widest, 0.9, 2e-3) << "trial " << trial << ": the box should touch the margin";
    }
}

Sample2 lens_sample(std::uint32_t i) {
    return {static_cast<float>((i * 7919u) % 1000u) / 1000.0f,
            static_cast<float>((i * 104729u) % 997u) / 997.0f};
}

TEST(ThinLens, ZeroApertureIsExactlyThePinhole) {
    const Camera cam({0, 1, -3}, {0, -0.2f, 1}, {0, 1, 0}, 3, 2, 1, 300, 200);
    for (std::uint32_t i = 0; i < 50; ++i) {
        const Ray a = cam.generate_ray(17.3f + i, 99.5f);
        const Ray b = cam.generate_ray(17.3f + i, 99.5f, lens_sample(i));
        EXPECT_EQ(a.origin, b.origin);
        EXPECT_EQ(a.direction, b.direction);
    }
}

TEST(ThinLens, RaysThroughOneFilmPointMeetOnTheFocusPlane) {
    Camera cam = Camera::look_at({1, 2, -5}, {0, 0.5f, 2}, {0, 1, 0}, 40, 320, 180);
    const Float focus = 6.5f, aperture = 0.3f;
    cam.set_lens(aperture, focus);
    const Vector3 v = cam.view_direction();
    const Point3 p{1, 2, -5};
    for (auto [fx, fy] : {std::pair{160.0f, 90.0f}, std::pair{3.5f, 170.25f}}) {
        // The pinhole ray's point on the plane {x : (x - P).V = focus}.
        const Ray pin = cam.generate_ray(fx, fy);
        const Point3 target = pin.at(focus / dot(pin.direction, v));
        for (std::uint32_t i = 0; i < 64; ++i) {
            const Ray r = cam.generate_ray(fx, fy, lens_sample(i));
            // Origins lie on the aperture disk, in the lens plane.
            EXPECT_LE(length(r.origin - p), aperture * (1 + 1e-5f));
            EXPECT_NEAR(dot(r.origin - p, v), 0, 1e-5);
            EXPECT_NEAR(length(r.direction), 1, 1e-6);
            // ...and every ray passes through the same point of the focus plane.
            const Float t = (focus - dot(r.origin - p, v)) / dot(r.direction, v);
            EXPECT_NEAR(length(r.at(t) - target), 0, 2e-5f * focus) << i;
        }
    }
}

TEST(ThinLens, LensSamplesCoverTheAperture) {
    Camera cam({0, 0, 0}, {0, 0, 1}, {0, 1, 0}, 2, 2, 1, 10, 10);
    cam.set_lens(1, 5);
    double mean_x = 0, max_r = 0;
    for (std::uint32_t i = 0; i < 1000; ++i) {
        const Ray r = cam.generate_ray(5, 5, lens_sample(i));
        mean_x += r.origin.x;
        max_r = std::max(max_r, static_cast<double>(length(r.origin - Point3{0, 0, 0})));
    }
    EXPECT_NEAR(mean_x / 1000, 0, 0.05);
    EXPECT_GT(max_r, 0.95);  // reaches the rim
}

// The footprint model against the rays of the neighbouring pixels themselves: where the ray
// through pixel (x + 1, y) and through (x, y - 1) meet the plane of the point (for a pinhole and
// an orthographic camera, a floor and a tilted wall).
TEST(Camera, PixelFootprintIsWhereTheNeighbouringRaysMeetThePlane) {
    const int w = 320, h = 200;
    const Camera cams[] = {Camera::look_at({0, 2, -5}, {0.5f, 0, 3}, {0, 1, 0}, 45, w, h),
                           Camera::orthographic({0, 2, -5}, Vector3{0.1f, -0.4f, 1}, {0, 1, 0}, 6, w, h)};
    const std::pair<Normal3, float> planes[] = {{Normal3{0, 1, 0}, 0}, {normalize(Normal3{0.3f, 0.2f, -1}), -8}};
    for (const Camera& cam : cams) {
        const PixelFootprint fp = cam.footprint(1);
        for (const auto& plane : planes) {
            const Normal3 n = plane.first;  // (not a structured binding: clang 14's lambdas cannot capture one)
            const float offset = plane.second;
            const auto meet = [&](float fx, float fy) -> std::optional<Point3> {
                const Ray r = cam.generate_ray(fx, fy);
                const float denom = dot(r.direction, n);
                if (std::abs(denom) < 1e-6f) return std::nullopt;
                const float t = (offset - dot(to_vector(r.origin), to_vector(n))) / denom;
                if (!(t > 0)) return std::nullopt;
                return r.at(t);
            };
            int checked = 0;
            for (int k = 0; k < 40; ++k) {
                const float fx = 20.0f + 7 * k, fy = 10.0f + 4.5f * k;
                const auto p = meet(fx, fy), px = meet(fx + 1, fy), py = meet(fx, fy - 1);
                if (!p || !px || !py) continue;
                Vector3 dpdx, dpdy;
                ASSERT_TRUE(fp.at(*p, n, dpdx, dpdy));
                const float tol = 2e-3f * (length(*px - *p) + length(*py - *p));
                EXPECT_NEAR(dpdx.x, (*px - *p).x, tol) << k;
                EXPECT_NEAR(dpdx.y, (*px - *p).y, tol) << k;
                EXPECT_NEAR(dpdx.z, (*px - *p).z, tol) << k;
                EXPECT_NEAR(dpdy.x, (*py - *p).x, tol) << k;
                EXPECT_NEAR(dpdy.y, (*py - *p).y, tol) << k;
                EXPECT_NEAR(dpdy.z, (*py - *p).z, tol) << k;
                ++checked;
            }
            EXPECT_GT(checked, 10);
        }
        // Scaled as asked.
        Vector3 a, b, c, d;
        ASSERT_TRUE(fp.at({0, 0, 3}, Normal3{0, 1, 0}, a, b));
        ASSERT_TRUE(cam.footprint(0.25f).at({0, 0, 3}, Normal3{0, 1, 0}, c, d));
        EXPECT_NEAR(c.z, 0.25f * a.z, 1e-6f);
    }
}

}  // namespace
}  // namespace glint
