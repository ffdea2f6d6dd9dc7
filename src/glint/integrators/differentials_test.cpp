// Ray differentials through specular bounces (integrators/differentials.h) against the rays of the
// neighbouring pixels themselves, traced, reflected and refracted on the analytic surfaces by the
// test, with no use of the code under test: a flat mirror (where the footprint is exactly that of
// the mirror-image camera), a chrome sphere, a smooth-shaded mesh sphere and a glass ball.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <optional>
#include <sstream>
#include <string>

#include "glint/builder/build.h"
#include "glint/formats/scene_yaml.h"
#include "glint/integrators/differentials.h"
#include "glint/materials/fresnel.h"

namespace glint {
namespace {

RenderJob job_from(const std::string& yaml) {
    auto sources = std::make_shared<SourceFiles>();
    return build(parse_scene(yaml, "scene.yaml", sources), {}, sources);
}

// 64 spp: the footprint is scaled by 1/8 (an eighth of a pixel), and so are the test's neighbours.
const float kStep = 0.125f;
const std::string kView =
    "camera: {type: look_at, from: [0, 1.5, -4], to: [0, 0.8, 0], fov: 40}\n"
    "film: {width: 320, height: 200}\nsampler: {spp: 64}\nintegrator: {type: path}\n";

std::optional<float> hit_plane(Point3 o, Vector3 d, Normal3 n, float offset) {
    const float denom = dot(d, n);
    if (std::abs(denom) < 1e-6f) return std::nullopt;
    const float t = (offset - dot(to_vector(o), to_vector(n))) / denom;
    return t > 0 ? std::optional<float>(t) : std::nullopt;
}

std::optional<float> hit_sphere(Point3 o, Vector3 d, Point3 c, float r, bool far) {
    const Vector3 oc = o - c;
    const float b = dot(oc, d) / dot(d, d), cc = (dot(oc, oc) - r * r) / dot(d, d);
    const float disc = b * b - cc;
    if (disc < 0) return std::nullopt;
    const float t = far ? -b + std::sqrt(disc) : -b - std::sqrt(disc);
    return t > 1e-4f ? std::optional<float>(t) : std::nullopt;
}

// The test's own tracer: the ray through film point (fx, fy), turned at each surface by `turn`
// (analytic), until it meets the floor y = 0.
template <typename Turn>
std::optional<Point3> to_floor(const Camera& cam, float fx, float fy, Turn turn) {
    const Ray r = cam.generate_ray(fx, fy);
    Point3 o = r.origin;
    Vector3 d = r.direction;
    if (!turn(o, d)) return std::nullopt;
    const auto t = hit_plane(o, d, Normal3{0, 1, 0}, 0);
    if (!t) return std::nullopt;
    return o + d * *t;
}

// Glint's side: the path's ray from the pixel through the scene's specular surfaces (each sample of
// a smooth BSDF is the one reflection or refraction), its offset rays carried by
// scatter_differential, and where they meet the floor.
struct Carried {
    Point3 q;
    Vector3 dpdx, dpdy;
};
std::optional<Carried> carried_to_floor(const RenderJob& job, float fx, float fy, float ior) {
    const Scene& scene = job.scene;
    Ray ray = job.camera.generate_ray(fx, fy);
    std::optional<RayDifferential> diff;
    for (int bounce = 0; bounce < 4; ++bounce) {
        const auto h = scene.intersect(ray);
        if (!h) break;
        const SurfaceInteraction si = scene.interaction(ray, *h, diff ? &*diff : nullptr);
        const Vector3 wo = -ray.direction;
        Vector3 wi = reflect(ray.direction, si.ns);
        float eta = 1;
        if (ior != 1 && !refract(wo, to_vector(si.ns), ior, wi, eta)) return std::nullopt;
        const Ray next = spawn_ray(si.p, si.n, wi);
        diff = scatter_differential(scene, si, ray.direction, diff ? &*diff : nullptr, wi, eta, next.origin);
        if (!diff) return std::nullopt;
        ray = next;
    }
    const auto t = hit_plane(ray.origin, ray.direction, Normal3{0, 1, 0}, 0);
    if (!t || !diff) return std::nullopt;
    Carried c{ray.at(*t), {}, {}};
    if (!diff->at(c.q, Normal3{0, 1, 0}, c.dpdx, c.dpdy)) return std::nullopt;
    return c;
}

// Compares glint's carried footprint on the floor with the brute-force neighbours (an eighth of a
// pixel to the right and up, the footprint's own directions and scale), over a grid of pixels; returns how many were compared.
template <typename Turn>
int compare(const RenderJob& job, float ior, Turn turn, float rel_tol, int fx0, int fx1, int fy0, int fy1) {
    int checked = 0;
    for (int fy = fy0; fy < fy1; fy += 7) {
        for (int fx = fx0; fx < fx1; fx += 9) {
            const float cx = fx + 0.5f, cy = fy + 0.5f;
            const auto p = to_floor(job.camera, cx, cy, turn);
            const auto px = to_floor(job.camera, cx + kStep, cy, turn), py = to_floor(job.camera, cx, cy - kStep, turn);
            // Floor points far away are met at grazing angles, where any round-off is magnified.
            if (!p || !px || !py || length(to_vector(*p)) > 8) continue;
            const auto c = carried_to_floor(job, cx, cy, ior);
            if (!c) continue;
            // The same path (within the push off each surface and, on a mesh, its facets).
            EXPECT_LT(length(c->q - *p), 5e-3f * (1 + length(to_vector(*p)))) << fx << ", " << fy;
            const Vector3 ex = *px - *p, ey = *py - *p;
            EXPECT_LT(length(c->dpdx - ex), rel_tol * length(ex)) << fx << ", " << fy;
            EXPECT_LT(length(c->dpdy - ey), rel_tol * length(ey)) << fx << ", " << fy;
            ++checked;
        }
    }
    return checked;
}

// A flat mirror: the offset rays reflect as the rays do, exactly (the mirror-image camera's
// footprint). The camera's direct-view model, which glint used before, is far off there.
TEST(Differentials, AFlatMirrorCarriesTheNeighbouringRaysExactly) {
    const RenderJob job = job_from(kView +
                                   "materials: {m: {type: conductor, reflectance: [1, 1, 1]}}\n"
                                   "objects:\n  - {type: quad, corner: [-3, -1, 2], edge1: [6, 0, 0], "
                                   "edge2: [0, 4, -1], material: m}\n");
    ASSERT_TRUE(job.scene.footprint.has_value());
    // The mirror's plane through (-3, -1, 2) spanned by x and (0, 4, -1).
    const Normal3 m = normalize(Normal3(cross(Vector3{1, 0, 0}, Vector3{0, 4, -1})));
    const float offset = dot(Vector3{-3, -1, 2}, to_vector(m));
    const auto turn = [&](Point3& o, Vector3& d) {
        const auto t = hit_plane(o, d, m, offset);
        if (!t) return false;
        o = o + d * *t;
        d = reflect(d, m);
        return true;
    };
    EXPECT_GT(compare(job, 1, turn, 2e-3f, 0, 320, 0, 200), 200);
    // The direct-view model at the same floor points differs by far more than that tolerance.
    const auto p = to_floor(job.camera, 160.5f, 60.5f, turn), px = to_floor(job.camera, 160.5f + kStep, 60.5f, turn);
    ASSERT_TRUE(p && px);
    Vector3 dx, dy;
    ASSERT_TRUE(job.scene.footprint->at(*p, Normal3{0, 1, 0}, dx, dy));
    EXPECT_GT(length(dx - (*px - *p)), 0.2f * length(*px - *p));
}

// A sphere of radius r at c, as the test's own mirror or lens.
struct Ball {
    Point3 c;
    float r;
};
auto mirror_ball(Ball b) {
    return [b](Point3& o, Vector3& d) {
        const auto t = hit_sphere(o, d, b.c, b.r, false);
        if (!t) return false;
        o = o + d * *t;
        const Normal3 n((o - b.c) / b.r);
        if (std::abs(dot(d, n)) < 0.25f) return false;  // near the silhouette: second order is large
        d = reflect(d, n);
        return true;
    };
}

// A chrome sphere spreads the offset rays: the carried footprint follows the neighbouring rays
// reflected at their own points (to second order in the pixel: within 3 %).
TEST(Differentials, AChromeSphereSpreadsThemAsTheNeighbouringRays) {
    const RenderJob job = job_from(kView +
                                   "materials: {m: {type: conductor, reflectance: [1, 1, 1]}}\n"
                                   "objects: [{type: sphere, center: [0, 1, 0], radius: 0.9, material: m}]\n");
    EXPECT_GT(compare(job, 1, mirror_ball({{0, 1, 0}, 0.9f}), 0.03f, 100, 220, 40, 200), 50);
}

// The same sphere as a smooth-shaded mesh (a fine UV sphere with its exact normals at the
// vertices): the interpolated normals turn the offset rays as the sphere does (within 10 %: the
// mesh's normals bend linearly across each triangle).
TEST(Differentials, ASmoothMeshSphereSpreadsThemAsTheSphere) {
    const int stacks = 96, slices = 192;
    std::ostringstream pos, nrm, idx;
    const float r = 0.9f;
    for (int i = 0; i <= stacks; ++i) {
        for (int j = 0; j <= slices; ++j) {
            const double th = std::numbers::pi * i / stacks, ph = 2 * std::numbers::pi * j / slices;
            const double x = std::sin(th) * std::cos(ph), y = std::cos(th), z = std::sin(th) * std::sin(ph);
            pos << (i || j ? ", " : "") << r * x << ", " << 1 + r * y << ", " << r * z;
            nrm << (i || j ? ", " : "") << x << ", " << y << ", " << z;
        }
    }
    bool first = true;
    for (int i = 0; i < stacks; ++i) {
        for (int j = 0; j < slices; ++j) {
            const int a = i * (slices + 1) + j, b = a + slices + 1;
            idx << (first ? "" : ", ") << a << ", " << a + 1 << ", " << b << ", " << a + 1 << ", " << b + 1 << ", " << b;
            first = false;
        }
    }
    const RenderJob job = job_from(kView + "materials: {m: {type: conductor, reflectance: [1, 1, 1]}}\n" +
                                   "objects: [{type: mesh, material: m, positions: [" + pos.str() + "], normals: [" +
                                   nrm.str() + "], indices: [" + idx.str() + "]}]\n");
    EXPECT_GT(compare(job, 1, mirror_ball({{0, 1, 0}, r}), 0.10f, 100, 220, 40, 200), 50);
}

// A glass ball refracts them twice, in and out (Snell's law on the analytic sphere, by the test).
TEST(Differentials, AGlassBallRefractsThemAsTheNeighbouringRays) {
    const float ior = 1.5f;
    const Ball b{{0, 2.5f, 0}, 0.9f};
    // Looking down through the ball, so that the rays meet the floor well beyond its focus.
    const RenderJob job = job_from(
        "camera: {type: look_at, from: [0, 6, -4], to: [0, 2.5, 0], fov: 40}\n"
        "film: {width: 320, height: 200}\nsampler: {spp: 64}\nintegrator: {type: path}\n"
        "materials: {g: {type: dielectric, ior: 1.5}}\n"
        "objects: [{type: sphere, center: [0, 2.5, 0], radius: 0.9, material: g}]\n");
    const auto turn = [&](Point3& o, Vector3& d) {
        for (int k = 0; k < 2; ++k) {
            const auto t = hit_sphere(o, d, b.c, b.r, k == 1);
            if (!t) return false;
            o = o + d * *t;
            const Vector3 out = (o - b.c) / b.r;  // outward
            const Vector3 n = k == 0 ? out : -out;  // on the side the ray comes from
            if (std::abs(dot(d, n)) < 0.25f) return false;
            float crossed = 1;
            if (!refract(-d, n, k == 0 ? ior : 1 / ior, d, crossed)) return false;
        }
        return true;
    };
    EXPECT_GT(compare(job, ior, turn, 0.05f, 120, 200, 60, 140), 20);
}

}  // namespace
}  // namespace glint
