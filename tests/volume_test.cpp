// The volumetric path tracer against known answers: transmittance through a sphere of medium,
// white furnaces with scattering interiors, an infinite emitting medium, single scattering in a
// thin slab, the three light strategies agreeing, empty media changing nothing, thread counts,
// and the scene errors of media.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>

#include "glint/integrators/integrator.h"
#include "glint/builder/build.h"
#include "glint/formats/scene_yaml.h"
#include "glint/assets/vdb.h"
#include "glint/render/render.h"

#include "testing.h"

namespace glint {
namespace {

RenderJob job_from(const std::string& yaml, const std::string& path = "scene.yaml") {
    auto sources = std::make_shared<SourceFiles>();
    return build(parse_scene(yaml, path, sources), {}, sources);
}

Film render_job(const RenderJob& job, int spp, int threads = 0) {
    Film film(job.film_width, job.film_height);
    RenderOptions o = job.options;
    o.spp = spp;
    o.threads = threads;
    render(job.scene, job.camera, *job.integrator, o, film);
    return film;
}

struct Estimate {
    Color mean;
    Color stderr_;
};

// The integrator's estimate along one ray, averaged over n independent samples.
Estimate mean_li(const RenderJob& job, const Ray& ray, int n, std::uint32_t seed = 1) {
    const PixelSampler sampler(SamplerType::kIndependent, static_cast<std::uint32_t>(n), seed);
    double s[3] = {0, 0, 0}, s2[3] = {0, 0, 0};
    RayCounter counter;
    for (int i = 0; i < n; ++i) {
        SampleStream stream(sampler, static_cast<std::uint32_t>(i));
        const Color c = job.integrator->li(job.scene, ray, stream, counter);
        for (int k = 0; k < 3; ++k) s[k] += c[k], s2[k] += double(c[k]) * c[k];
    }
    Estimate e;
    float m[3], se[3];
    for (int k = 0; k < 3; ++k) {
        m[k] = float(s[k] / n);
        se[k] = float(std::sqrt(std::max(0.0, s2[k] / n - double(m[k]) * m[k]) / n));
    }
    e.mean = {m[0], m[1], m[2]};
    e.stderr_ = {se[0], se[1], se[2]};
    return e;
}

void expect_close(const Estimate& e, Color expect, const std::string& what, float slack = 1e-3f) {
    for (int k = 0; k < 3; ++k)
        EXPECT_NEAR(e.mean[k], expect[k], 4 * e.stderr_[k] + slack) << what << ", channel " << k;
}

// An absorbing sphere (interface boundary) in front of a background of radiance 1: along a ray
// at distance b from the centre the camera sees exp(-sigma_c 2 sqrt(r^2 - b^2)).
TEST(Volume, AbsorbingSphereTransmitsExpOfChord) {
    const RenderJob job = job_from(R"(
integrator: {type: path, max_depth: 8}
background: {type: constant, color: [1, 1, 1]}
media:
  ink: {type: homogeneous, sigma_a: [0.3, 0.8, 1.6], sigma_s: [0, 0, 0]}
objects:
  - {type: sphere, center: [0, 0, 5], radius: 1.5, material: interface, interior: ink}
)");
    for (const float b : {0.0f, 0.7f, 1.3f}) {
        const Ray ray{{b, 0, -2}, {0, 0, 1}};
        const float chord = 2 * std::sqrt(1.5f * 1.5f - b * b);
        const Color expect{std::exp(-0.3f * chord), std::exp(-0.8f * chord), std::exp(-1.6f * chord)};
        expect_close(mean_li(job, ray, 40000), expect, "b = " + std::to_string(b));
    }
}

// Coloured glass: a glass sphere (index 1.5) with an absorbing interior in a uniform
// environment of radiance 1, seen along a diameter. At normal incidence every path stays on the
// axis; with F = ((n - 1) / (n + 1))^2 and x = exp(-sigma_c 2r) the radiance is
//   F + (1 - F)^2 x / (1 - F x)
// (the front reflection, then light that enters and leaves after 0, 2, 4 ... inner reflections).
TEST(Volume, AbsorbingGlassSphereAlongItsAxisMatchesFresnelSeries) {
    const RenderJob job = job_from(R"(
integrator: {type: path, max_depth: 64, rr_depth: 64}
background: {type: constant, color: [1, 1, 1]}
media:
  tint: {type: homogeneous, sigma_a: [0.2, 0.6, 1.2], sigma_s: [0, 0, 0]}
objects:
  - {type: sphere, center: [0, 0, 4], radius: 1, material: {type: dielectric, ior: 1.5}, interior: tint}
)");
    const float f = 0.04f;
    Color expect;
    for (int c = 0; c < 3; ++c) {
        const float x = std::exp(-Color{0.2f, 0.6f, 1.2f}[c] * 2);
        (c == 0 ? expect.r : c == 1 ? expect.g : expect.b) = f + (1 - f) * (1 - f) * x / (1 - f * x);
    }
    expect_close(mean_li(job, Ray{{0, 0, 0}, {0, 0, 1}}, 40000), expect, "glass", 2e-3f);
}

// Non-absorbing media (albedo 1) of any density and g, inside a uniform environment of
// radiance 1: every path ends in the environment with weight 1, so every pixel is 1.
std::string furnace(const std::string& medium, const std::string& boundary) {
    return R"(
camera: {type: look_at, from: [0, 0, -3], to: [0, 0, 0], fov: 45}
film: {width: 12, height: 12, filter: {type: box}}
integrator: {type: path, max_depth: 1000}
background: {type: constant, color: [1, 1, 1]}
media:
  m: )" + medium + R"(
objects:
  - {type: sphere, center: [0, 0, 0], radius: 1, material: )" + boundary + R"(, interior: m}
)";
}

TEST(Volume, WhiteFurnaceScatteringSphereIsOne) {
    for (const std::string boundary : {"interface", "{type: dielectric, ior: 1.5}"}) {
        for (const std::string medium : {"{type: homogeneous, albedo: 1, density: 0.5, g: 0}",
                                         "{type: homogeneous, albedo: 1, density: 4, g: 0.8}",
                                         "{type: homogeneous, albedo: 1, density: 10, g: -0.5}"}) {
            const RenderJob job = job_from(furnace(medium, boundary));
            const Film film = render_job(job, 32);
            double sum = 0;
            for (const Color& c : film.pixels()) sum += c.r + c.g + c.b;
            EXPECT_NEAR(sum / (3.0 * double(film.pixels().size())), 1, 0.01) << boundary << " " << medium;
        }
    }
}

// An infinite medium of albedo a emitting sigma_a Le per unit length: the radiance gathered
// before the (k+1)-th scattering is Le (1 - a^(k+1)) (each event absorbs 1 - a of what goes on),
// and Le itself without a bound.
TEST(Volume, InfiniteEmittingMediumMatchesClosedForm) {
    for (const int k : {0, 1, 3}) {
        const RenderJob job = job_from(R"(
integrator: {type: path, max_depth: )" + std::to_string(k) + R"(, rr_depth: 1000}
background: {type: constant, color: [0, 0, 0]}
medium: glow
media:
  glow: {type: homogeneous, sigma_a: [0.5, 1, 0.25], sigma_s: [0.5, 1, 0.75], emission: [2, 1, 0.5], g: 0.5}
)");
        const Color a{0.5f, 0.5f, 0.75f}, le{2, 1, 0.5f};
        Color expect;
        for (int c = 0; c < 3; ++c) (c == 0 ? expect.r : c == 1 ? expect.g : expect.b) = le[c] * (1 - std::pow(a[c], float(k + 1)));
        expect_close(mean_li(job, Ray{{0, 0, 0}, {0, 0, 1}}, 40000), expect, "max_depth " + std::to_string(k), 2e-3f);
    }
}

// Single scattering in a slab 0 <= z <= L (an interface box, very wide) lit by a sun whose light
// travels along (sin t, 0, cos t), seen along +z from outside:
//   L = sigma_s p(cos t) E (1 - exp(-sigma_t L k)) / (sigma_t k),  k = 1 + 1 / cos t.
TEST(Volume, SingleScatteringSlabMatchesClosedForm) {
    const float theta = 0.5f, sigma_s = 0.15f, sigma_a = 0.05f, L = 1.0f, g = 0.3f;
    const std::string yaml = R"(
integrator: {type: path, max_depth: 1}
background: {type: constant, color: [0, 0, 0]}
lights:
  - {type: directional, direction: [)" + std::to_string(std::sin(theta)) + ", 0, " + std::to_string(std::cos(theta)) + R"(], intensity: [2, 2, 2]}
media:
  slab: {type: homogeneous, sigma_a: [0.05, 0.05, 0.05], sigma_s: [0.15, 0.15, 0.15], g: 0.3}
objects:
  - {type: box, min: [-1000, -1000, 0], max: [1000, 1000, 1], material: interface, interior: slab}
)";
    const RenderJob job = job_from(yaml);
    const float st = sigma_s + sigma_a, k = 1 + 1 / std::cos(theta);
    const float p = HgPhase::eval_cos(std::cos(theta), g);
    const float expect = sigma_s * p * 2 * (1 - std::exp(-st * L * k)) / (st * k);
    expect_close(mean_li(job, Ray{{0.5f, 0.25f, -1}, {0, 0, 1}}, 100000), Color{expect}, "slab", 1e-5f);
}

