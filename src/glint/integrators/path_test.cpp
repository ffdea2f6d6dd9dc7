// The path tracer against known answers: white furnaces, the three light strategies agreeing,
// and error falling as 1 / sqrt(spp) on the Cornell box.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "glint/integrators/integrator.h"
#include "glint/builder/build.h"
#include "glint/formats/scene_yaml.h"
#include "glint/render/render.h"
#include "testing.h"

namespace glint {
namespace {

RenderJob job_from(const std::string& yaml, Overrides o = {}) {
    auto sources = std::make_shared<SourceFiles>();
    return build(parse_scene(yaml, "scene.yaml", sources), o, sources);
}

Film render_job(const RenderJob& job, int spp, std::uint64_t seed = 0) {
    Film film(job.film_width, job.film_height);
    RenderOptions o = job.options;
    o.spp = spp;
    o.seed = seed;
    render(job.scene, job.camera, *job.integrator, o, film);
    return film;
}

// A unit sphere filling most of a 24 x 24 view, in a uniform environment of radiance 1.
std::string furnace(const std::string& material) {
    return R"(
camera: {type: look_at, from: [0, 0, -3], to: [0, 0, 0], fov: 45}
film: {width: 24, height: 24}
integrator: {type: path, max_depth: 64}
background: {type: constant, color: [1, 1, 1]}
objects:
  - {type: sphere, center: [0, 0, 0], radius: 1, material: )" + material + "}\n";
}

// Every pixel, sphere or sky, sees radiance 1 when nothing is absorbed.
void expect_furnace(const std::string& material, double tolerance) {
    const RenderJob job = job_from(furnace(material));
    const Film film = render_job(job, 64);
    double sum = 0, worst = 0;
    for (const Color& c : film.pixels()) {
        sum += c.g;
        worst = std::max(worst, std::abs(c.g - 1.0));
    }
    const double mean = sum / static_cast<double>(film.pixels().size());
    EXPECT_NEAR(mean, 1, tolerance) << material;
    EXPECT_LT(worst, 0.1) << material;  // 64 spp: no pixel strays far
}

TEST(Path, WhiteFurnaceDiffuseSphereIsOne) { expect_furnace("{type: diffuse, albedo: 1}", 0.002); }

TEST(Path, WhiteFurnaceRoughConductorIsOne) {
    // Reflectance 1 at every angle; roughness 0.8 (alpha 0.64) loses ~20% between microfacets
    // in single scattering, which the multiple-scattering term must return.
    expect_furnace("{type: conductor, reflectance: 1, roughness: 0.8}", 0.005);
}

TEST(Path, FurnaceWithHalfAlbedoReflectsHalfOnce) {
    // A convex sphere scatters each path once: albedo 0.5 gives exactly 0.5 on the sphere.
    const RenderJob job = job_from(furnace("{type: diffuse, albedo: 0.5}"));
    const Film film = render_job(job, 64);
    EXPECT_NEAR(film.at(12, 12).g, 0.5, 0.01);
}

TEST(Path, WhiteFurnaceDiffuseTransmissionIsOne) {
    // Half reflected, half transmitted into the sphere and out again: nothing absorbed.
    const RenderJob job = job_from(furnace("{type: diffuse_transmission, reflectance: 0.5, transmittance: 0.5}"));
    const Film film = render_job(job, 256);  // paths wander inside: more samples than expect_furnace's
    double sum = 0, worst = 0;
    for (const Color& c : film.pixels()) sum += c.g, worst = std::max(worst, std::abs(c.g - 1.0));
    EXPECT_NEAR(sum / static_cast<double>(film.pixels().size()), 1, 0.003);
    EXPECT_LT(worst, 0.1);
}

// A closed cube tiled by 6 x 6 emitting quads per face (216 lights), each of radiance 1 inwards
// on a diffuse wall of albedo 0.5: radiance L = 1 + 0.5 L everywhere inside, so every pixel sees
// 2, whichever light sampler chooses among the lights (a pmf that disagreed with the choices,
// in next-event estimation or in the MIS weight of an emitter found by the BSDF, would show).
std::string many_light_furnace(const std::string& light_sampler) {
    std::string y = R"(
camera: {type: look_at, from: [0.1, -0.2, 0.05], to: [0.5, 0.1, 1], fov: 100}
film: {width: 16, height: 16}
integrator: {type: path, max_depth: 64, light_sampler: )" + light_sampler + R"(}
background: {type: constant, color: [0, 0, 0]}
materials:
  wall: {type: diffuse, albedo: 0.5, emission: [1, 1, 1]}
objects:
)";
    constexpr int k = 6;
    constexpr float h = 2.0f / k;
    for (int a = 0; a < 3; ++a) {
        const int b = (a + 1) % 3, c = (a + 2) % 3;  // e_b x e_c = e_a
        for (const float side : {-1.0f, 1.0f}) {
            for (int i = 0; i < k; ++i) {
                for (int j = 0; j < k; ++j) {
                    float corner[3], e1[3] = {0, 0, 0}, e2[3] = {0, 0, 0};
                    corner[a] = side;
                    corner[b] = -1 + i * h;
                    corner[c] = -1 + j * h;
                    // Facing inwards, -side e_a: (e_b, e_c) on the low side, (e_c, e_b) on the high.
                    (side < 0 ? e1 : e2)[b] = h;
                    (side < 0 ? e2 : e1)[c] = h;
                    y += "  - {type: quad, corner: [" + std::to_string(corner[0]) + ", " + std::to_string(corner[1]) + ", " +
                         std::to_string(corner[2]) + "], edge1: [" + std::to_string(e1[0]) + ", " + std::to_string(e1[1]) +
                         ", " + std::to_string(e1[2]) + "], edge2: [" + std::to_string(e2[0]) + ", " +
                         std::to_string(e2[1]) + ", " + std::to_string(e2[2]) + "], material: wall}\n";
                }
            }
        }
    }
    return y;
}

