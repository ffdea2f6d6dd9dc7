// Spectral rendering (issue 36) against independent values: the CIE tables' published sums,
// D65's chromaticity, Planck's and Stefan-Boltzmann's laws, Schott's catalogue indices of BK7,
// RGB round trips through the upsampling (and the scene's constant colours, upsampled once, against
// the scalar sigmoid), the sampled wavelengths' density, and through the path tracer: white
// furnaces, a gold mirror against the closed-form Fresnel integrated over the spectrum, two lamps
// of different colours against RGB mode, the bits for one thread and two, and the RGB mode left
// as it was.
#include "glint/spectra/spectrum.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>

#include "glint/builder/build.h"
#include "glint/formats/pbrt.h"
#include "glint/formats/scene_writer.h"
#include "glint/formats/scene_yaml.h"
#include "glint/materials/bsdf.h"
#include "glint/materials/fresnel.h"
#include "glint/render/render.h"
#include "glint/spectra/rgb_spectrum.h"

namespace glint {
namespace {

float max_error(Color a, Color b) {
    return std::max({std::abs(a.r - b.r), std::abs(a.g - b.g), std::abs(a.b - b.b)});
}

TEST(Spectra, CieTablesIntegrateToThePublishedSums) {
    // The CIE 1931 2-degree functions at 1 nm over 360-830 nm: y-bar sums to 106.857, and x-bar
    // and z-bar to the same within the table's rounding (equal energy is x = y = 1/3).
    double x = 0, y = 0, z = 0;
    for (int l = 360; l <= 830; ++l) {
        const Xyz c = cie_xyz(float(l));
        x += c.x, y += c.y, z += c.z;
    }
    EXPECT_NEAR(y, 106.857, 0.01);
    EXPECT_NEAR(cie_y_integral(), 106.857, 0.01);
    EXPECT_NEAR(x / y, 1, 5e-4);
    EXPECT_NEAR(z / y, 1, 5e-4);
    EXPECT_NEAR(cie_xyz(555).y, 1.0, 1e-4);  // y-bar peaks at 1 at 555 nm
}

TEST(Spectra, D65HasItsWhitePointAndImagesAsWhite) {
    const Xyz w = spectrum_to_xyz(d65());
    EXPECT_NEAR(w.y, 1, 1e-5);  // normalised to Y = 1
    const double s = w.x + w.y + w.z;
    EXPECT_NEAR(w.x / s, 0.31272, 2e-4);  // CIE 15: x = 0.31272, y = 0.32903
    EXPECT_NEAR(w.y / s, 0.32903, 2e-4);
    EXPECT_LT(max_error(xyz_to_linear_srgb(w), Color{1}), 1e-3f);
}

TEST(Spectra, BlackbodyFollowsPlanckAndStefanBoltzmann) {
    // Planck at 5000 K and 500 nm, by hand: 2hc^2 / l^5 / (exp(hc / (l k T)) - 1) = 1.2107e13 W/(m^2 sr m).
    EXPECT_NEAR(planck(500, 5000) / 1.2107e13, 1, 1e-3);
    // pi times the radiance over all wavelengths is sigma T^4 (5.670374e-8 W m^-2 K^-4).
    for (const float t : {3000.0f, 6500.0f}) {
        double sum = 0;
        for (double l = 50; l < 100000; l += 0.5) sum += planck(float(l), t) * 0.5e-9;
        EXPECT_NEAR(std::numbers::pi * sum / (5.670374e-8 * std::pow(t, 4.0)), 1, 2e-3) << t;
    }
    // Normalised: 1 at Wien's peak (2897.77 um K / T), less on either side.
    EXPECT_NEAR(blackbody_normalised(2897.7721f / 5.0f, 5000), 1, 1e-5);
    EXPECT_LT(blackbody_normalised(500, 5000), 1);
    EXPECT_LT(blackbody_normalised(700, 5000), 1);
    EXPECT_EQ(blackbody_normalised(500, 0), 0);
}

TEST(Spectra, SellmeierGivesTheCatalogueIndicesOfBk7) {
    // Schott N-BK7: B = 1.03961212, 0.231792344, 1.01046945; C = 0.00600069867, 0.0200179144,
    // 103.560653 um^2. Catalogue: n_d (587.56) = 1.5168, n_F (486.13) = 1.52238, n_C (656.27) = 1.51432.
    const float b[3] = {1.03961212f, 0.231792344f, 1.01046945f}, c[3] = {0.00600069867f, 0.0200179144f, 103.560653f};
    const Spectrum bk7 = Spectrum::sellmeier(b, c);
    EXPECT_NEAR(bk7(587.56f), 1.5168, 1e-4);
    EXPECT_NEAR(bk7(486.13f), 1.52238, 1e-4);
    EXPECT_NEAR(bk7(656.27f), 1.51432, 1e-4);
    EXPECT_FALSE(bk7.constant());
    // pbrt-v4's tabulated BK7 agrees with the formula.
    EXPECT_NEAR((*named_spectrum("glass-BK7"))(587.56f), 1.5168, 5e-4);
    // Cauchy through n_d and the Abbe number gives them back.
    const Spectrum cauchy = Spectrum::from_abbe(1.5168f, 64.17f);
    EXPECT_NEAR(cauchy(587.56f), 1.5168, 1e-5);
    EXPECT_NEAR((1.5168 - 1) / (cauchy(486.13f) - cauchy(656.27f)), 64.17, 0.01);
}

TEST(Spectra, PrismDeviationFollowsSnellAtEachWavelength) {
    // A 45-degree prism of F11 glass, a ray in at 50 degrees: each wavelength's index through the
    // glass lobe twice (in at the first face, out at the second) against the closed form
    // delta = theta1 + asin(n sin(A - asin(sin theta1 / n))) - A. Blue bends more than red.
    const Spectrum glass = Spectrum::tabulated(*named_spectrum("glass-F11"));
    const float apex = 45 * std::numbers::pi_v<float> / 180, theta1 = 50 * std::numbers::pi_v<float> / 180;
    float previous = 0;
    for (const float lambda : {450.0f, 500.0f, 550.0f, 600.0f, 650.0f}) {
        const float n = glass(lambda);
        DielectricLobe lobe;
        lobe.eta = n;
        // First face (normal +z): the incoming direction's reverse is wo.
        const Vector3 wo1{std::sin(theta1), 0, std::cos(theta1)};
        auto s1 = lobe.sample(wo1, 0.999f, {0.5f, 0.5f});  // uc near 1: the refracted branch
        ASSERT_TRUE(s1 && s1->wi.z < 0) << lambda;
        const float inside = std::atan2(-s1->wi.x, -s1->wi.z);  // angle from -z, in the xz plane
        // Second face, tilted by the apex angle; inside the glass the lobe sees index 1 / n from
        // the other side: wo is the reverse of the ray, in the face's frame (normal pointing out).
        const float incidence2 = apex - std::abs(inside);
        const Vector3 wo2{std::sin(incidence2), 0, -std::cos(incidence2)};  // below the face: inside
        auto s2 = lobe.sample(wo2, 0.999f, {0.5f, 0.5f});
        ASSERT_TRUE(s2 && s2->wi.z > 0) << lambda;
        const float theta2 = std::atan2(std::abs(s2->wi.x), s2->wi.z);
        const float deviation = theta1 + theta2 - apex;
        const float closed = theta1 + std::asin(n * std::sin(apex - std::asin(std::sin(theta1) / n))) - apex;
        EXPECT_NEAR(deviation, closed, 1e-4f) << lambda;
        if (previous > 0) EXPECT_LT(deviation, previous) << lambda;  // longer waves bend less
        previous = deviation;
    }
}

TEST(Spectra, UpsampledReflectancesComeBackAsTheirRgb) {
    // Every colour of a 0.1 grid over the sRGB cube, lit by D65 and integrated at 1 nm.
    int inner = 0;
    float worst_inner = 0, worst = 0;
    for (int r = 0; r <= 10; ++r)
        for (int g = 0; g <= 10; ++g)
            for (int b = 0; b <= 10; ++b) {
                const Color rgb{r / 10.0f, g / 10.0f, b / 10.0f};
                const RgbSigmoid s = rgb_sigmoid(rgb);
                const Color back = xyz_to_linear_srgb(spectrum_to_xyz([&](float l) { return s(l) * d65()(l); }));
                const float e = max_error(back, rgb);
                worst = std::max(worst, e);
                if (std::max({rgb.r, rgb.g, rgb.b}) <= 0.9f) worst_inner = std::max(worst_inner, e), ++inner;
                for (float l = 360; l <= 830; l += 10) ASSERT_TRUE(s(l) >= 0 && s(l) <= 1);
            }
    EXPECT_EQ(inner, 1000);
    EXPECT_LT(worst, 1e-3f);
    // Between the grid's colours: random ones, where the table's interpolation errs most (near
    // white and near the saturated edges; docs/spectral.md).
    int over = 0;
    float worst_random = 0;
    constexpr int kRandom = 4000;
    for (int i = 0; i < kRandom; ++i) {
        const auto u = [&](int c) { return float((std::uint64_t(i) * 2654435761u * (c + 1) + 12345u * c) % 100003u) / 100003.0f; };
        const Color rgb{u(0), u(1), u(2)};
        const RgbSigmoid s = rgb_sigmoid(rgb);
        const float e = max_error(xyz_to_linear_srgb(spectrum_to_xyz([&](float l) { return s(l) * d65()(l); })), rgb);
        worst_random = std::max(worst_random, e);
        over += e > 1e-3f;
    }
    EXPECT_LT(over, kRandom / 200);  // under 0.5 % of colours beyond 1e-3
    EXPECT_LT(worst_random, 7e-3f);
    std::printf("round trip: grid worst %.2e; random: worst %.2e, %d of %d beyond 1e-3\n", worst, worst_random, over,
                kRandom);
}

TEST(Spectra, WavelengthsAreDrawnByTheirDensity) {
    // The density integrates to 1; the three wavelengths of one draw are spread a third apart in
    // the CDF; a histogram of many draws follows the density.
    double integral = 0;
    for (double l = 360; l < 830; l += 0.01) integral += visible_wavelength_pdf(float(l + 0.005)) * 0.01;
    EXPECT_NEAR(integral, 1, 1e-4);
    constexpr int kBins = 47, kDraws = 30000;
    std::vector<double> hist(kBins, 0);
    for (int i = 0; i < kDraws; ++i) {
        const Wavelengths wl = sample_wavelengths((i + 0.5f) / kDraws);
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(wl.pdf[c], visible_wavelength_pdf(wl.lambda[c]), 1e-6f);
            hist[std::min(kBins - 1, int((wl.lambda[c] - 360) / 10))] += 1.0 / (3.0 * kDraws);
        }
    }
    for (int b = 0; b < kBins; ++b) {
        double p = 0;
        for (double l = 360 + 10 * b; l < 370 + 10 * b; l += 0.01) p += visible_wavelength_pdf(float(l + 0.005)) * 0.01;
        EXPECT_NEAR(hist[b], p, 2e-4) << b;
    }
}

TEST(Spectra, TheFilmEstimateOfAnIlluminantIsItsColour) {
    // Radiance of an RGB illuminant at sampled wavelengths, through film_rgb, averages to the RGB.
    for (const Color rgb : {Color{1, 1, 1}, Color{0.8f, 0.3f, 0.1f}, Color{0.05f, 0.2f, 0.9f}}) {
        Color sum{0};
        constexpr int n = 20000;
        for (int i = 0; i < n; ++i) {
            const Wavelengths wl = sample_wavelengths((i + 0.5f) / n);
            sum += film_rgb(upsample_illuminant(rgb, wl), wl);
        }
        EXPECT_LT(max_error(sum / n, rgb), 2e-3f) << rgb.r << " " << rgb.g << " " << rgb.b;
    }
    // After a dispersive event the hero alone carries the estimate: still unbiased.
    Color sum{0};
    constexpr int n = 20000;
    for (int i = 0; i < n; ++i) {
        Wavelengths wl = sample_wavelengths((i + 0.5f) / n);
        terminate_secondary(wl);
        sum += film_rgb(d65().at(wl), wl);
    }
    EXPECT_LT(max_error(sum / n, Color{1}), 5e-3f);
    // An emitter's spectrum: the colour added for it when the camera sees it directly
    // (film_colour) is the expectation of the estimate it replaces.
    for (const Spectrum& e : {Spectrum::blackbody(3000).normalised_emission(),
                              Spectrum::tabulated(*named_spectrum("stdillum-F4")).normalised_emission(),
                              Spectrum::tabulated(PiecewiseLinearSpectrum({400, 700}, {1, 3})).normalised_emission()}) {
        Color mc{0};
        for (int i = 0; i < n; ++i) {
            const Wavelengths wl = sample_wavelengths((i + 0.5f) / n);
            mc += film_rgb(e.at(wl), wl);
        }
        const Color exact = e.film_colour();
        EXPECT_LT(max_error(mc / n, exact), 3e-3f * exact.max_component())
            << mc.r / n << " " << mc.g / n << " " << mc.b / n << " vs " << exact.r << " " << exact.g << " " << exact.b;
        EXPECT_NEAR(luminance(exact), 1, 1e-3);
    }
    // A narrow band at 600 nm is out of the sRGB gamut (its blue is negative); as an emitter's
    // RGB stand-in it is clipped to the gamut and keeps luminance 1.
    const Spectrum band = Spectrum::tabulated(PiecewiseLinearSpectrum({590, 600, 610}, {0, 1, 0})).normalised_emission();
    EXPECT_LT(band.film_colour().b, -0.01f);
    const Color stand_in = band.emission_rgb();
    EXPECT_GE(std::min({stand_in.r, stand_in.g, stand_in.b}), 0.0f);
    EXPECT_NEAR(luminance(stand_in), 1, 1e-5);
}

TEST(Spectra, WhiteBalanceAdaptsADaylightWhiteToD65) {
    // The daylight whites against CIE 15's published chromaticities of D50 and D65 (their CCTs on
    // the old c2, 5000 and 6500 K), and against the D65 table: the same point within 5e-4. (pbrt-v4's
    // "stdillum-D50" table is not a check: its chromaticity is (0.3368, 0.3580), not D50's.)
    const auto xy = [](Xyz c) { return std::pair{c.x / (c.x + c.y + c.z), c.y / (c.x + c.y + c.z)}; };
    const auto [x50, y50] = xy(daylight_white(5000));
    EXPECT_NEAR(x50, 0.3457, 5e-4);
    EXPECT_NEAR(y50, 0.3585, 5e-4);
    const auto [x65, y65] = xy(daylight_white(6500));
    EXPECT_NEAR(x65, 0.3127, 5e-4);
    EXPECT_NEAR(y65, 0.3290, 5e-4);
    const auto [xt, yt] = xy(spectrum_to_xyz(d65()));
    EXPECT_NEAR(x65, xt, 5e-4);
    EXPECT_NEAR(y65, yt, 5e-4);
    // White balance for 6500 K is nearly nothing; for 5000 K and 3000 K (a black body) the white
    // of that temperature becomes grey.
    const ColorMatrix none = white_balance(6500);
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) EXPECT_NEAR(none.m[i][j], i == j ? 1 : 0, 3e-3) << i << j;
    for (const float t : {5000.0f, 3000.0f}) {
        const Color d50 = white_balance(t)(xyz_to_linear_srgb(daylight_white(t)));
        EXPECT_LT(max_error(d50 / d50.g, Color{1}), 1e-4f) << t << ": " << d50.r << " " << d50.g << " " << d50.b;
    }
}