// Single scattering of a point light inside a chromatic slab (the light 0.3 off the camera
// ray, where the 1/r^2 falloff peaks sharply), against the integral along the ray by Simpson's
// rule: L = int_0^2 sigma_s e^{-sigma_t z} p(cos) I e^{-sigma_t r(z)} / r(z)^2 dz. The path
// tracer draws the distance for light sampling from the free-flight and the equiangular density
// mixed; the same holds with the light outside the slab, behind the ray's entry (equiangular only
// partly inside the segment) and for a spot light whose cone (up to 73 degrees off its axis here)
// covers the segment.
TEST(Volume, PointLightSingleScatteringMatchesQuadrature) {
    const Color sigma_a{0.05f, 0.1f, 0.2f}, sigma_s{0.4f, 0.3f, 0.2f};
    const float g = 0.4f, I = 3;
    for (const Point3 light : {Point3{0.3f, 0, 1}, Point3{0.5f, 0.2f, -0.4f}}) {
        for (const bool spot : {false, true}) {
            const std::string pos = "[" + std::to_string(light.x) + ", " + std::to_string(light.y) + ", " +
                                    std::to_string(light.z) + "]";
            const std::string light_yaml =
                spot ? "{type: spot, position: " + pos + ", direction: [-1, 0, 0], cone_angle: 89, falloff_start: 89, intensity: [3, 3, 3]}"
                     : "{type: point, position: " + pos + ", intensity: [3, 3, 3]}";
            if (spot && light.z < 0) continue;  // the segment must lie inside the cone
            const RenderJob job = job_from(R"(
integrator: {type: path, max_depth: 1}
background: {type: constant, color: [0, 0, 0]}
lights:
  - )" + light_yaml + R"(
media:
  slab: {type: homogeneous, sigma_a: [0.05, 0.1, 0.2], sigma_s: [0.4, 0.3, 0.2], g: 0.4}
objects:
  - {type: box, min: [-1000, -1000, 0], max: [1000, 1000, 2], material: interface, interior: slab}
)");
            Color expect;
            for (int c = 0; c < 3; ++c) {
                const double st = sigma_a[c] + sigma_s[c];
                const auto f = [&](double z) {
                    const double dx = light.x, dy = light.y, dz = light.z - z;
                    const double r2 = dx * dx + dy * dy + dz * dz, r = std::sqrt(r2);
                    const float cos = float(-dz / r);  // wo = -z, wi towards the light
                    // Of the way to a light below the slab (z < 0), only the part above z = 0
                    // lies in the medium.
                    const double inside = light.z < 0 ? r * z / (z - light.z) : r;
                    return sigma_s[c] * std::exp(-st * z) * HgPhase::eval_cos(cos, g) * I * std::exp(-st * inside) / r2;
                };
                const int n = 20000;
                const double h = 2.0 / n;
                double sum = f(0) + f(2);
                for (int i = 1; i < n; ++i) sum += (i % 2 ? 4 : 2) * f(i * h);
                (c == 0 ? expect.r : c == 1 ? expect.g : expect.b) = float(sum * h / 3);
            }
            expect_close(mean_li(job, Ray{{0, 0, -1}, {0, 0, 1}}, 200000, 11), expect,
                         spot ? "spot light" : "point light", 1e-4f);
        }
    }
}