TEST(Path, FurnaceOfManyLightsIsTwoWithEitherLightSampler) {
    for (const std::string sampler : {"bvh", "power"}) {
        const RenderJob job = job_from(many_light_furnace(sampler));
        ASSERT_EQ(job.scene.light_sampler().count(), 216u);
        const Film film = render_job(job, 64);
        double sum = 0, worst = 0;
        for (const Color& c : film.pixels()) sum += c.g, worst = std::max(worst, std::abs(c.g - 2.0));
        EXPECT_NEAR(sum / static_cast<double>(film.pixels().size()), 2, 0.02) << sampler;
        EXPECT_LT(worst, 0.3) << sampler;
    }
}

// A mix picks its second material with probability `amount` at each point: a sphere of
// mix(white, black, 0.25) scatters each path once with probability 0.75, so its pixels average
// 0.75 (64 spp per pixel at different points, ~200 pixels).
TEST(Path, MixChoosesItsSecondMaterialWithProbabilityAmount) {
    const RenderJob job = job_from(R"(
camera: {type: look_at, from: [0, 0, -3], to: [0, 0, 0], fov: 45}
film: {width: 24, height: 24}
integrator: {type: path, max_depth: 64}
background: {type: constant, color: [1, 1, 1]}
materials:
  white: {type: diffuse, albedo: 1}
  black: {type: diffuse, albedo: 0}
  speckled: {type: mix, materials: [white, black], amount: 0.25}
objects:
  - {type: sphere, center: [0, 0, 0], radius: 1, material: speckled}
)");
    const Film film = render_job(job, 64);
    double sum = 0;
    int n = 0;
    for (int row = 0; row < 24; ++row)
        for (int col = 0; col < 24; ++col)
            if (std::hypot(col + 0.5 - 12, row + 0.5 - 12) < 8) sum += film.at(col, row).g, ++n;
    EXPECT_NEAR(sum / n, 0.75, 0.02) << n << " pixels";
    // Deterministic: the same image on a second run.
    const Film again = render_job(job, 64);
    for (std::size_t i = 0; i < film.pixels().size(); ++i) ASSERT_EQ(film.pixels()[i].g, again.pixels()[i].g);
}