// --- Through the path tracer --------------------------------------------------------------

RenderJob job_from(const std::string& yaml, Overrides o = {}) {
    auto sources = std::make_shared<SourceFiles>();
    return build(parse_scene(yaml, "scene.yaml", sources), o, sources);
}

Film render_job(const RenderJob& job, int spp, int threads = 0) {
    Film film(job.film_width, job.film_height);
    RenderOptions o = job.options;
    o.spp = spp;
    if (threads > 0) o.threads = threads;
    render(job.scene, job.camera, *job.integrator, o, film);
    return film;
}

std::string furnace(const std::string& material, int size = 24) {
    return "camera: {type: look_at, from: [0, 0, -3], to: [0, 0, 0], fov: 45}\n"
           "film: {width: " + std::to_string(size) + ", height: " + std::to_string(size) + "}\n"
           "integrator: {type: path, max_depth: 64, spectral: true}\n"
           "background: {type: constant, color: [1, 1, 1]}\n"
           "objects:\n  - {type: sphere, center: [0, 0, 0], radius: 1, material: " + material + "}\n";
}

Color mean(const Film& film) {
    Color sum{0};
    for (const Color& c : film.pixels()) sum += c;
    return sum / float(film.pixels().size());
}

TEST(Spectra, WhiteFurnacesReturnOneInSpectralMode) {
    // Lossless materials in a white (D65) sky: every pixel's mean is white. Dispersive glass too,
    // and a smooth coat over a white base and a scattering, non-absorbing slab (light leaves
    // again after however many passes).
    for (const char* m : {"{type: diffuse, albedo: 1}", "{type: dielectric, ior: glass-F11}",
                          "{type: dielectric, ior: 1.5, abbe: 20}",
                          "{type: pbr, base_color: 1, metallic: 0, roughness: 0, transmission: 1, ior: glass-F11}",
                          "{type: conductor, reflectance: 1, roughness: 0.5}",
                          "{type: diffuse_transmission, reflectance: 0.5, transmittance: 0.5}",
                          "{type: coated_diffuse, albedo: 1, ior: 1.5, thickness: 0.5, layer_albedo: [1, 1, 1], max_depth: 1000}"}) {
        const Color c = mean(render_job(job_from(furnace(m)), 64));
        EXPECT_LT(max_error(c, Color{1}), 0.01f) << m << ": " << c.r << " " << c.g << " " << c.b;
    }
}