// The same slab under a soft sun: light sampling alone, phase sampling alone and MIS estimate
// the same radiance (an area-like light every strategy can reach).
TEST(Volume, LightPhaseAndMisStrategiesAgreeInMedia) {
    const auto scene = [](const char* strategy) {
        return std::string(R"(
integrator: {type: path, max_depth: 3, strategy: )") + strategy + R"(}
background: {type: constant, color: [0, 0, 0]}
lights:
  - {type: directional, direction: [0.3, 0, 1], intensity: [2, 2, 2], angular_diameter: 40}
media:
  slab: {type: homogeneous, sigma_a: [0.05, 0.1, 0.2], sigma_s: [0.4, 0.3, 0.2], g: 0.6}
objects:
  - {type: box, min: [-1000, -1000, 0], max: [1000, 1000, 2], material: interface, interior: slab}
)";
    };
    const Ray ray{{0, 0, -1}, normalize(Vector3{0.1f, 0, 1})};
    const Estimate mis = mean_li(job_from(scene("mis")), ray, 100000, 3);
    const Estimate light = mean_li(job_from(scene("light")), ray, 100000, 5);
    const Estimate phase = mean_li(job_from(scene("bsdf")), ray, 400000, 7);
    for (int c = 0; c < 3; ++c) {
        const auto z = [&](const Estimate& a, const Estimate& b) {
            return std::abs(a.mean[c] - b.mean[c]) / std::hypot(a.stderr_[c], b.stderr_[c]);
        };
        EXPECT_LT(z(mis, light), 4.5) << "channel " << c << ": " << mis.mean[c] << " vs " << light.mean[c];
        EXPECT_LT(z(mis, phase), 4.5) << "channel " << c << ": " << mis.mean[c] << " vs " << phase.mean[c];
        EXPECT_GT(mis.mean[c], 1e-3f);
    }
}