TEST(Path, MixMistakesAreLocatedErrors) {
    const auto error_of = [](const std::string& materials) {
        try {
            job_from("materials:\n" + materials + "objects:\n  - {type: sphere, center: [0, 0, 0], radius: 1, material: a}\n");
        } catch (const SceneError& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    EXPECT_NE(error_of("  a: {type: mix, materials: [b, whit]}\n  b: {type: diffuse}\n")
                  .find("scene.yaml:2:33: error: mix: unknown material 'whit'"),
              std::string::npos);
    EXPECT_EQ(error_of("  a: {type: mix, materials: [b, whit]}\n  b: {type: diffuse}\n").find("contains itself"),
              std::string::npos);  // an unknown name is not also a cycle
    EXPECT_NE(error_of("  a: {type: mix, materials: [b, b]}\n  b: {type: mix, materials: [a, a]}\n")
                  .find("mix: the mix contains itself"),
              std::string::npos);
}

// A small scene every strategy can render (area lights only; no deltas): a diffuse floor, a
// rough metal sphere and a plastic sphere, lit by a quad light, a sphere light and the sky. In
// units of centimetres, like the Cornell box: surface offsets then matter (a shadow ray that
// ended a fixed fraction short of the light once hit the light itself from the sphere tops; the
// scene sits 1000 units from the origin, where the offsets are largest).
constexpr const char* kStrategyScene = R"(
camera: {type: look_at, from: [1000, 200, -600], to: [1000, 70, 0], fov: 40}
film: {width: 16, height: 12}
sampler: {type: independent}
integrator: {type: path, max_depth: 4, strategy: STRATEGY}
background: {type: constant, color: [0.2, 0.25, 0.3]}
materials:
  floor: {type: diffuse, albedo: [0.7, 0.7, 0.7]}
  metal: {type: conductor, metal: gold, roughness: 0.4}
  plastic: {type: plastic, albedo: [0.2, 0.4, 0.8], roughness: 0.3}
  lamp: {type: diffuse, albedo: 0, emission: [6, 6, 6]}
objects:
  - {type: quad, corner: [600, 0, -400], edge1: [0, 0, 800], edge2: [800, 0, 0], material: floor}
  - {type: sphere, center: [920, 70, 0], radius: 70, material: metal}
  - {type: sphere, center: [1090, 60, 30], radius: 60, material: plastic}
  - {type: quad, corner: [900, 180, -100], edge1: [200, 0, 0], edge2: [0, 0, 200], material: lamp}
  - {type: sphere, center: [1250, 200, -100], radius: 30, material: lamp}
)";

TEST(Path, LightSamplingBsdfSamplingAndMisAgree) {
    // Per strategy, the image mean over independent seeds, and its standard error.
    const auto estimate = [](const std::string& strategy) {
        std::string yaml = kStrategyScene;
        yaml.replace(yaml.find("STRATEGY"), 8, strategy);
        const RenderJob job = job_from(yaml);
        std::vector<double> means;
        for (std::uint64_t seed = 0; seed < 12; ++seed) {
            const Film film = render_job(job, 32, seed * 7919 + 1);
            double sum = 0;
            for (const Color& c : film.pixels()) sum += c.r + c.g + c.b;
            means.push_back(sum / static_cast<double>(film.pixels().size()));
        }
        double m = 0, v = 0;
        for (double x : means) m += x;
        m /= static_cast<double>(means.size());
        for (double x : means) v += (x - m) * (x - m);
        v /= static_cast<double>(means.size() - 1);
        return std::pair{m, std::sqrt(v / static_cast<double>(means.size()))};
    };
    const auto mis = estimate("mis"), light = estimate("light"), bsdf = estimate("bsdf");
    const auto z = [](std::pair<double, double> a, std::pair<double, double> b) {
        return std::abs(a.first - b.first) / std::sqrt(a.second * a.second + b.second * b.second);
    };
    EXPECT_LT(z(mis, light), 4) << mis.first << " vs " << light.first;
    EXPECT_LT(z(mis, bsdf), 4) << mis.first << " vs " << bsdf.first;
    EXPECT_LT(z(light, bsdf), 4) << light.first << " vs " << bsdf.first;
    // And MIS is the least noisy of the three.
    EXPECT_LT(mis.second, bsdf.second);
    std::printf("image mean: mis %.4f +- %.4f, light %.4f +- %.4f, bsdf %.4f +- %.4f\n", mis.first,
                mis.second, light.first, light.second, bsdf.first, bsdf.second);
}

// Relative mean squared error, (a - r)^2 / (r^2 + 0.01) averaged over pixels and channels: the
// light's edge pixels (radiance 17 beside 0) would otherwise decide a plain RMSE alone.
double rel_mse(const Film& a, const Film& ref) {
    double sum = 0;
    for (std::size_t i = 0; i < a.pixels().size(); ++i) {
        for (int k = 0; k < 3; ++k) {
            const double r = ref.pixels()[i][k], d = a.pixels()[i][k] - r;
            sum += d * d / (r * r + 0.01);
        }
    }
    return sum / (3.0 * static_cast<double>(a.pixels().size()));
}

// scenes/texture-filtering.yaml (a receding checker and image) at 96 x 54 and 1 spp: filtered, its
// error against the pixels' means (256 spp, box pixel filter, no texture filtering) is under the
// unfiltered error (EWA's under half; measured 0.17 of it), and the same bits for one thread or two (docs/textures.md has the full
// measurement, bench/texture_filtering.sh).
TEST(Path, FilteredTexturesAtOneSampleAreCloserToThePixelMean) {
    const auto job = [](std::optional<TextureFilter> f) {
        Overrides o;
        o.width = 96;
        o.height = 54;
        o.texture_filter = f;
        auto sources = std::make_shared<SourceFiles>();
        return build(load_scene_file(std::string(GLINT_SOURCE_DIR) + "/scenes/texture-filtering.yaml", sources), o,
                     sources);
    };
    const RenderJob none = job(TextureFilter::kBilinear), ewa = job(std::nullopt), tri = job(TextureFilter::kTrilinear);
    ASSERT_FALSE(none.scene.footprint.has_value());
    ASSERT_TRUE(ewa.scene.footprint.has_value());
    const Film ref = render_job(none, 256, 7);
    const double e_none = rel_mse(render_job(none, 1), ref), e_ewa = rel_mse(render_job(ewa, 1), ref),
                 e_tri = rel_mse(render_job(tri, 1), ref);
    EXPECT_LT(e_ewa, 0.5 * e_none);
    EXPECT_LT(e_tri, 0.75 * e_none);  // isotropic: blurs a grazing view more than EWA
    std::printf("relative MSE at 1 spp: none %.5f, trilinear %.5f, ewa %.5f\n", e_none, e_tri, e_ewa);
    // Threads do not change the bits.
    RenderOptions one = ewa.options, two = ewa.options;
    one.threads = 1;
    two.threads = 2;
    Film a(ewa.film_width, ewa.film_height), b(ewa.film_width, ewa.film_height);
    render(ewa.scene, ewa.camera, *ewa.integrator, one, a);
    render(ewa.scene, ewa.camera, *ewa.integrator, two, b);
    EXPECT_EQ(a.pixels(), b.pixels());
}

// An environment map of one-texel checks, w x h.
Image one_texel_checks(int w, int h) {
    Image checks{w, h, {}, {}};
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) checks.texels.push_back(Color{static_cast<float>((x + y) & 1)});
    return checks;
}