TEST(Spectra, GoldMirrorReflectsTheFresnelOfItsMeasuredIndex) {
    // A smooth gold sphere in a D65 sky, seen at the centre (normal incidence): the pixel is the
    // colour of R(lambda) D65(lambda), R = ((n-1)^2 + k^2) / ((n+1)^2 + k^2) from the tables.
    const PiecewiseLinearSpectrum& n = *named_spectrum("metal-Au-eta");
    const PiecewiseLinearSpectrum& k = *named_spectrum("metal-Au-k");
    const Color expected = xyz_to_linear_srgb(spectrum_to_xyz([&](float l) {
        const double a = n(l), b = k(l);
        return float(((a - 1) * (a - 1) + b * b) / ((a + 1) * (a + 1) + b * b)) * d65()(l);
    }));
    const std::string scene = "camera: {type: look_at, from: [0, 0, -30], to: [0, 0, 0], fov: 0.5}\n"
                              "film: {width: 4, height: 4}\n"
                              "integrator: {type: path, max_depth: 4, spectral: true}\n"
                              "background: {type: constant, color: [1, 1, 1]}\n"
                              "objects:\n  - {type: sphere, center: [0, 0, 0], radius: 1, material: {type: conductor, metal: gold}}\n";
    const Color c = mean(render_job(job_from(scene), 4096));
    EXPECT_LT(max_error(c, expected), 0.01f) << c.r << " " << c.g << " " << c.b << " vs " << expected.r << " "
                                             << expected.g << " " << expected.b;
    // RGB mode's three-sample index gives a visibly different gold.
    Overrides rgb;
    rgb.spectral = false;
    const Color c_rgb = mean(render_job(job_from(scene, rgb), 16));
    EXPECT_GT(max_error(c_rgb, expected), 0.01f);
}