constexpr const char* kFogScene = R"(
camera: {type: look_at, from: [0, 1, -4], to: [0, 0, 0], fov: 50}
film: {width: 24, height: 16}
integrator: {type: path, max_depth: 6}
background: {type: constant, color: [0.3, 0.4, 0.6]}
lights:
  - {type: directional, direction: [-0.4, -1, 0.3], intensity: [2, 2, 2]}
  - {type: point, position: [1, 2, -1], intensity: [3, 2, 1]}
media:
  fog: {type: homogeneous, albedo: [0.9, 0.8, 0.7], density: DENSITY, g: 0.4}
materials:
  glass: {type: dielectric, ior: 1.5}
objects:
  - {type: plane, point: [0, -1, 0], normal: [0, 1, 0], material: {type: diffuse, albedo: 0.6}}
  - {type: sphere, center: [-1, 0, 1], radius: 1, material: glass}
  - {type: sphere, center: [1.2, 0, 0.5], radius: 0.8, material: {type: diffuse, albedo: [0.8, 0.3, 0.2]}}
)";

std::string fog(const std::string& density, const std::string& extra) {
    std::string s = kFogScene;
    s.replace(s.find("DENSITY"), 7, density);
    return s + extra;
}

bool identical(const Film& a, const Film& b) {
    return a.pixels().size() == b.pixels().size() &&
           std::equal(a.pixels().begin(), a.pixels().end(), b.pixels().begin());
}

TEST(Volume, EmptyCameraMediumRendersBitIdenticalToNone) {
    const Film with = render_job(job_from(fog("0", "medium: fog\n")), 8);
    const Film without = render_job(job_from(fog("0", "")), 8);
    EXPECT_TRUE(identical(with, without));
}