// The scene of `yaml` under environment map `map`, its textures read with `filter` (none: the
// scene's default, EWA).
RenderJob under_environment(const std::string& yaml, const Image& map, std::optional<TextureFilter> filter) {
    Overrides o;
    o.texture_filter = filter;
    auto sources = std::make_shared<SourceFiles>();
    RenderJob j = build(parse_scene(yaml, "env.yaml", sources), o, sources);
    j.scene.background = EnvironmentMap::make(map, 1);
    j.scene.commit();
    return j;
}

// Relative MSE at 1 spp of a job read unfiltered and filtered, against the unfiltered job's
// pixels' means (256 spp), printed under `what`.
std::pair<double, double> errors_at_1spp(const RenderJob& none, const RenderJob& filtered, const char* what) {
    const Film ref = render_job(none, 256, 7);
    const double e_none = rel_mse(render_job(none, 1), ref), e_filtered = rel_mse(render_job(filtered, 1), ref);
    std::printf("%s, relative MSE at 1 spp: unfiltered %.5f, filtered %.5f\n", what, e_none, e_filtered);
    return {e_none, e_filtered};
}

// An environment map of one-texel checks (1024 x 512), seen directly at about 2.7 texels per
// pixel: read over the pixel's angle (trilinear MIP), 1 spp is closer to the pixels' means (256
// spp, unfiltered) than one bilinear lookup per sample; a constant map reads its constant.
TEST(Path, TheEnvironmentSeenByTheCameraIsFilteredOverThePixel) {
    const Image checks = one_texel_checks(1024, 512);
    const auto job = [&](std::optional<TextureFilter> f) {
        return under_environment("camera: {type: look_at, from: [0, 0, 0], to: [0, 0.3, 1], fov: 40}\n"
                                 "film: {width: 64, height: 32}\nintegrator: {type: path, max_depth: 1}\n",
                                 checks, f);
    };
    const RenderJob none = job(TextureFilter::kBilinear), filtered = job(std::nullopt);
    ASSERT_FALSE(none.scene.footprint.has_value());
    ASSERT_TRUE(filtered.scene.footprint.has_value());
    const auto [e_none, e_filtered] = errors_at_1spp(none, filtered, "environment");
    EXPECT_LT(e_filtered, 0.5 * e_none);
    RenderJob flat = job(std::nullopt);
    flat.scene.background = EnvironmentMap::make(Image{8, 4, std::vector<Color>(32, Color{0.25f, 0.5f, 2}), {}}, 3);
    flat.scene.commit();
    for (const Vector3 d : {Vector3{0, 0, 1}, normalize(Vector3{1, 2, -3}), Vector3{0, 1, 0}}) {
        const Color c = flat.scene.background_seen(d);
        EXPECT_NEAR(c.r, 0.75f, 1e-5f);
        EXPECT_NEAR(c.b, 6, 1e-4f);
    }
}