TEST(Spectra, MediaAbsorbByWavelength) {
    // A sphere of absorbing medium behind an interface (no refraction), radius 1, seen through its
    // centre against a white sky: a grey sigma_a of 0.5 leaves exp(-1) at every wavelength; a
    // coloured one leaves, per channel, the colour of exp(-2 sigma_a(lambda)) D65(lambda), with
    // sigma_a(lambda) the upsampled spectrum, integrated here at 1 nm.
    const auto scene = [](const char* sigma_a) {
        return std::string("camera: {type: look_at, from: [0, 0, -30], to: [0, 0, 0], fov: 0.05}\n"
                           "film: {width: 4, height: 4}\n"
                           "integrator: {type: path, max_depth: 8, spectral: true}\n"
                           "background: {type: constant, color: [1, 1, 1]}\n"
                           "media:\n  ink: {type: homogeneous, sigma_a: ") +
               sigma_a + ", sigma_s: [0, 0, 0]}\n"
                         "objects:\n  - {type: sphere, center: [0, 0, 0], radius: 1, material: {type: interface}, "
                         "interior: ink}\n";
    };
    const Color grey = mean(render_job(job_from(scene("[0.5, 0.5, 0.5]")), 64));
    EXPECT_LT(max_error(grey, Color{std::exp(-1.0f)}), 3e-3f) << grey.r << " " << grey.g << " " << grey.b;
    const Color sigma{0.9f, 0.3f, 0.1f};
    const Color expected = xyz_to_linear_srgb(spectrum_to_xyz([&](float l) {
        Wavelengths one;
        one.lambda[0] = one.lambda[1] = one.lambda[2] = l;
        return std::exp(-2 * upsample_unbounded(sigma, one).r) * d65()(l);
    }));
    const Color c = mean(render_job(job_from(scene("[0.9, 0.3, 0.1]")), 1024));
    EXPECT_LT(max_error(c, expected), 0.01f) << c.r << " " << c.g << " " << c.b << " vs " << expected.r << " "
                                             << expected.g << " " << expected.b;
}

TEST(Spectra, ConstantColoursAreUpsampledOnceAtCommit) {
    // The scene keeps each constant texture's upsampling (Scene::commit); read at any
    // wavelengths it is the scalar sigmoid of the colour's coefficients (rgb_spectrum_model.h's
    // formula, not the SIMD one), a grey its clamped value, and other textures have none.
    const RenderJob job = job_from(
        "camera: {type: look_at, from: [0, 0, -3], to: [0, 0, 0], fov: 45}\n"
        "film: {width: 4, height: 4}\n"
        "integrator: {type: path, spectral: true}\n"
        "objects:\n"
        "  - {type: sphere, center: [-1, 0, 0], radius: 0.5, material: {type: diffuse, albedo: [0.63, 0.065, 0.05]}}\n"
        "  - {type: sphere, center: [1, 0, 0], radius: 0.5, material: {type: diffuse, albedo: [1.5, 1.5, 1.5]}}\n"
        "  - {type: sphere, center: [0, 1, 0], radius: 0.5, material: {type: diffuse, albedo: {type: checker, "
        "even: [0.1, 0.2, 0.3], odd: [0.9, 0.9, 0.9]}}}\n");
    const Scene& scene = job.scene;
    int colours = 0, greys = 0, others = 0;
    for (TextureId id = 0; id < scene.textures.size(); ++id) {
        const RgbReflectance* r = scene.texture_reflectance(id);
        const auto* c = std::get_if<ConstantTexture>(&scene.textures[id]);
        if (!c) {
            EXPECT_EQ(r, nullptr);
            ++others;
            continue;
        }
        ASSERT_NE(r, nullptr);
        const bool grey = c->value.r == c->value.g && c->value.g == c->value.b;
        (grey ? greys : colours) += 1;
        const RgbSigmoid sigmoid = rgb_sigmoid(c->value);
        for (float u : {0.05f, 0.4f, 0.77f}) {
            const Wavelengths wl = sample_wavelengths(u);
            const Color v = r->at(wl);
            for (int i = 0; i < 3; ++i) {
                const float expected = grey ? std::clamp(c->value.r, 0.0f, 1.0f) : sigmoid(wl.lambda[i]);
                EXPECT_NEAR(v[i], expected, 1e-6f) << id << " at " << wl.lambda[i] << " nm";
            }
        }
    }
    EXPECT_GE(colours, 1);
    EXPECT_GE(greys, 1);
    EXPECT_GE(others, 1);
}

TEST(Spectra, AnIlluminantMadeReadyOnceIsItsFormula) {
    // A light's RGB made ready once (the path tracer keeps one per thread) and read at many
    // wavelengths: m = 2 max(rgb), m times the scalar sigmoid of rgb / m, times D65 (the
    // formula in rgb_spectrum.h, evaluated here by the scalar model); nothing for a light with
    // no positive channel; a grey is flat before D65.
    for (const Color rgb : {Color{17, 12, 4}, Color{0.8f, 0.3f, 0.1f}, Color{2, 2, 2}, Color{0, 0, 0},
                            Color{-1, 0, 0}, Color{-1, 3, 0.5f}}) {
        const RgbIlluminant ready(rgb);
        const float m = 2 * std::max({rgb.r, rgb.g, rgb.b});
        const Color shape = m > 0 ? rgb / m : Color{0};
        const bool grey = shape.r == shape.g && shape.g == shape.b;
        const RgbSigmoid sigmoid = rgb_sigmoid(shape);
        for (float u : {0.01f, 0.3f, 0.5f, 0.93f}) {
            const Wavelengths wl = sample_wavelengths(u);
            const Color v = ready.at(wl);
            for (int i = 0; i < 3; ++i) {
                const float l = wl.lambda[i];
                const float s = grey ? std::clamp(shape.r, 0.0f, 1.0f) : sigmoid(l);
                const float expected = m > 0 ? m * s * d65()(l) : 0.0f;
                EXPECT_NEAR(v[i], expected, 1e-5f * std::max(1.0f, expected))
                    << rgb.r << " " << rgb.g << " " << rgb.b << " at " << l;
            }
            EXPECT_EQ(v, upsample_illuminant(rgb, wl));
        }
    }
}