TEST(Volume, EmptyMediumInsideInterfaceRendersBitIdenticalToVacuum) {
    const std::string box = "  - {type: box, min: [-3, -0.5, -2], max: [3, 2, 3], material: interface, interior: INSIDE}\n";
    std::string a = box, b = box;
    a.replace(a.find("INSIDE"), 6, "fog");
    b.replace(b.find("INSIDE"), 6, "none");
    const Film with = render_job(job_from(fog("0", "") + a), 8);
    const Film without = render_job(job_from(fog("0", "") + b), 8);
    EXPECT_TRUE(identical(with, without));
}

TEST(Volume, ImagesIdenticalForAnyThreadCount) {
    const RenderJob job = job_from(fog("0.3", "medium: fog\n"));
    const Film one = render_job(job, 4, 1);
    const Film two = render_job(job, 4, 2);
    const Film three = render_job(job, 4, 3);
    EXPECT_TRUE(identical(one, two));
    EXPECT_TRUE(identical(one, three));
    double sum = 0;
    for (const Color& c : one.pixels()) sum += c.g;
    EXPECT_GT(sum, 0);
}

// Errors of media, each at its line and column, collected in one run.
std::string errors_of(const std::string& yaml, const std::string& path = "scene.yaml") {
    try {
        job_from(yaml, path);
    } catch (const SceneError& e) {
        return e.what();
    }
    return "";
}

TEST(Volume, MediumErrorsAreLocated) {
    const std::string e = errors_of(R"(media:
  a: {type: homogeneous, sigma_a: [1, -1, 0], sigma_s: [0, 0, 0]}
  b: {type: homogeneous, albedo: 0.5, density: 1, g: 1}
  c: {type: homogeneous, albedo: 0.5, sigma_s: [1, 1, 1]}
  d: {type: homogeneous, albedo: 1.5}
  e: {type: homogeneous, sigma_a: [.nan, 0, 0]}
)");
    EXPECT_NE(e.find("scene.yaml:2:"), std::string::npos) << e;
    EXPECT_NE(e.find("scene.yaml:3:"), std::string::npos) << e;
    EXPECT_NE(e.find("g must lie in (-1, 1)"), std::string::npos) << e;
    EXPECT_NE(e.find("scene.yaml:4:"), std::string::npos) << e;
    EXPECT_NE(e.find("not both"), std::string::npos) << e;
    EXPECT_NE(e.find("scene.yaml:5:"), std::string::npos) << e;
    EXPECT_NE(e.find("albedo must be in [0, 1]"), std::string::npos) << e;
    EXPECT_NE(e.find("scene.yaml:6:"), std::string::npos) << e;
    // Names are resolved after parsing: every unknown one is reported, with a suggestion.
    const std::string n = errors_of(R"(media:
  smoke: {type: homogeneous, albedo: 0.5, density: 1}
medium: smoek
objects:
  - {type: sphere, center: [0, 0, 0], radius: 1, material: interface, interior: fog}
)");
    EXPECT_NE(n.find("scene.yaml:3:9: error: unknown medium 'smoek'; did you mean 'smoke'?"), std::string::npos) << n;
    EXPECT_NE(n.find("scene.yaml:5:81: error: unknown medium 'fog'"), std::string::npos) << n;
}

TEST(Volume, GridFileErrorsAreLocated) {
    const testing::TempDir tmp;  // removed at the end of the test, whatever fails
    const std::filesystem::path& dir = tmp.path();
    const VoxelGrid v = VoxelGrid::from_function({0, 0, 0}, {4, 4, 4}, [](int, int, int) { return 1.0f; });
    write_vdb(dir / "cloud.vdb", {{"density", &v}, {"heat", &v}}, 0.1f);
    const std::string scene = (dir / "scene.yaml").string();
    const auto media = [](const std::string& body) { return "media:\n  smoke: " + body + "\n"; };
    // Missing file.
    std::string e = errors_of(media("{type: grid, file: nothere.vdb, albedo: 0.5}"), scene);
    EXPECT_NE(e.find("scene.yaml:2:"), std::string::npos) << e;
    EXPECT_NE(e.find("no such file"), std::string::npos) << e;
    // A grid name the file does not have, with a suggestion.
    e = errors_of(media("{type: grid, file: cloud.vdb, grid: densty}"), scene);
    EXPECT_NE(e.find("no grid named 'densty'; did you mean 'density'?"), std::string::npos) << e;
    EXPECT_NE(e.find("scene.yaml:2:46"), std::string::npos) << e;
    // Not a VDB at all.
    std::ofstream(dir / "bad.vdb") << "not a vdb";
    e = errors_of(media("{type: grid, file: bad.vdb}"), scene);
    EXPECT_NE(e.find("not a readable OpenVDB file"), std::string::npos) << e;
    // The good file builds.
    EXPECT_EQ(errors_of(media("{type: grid, file: cloud.vdb, temperature_grid: heat, temperature_scale: 1000}"), scene), "");
}

