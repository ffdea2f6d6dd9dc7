#include "glint/render/render.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>

#include "glint/builder/build.h"
#include "glint/formats/scene_yaml.h"

namespace glint {
namespace {

RenderJob load(const std::string& name, Overrides overrides = {}) {
    auto sources = std::make_shared<SourceFiles>();
    return build(load_scene_file(std::string(GLINT_SOURCE_DIR) + "/scenes/seed/" + name, sources),
                 overrides, sources);
}

Film render_with(const RenderJob& job, int threads, int tile, int spp) {
    Film film(job.film_width, job.film_height);
    RenderOptions o = job.options;
    o.threads = threads;
    o.tile_size = tile;
    o.spp = spp;
    render(job.scene, job.camera, *job.integrator, o, film);
    return film;
}

TEST(Render, ImageIsBitIdenticalForAnyThreadCountAndTileSize) {
    Overrides o;
    o.width = 97;  // not a multiple of any tile size
    o.height = 61;
    const RenderJob job = load("fig14-reflections.yaml", o);
    for (int spp : {1, 5}) {
        const Film a = render_with(job, 1, 16, spp);
        for (auto [threads, tile] : {std::pair{2, 16}, std::pair{2, 7}, std::pair{4, 1}}) {
            const Film b = render_with(job, threads, tile, spp);
            ASSERT_EQ(0, std::memcmp(a.pixels().data(), b.pixels().data(),
                                     a.pixels().size() * sizeof(Color)))
                << "threads " << threads << " tile " << tile << " spp " << spp;
        }
        // And across runs.
        const Film c = render_with(job, 2, 16, spp);
        ASSERT_EQ(0, std::memcmp(a.pixels().data(), c.pixels().data(),
                                 a.pixels().size() * sizeof(Color)));
    }
}

// A crop renders exactly the whole frame's pixels: same rays, same samples.
TEST(Render, ACropHoldsExactlyTheWholeFramesPixels) {
    auto sources = std::make_shared<SourceFiles>();
    SceneDescription d = load_scene_file(
        std::string(GLINT_SOURCE_DIR) + "/scenes/seed/fig14-reflections.yaml", sources);
    d.film.width.value = 61;
    d.film.height.value = 40;
    const RenderJob whole = build(d, {}, sources);
    d.film.pixel_bounds = Located<std::array<int, 4>>{{10, 45, 7, 30}, {}};
    const RenderJob crop = build(d, {}, sources);
    ASSERT_EQ(crop.film_width, 35);
    ASSERT_EQ(crop.film_height, 23);
    // pbrt's crop window: pixel bounds ceil(61 * 0.25) = 16 to ceil(61 * 0.5) = 31.
    d.film.pixel_bounds.reset();
    d.film.crop_window = Located<std::array<float, 4>>{{0.25f, 0.5f, 0, 1}, {}};
    const RenderJob fraction = build(d, {}, sources);
    EXPECT_EQ(fraction.film_width, 15);
    EXPECT_EQ(fraction.options.offset_x, 16);
    EXPECT_EQ(fraction.film_height, 40);
    for (int spp : {1, 3}) {
        const Film a = render_with(whole, 2, 16, spp);
        const Film b = render_with(crop, 2, 5, spp);
        for (int row = 0; row < 23; ++row)
            for (int col = 0; col < 35; ++col) {
                const Color x = a.at(col + 10, row + 7), y = b.at(col, row);
                ASSERT_TRUE(x.r == y.r && x.g == y.g && x.b == y.b) << col << "," << row << " spp " << spp;
            }
    }
    d.film.crop_window = Located<std::array<float, 4>>{{0.5f, 0.5f, 0, 1}, {}};
    EXPECT_THROW(build(d, {}, sources), SceneError);  // no pixel
}

TEST(Render, ScaleMultipliesEveryPixel) {
    Overrides o;
    o.width = 40;
    o.height = 30;
    RenderJob job = load("fig14-reflections.yaml", o);
    const Film a = render_with(job, 2, 16, 2);
    job.options.scale = 4;  // a power of two: exactly 4x in floating point
    const Film b = render_with(job, 2, 16, 2);
    for (std::size_t i = 0; i < a.pixels().size(); ++i) {
        ASSERT_EQ(a.pixels()[i].r * 4, b.pixels()[i].r);
        ASSERT_EQ(a.pixels()[i].b * 4, b.pixels()[i].b);
    }
}

TEST(Render, OneSampleIsThePixelCentre) {
    Overrides o;
    o.width = 40;
    o.height = 30;
    const RenderJob job = load("fig12-shadows.yaml", o);
    const Film film = render_with(job, 2, 16, 1);
    RayCounter counter;
    const PixelSampler sampler(SamplerType::kSobol, 1, 0);
    for (auto [col, row] : {std::pair{0, 0}, std::pair{17, 21}, std::pair{39, 29}}) {
        SampleStream samples(sampler, 0);
        const Color expected = job.integrator->li(
            job.scene, job.camera.generate_ray(col + 0.5f, row + 0.5f), samples, counter);
        EXPECT_EQ(film.at(col, row), expected);
    }
}

// A flat, screen-parallel checker whose cells meet at x = 0, seen by a 3-pixel-wide film: the
// middle pixel's left half sees x < 0 (odd = 0), its right half x >= 0 (even = 1).
RenderJob edge_scene(const std::string& filter) {
    auto sources = std::make_shared<SourceFiles>();
    const SceneDescription d = parse_scene(
        "camera: {position: [0, 50, 0], direction: [0, 0, 1], viewport_width: 3, "
        "viewport_height: 1, near: 1}\n"
        "film: {width: 3, height: 1, filter: " + filter + "}\n"
        "integrator: {type: flat}\n"
        "objects:\n"
        "  - {type: plane, point: [0, 0, 5], normal: [0, 0, -1],\n"
        "     material: {color: {type: checker, size: 100, even: [1, 1, 1], odd: [0, 0, 0]}}}\n",
        "edge.yaml", sources);
    return build(d, {}, sources);
}

TEST(Render, StratifiedSamplesSplitAnEdgePixelInHalf) {
    // The 16 samples are stratified in x (n-rooks), so exactly 8 fall on each side: 0.5.
    const RenderJob job = edge_scene("{type: box}");
    const Film one = render_with(job, 1, 16, 1);
    EXPECT_EQ(one.at(0, 0).r, 0);
    EXPECT_EQ(one.at(2, 0).r, 1);
    const Film aa = render_with(job, 1, 16, 16);
    EXPECT_FLOAT_EQ(aa.at(1, 0).r, 0.5f);
    EXPECT_EQ(aa.at(0, 0).r, 0);
    EXPECT_EQ(aa.at(2, 0).r, 1);
}

TEST(Render, ThinLensBlursOnlyWhatIsOutOfFocus) {
    // A white sphere (flat integrator) on a black background, radius 1 at distance 10. Rendered
    // with a wide aperture, focused on the sphere its silhouette stays crisp (few grey pixels);
    // focused far behind it, the edge spreads over many grey pixels.
    auto grey_pixels = [](Float focus) {
        auto sources = std::make_shared<SourceFiles>();
        const SceneDescription d = parse_scene(
            "camera: {type: look_at, from: [0, 0, -10], to: [0, 0, 0], fov: 20, "
            "aperture_radius: 0.4, focus_distance: " + std::to_string(focus) + "}\n"
            "film: {width: 64, height: 64}\n"
            "integrator: {type: flat}\n"
            "background: {type: constant, color: [0, 0, 0]}\n"
            "objects: [{type: sphere, center: [0, 0, 0], radius: 1, material: {color: [1, 1, 1]}}]\n",
            "dof.yaml", sources);
        const RenderJob job = build(d, {}, sources);
        const Film film = render_with(job, 2, 16, 64);
        int grey = 0;
        for (const Color& c : film.pixels()) grey += c.r > 0.05f && c.r < 0.95f;
        return grey;
    };
    const int sharp = grey_pixels(9);  // the sphere's front is at distance 9
    const int blurred = grey_pixels(40);
    EXPECT_GT(sharp, 0);              // anti-aliased edge pixels
    EXPECT_GT(blurred, 3 * sharp);    // the defocused edge is much wider
}

TEST(Render, AWiderFilterSpreadsTheEdgeIntoNeighbours) {
    // The same half-and-half edge as above: with the default box filter the outer pixels see only
    // their own side; a tent of radius 1.5 reaches across the edge from the left pixel (centre
    // at -1, edge at 0), so it picks up some white and the middle pixel stays at one half.
    auto render_edge = [](const std::string& filter) {
        return render_with(edge_scene(filter), 1, 16, 256);
    };
    const Film box = render_edge("{type: box}");
    EXPECT_EQ(box.at(0, 0).r, 0);
    const Film tent = render_edge("{type: tent, radius: 1.5}");
    // Tent centred at -1 with radius 1.5: the weight beyond 0 is the tip triangle,
    // (0.5 * 0.5 * (1/3)) / 1.5 = 1/18 of the total.
    EXPECT_NEAR(tent.at(0, 0).r, 1.0 / 18, 0.01);
    EXPECT_NEAR(tent.at(1, 0).r, 0.5, 0.01);
}

TEST(Render, LowDiscrepancySamplesGiveLowerErrorThanIndependentOnes) {
    // Figure 7's sphere silhouette at 16 spp with each sampler, against a 1024-spp reference:
    // the stratified and Sobol patterns must beat independent random samples (deterministic:
    // the seeds are fixed, so this is not a flaky comparison).
    Overrides o;
    o.width = 64;
    o.height = 36;
    RenderJob job = load("fig07-sphere.yaml", o);
    job.options.sampler = SamplerType::kStratified;
    const Film reference = render_with(job, 2, 16, 4096);
    auto rmse = [&](SamplerType type) {
        job.options.sampler = type;
        const Film f = render_with(job, 2, 16, 16);
        double sum = 0;
        for (std::size_t i = 0; i < f.pixels().size(); ++i) {
            const double d = f.pixels()[i].g - reference.pixels()[i].g;
            sum += d * d;
        }
        return std::sqrt(sum / static_cast<double>(f.pixels().size()));
    };
    const double independent = rmse(SamplerType::kIndependent);
    const double sobol = rmse(SamplerType::kSobol);
    const double stratified = rmse(SamplerType::kStratified);
    EXPECT_GT(independent, 0);
    std::printf("rmse at 16 spp: independent %.5f, stratified %.5f, sobol %.5f\n", independent,
                stratified, sobol);
    EXPECT_LT(sobol, 0.75 * independent) << sobol << " vs " << independent;
    EXPECT_LT(stratified, 0.75 * independent) << stratified << " vs " << independent;
}

TEST(Render, StatsCountEveryRay) {
    Overrides o;
    o.width = 16;
    o.height = 9;
    const RenderJob job = load("fig07-sphere.yaml", o);
    Film film(job.film_width, job.film_height);
    RenderOptions opts = job.options;
    opts.spp = 3;
    const RenderStats s = render(job.scene, job.camera, *job.integrator, opts, film);
    EXPECT_EQ(s.samples, 16u * 9u * 3u);
    EXPECT_EQ(s.rays, 16u * 9u * 3u);  // flat: one camera ray per sample
}

RenderJob load_any(const std::string& path, Overrides overrides) {
    auto sources = std::make_shared<SourceFiles>();
    return build(load_scene_file(std::string(GLINT_SOURCE_DIR) + "/" + path, sources), overrides, sources);
}

// Whitted's packets (up to 16 pixels of a row traced together, each bounce's rays asked of the
// scene at once) give the pixel-by-pixel image to the bit: on the article's scenes (the SIMD
// sphere set), with soft shadows, a thin lens and an exposure scale, and on scenes the packet
// query answers ray by ray (quads and disks, image textures, fog's interface surfaces). The
// width, 67, leaves short packets at every tile's edge.
TEST(Render, WhittedPacketsGiveThePixelByPixelImage) {
    for (const char* path : {"scenes/seed/fig12-shadows.yaml", "scenes/seed/fig14-reflections.yaml",
                             "scenes/seed/fig14-soft.yaml", "scenes/fig14-dof.yaml", "scenes/shapes.yaml",
                             "scenes/textures.yaml", "scenes/volumes/fig14-fog.yaml"}) {
        SCOPED_TRACE(path);
        Overrides o;
        o.width = 67;
        o.height = 29;
        o.spp = 1;
        RenderJob job = load_any(path, o);
        job.integrator = std::make_unique<WhittedIntegrator>(WhittedSettings{0.1f, true, 5});
        RenderStats stats[2];
        Film films[2] = {Film(job.film_width, job.film_height), Film(job.film_width, job.film_height)};
        for (const bool packets : {false, true}) {
            RenderOptions opts = job.options;
            opts.packets = packets;
            opts.threads = 2;
            opts.scale = 1.5f;
            stats[packets] = render(job.scene, job.camera, *job.integrator, opts, films[packets]);
        }
        EXPECT_EQ(stats[0].rays, stats[1].rays);
        std::size_t lit = 0;
        for (std::size_t i = 0; i < films[0].pixels().size(); ++i) {
            const Color a = films[0].pixels()[i], b = films[1].pixels()[i];
            ASSERT_EQ(0, std::memcmp(&a, &b, sizeof(Color))) << "pixel " << i;
            lit += a.r != films[0].pixels()[0].r;
        }
        EXPECT_GT(lit, 0u);  // not a blank image
    }
}

// render_8bit writes encode_8bit of the film render() fills, code for code (raw and sRGB, a
// tone curve, an exposure), for PNG and PPM output without a float film.
TEST(Render, EightBitSweepGivesTheFilmsCodes) {
    Overrides o;
    o.width = 53;
    o.height = 31;
    const RenderJob job = load("fig14-reflections.yaml", o);
    Film film(job.film_width, job.film_height);
    render(job.scene, job.camera, *job.integrator, job.options, film);
    for (const DisplaySettings d : {DisplaySettings{Encoding::kRaw, ToneCurve::kClamp, 0},
                                    DisplaySettings{Encoding::kSrgb, ToneCurve::kClamp, 0},
                                    DisplaySettings{Encoding::kSrgb, ToneCurve::kAces, 0.5f}}) {
        std::vector<std::uint8_t> rgb(static_cast<std::size_t>(job.film_width) * job.film_height * 3);
        render_8bit(job.scene, job.camera, *job.integrator, job.options, d, job.film_width, job.film_height, rgb.data());
        for (std::size_t i = 0; i < film.pixels().size(); ++i)
            for (int k = 0; k < 3; ++k)
                ASSERT_EQ(rgb[3 * i + static_cast<std::size_t>(k)], encode_8bit(film.pixels()[i][k], d)) << i;
    }
}

}  // namespace
}  // namespace glint