TEST(Spectra, TwoLightsOfDifferentColoursKeepTheirColours) {
    // A grey floor lit by a red and a blue sphere: paths sample one light and meet the other
    // (the path tracer keeps the last RGB emitter's upsampling). The spectral image's mean is
    // the RGB mode's (a grey reflectance times an upsampled illuminant images as the light's
    // colour, within the round trip's 1e-3), within the two renders' noise.
    const std::string scene = "camera: {type: look_at, from: [0, 3, -4], to: [0, 0, 0], fov: 40}\n"
                              "film: {width: 8, height: 8}\n"
                              "integrator: {type: path, max_depth: 4, spectral: true}\n"
                              "objects:\n"
                              "  - {type: plane, point: [0, 0, 0], normal: [0, 1, 0], material: {type: diffuse, albedo: 0.5}}\n"
                              "  - {type: sphere, center: [-1, 1, 0], radius: 0.4, material: {type: diffuse, albedo: 0, "
                              "emission: [4, 0.2, 0.1]}}\n"
                              "  - {type: sphere, center: [1, 1, 0], radius: 0.4, material: {type: diffuse, albedo: 0, "
                              "emission: [0.1, 0.3, 4]}}\n";
    Overrides rgb;
    rgb.spectral = false;
    const Color spectral = mean(render_job(job_from(scene), 1024));
    const Color reference = mean(render_job(job_from(scene, rgb), 1024));
    for (int i = 0; i < 3; ++i)
        EXPECT_NEAR(spectral[i], reference[i], 0.01f * reference.max_component())
            << "channel " << i << ": " << spectral.r << " " << spectral.g << " " << spectral.b << " vs " << reference.r
            << " " << reference.g << " " << reference.b;
    std::printf("two lights: spectral %.4f %.4f %.4f, rgb %.4f %.4f %.4f\n", spectral.r, spectral.g, spectral.b,
                reference.r, reference.g, reference.b);
}

TEST(Spectra, OneThreadOrTwoGiveTheSameBits) {
    const RenderJob job = job_from(furnace("{type: dielectric, ior: glass-F11}", 16));
    EXPECT_EQ(render_job(job, 8, 1).pixels(), render_job(job, 8, 2).pixels());
}

TEST(Spectra, LightsSeenDirectlyHaveNoColourNoise) {
    // An RGB emitter and a sky filling the view, one sample per pixel: spectral mode records the
    // expectation over the wavelengths, the colour itself (within the upsampling's round trip),
    // so every pixel is the same; seen in a mirror (one bounce), it is estimated and noisy.
    const std::string head = "camera: {type: look_at, from: [0, 0, -3], to: [0, 0, 0], fov: 10}\n"
                             "film: {width: 8, height: 8}\n"
                             "integrator: {type: path, max_depth: 4, spectral: true}\n";
    const Color colour{3, 1.5f, 0.25f};
    for (const std::string& scene :
         {head + "background: {type: constant, color: [0, 0, 0]}\nobjects:\n  - {type: sphere, center: [0, 0, 0], "
                 "radius: 1, material: {type: diffuse, albedo: 0, emission: [3, 1.5, 0.25]}}\n",
          head + "background: {type: constant, color: [3, 1.5, 0.25]}\n"}) {
        const Film film = render_job(job_from(scene), 1);
        for (const Color& c : film.pixels())
            ASSERT_LT(max_error(c, colour), 2e-3f * 3) << scene << c.r << " " << c.g << " " << c.b;
    }
    const Film mirror = render_job(job_from(head + "background: {type: constant, color: [3, 1.5, 0.25]}\nobjects:\n"
                                                   "  - {type: sphere, center: [0, 0, 0], radius: 1, material: "
                                                   "{type: conductor, reflectance: 1, roughness: 0}}\n"),
                                   1);
    float spread = 0;
    for (const Color& c : mirror.pixels()) spread = std::max(spread, max_error(c, mirror.pixels().front()));
    EXPECT_GT(spread, 0.05f);
}

TEST(Spectra, EmittersGivenAsSpectraImageAsTheirColour) {
    // An emitting sphere filling the view, of strength 2 (luminance) and a black body's or
    // illuminant A's spectrum: spectral mode records the spectrum's colour through the film
    // (the estimate's expectation, above), RGB mode its colour (computed from the spectrum at
    // 1 nm); they agree, and the luminance is 2.
    for (const char* spectrum : {"{blackbody: 3000}", "stdillum-A", "[400, 1, 700, 3]"}) {
        const std::string scene = std::string("camera: {type: look_at, from: [0, 0, -3], to: [0, 0, 0], fov: 10}\n"
                                              "film: {width: 8, height: 8}\n"
                                              "integrator: {type: path, max_depth: 1, spectral: true}\n"
                                              "background: {type: constant, color: [0, 0, 0]}\n"
                                              "objects:\n  - {type: sphere, center: [0, 0, 0], radius: 1, material: "
                                              "{type: diffuse, albedo: 0, emission: [2, 2, 2], emission_spectrum: ") +
                                  spectrum + "}}\n";
        const Color spectral = mean(render_job(job_from(scene), 256));
        Overrides rgb;
        rgb.spectral = false;
        const Color colour = mean(render_job(job_from(scene, rgb), 1));
        EXPECT_NEAR(0.2126f * colour.r + 0.7152f * colour.g + 0.0722f * colour.b, 2, 1e-4) << spectrum;
        EXPECT_LT(max_error(spectral, colour), 0.01f * 2) << spectrum << ": " << spectral.r << " " << spectral.g << " "
                                                          << spectral.b << " vs " << colour.r << " " << colour.g << " "
                                                          << colour.b;
    }
    // A point light too: its spectrum reaches the shaded point through next-event estimation.
    const std::string lit = "camera: {type: look_at, from: [0, 0, -3], to: [0, 0, 0], fov: 10}\n"
                            "film: {width: 8, height: 8}\n"
                            "integrator: {type: path, max_depth: 1, spectral: true}\n"
                            "background: {type: constant, color: [0, 0, 0]}\n"
                            "lights:\n  - {type: point, position: [0, 0, -3], intensity: [9, 9, 9], spectrum: {blackbody: 2000}}\n"
                            "objects:\n  - {type: quad, corner: [-5, -5, 0], edge1: [10, 0, 0], edge2: [0, 10, 0], "
                            "material: {type: diffuse, albedo: 1}}\n";
    Overrides rgb;
    rgb.spectral = false;
    const Color a = mean(render_job(job_from(lit), 256)), b = mean(render_job(job_from(lit, rgb), 1));
    EXPECT_LT(max_error(a, b), 0.01f * b.max_component()) << a.r << " " << a.g << " " << a.b << " vs " << b.r << " " << b.g << " " << b.b;
    EXPECT_GT(b.r, 2 * b.b);  // 2000 K is red
}

