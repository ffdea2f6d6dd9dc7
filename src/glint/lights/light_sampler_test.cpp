// Light sampling: every routine's directions against its own density (chi-square), closed-form
// irradiance from spheres and disks, selection by power, and the spot light's cone.
#include "glint/lights/light_sampler.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "glint/samplers/hash.h"
#include "glint/samplers/warp.h"
#include "glint/scene.h"
#include "sphere_chi2.h"

namespace glint {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;

Sample2 rnd2(std::uint32_t seed, std::uint32_t i) {
    return {to_unit_float(hash_combine(seed, 2 * i)), to_unit_float(hash_combine(seed, 2 * i + 1))};
}

// One emitting shape of each kind around the origin, a soft sun, and an environment map with a
// bright patch; `which` picks the lights the scene holds.
Scene light_scene(bool env_map) {
    Scene s;
    s.materials.push_back(DiffuseMaterial{0});
    s.materials.push_back(DiffuseMaterial{0});
    s.textures.push_back(ConstantTexture{Color{0.5f}});
    s.emission = {Emission{}, Emission{Color{2, 3, 4}, true, std::nullopt}};  // two-sided: seen from p either way
    s.spheres.push_back({{0, 4, 1}, 1.5f, 1});
    s.quads.push_back(Quad::make({-1, -3, -1}, {2, 0, 0.5f}, {0, 0.3f, 2}, 1));
    s.disks.push_back({{3, 0, 0}, Normal3{-1, 0, 0}, 1.2f, 1});
    s.triangles.push_back({{-2, 1, 3}, {-3, 2, 1}, {-2.5f, -1, 2}, 1});
    // A one-triangle mesh, placed by a transform that rotates, mirrors and moves it.
    TriangleMesh mesh;
    mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0.5f}};
    mesh.indices = {0, 1, 2};
    mesh.material = 1;
    s.meshes.push_back(mesh);
    s.instances.push_back({0, Transform::translate({1, -1, -3}) * Transform::rotate(30, {1, 1, 0}) *
                                   Transform::scale({1, -1.5f, 1}), std::nullopt});
    DirectionalLight sun{normalize(Vector3{0.3f, -1, 0.2f}), Color{3}};
    const float s4 = std::sin(8 * kPi / 180 / 4);  // an 8-degree sun, large enough to histogram
    sun.one_minus_cos = 2 * s4 * s4;
    s.lights.push_back(sun);
    if (env_map) {
        Image image{32, 16, std::vector<Color>(32 * 16, Color{0.2f}), {}};
        for (int y = 3; y < 6; ++y)
            for (int x = 20; x < 24; ++x) image.texels[static_cast<std::size_t>(y * 32 + x)] = Color{50};
        s.background = EnvironmentMap::make(image, 1);
    } else {
        s.background = ConstantBackground{Color{0.3f}};
    }
    s.commit();
    return s;
}

// The point where direction wi from p meets light `l` (for pdf_li), if it does.
std::optional<Point3> on_light(const Scene& s, const LightSampler& ls, std::uint32_t l, Point3 p,
                               Vector3 wi) {
    const Ray ray{p, wi};
    if (l == ls.environment()) return p;
    if (const auto* a = std::get_if<AreaLight>(&ls.light(l))) {
        std::optional<Float> t;
        switch (a->kind) {
            case ShapeKind::kSphere: t = s.spheres[a->index].intersect(ray); break;
            case ShapeKind::kQuad: t = s.quads[a->index].intersect(ray); break;
            case ShapeKind::kDisk: t = s.disks[a->index].intersect(ray); break;
            case ShapeKind::kTriangle: t = s.triangles[a->index].intersect(ray); break;
            case ShapeKind::kMesh: t = s.world_triangle(a->index, a->prim).intersect(ray); break;
            case ShapeKind::kPlane: break;
        }
        if (!t) return std::nullopt;
        return ray.at(*t);
    }
    return p;  // the soft sun: pdf_li ignores the point
}

TEST(LightSampler, EveryLightSamplesItsOwnDensityChiSquare) {
    for (const bool env_map : {false, true}) {
        const Scene s = light_scene(env_map);
        const LightSampler& ls = s.light_sampler();
        ASSERT_EQ(ls.count(), 7u);  // sun, five area lights, environment
        const Point3 p{0.1f, 0.2f, -0.3f};
        for (std::uint32_t l = 0; l < ls.count(); ++l) {
            const auto fit = testing::fit_sphere(
                [&](int i) -> std::optional<Vector3> {
                    const auto sample = ls.sample_li(s, l, p, rnd2(l + 10, static_cast<std::uint32_t>(i)));
                    if (!sample || sample->pdf <= 0) return std::nullopt;
                    return sample->wi;
                },
                [&](Vector3 wi) -> double {
                    const auto q = on_light(s, ls, l, p, wi);
                    return q ? ls.pdf_li(s, l, p, wi, *q) : 0.0;
                },
                300000, 36, 72, 16);
            EXPECT_TRUE(fit.ok()) << "light " << l << (env_map ? " (map)" : "") << ": " << fit.report();
            EXPECT_NEAR(fit.pdf_integral, 1 - fit.other_fraction, 0.01) << "light " << l;
        }
    }
}