// The same environment seen in a chrome ball that fills the view: the ball spreads each pixel
// over many times the angle a direct view covers, and the path's offset rays, reflected at the
// ball (integrators/differentials.h), carry that spread to the lookup. 1 spp, filtered, comes
// close to the pixels' means; read with a direct view's angle it stays nearly as far off as
// unfiltered.
TEST(Path, TheEnvironmentSeenInAChromeBallIsFilteredOverThePixel) {
    // Checks of one texel, each a bit over twice a pixel's angle in a direct view.
    const Image checks = one_texel_checks(256, 128);
    const auto job = [&](std::optional<TextureFilter> f) {
        return under_environment("camera: {type: look_at, from: [0, 0, -4], to: [0, 0, 0], fov: 30}\n"
                                 "film: {width: 48, height: 48}\nintegrator: {type: path, max_depth: 2}\n"
                                 "materials: {chrome: {type: conductor, reflectance: [1, 1, 1]}}\n"
                                 "objects: [{type: sphere, center: [0, 0, 0], radius: 1, material: chrome}]\n",
                                 checks, f);
    };
    const auto [e_none, e_filtered] =
        errors_at_1spp(job(TextureFilter::kBilinear), job(std::nullopt), "environment in a chrome ball");
    EXPECT_LT(e_filtered, 0.2 * e_none);
}