TEST(Spectra, ReflectanceSpectraAreReadAsTheyAre) {
    // A quad of a two-band (magenta) reflectance spectrum lit by a green point light (a narrow
    // band about 550 nm, where the magenta reflects 0.05). Its colour
    // is the film's integral of reflectance x light at 1 nm, times the geometry, which RGB mode
    // gives for a white quad (luminance(light colour) = 1). The spectrum's RGB upsampled again
    // would give another colour under this light: the test tells the two apart.
    const std::string band = "[380, 0.9, 480, 0.9, 500, 0.05, 600, 0.05, 620, 0.9, 780, 0.9]";
    const auto scene = [](const std::string& albedo) {
        return "camera: {type: look_at, from: [0, 0, -3], to: [0, 0, 0], fov: 10}\n"
               "film: {width: 8, height: 8}\n"
               "integrator: {type: path, max_depth: 1, spectral: true}\n"
               "background: {type: constant, color: [0, 0, 0]}\n"
               "lights:\n  - {type: point, position: [0, 0, -3], intensity: [9, 9, 9], spectrum: [530, 0, 550, 1, 570, 0]}\n"
               "objects:\n  - {type: quad, corner: [-5, -5, 0], edge1: [10, 0, 0], edge2: [0, 10, 0], "
               "material: {type: diffuse, albedo: " + albedo + "}}\n";
    };
    Overrides rgb;
    rgb.spectral = false;
    const float geometry = luminance(mean(render_job(job_from(scene("1"), rgb), 1)));
    const PiecewiseLinearSpectrum r({380, 480, 500, 600, 620, 780}, {0.9f, 0.9f, 0.05f, 0.05f, 0.9f, 0.9f});
    const Spectrum light = Spectrum::tabulated(PiecewiseLinearSpectrum({530, 550, 570}, {0, 1, 0})).normalised_emission();
    const Color exact = xyz_to_linear_srgb(spectrum_to_xyz([&](float l) { return r(l) * light(l); })) * geometry;
    const Color under_d65 = xyz_to_linear_srgb(spectrum_to_xyz([&](float l) { return r(l) * d65()(l); }));
    const Color upsampled = xyz_to_linear_srgb(spectrum_to_xyz([&](float l) {
                                Wavelengths wl;
                                wl.lambda[0] = wl.lambda[1] = wl.lambda[2] = l;
                                return upsample_reflectance(under_d65, wl).r * light(l);
                            })) * geometry;
    const float tolerance = 0.01f * exact.max_component();
    ASSERT_GT(max_error(exact, upsampled), 3 * tolerance);
    const Color c = mean(render_job(job_from(scene("{type: constant, spectrum: " + band + "}")), 256));
    EXPECT_LT(max_error(c, exact), tolerance) << c.r << " " << c.g << " " << c.b << " vs " << exact.r << " " << exact.g
                                              << " " << exact.b << " (upsampled: " << upsampled.r << " " << upsampled.g
                                              << " " << upsampled.b << ")";
    // RGB mode uses the colour under D65.
    const Color in_rgb = mean(render_job(job_from(scene("{type: constant, spectrum: " + band + "}"), rgb), 1));
    const Color white = mean(render_job(job_from(scene("1"), rgb), 1));
    EXPECT_LT(max_error(in_rgb, white * under_d65), 1e-4f * white.max_component());
}

TEST(Spectra, PbrtReflectanceSpectraAreKeptAndWritten) {
    // pbrt-v4's "spectrum reflectance" becomes a constant texture holding the spectrum, and the
    // YAML writer writes it so that it renders the same image.
    const std::string pbrt = R"(LookAt 0 0 -3  0 0 0  0 1 0
Camera "perspective" "float fov" [ 10 ]
Film "rgb" "integer xresolution" [ 8 ] "integer yresolution" [ 8 ]
WorldBegin
LightSource "point" "point3 from" [ 0 0 -3 ] "spectrum I" [ 530 0 550 1 570 0 ]
Material "diffuse" "spectrum reflectance" [ 380 0.9 480 0.9 500 0.05 600 0.05 620 0.9 780 0.9 ]
Shape "bilinearmesh" "point3 P" [ -5 -5 0  5 -5 0  -5 5 0  5 5 0 ]
)";
    const auto dir = std::filesystem::temp_directory_path() / "glint_spectra_writer";
    std::filesystem::create_directories(dir);
    auto sources = std::make_shared<SourceFiles>();
    const SceneDescription d = parse_pbrt(pbrt, (dir / "s.pbrt").string(), sources);
    ASSERT_EQ(d.materials.size(), 1u);
    const TextureDesc& texture = d.materials.front().material.color;
    ASSERT_TRUE(texture.spectrum != nullptr);
    EXPECT_FLOAT_EQ((*texture.spectrum)(550), 0.05f);
    const WrittenScene w = write_scene_yaml(d, dir / "s.yaml");
    EXPECT_NE(w.yaml.find("spectrum: [380, 0.9, 480, 0.9, 500, 0.05"), std::string::npos) << w.yaml;
    const SceneDescription back = parse_scene(w.yaml, (dir / "s.yaml").string(), sources);
    // The same image: the light's strength, its luminance, is re-derived from the written colour,
    // so the last bits may differ.
    const Film a = render_job(build(d, {}, sources), 16), b = render_job(build(back, {}, sources), 16);
    ASSERT_EQ(a.pixels().size(), b.pixels().size());
    for (std::size_t i = 0; i < a.pixels().size(); ++i)
        ASSERT_LT(max_error(a.pixels()[i], b.pixels()[i]), 1e-5f * a.pixels()[i].max_component() + 1e-9f) << i;
    std::filesystem::remove_all(dir);
}