// Irradiance from a sphere of radiance L seen at angle theta_max, facing it: pi L sin^2 theta_max
// (the cone sampling); a disk on axis: pi L r^2 / (r^2 + h^2) (area sampling).
TEST(LightSampler, IrradianceFromSphereAndDiskMatchesClosedForms) {
    Scene s;
    s.materials = {DiffuseMaterial{0}};
    s.textures = {ConstantTexture{Color{0}}};
    s.emission = {Emission{Color{1}, false, std::nullopt}};
    s.spheres.push_back({{0, 3, 0}, 1, 0});
    s.disks.push_back({{0, -2, 0}, Normal3{0, 1, 0}, 1.5f, 0});
    s.background = ConstantBackground{Color{0}};
    s.commit();
    const LightSampler& ls = s.light_sampler();
    const auto irradiance = [&](std::uint32_t l, Vector3 n) {
        double sum = 0;
        constexpr int kN = 200000;
        for (int i = 0; i < kN; ++i) {
            const auto x = ls.sample_li(s, l, {0, 0, 0}, rnd2(3, static_cast<std::uint32_t>(i)));
            if (x) sum += x->L.r * std::max(0.0f, dot(x->wi, n)) / x->pdf;
        }
        return sum / kN;
    };
    EXPECT_NEAR(irradiance(ls.light_of(ShapeKind::kSphere, 0), {0, 1, 0}), kPi / 9, 2e-3);
    EXPECT_NEAR(irradiance(ls.light_of(ShapeKind::kDisk, 0), {0, -1, 0}), kPi * 2.25 / (2.25 + 4), 3e-3);
}

TEST(LightSampler, LightsArePickedInProportionToPower) {
    Scene s;
    s.lights.push_back(PointLight{{0, 0, 0}, Color{1}});
    s.lights.push_back(PointLight{{0, 0, 0}, Color{3}});
    s.background = ConstantBackground{Color{0}};
    s.commit();
    const LightSampler& ls = s.light_sampler();
    ASSERT_EQ(ls.count(), 2u);  // a black environment is no light
    EXPECT_NEAR(ls.pmf(0), 0.25f, 1e-6f);
    EXPECT_NEAR(ls.pmf(1), 0.75f, 1e-6f);
}

// An emitting mesh cut by an alpha mask emits nothing from its holes: light samples on it give
// the irradiance that rays meeting the mesh find through the intersection's alpha test (the
// independent path), for a cutoff mask (a checker cuts half) and a stochastic one (alpha 0.3).
TEST(LightSampler, AlphaHolesInEmittersEmitNothing) {
    for (const bool stochastic : {false, true}) {
        Scene s;
        s.materials = {DiffuseMaterial{0}};
        s.textures = {ConstantTexture{Color{0}}};
        s.textures.push_back(stochastic ? Texture{ConstantTexture{Color{0.3f}}}
                                        : Texture{CheckerTexture{0.25f, Color{1}, Color{0}}});
        s.emission = {Emission{Color{1}, false, std::nullopt}};
        TriangleMesh mesh;  // a unit square at y = 1, facing down
        mesh.positions = {{-0.5f, 1, -0.5f}, {0.5f, 1, -0.5f}, {0.5f, 1, 0.5f}, {-0.5f, 1, 0.5f}};
        mesh.indices = {0, 1, 2, 0, 2, 3};
        s.meshes.push_back(mesh);
        s.alpha_masks.push_back({1, 0.5f, stochastic});
        s.instances.push_back({0, Transform{}, std::nullopt, 0});
        s.background = ConstantBackground{Color{0}};
        s.commit();
        const LightSampler& ls = s.light_sampler();
        ASSERT_EQ(ls.count(), 2u);
        const Point3 p{0.1f, 0, 0.05f};
        constexpr int kN = 400000;
        double by_light = 0;
        for (std::uint32_t t = 0; t < 2; ++t) {
            const std::uint32_t l = ls.light_of(ShapeKind::kMesh, 0, t);
            for (int i = 0; i < kN; ++i) {
                const auto x = ls.sample_li(s, l, p, rnd2(60 + t, static_cast<std::uint32_t>(i)));
                if (x && x->pdf > 0) by_light += x->L.g * std::max(0.0f, x->wi.y) / x->pdf;
            }
        }
        by_light /= kN;
        // Cosine-weighted directions: E = pi x the share of rays that meet the emitting mesh.
        double met = 0;
        for (int i = 0; i < 4 * kN; ++i) {
            const Vector3 d = sample_cosine_hemisphere(rnd2(70, static_cast<std::uint32_t>(i)));
            met += s.intersect(Ray{p, Vector3{d.x, d.z, d.y}}).has_value() ? 1 : 0;  // z up -> y up
        }
        const double by_rays = kPi * met / (4 * kN);
        EXPECT_NEAR(by_light, by_rays, 0.01 * by_rays + 2e-3) << (stochastic ? "stochastic" : "cutoff");
        // And the holes are really there: the whole square gives 0.74 here.
        EXPECT_LT(by_light, stochastic ? 0.3 : 0.5);
    }
}

TEST(SpotLight, FullInsideNoneOutsideSmoothBetween) {
    const SpotLight spot{{0, 0, 0}, {0, -1, 0}, Color{1}, std::cos(20 * kPi / 180),
                         std::cos(30 * kPi / 180)};
    EXPECT_EQ(spot.falloff({0, -1, 0}), 1);
    EXPECT_EQ(spot.falloff(Vector3{std::sin(31 * kPi / 180), -std::cos(31 * kPi / 180), 0}), 0);
    const float mid = spot.falloff(Vector3{std::sin(25 * kPi / 180), -std::cos(25 * kPi / 180), 0});
    EXPECT_GT(mid, 0.3f);
    EXPECT_LT(mid, 0.7f);
}

}  // namespace
}  // namespace glint
