// End-to-end checks of the article's figures: each scene file in scenes/seed is loaded, built
// and rendered, and chosen pixels are compared with values derived by hand from the article's
// formulas (using the double-precision reference in reference.h, never the renderer's code).
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cmath>

#include "glint/builder/build.h"
#include "glint/image/image_io.h"
#include "glint/formats/scene_yaml.h"
#include "glint/render/render.h"
#include "reference.h"
#include "testing.h"

namespace glint {
namespace {

namespace ref = reference;

// An odd-sized film, so that the middle pixel's centre is exactly the image centre.
constexpr int kW = 161, kH = 91;
constexpr double kViewW = 2.0 * 16 / 9, kViewH = 2;

Film render_figure(const std::string& name, int w = kW, int h = kH) {
    auto sources = std::make_shared<SourceFiles>();
    Overrides o;
    o.width = w;
    o.height = h;
    const RenderJob job = build(
        load_scene_file(std::string(GLINT_SOURCE_DIR) + "/scenes/seed/" + name, sources), o,
        sources);
    Film film(job.film_width, job.film_height);
    render(job.scene, job.camera, *job.integrator, job.options, film);
    return film;
}

void expect_color(Color c, ref::V e, double tol = 2e-6) {
    EXPECT_NEAR(c.r, e[0], tol);
    EXPECT_NEAR(c.g, e[1], tol);
    EXPECT_NEAR(c.b, e[2], tol);
}

ref::V fig_dir(int col, int row) { return ref::camera_dir({0, 0, 1}, kViewW, kViewH, 1, kW, kH, col, row); }

TEST(Figures, Fig06SkyIsTheArticlesGradient) {
    const Film f = render_figure("fig06-sky.yaml");
    // Centre: D = (0,0,1), t = 0.5: (0.75, 0.85, 1).
    expect_color(f.at(80, 45), {0.75, 0.85, 1.0});
    for (auto [c, r] : {std::pair{0, 0}, std::pair{160, 90}, std::pair{33, 70}})
        expect_color(f.at(c, r), ref::sky(fig_dir(c, r)));
    EXPECT_LT(f.at(80, 0).r, f.at(80, 90).r);  // darker blue towards the top
}

TEST(Figures, Fig07SphereIsSolidGreenWhereHit) {
    const Film f = render_figure("fig07-sphere.yaml");
    expect_color(f.at(80, 45), {0, 1, 0});
    expect_color(f.at(0, 0), ref::sky(fig_dir(0, 0)));
    // The sphere (centre (0,0,1), r = 1, seen from (0,0,-1)) subtends asin(1/2) = 30 degrees:
    // a pixel is green exactly when its ray is within 30 degrees of +z.
    for (int col = 0; col < kW; col += 7) {
        const ref::V d = fig_dir(col, 45);
        if (std::abs(d[2] - std::cos(M_PI / 6)) < 1e-3) continue;  // too close to the rim
        const bool inside = d[2] > std::cos(M_PI / 6);
        EXPECT_EQ(f.at(col, 45).g == 1 && f.at(col, 45).r == 0, inside) << col;
    }
}

TEST(Figures, Fig09NormalsAreHalfNPlusOne) {
    const Film f = render_figure("fig09-normals.yaml");
    expect_color(f.at(80, 45), {0.5, 0.5, 0});  // N = (0,0,-1)
    const ref::V o{0, 0, -1};
    for (auto [c, r] : {std::pair{70, 40}, std::pair{95, 60}, std::pair{60, 30}}) {
        const ref::V d = fig_dir(c, r);
        const auto t = ref::hit_sphere(o, d, {0, 0, 1}, 1);
        ASSERT_TRUE(t);
        const ref::V n = ref::sub(ref::add(o, ref::mul(d, *t)), {0, 0, 1});
        expect_color(f.at(c, r), {(n[0] + 1) / 2, (n[1] + 1) / 2, (n[2] + 1) / 2}, 2e-5);
    }
}

TEST(Figures, Fig10DiffuseIsAmbientPlusLambert) {
    const Film f = render_figure("fig10-diffuse.yaml");
    // Centre: N = (0,0,-1), -L = (1,1,-1)/sqrt3, -L.N = 1/sqrt3: 0.1 + 0.57735 = 0.67735.
    const double centre = 0.1 + 1 / std::sqrt(3.0);
    expect_color(f.at(80, 45), {centre, centre, centre});
    // Elsewhere on the sphere: 0.1 + max(0, -L.N).
    const ref::V o{0, 0, -1}, to_light = ref::unit({1, 1, -1});
    for (auto [c, r] : {std::pair{70, 40}, std::pair{95, 60}, std::pair{60, 60}}) {
        const ref::V d = fig_dir(c, r);
        const auto t = ref::hit_sphere(o, d, {0, 0, 1}, 1);
        ASSERT_TRUE(t);
        const ref::V n = ref::sub(ref::add(o, ref::mul(d, *t)), {0, 0, 1});
        const double v = 0.1 + std::max(0.0, ref::dot(n, to_light));
        expect_color(f.at(c, r), {v, v, v}, 2e-5);
    }
}

TEST(Figures, Fig10RawPngHoldsTheArticlesDisplayValues) {
    // Through the whole pipeline to a file: raw encoding is clamp, x255, round; no curve.
    auto sources = std::make_shared<SourceFiles>();
    Overrides o;
    o.width = kW;
    o.height = kH;
    const RenderJob job = build(
        load_scene_file(std::string(GLINT_SOURCE_DIR) + "/scenes/seed/fig10-diffuse.yaml", sources),
        o, sources);
    ASSERT_EQ(job.display.encoding, Encoding::kRaw);
    Film film(job.film_width, job.film_height);
    render(job.scene, job.camera, *job.integrator, job.options, film);
    const testing::TempDir dir;
    const auto path = dir / "fig10.png";
    write_image(path, film, job.display);
    auto in = OIIO::ImageInput::open(path.string());
    ASSERT_TRUE(in);
    std::vector<unsigned char> px(static_cast<std::size_t>(kW) * kH * 3);
    ASSERT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, px.data()));
    in->close();
    const std::size_t centre = (45 * kW + 80) * 3;
    EXPECT_EQ(px[centre], 173);  // round(0.67735 * 255) = round(172.72)
}