TEST(Spectra, MeasuredMetalsAreWrittenAsTheirSpectra) {
    // A conductor of pbrt-v4's named gold and of brass (CuZn, which has no RGB preset) becomes
    // YAML eta/k by name, and the YAML renders the same image in both modes; YAML takes a metal's
    // spectra by name, as a table, or as `metal: gold`.
    const std::string pbrt = R"(LookAt 0 0 -3  0 0 0  0 1 0
Camera "perspective" "float fov" [ 30 ]
Film "rgb" "integer xresolution" [ 8 ] "integer yresolution" [ 8 ]
WorldBegin
LightSource "infinite" "rgb L" [ 1 1 1 ]
AttributeBegin
Material "conductor" "spectrum eta" "metal-Au-eta" "spectrum k" "metal-Au-k" "float roughness" 0.2
Shape "sphere" "float radius" 0.5
AttributeEnd
Translate 0.6 0 0
Material "conductor" "spectrum eta" "metal-CuZn-eta" "spectrum k" "metal-CuZn-k" "float roughness" 0.2
Shape "sphere" "float radius" 0.4
)";
    const auto dir = std::filesystem::temp_directory_path() / "glint_spectra_metals";
    std::filesystem::create_directories(dir);
    auto sources = std::make_shared<SourceFiles>();
    const SceneDescription d = parse_pbrt(pbrt, (dir / "m.pbrt").string(), sources);
    const WrittenScene w = write_scene_yaml(d, dir / "m.yaml");
    EXPECT_NE(w.yaml.find("eta: metal-Au-eta, k: metal-Au-k"), std::string::npos) << w.yaml;
    EXPECT_NE(w.yaml.find("eta: metal-CuZn-eta, k: metal-CuZn-k"), std::string::npos) << w.yaml;
    const SceneDescription back = parse_scene(w.yaml, (dir / "m.yaml").string(), sources);
    for (const bool spectral : {true, false}) {
        Overrides o;
        o.spectral = spectral;
        EXPECT_EQ(render_job(build(d, o, sources), 4).pixels(), render_job(build(back, o, sources), 4).pixels()) << spectral;
    }
    // In YAML: by name, as `metal: gold`, and as a table (gold's own values at 1 nm steps would
    // do; three points of it here) give gold's spectra in spectral mode.
    const Color by_name = mean(render_job(job_from(furnace("{type: conductor, eta: metal-Au-eta, k: metal-Au-k}")), 16));
    const Color preset = mean(render_job(job_from(furnace("{type: conductor, metal: gold}")), 16));
    EXPECT_EQ(by_name, preset);
    const Color table = mean(render_job(job_from(furnace("{type: conductor, eta: [400, 1.5, 550, 0.4, 700, 0.15], "
                                                         "k: [400, 1.9, 550, 2.4, 700, 4]}")), 16));
    EXPECT_GT(table.r, table.b + 0.2f);  // gold-like: reflects red, absorbs blue
    std::filesystem::remove_all(dir);
}

TEST(Spectra, YamlReadsSpectraFromFiles) {
    // `{file: name.spd}` (pbrt-v4's format: pairs, '#' comments, relative to the scene file) is
    // the same spectrum as the pairs inline, for an emitter, a reflectance and a metal's k.
    const auto dir = std::filesystem::temp_directory_path() / "glint_spectra_files";
    std::filesystem::create_directories(dir);
    std::ofstream(dir / "warm.spd") << "# a warm light\n400 0.5\n550 1.0 700 2.0\n";
    std::ofstream(dir / "bad.spd") << "400 0.5 550 x\n";
    const auto scene = [&](const std::string& emission, const std::string& albedo, const std::string& k) {
        return "camera: {type: look_at, from: [0, 0, -3], to: [0, 0, 0], fov: 30}\n"
               "film: {width: 8, height: 8}\n"
               "integrator: {type: path, max_depth: 3, spectral: true}\n"
               "background: {type: constant, color: [0.2, 0.2, 0.2]}\n"
               "objects:\n"
               "  - {type: sphere, center: [0, 1.2, 1], radius: 0.5, material: {type: diffuse, albedo: 0, "
               "emission: [4, 4, 4], emission_spectrum: " + emission + "}}\n"
               "  - {type: sphere, center: [-0.5, 0, 0], radius: 0.5, material: {type: diffuse, albedo: " + albedo + "}}\n"
               "  - {type: sphere, center: [0.5, 0, 0], radius: 0.5, material: {type: conductor, eta: metal-Au-eta, k: " +
               k + "}}\n";
    };
    const std::string path = (dir / "s.yaml").string();
    const auto render_text = [&](const std::string& text) {
        auto sources = std::make_shared<SourceFiles>();
        return render_job(build(parse_scene(text, path, sources), {}, sources), 4).pixels();
    };
    const std::string warm = "[400, 0.5, 550, 1.0, 700, 2.0]";
    const std::string warm_reflectance = "[400, 0.25, 550, 0.5, 700, 1.0]";
    std::ofstream(dir / "reflect.spd") << "400 0.25 550 0.5 700 1.0\n";
    EXPECT_EQ(render_text(scene("{file: warm.spd}", "{type: constant, spectrum: {file: reflect.spd}}", "{file: warm.spd}")),
              render_text(scene(warm, "{type: constant, spectrum: " + warm_reflectance + "}", warm)));
    const auto error = [&](const std::string& text) {
        try {
            auto sources = std::make_shared<SourceFiles>();
            parse_scene(text, path, sources);
        } catch (const SceneError& e) {
            const Diagnostic& d = e.diagnostics().front();
            return std::to_string(d.loc.line) + ":" + std::to_string(d.loc.column) + ": " + d.message;
        }
        return std::string("no error");
    };
    EXPECT_EQ(error(scene("{file: missing.spd}", "1", warm)),
              "6:138: spectrum: " + (dir / "missing.spd").string() + " cannot be read");
    EXPECT_EQ(error(scene("{file: bad.spd}", "1", warm)),
              "6:138: spectrum: " + (dir / "bad.spd").string() + ": \"x\" is not a number");
    std::filesystem::remove_all(dir);
}

TEST(Spectra, WhiteBalancedRenderOfAWarmLightIsNeutral) {
    // A white quad lit by illuminant A (2856 K): yellow as it is, about grey with white_balance
    // 2856 (von Kries is not exact for a black body far from daylight: within 3 %), in spectral
    // and in RGB mode; and the pbrt-v4 film parameter does the same.
    const auto scene = [](const std::string& balance) {
        return "camera: {type: look_at, from: [0, 0, -3], to: [0, 0, 0], fov: 10}\n"
               "film: {width: 8, height: 8}\n"
               "integrator: {type: path, max_depth: 1, spectral: true" + balance + "}\n"
               "background: {type: constant, color: [0, 0, 0]}\n"
               "lights:\n  - {type: point, position: [0, 0, -3], intensity: [9, 9, 9], spectrum: stdillum-A}\n"
               "objects:\n  - {type: quad, corner: [-5, -5, 0], edge1: [10, 0, 0], edge2: [0, 10, 0], "
               "material: {type: diffuse, albedo: 1}}\n";
    };
    const Color warm = mean(render_job(job_from(scene("")), 64));
    EXPECT_GT(warm.r, 1.5f * warm.b);
    for (const bool spectral : {true, false}) {
        Overrides o;
        o.spectral = spectral;
        const Color c = mean(render_job(job_from(scene(", white_balance: 2856"), o), 64));
        EXPECT_LT(max_error(c / c.g, Color{1}), 0.03f) << spectral << ": " << c.r << " " << c.g << " " << c.b;
    }
    auto sources = std::make_shared<SourceFiles>();
    const SceneDescription d = parse_pbrt("Film \"rgb\" \"float whitebalance\" [ 2856 ]\nWorldBegin\n", "wb.pbrt", sources);
    EXPECT_EQ(d.integrator.path.white_balance, 2856.0f);
    EXPECT_NE(write_scene_yaml(d, "wb.yaml").yaml.find("white_balance: 2856"), std::string::npos);
    EXPECT_THROW(parse_pbrt("Film \"rgb\" \"float whitebalance\" [ 50 ]\nWorldBegin\n", "wb.pbrt", sources), SceneError);
}