// A checker floor seen in a flat mirror: the footprint there is the mirror-image camera's, which
// the path's offset rays carry (the camera's direct-view model takes the floor as nearer than it
// is and filters too little). The floor is lit by a uniform sky, found by cosine-weighted BSDF
// samples, so each pixel's only noise is where its samples fall; the mirror is small and far
// from the floor it shows, so that the floor hardly sees it.
TEST(Path, AFloorSeenInAMirrorIsFilteredOverThePixel) {
    const auto job = [&](std::optional<TextureFilter> f) {
        Overrides o;
        o.texture_filter = f;
        auto sources = std::make_shared<SourceFiles>();
        return build(parse_scene("camera: {type: look_at, from: [0, 6, 0], to: [0, 6, 1], fov: 20}\n"
                                 "film: {width: 64, height: 48}\n"
                                 "integrator: {type: path, max_depth: 2, strategy: bsdf}\n"
                                 "background: {type: constant, color: [1, 1, 1]}\n"
                                 "materials:\n  chrome: {type: conductor, reflectance: [1, 1, 1]}\n"
                                 "  floor: {type: diffuse, albedo: {type: checker, size: 0.25, even: [0.9, 0.9, 0.9], "
                                 "odd: [0.1, 0.1, 0.1]}}\n"
                                 "objects:\n  - {type: quad, corner: [-1, 5, 2], edge1: [2, 0, 0], edge2: [0, 2, -1.2], "
                                 "material: chrome}\n"
                                 "  - {type: quad, corner: [-100, 0, -100], edge1: [0, 0, 200], edge2: [200, 0, 0], "
                                 "material: floor}\n",
                                 "mirror.yaml", sources),
                     o, sources);
    };
    const auto [e_none, e_filtered] =
        errors_at_1spp(job(TextureFilter::kBilinear), job(std::nullopt), "checker floor in a mirror");
    EXPECT_LT(e_filtered, 0.25 * e_none);
}

// scenes/cornell-box.yaml at 32 x 32.
RenderJob cornell_box_32() {
    Overrides o;
    o.width = 32;
    o.height = 32;
    auto sources = std::make_shared<SourceFiles>();
    return build(
        load_scene_file(std::string(GLINT_SOURCE_DIR) + "/scenes/cornell-box.yaml", sources), o,
        sources);
}

TEST(Path, CornellBoxErrorFallsAsOneOverSqrtSpp) {
    RenderJob job = cornell_box_32();
    job.options.sampler = SamplerType::kIndependent;  // the textbook rate; Sobol does better
    // Under the sanitizers half the work: a reference of 2048 spp, whose own noise adds 1.5 % to
    // the error at 64 spp (the slope moves by about 0.01). Fewer spp do not do: at 1 spp the error
    // is not yet in its 1 / sqrt(spp) regime.
    const Film reference = render_job(job, testing::kSanitized ? 2048 : 4096, 999);
    // The error at each spp: the root of the relative MSE, averaged over four seeds.
    const std::vector<double> spps{4, 16, 64};
    std::vector<double> errors;
    for (double spp : spps) {
        double mse = 0;
        for (std::uint64_t seed = 1; seed <= 4; ++seed)
            mse += rel_mse(render_job(job, static_cast<int>(spp), seed), reference) / 4;
        errors.push_back(std::sqrt(mse));
    }
    // Least-squares slope of log error against log spp.
    double mx = 0, my = 0, sxx = 0, sxy = 0;
    for (std::size_t i = 0; i < spps.size(); ++i) mx += std::log(spps[i]), my += std::log(errors[i]);
    mx /= 3, my /= 3;
    for (std::size_t i = 0; i < spps.size(); ++i) {
        sxx += (std::log(spps[i]) - mx) * (std::log(spps[i]) - mx);
        sxy += (std::log(spps[i]) - mx) * (std::log(errors[i]) - my);
    }
    const double slope = sxy / sxx;
    std::printf("relative rmse at 4/16/64 spp: %.4f %.4f %.4f, slope %.3f\n", errors[0], errors[1], errors[2],
                slope);
    EXPECT_NEAR(slope, -0.5, 0.08);
}

}  // namespace
}  // namespace glint