TEST(Figures, Fig12ShadowedGroundGetsAmbientOnlyAndLitGroundIsLambert) {
    const Film f = render_figure("fig12-shadows.yaml");
    const ref::V o{0, 0, -1}, to_light = ref::unit({1, 1, -1});
    const ref::V small{0, 0, 1}, big{0, -101, 1};
    // Ground points seen through chosen pixels; classify each independently.
    int shadowed = 0, lit = 0;
    for (int row = 50; row < kH; row += 3) {
        for (int col = 0; col < kW; col += 5) {
            const ref::V d = fig_dir(col, row);
            if (ref::hit_sphere(o, d, small, 1)) continue;  // the white sphere is in front
            const auto t = ref::hit_sphere(o, d, big, 100);
            if (!t) continue;
            const ref::V p = ref::add(o, ref::mul(d, *t));
            const ref::V n = ref::unit(ref::sub(p, big));
            // Is the shadow ray towards -L blocked by the small sphere? Skip near-grazing cases
            // (the shadow's edge), where float and double may legitimately disagree.
            const ref::V fq = ref::sub(p, small);
            const double b = ref::dot(fq, to_light);
            const double miss_distance = std::sqrt(std::max(0.0, ref::dot(fq, fq) - b * b));
            if (std::abs(miss_distance - 1) < 1e-3) continue;
            const bool in_shadow = b < 0 && miss_distance < 1;
            const double k[3] = {0.8, 0.8, 0.2};
            const double light = in_shadow ? 0 : std::max(0.0, ref::dot(n, to_light));
            expect_color(f.at(col, row), {k[0] * (0.1 + light), k[1] * (0.1 + light),
                                          k[2] * (0.1 + light)}, 3e-5);
            (in_shadow ? shadowed : lit)++;
        }
    }
    EXPECT_GT(shadowed, 10);  // the test really looked at both kinds of point
    EXPECT_GT(lit, 100);
    // A point picked by hand: the ground at x = -1.8, z = 2.2 (y = -101 + sqrt(100^2 - 1.8^2 -
    // 1.2^2) = -1.0234) is shadowed: its ray towards the light passes 0.82 from the white
    // sphere's centre. The pixel that sees it gets ambient only, 0.1 K = (0.08, 0.08, 0.02).
    const double gy = -101 + std::sqrt(10000 - 1.8 * 1.8 - 1.2 * 1.2);
    const ref::V to_point = ref::sub({-1.8, gy, 2.2}, o);  // the point seen from the camera
    const double x_view = to_point[0] / to_point[2], y_view = to_point[1] / to_point[2];  // z = 1
    const int col = static_cast<int>((x_view + kViewW / 2) / kViewW * kW);
    const int row = static_cast<int>((kViewH / 2 - y_view) / kViewH * kH);
    ASSERT_FALSE(ref::hit_sphere(o, fig_dir(col, row), small, 1));  // not hidden by the sphere
    expect_color(f.at(col, row), {0.08, 0.08, 0.02}, 1e-6);
}