// A grid medium from a .vdb (density 1 and an emission grid of 2 over a 16^3 block, voxels
// 0.25 wide, moved by the medium's transform) that absorbs and emits: along a ray inside the
// constant region the radiance is Le (1 - exp(-sigma_a L)) (emission-absorption, no scattering).
TEST(Volume, EmittingGridMatchesEmissionAbsorptionClosedForm) {
    const testing::TempDir tmp;  // removed at the end of the test, whatever fails
    const std::filesystem::path& dir = tmp.path();
    const VoxelGrid one = VoxelGrid::from_function({0, 0, 0}, {16, 16, 16}, [](int, int, int) { return 1.0f; });
    const VoxelGrid two = VoxelGrid::from_function({0, 0, 0}, {16, 16, 16}, [](int, int, int) { return 2.0f; });
    write_vdb(dir / "block.vdb", {{"density", &one}, {"glow", &two}}, 0.25f);
    // World block [10, 13.75] x [0, 3.75] x [0, 3.75] (voxel centres); the boundary box lies
    // inside the region where trilinear interpolation is exactly constant.
    const RenderJob job = job_from(R"(
integrator: {type: path, max_depth: 4}
background: {type: constant, color: [0, 0, 0]}
media:
  block: {type: grid, file: block.vdb, sigma_a: [0.4, 0.8, 1.6], sigma_s: [0, 0, 0],
          emission_grid: glow, emission: [1, 0.5, 0.25], emission_scale: 1.5, transform: {translate: [10, 0, 0]}}
objects:
  - {type: box, min: [10.5, 0.5, 0.5], max: [13.0, 3.0, 3.0], material: interface, interior: block}
)", (dir / "scene.yaml").string());
    const float len = 2.5f;
    const Color sigma{0.4f, 0.8f, 1.6f}, le = Color{1, 0.5f, 0.25f} * (2 * 1.5f);
    Color expect;
    for (int c = 0; c < 3; ++c) (c == 0 ? expect.r : c == 1 ? expect.g : expect.b) = le[c] * (1 - std::exp(-sigma[c] * len));
    expect_close(mean_li(job, Ray{{9, 1.7f, 1.9f}, {1, 0, 0}}, 60000), expect, "emitting grid", 2e-3f);
}