namespace glint {
namespace {

// Closed forms for the delta lights: a white diffuse floor of albedo a at distance h straight
// below a point light of intensity I reflects a I / (pi h^2) towards a camera above it; under a
// spot light the same, times the falloff (1 inside the inner cone, 0 outside the outer one).
TEST(Path, PointAndSpotLightsMatchClosedForms) {
    const auto centre = [](const std::string& light) {
        const RenderJob job = job_from(R"(
camera: {type: look_at, from: [0, 1, 0.001], to: [0, 0, 0], fov: 1}
film: {width: 1, height: 1}
integrator: {type: path, max_depth: 1}
background: {type: constant, color: [0, 0, 0]}
lights: [)" + light + R"(]
objects:
  - {type: quad, corner: [-5, 0, -5], edge1: [0, 0, 10], edge2: [10, 0, 0], material: {type: diffuse, albedo: 0.5}}
)");
        return render_job(job, 1).at(0, 0).g;
    };
    const float expected = 0.5f * 8 / (3.14159265f * 4);
    EXPECT_NEAR(centre("{type: point, position: [0, 2, 0], intensity: [8, 8, 8]}"), expected, 1e-4f);
    EXPECT_NEAR(centre("{type: spot, position: [0, 2, 0], direction: [0, -1, 0], intensity: [8, 8, 8]}"),
                expected, 1e-4f);
    EXPECT_EQ(centre("{type: spot, position: [0, 2, 0], direction: [1, 0, 0], intensity: [8, 8, 8]}"), 0);
}

// The Cornell data is right-handed: with `handedness: right` its red wall (x = 550) is on the
// image's left and the green wall (x = 0) on its right.
TEST(Path, CornellBoxRedWallIsOnTheLeft) {
    RenderJob job = cornell_box_32();
    job.integrator = std::make_unique<FlatIntegrator>();
    const Film film = render_job(job, 1);
    const Color left = film.at(2, 16), right = film.at(29, 16);
    EXPECT_GT(left.r, 5 * left.g) << "left wall";
    EXPECT_GT(right.g, 2 * right.r) << "right wall";
}

}  // namespace
}  // namespace glint

namespace glint {
namespace {

// The denoiser's features through smooth glass are those of the surface seen through it: a
// checker floor (albedo 0.1 | 0.9) under a sheet of glass that fills the view shows both albedos
// in the albedo AOV, not the glass's one colour, so the checker's edges guide the filter.
TEST(Path, FeaturesThroughSmoothGlassAreThoseOfTheSurfaceBehind) {
    const RenderJob job = job_from(R"(
camera: {type: look_at, from: [0, 4, 0], to: [0, 0, 0], up: [0, 0, 1], fov: 60}
film: {width: 32, height: 32}
integrator: {type: path, max_depth: 8}
background: {type: constant, color: [1, 1, 1]}
materials:
  floor: {type: diffuse, albedo: {type: checker, size: 1, even: [0.9, 0.9, 0.9], odd: [0.1, 0.1, 0.1]}}
  glass: {type: dielectric, ior: 1.5}
objects:
  - {type: quad, corner: [-10, 0, -10], edge1: [0, 0, 20], edge2: [20, 0, 0], material: floor}
  - {type: quad, corner: [-10, 2, -10], edge1: [0, 0, 20], edge2: [20, 0, 0], material: glass}
)");
    Film film(job.film_width, job.film_height);
    film.enable_aovs();
    RenderOptions o = job.options;
    o.spp = 16;
    render(job.scene, job.camera, *job.integrator, o, film);
    int dark = 0, light = 0;
    for (const Color& a : film.albedo()) {
        dark += a.r < 0.3f ? 1 : 0;
        light += a.r > 0.6f ? 1 : 0;
    }
    const int n = job.film_width * job.film_height;
    EXPECT_GT(dark, n / 5) << dark << " dark, " << light << " light of " << n;
    EXPECT_GT(light, n / 5) << dark << " dark, " << light << " light of " << n;
    // Depth is the distance travelled to the floor: past the glass at 2, more than 4.
    for (const float z : film.depth()) EXPECT_GT(z, 4.0f);
}

}  // namespace
}  // namespace glint