TEST(Spectra, AConstantSkyShinesItsSpectrum) {
    // pbrt-v4's "infinite" light of a spectrum (a narrow green band) over a magenta sphere that
    // fills the view, with one bounce: every pixel is the film's integral of reflectance x sky
    // at 1 nm (the sky's colour upsampled instead would light the magenta by its 0.05 far less
    // often: the test tells the two apart). The sky seen directly is the spectrum's colour; YAML's
    // constant background takes the same `spectrum`, and glint convert writes it.
    const std::string pbrt = R"(LookAt 0 0 -3  0 0 0  0 1 0
Camera "perspective" "float fov" [ 10 ]
Film "rgb" "integer xresolution" [ 8 ] "integer yresolution" [ 8 ]
Integrator "path" "integer maxdepth" [ 1 ]
WorldBegin
LightSource "infinite" "spectrum L" [ 530 0 550 1 570 0 ]
Material "diffuse" "spectrum reflectance" [ 380 0.9 480 0.9 500 0.05 600 0.05 620 0.9 780 0.9 ]
Shape "sphere" "float radius" 1
)";
    auto sources = std::make_shared<SourceFiles>();
    const SceneDescription d = parse_pbrt(pbrt, "sky.pbrt", sources);
    const PiecewiseLinearSpectrum r({380, 480, 500, 600, 620, 780}, {0.9f, 0.9f, 0.05f, 0.05f, 0.9f, 0.9f});
    const Spectrum sky = Spectrum::tabulated(PiecewiseLinearSpectrum({530, 550, 570}, {0, 1, 0})).normalised_emission();
    const Color exact = xyz_to_linear_srgb(spectrum_to_xyz([&](float l) { return r(l) * sky(l); }));
    const Color c = mean(render_job(build(d, {}, sources), 256));
    EXPECT_LT(max_error(c, exact), 0.01f * exact.max_component())
        << c.r << " " << c.g << " " << c.b << " vs " << exact.r << " " << exact.g << " " << exact.b;
    const WrittenScene w = write_scene_yaml(d, "sky.yaml");
    EXPECT_NE(w.yaml.find("background: {type: constant, color: "), std::string::npos) << w.yaml;
    EXPECT_NE(w.yaml.find(", spectrum: [530, 0, 550, 1, 570, 0]}"), std::string::npos) << w.yaml;
    const Color back = mean(render_job(build(parse_scene(w.yaml, "sky.yaml", sources), {}, sources), 256));
    EXPECT_LT(max_error(back, c), 1e-5f * c.max_component() + 1e-7f);
}

std::string first_error(const std::string& yaml) {
    try {
        job_from(yaml);
    } catch (const SceneError& e) {
        const Diagnostic& d = e.diagnostics().front();
        return std::to_string(d.loc.line) + ":" + std::to_string(d.loc.column) + ": " + d.message;
    }
    return "no error";
}

TEST(Spectra, MalformedSpectraAreLocatedErrors) {
    const std::string head = "camera: {type: look_at, from: [0, 0, -3], to: [0, 0, 0], fov: 45}\nobjects:\n";
    EXPECT_EQ(first_error(head + "  - {type: sphere, center: [0, 0, 0], radius: 1, material: {type: dielectric, ior: glass-BK8}}\n"),
              "3:84: ior: unknown glass 'glass-BK8'; did you mean 'glass-BK7'? (known: glass-BK7, glass-BAF10, "
              "glass-FK51A, glass-LASF9, glass-F5, glass-F10, glass-F11)");
    EXPECT_EQ(first_error(head + "  - {type: sphere, center: [0, 0, 0], radius: 1, material: {type: dielectric, ior: {sellmeier: [1, 2]}}}\n"),
              "3:96: sellmeier: expected 6 numbers [B1, B2, B3, C1, C2, C3]");
    EXPECT_EQ(first_error(head + "  - {type: sphere, center: [0, 0, 0], radius: 1, material: {type: plastic, ior: glass-BK7}}\n"),
              "3:81: material: a dispersive 'ior' (a glass or Sellmeier's coefficients) is for a dielectric or pbr");
    EXPECT_EQ(first_error(head + "  - {type: sphere, center: [0, 0, 0], radius: 1, material: {type: diffuse, emission: [1, 1, 1], "
                                 "emission_spectrum: [500, 1, 400, 1]}}\n"),
              "3:125: spectrum: the wavelengths must increase (400 after 500)");
    EXPECT_EQ(first_error(head + "  - {type: sphere, center: [0, 0, 0], radius: 1, material: {type: diffuse, emission: [1, 1, 1], "
                                 "emission_spectrum: stdillum-D66}}\n"),
              "3:116: spectrum: unknown name 'stdillum-D66'; did you mean 'stdillum-D65'?");
    EXPECT_EQ(first_error(head + "  - {type: sphere, center: [0, 0, 0], radius: 1, material: {type: dielectric, "
                                 "ior: {sellmeier: [1, 0, 0, 0.25, 0, 0]}}}\n"),
              "3:84: ior: the index at 361 nm is 0; it must be in (0, 10] from 360 to 830 nm");
    EXPECT_EQ(first_error(head + "  - {type: sphere, center: [0, 0, 0], radius: 1, material: {type: dielectric, abbe: 30}}\n"),
              "3:85: material: 'abbe' goes with a number 'ior' (the index at 587.56 nm)");
    EXPECT_EQ(first_error(head + "  - {type: sphere, center: [0, 0, 0], radius: 1, material: {type: diffuse, albedo: "
                                 "{type: constant, spectrum: [400, 0.5, 700, 1.5]}}}\n"),
              "3:111: constant texture: a reflectance spectrum is at most 1; it is 1.5 at 700 nm");
    EXPECT_EQ(first_error(head + "  - {type: sphere, center: [0, 0, 0], radius: 1, material: {type: diffuse, albedo: "
                                 "{type: constant, color: 1, spectrum: metal-Au-eta}}}\n"),
              "3:121: constant texture: give 'color' or 'spectrum', not both");
}

}  // namespace
}  // namespace glint