TEST(Figures, Fig14FloorFollowsTheArticlesShadingAndChecker) {
    // Camera P = (0,1.6,-1.5), V = normalize(0,-0.25,1). For floor pixels whose reflection and
    // shadow rays miss all nine spheres, colour = 0.7 d + 0.3 d * sky(R), d = K (0.1 + 1/sqrt3),
    // K = 0.9 where floor(x) + floor(z) is even, else 0.1.
    const int w = 161, h = 91;
    const Film f = render_figure("fig14-reflections.yaml", w, h);
    const ref::V o{0, 1.6, -1.5};
    const ref::V to_light = ref::unit({1, 1, -1});
    std::vector<ref::V> centres;
    for (double z : {2.5, 4.7, 6.9})
        for (double x : {-2.2, 0.0, 2.2}) centres.push_back({x, 0, z});
    auto blocked = [&](ref::V from, ref::V d) {
        for (const ref::V& c : centres)
            if (ref::hit_sphere(from, d, c, 1)) return true;
        return false;
    };
    int checked = 0, bright = 0;
    for (int row = 60; row < h; row += 2) {
        for (int col = 0; col < w; col += 3) {
            const ref::V d = ref::camera_dir({0, -0.25, 1}, kViewW, kViewH, 1, w, h, col, row);
            if (d[1] >= 0 || blocked(o, d)) continue;
            const double t = (-1 - o[1]) / d[1];
            const ref::V p = ref::add(o, ref::mul(d, t));
            // Stay clear of checker edges, where float and double may pick different squares.
            const double fx = p[0] - std::floor(p[0]), fz = p[2] - std::floor(p[2]);
            if (fx < 0.01 || fx > 0.99 || fz < 0.01 || fz > 0.99) continue;
            const ref::V r{d[0], -d[1], d[2]};
            if (blocked(p, r) || blocked(p, to_light)) continue;
            const bool even = (static_cast<long>(std::floor(p[0])) +
                               static_cast<long>(std::floor(p[2]))) % 2 == 0;
            const double k = even ? 0.9 : 0.1;
            const double dd = k * (0.1 + 1 / std::sqrt(3.0));
            const ref::V sky = ref::sky(r);
            expect_color(f.at(col, row), {0.7 * dd + 0.3 * dd * sky[0], 0.7 * dd + 0.3 * dd * sky[1],
                                          0.7 * dd + 0.3 * dd * sky[2]}, 3e-5);
            ++checked;
            bright += even;
        }
    }
    EXPECT_GT(checked, 100);
    EXPECT_GT(bright, 30);
    EXPECT_GT(checked - bright, 30);
}

TEST(Figures, Fig14SpheresReflectEachOther) {
    // The front-middle green sphere's reflection of its red neighbour: a pixel on the green
    // sphere's left flank whose reflected ray hits the red sphere (checked in double) must carry
    // more red than the same pixel would with the reflection replaced by the sky.
    const int w = 161, h = 91;
    const Film f = render_figure("fig14-reflections.yaml", w, h);
    const ref::V o{0, 1.6, -1.5};
    int found = 0;
    for (int col = 0; col < w; ++col) {
        for (int row = 30; row < 70; ++row) {
            const ref::V d = ref::camera_dir({0, -0.25, 1}, kViewW, kViewH, 1, w, h, col, row);
            const auto t = ref::hit_sphere(o, d, {0, 0, 2.5}, 1);
            if (!t || ref::hit_sphere(o, d, {-2.2, 0, 2.5}, 1)) continue;
            const ref::V p = ref::add(o, ref::mul(d, *t));
            const ref::V n = ref::sub(p, {0, 0, 2.5});
            const ref::V r = ref::sub(d, ref::mul(n, 2 * ref::dot(n, d)));
            if (!ref::hit_sphere(p, r, {-2.2, 0, 2.5}, 1)) continue;
            ++found;
            // Green sphere K = (0.2,0.9,0.2): its own red channel is at most 0.2 * 1.1; the
            // reflection multiplies d by the red sphere's colour, whose red is high.
            EXPECT_GT(f.at(col, row).r / f.at(col, row).g, 0.2 / 0.9) << col << "," << row;
        }
    }
    EXPECT_GT(found, 3);
}

}  // namespace
}  // namespace glint