// A grid given in the scene as `voxels` (nz x ny x nx, x fastest) filling the box min..max: the
// density varies along x alone, a_i in column i, voxels 1 unit wide. Trilinear interpolation
// between voxel centres, with 0 beyond the outermost ones, integrates along a line through voxel
// centres to the sum of the samples times the spacing: along x, sum(a_i); along z at column i,
// nz a_i. The absorbing-only medium then transmits exp(-sigma_a times that) of the background.
// The same voxels handed over as an array (the Python module's numpy memory) give the same
// estimate to the bit.
TEST(Volume, VoxelsInTheSceneTransmitExpOfTheirIntegral) {
    const float a[4] = {0.2f, 0.5f, 1.0f, 0.1f};
    std::string rows, plane;
    for (int j = 0; j < 2; ++j) plane += std::string(j ? ", " : "") + "[0.2, 0.5, 1.0, 0.1]";
    for (int k = 0; k < 3; ++k) rows += std::string(k ? ", " : "") + "[" + plane + "]";
    const auto scene = [](const std::string& voxels) {
        return "integrator: {type: path, max_depth: 4}\n"
               "background: {type: constant, color: [1, 1, 1]}\n"
               "media:\n"
               "  smoke: {type: grid, voxels: " + voxels + ", min: [10, 0, 0], max: [14, 2, 3],\n"
               "          sigma_a: [0.5, 0.5, 0.5], sigma_s: [0, 0, 0]}\n"
               "objects:\n"
               "  - {type: box, min: [9, -1, -1], max: [15, 3, 4], material: interface, interior: smoke}\n";
    };
    const RenderJob listed = job_from(scene("[" + rows + "]"));
    float values[24];
    for (int v = 0; v < 24; ++v) values[v] = a[v % 4];
    ArrayView view{values, nullptr, 3, 8};
    view.shape = {3, 2, 4};
    view.dims = 3;
    const InlineArrays arrays{view};
    auto sources = std::make_shared<SourceFiles>();
    const RenderJob handed = build(parse_scene(scene("'<array 0>'"), "scene.yaml", sources, 0, &arrays), {}, sources);
    float sum = 0;
    for (float x : a) sum += x;
    const Ray along_x{{8, 1, 1.5f}, {1, 0, 0}};
    expect_close(mean_li(listed, along_x, 40000), Color{std::exp(-0.5f * sum)}, "along x");
    for (int i = 0; i < 4; ++i) {
        const Ray along_z{{10.5f + float(i), 1, -2}, {0, 0, 1}};
        const Estimate e = mean_li(listed, along_z, 40000);
        expect_close(e, Color{std::exp(-0.5f * 3 * a[i])}, "along z, column " + std::to_string(i));
        EXPECT_EQ(mean_li(handed, along_z, 2000).mean.r, mean_li(listed, along_z, 2000).mean.r);
    }
}

// A small spherical light inside a large interface box (an empty medium) lights the ground
// outside the box: the irradiance is pi L (r/d)^2 cos(theta) whatever the box, so the ground's
// radiance is albedo L (r/d)^2 cos(theta). The shadow rays cross the box wall three units from
// the origin while the light is within one: a segment re-spawned past the wall must still end
// before the light. (It used to keep its length, so it overshot by the push off the wall, which
// grows with the distance from the origin, and struck the light: the ground went dark.)
TEST(Volume, AreaLightInsideInterfaceBoxGivesClosedFormIrradiance) {
    for (const float x : {0.0f, 10.0f}) {
        const auto at = [x](float v) { return std::to_string(x + v); };
        const RenderJob job = job_from(R"(
integrator: {type: path, max_depth: 1}
background: {type: constant, color: [0, 0, 0]}
media:
  empty: {type: homogeneous, sigma_a: [0, 0, 0], sigma_s: [0, 0, 0]}
materials:
  lamp: {type: diffuse, albedo: [0, 0, 0], emission: [100, 100, 100]}
  ground: {type: diffuse, albedo: [0.5, 0.5, 0.5]}
objects:
  - {type: plane, point: [0, 0, 0], normal: [0, 1, 0], material: ground}
  - {type: sphere, center: [)" + at(0) + R"(, 0.5, 0], radius: 0.1, material: lamp}
  - {type: box, min: [)" + at(-3) + R"(, 0.1, -3], max: [)" + at(3) + R"(, 3, 3], material: interface, interior: empty}
)");
        // The ground point (x + 4, 0, 0), beside the box: d^2 = 16.25, cos(theta) = 0.5 / d.
        const float d2 = 16.25f, expect = 0.5f * 100 * (0.01f / d2) * (0.5f / std::sqrt(d2));
        const Vector3 d = normalize(Vector3{-2, -1, 0});
        expect_close(mean_li(job, Ray{{x + 6, 1, 0}, d}, 40000), Color{expect}, "light at x = " + at(0), 1e-5f);
        // The ground point (x, 0, 4.5), beyond the far wall, whose shadow rays cross it slanting
        // (a segment continued parallel to itself, shifted by the push off the wall, ended
        // inside the light): d^2 = 20.5, cos(theta) = 0.5 / d.
        const float d2b = 20.5f, expect_b = 0.5f * 100 * (0.01f / d2b) * (0.5f / std::sqrt(d2b));
        expect_close(mean_li(job, Ray{{x, 1, 6.5f}, normalize(Vector3{0, -1, -2})}, 40000), Color{expect_b},
                     "beyond the wall, light at x = " + at(0), 1e-5f);
    }
}
}  // namespace
}  // namespace glint
