#include "glint/render/progressive.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>

#include "glint/builder/build.h"
#include "glint/session/checkpoint.h"
#include "glint/image/image_io.h"
#include "glint/formats/scene_yaml.h"
#include "testing.h"

namespace glint {
namespace {

RenderJob load(const std::string& path, int w, int h, int spp, bool aovs) {
    auto sources = std::make_shared<SourceFiles>();
    Overrides o;
    o.width = w;
    o.height = h;
    o.spp = spp;
    o.aovs = aovs;
    return build(load_scene_file(std::string(GLINT_SOURCE_DIR) + "/" + path, sources), o, sources);
}

RenderJob cornell(int spp, bool aovs = false) { return load("scenes/cornell-box.yaml", 40, 32, spp, aovs); }

Film film_for(const RenderJob& job, bool counts = false) {
    Film f(job.film_width, job.film_height);
    if (job.aovs) f.enable_aovs();
    if (counts) f.enable_sample_counts();
    return f;
}

template <typename T>
bool same_bytes(const T& a, const T& b) {
    return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(a[0])) == 0);
}

void expect_same(const Film& a, const Film& b) {
    EXPECT_TRUE(same_bytes(a.pixels(), b.pixels()));
    EXPECT_TRUE(same_bytes(a.albedo(), b.albedo()));
    EXPECT_TRUE(same_bytes(a.normal(), b.normal()));
    EXPECT_TRUE(same_bytes(a.depth(), b.depth()));
    EXPECT_TRUE(same_bytes(a.sample_counts(), b.sample_counts()));
}

// Every split of the samples into passes gives the bytes of the one-pass render: passes of
// 1, 3, 2 and 7 samples, on one thread or two, and a run stopped midway, saved to a checkpoint
// file, read back and continued.
TEST(Progressive, AnySplitIntoPassesGivesTheSameBytes) {
    const RenderJob job = cornell(13, true);
    Film whole = film_for(job);
    RenderOptions one_thread = job.options;
    one_thread.threads = 1;
    render(job.scene, job.camera, *job.integrator, one_thread, whole);

    RenderOptions two = job.options;
    two.threads = 2;
    two.tile_size = 7;
    ProgressiveRender split(job.scene, job.camera, *job.integrator, two, job.film_width, job.film_height, true);
    for (int n : {1, 3, 2, 7}) ASSERT_TRUE(split.run_pass(n));
    EXPECT_TRUE(split.finished());
    EXPECT_EQ(split.passes(), 4);
    Film a = film_for(job);
    split.resolve(a);
    expect_same(whole, a);

    glint::testing::TempDir dir;
    const auto file = dir / "c.ckpt";
    {
        ProgressiveRender first(job.scene, job.camera, *job.integrator, job.options, job.film_width,
                                job.film_height, true);
        ASSERT_TRUE(first.run_pass(5));
        write_checkpoint(file, 42, first.state());
    }
    Checkpoint c = read_checkpoint(file);
    EXPECT_EQ(c.fingerprint, 42u);
    EXPECT_EQ(c.state.spp_done, 5);
    ProgressiveRender resumed(job.scene, job.camera, *job.integrator, job.options, job.film_width,
                              job.film_height, true);
    resumed.restore(std::move(c.state));
    while (!resumed.finished()) ASSERT_TRUE(resumed.run_pass(resumed.next_pass_size()));
    Film b = film_for(job);
    resumed.resolve(b);
    expect_same(whole, b);
}

// One sample per pixel through the pass machinery equals the direct one-sample sweep (which the
// article's figures are checked with, bit for bit).
TEST(Progressive, OneSamplePassEqualsTheDirectSweep) {
    const RenderJob job = load("scenes/seed/fig14-reflections.yaml", 33, 21, 1, false);
    Film direct = film_for(job);
    render(job.scene, job.camera, *job.integrator, job.options, direct);
    ProgressiveRender p(job.scene, job.camera, *job.integrator, job.options, job.film_width, job.film_height, false);
    ASSERT_TRUE(p.run_pass(p.next_pass_size()));
    EXPECT_TRUE(p.finished());
    Film f = film_for(job);
    p.resolve(f);
    EXPECT_TRUE(same_bytes(direct.pixels(), f.pixels()));
}

TEST(Progressive, ACancelledPassLeavesTheStateOfTheCompletedOnes) {
    const RenderJob job = cornell(8);
    ProgressiveRender p(job.scene, job.camera, *job.integrator, job.options, job.film_width, job.film_height, false);
    ASSERT_TRUE(p.run_pass(2));
    const ProgressiveState before = p.state();
    std::atomic<bool> stop{true};
    EXPECT_FALSE(p.run_pass(2, &stop));
    EXPECT_EQ(p.spp_done(), 2);
    EXPECT_EQ(p.passes(), 1);
    EXPECT_TRUE(same_bytes(before.sum, p.state().sum));
    EXPECT_TRUE(same_bytes(before.weight, p.state().weight));
    // A render() cancelled says so.
    Film f = film_for(job);
    EXPECT_FALSE(render(job.scene, job.camera, *job.integrator, job.options, f, nullptr, &stop).complete);
    RenderOptions one = job.options;
    one.spp = 1;
    EXPECT_FALSE(render(job.scene, job.camera, *job.integrator, one, f, nullptr, &stop).complete);
}

TEST(Progressive, PassSizesDoubleAndATimeBudgetStopsThem) {
    const RenderJob job = cornell(64);
    ProgressiveRender p(job.scene, job.camera, *job.integrator, job.options, job.film_width, job.film_height, false);
    EXPECT_EQ(p.next_pass_size(), 1);
    EXPECT_EQ(p.next_pass_size(0), 0);  // no time left: no pass
    std::vector<int> ends;
    while (!p.finished()) {
        ASSERT_TRUE(p.run_pass(p.next_pass_size()));
        ends.push_back(p.spp_done());
    }
    // Short passes double (1, 2, 4, ...); none is capped on so small a film.
    EXPECT_EQ(ends, (std::vector<int>{1, 2, 4, 8, 16, 32, 64}));
    // With 1 ms left after a measured pass, nothing of the next pass fits.
    ProgressiveRender q(job.scene, job.camera, *job.integrator, job.options, job.film_width, job.film_height, false);
    ASSERT_TRUE(q.run_pass(4));
    EXPECT_EQ(q.next_pass_size(1e-9), 0);
    EXPECT_GE(q.next_pass_size(1e6), 1);
}

// A flat image (a constant sky, nothing else) has no noise: every pixel stops at the minimum.
TEST(Progressive, AdaptiveSamplingStopsAFlatImageAtTheMinimum) {
    glint::testing::TempDir dir;
    {
        std::ofstream(dir / "flat.yaml") << "film: {width: 24, height: 16}\n"
                                            "integrator: {type: path}\n"
                                            "background: {type: constant, color: [0.3, 0.5, 0.7]}\n";
    }
    auto sources = std::make_shared<SourceFiles>();
    Overrides o;
    o.spp = 256;
    RenderJob job = build(load_scene_file((dir / "flat.yaml").string(), sources), o, sources);
    job.options.noise_threshold = 0.01f;
    ProgressiveRender p(job.scene, job.camera, *job.integrator, job.options, job.film_width, job.film_height, false);
    EXPECT_EQ(p.min_spp(), adaptive_default_min_spp(0.01f));
    EXPECT_EQ(p.min_spp(), 64);  // Cycles: threshold 0.01 -> 64
    while (!p.finished()) ASSERT_TRUE(p.run_pass(p.next_pass_size()));
    EXPECT_EQ(p.spp_done(), 64);
    EXPECT_DOUBLE_EQ(p.converged_fraction(), 1.0);
    for (std::uint32_t n : p.state().samples) EXPECT_EQ(n, 64u);
    Film f = film_for(job, true);
    p.resolve(f);
    EXPECT_NEAR(f.at(3, 3).g, 0.5f, 1e-6f);
    EXPECT_EQ(f.sample_count(3, 3), 64.0f);
}

// On the Cornell box, noisy pixels sample on: the sample counts differ, some pixel reaches the
// maximum, every pixel has at least the minimum; the adaptive image agrees with a uniform one of
// many samples; and adaptive renders, too, are the same bytes however they are split.
TEST(Progressive, AdaptiveSamplingKeepsSamplingNoisyPixels) {
    RenderJob job = cornell(256);
    job.options.noise_threshold = 0.02f;
    job.options.min_spp = 16;
    Film adaptive = film_for(job, true);
    const RenderStats stats = render(job.scene, job.camera, *job.integrator, job.options, adaptive);
    const auto& counts = adaptive.sample_counts();
    const float lo = *std::min_element(counts.begin(), counts.end());
    const float hi = *std::max_element(counts.begin(), counts.end());
    EXPECT_EQ(lo, 16.0f);
    EXPECT_EQ(hi, 256.0f);
    double mean_count = 0;
    for (float c : counts) mean_count += c;
    mean_count /= static_cast<double>(counts.size());
    EXPECT_LT(mean_count, 200.0);  // a saving over 256 everywhere
    EXPECT_EQ(stats.samples, static_cast<std::uint64_t>(mean_count * static_cast<double>(counts.size()) + 0.5));

    // Against 256 spp everywhere: the image means agree within the noise.
    RenderJob uniform_job = cornell(256);
    Film uniform = film_for(uniform_job);
    render(uniform_job.scene, uniform_job.camera, *uniform_job.integrator, uniform_job.options, uniform);
    double a = 0, u = 0;
    for (std::size_t i = 0; i < counts.size(); ++i) {
        a += average(adaptive.pixels()[i]);
        u += average(uniform.pixels()[i]);
    }
    EXPECT_NEAR(a / u, 1.0, 0.02);

    // Split: stop after the pass that reaches 48, save, read back, continue.
    glint::testing::TempDir dir;
    ProgressiveRender first(job.scene, job.camera, *job.integrator, job.options, job.film_width, job.film_height, false);
    while (first.spp_done() < 48) ASSERT_TRUE(first.run_pass(first.next_pass_size()));
    write_checkpoint(dir / "a.ckpt", 7, first.state());
    ProgressiveRender second(job.scene, job.camera, *job.integrator, job.options, job.film_width, job.film_height, false);
    second.restore(read_checkpoint(dir / "a.ckpt").state);
    while (!second.finished()) ASSERT_TRUE(second.run_pass(second.next_pass_size()));
    Film b = film_for(job, true);
    second.resolve(b);
    expect_same(adaptive, b);
}

TEST(Progressive, RestoreRefusesAStateOfAnotherShape) {
    const RenderJob job = cornell(8);
    ProgressiveRender p(job.scene, job.camera, *job.integrator, job.options, job.film_width, job.film_height, false);
    ProgressiveState s = p.state();
    s.spp_target = 9;
    EXPECT_THROW(p.restore(s), std::runtime_error);
    s = p.state();
    s.aovs = true;
    EXPECT_THROW(p.restore(s), std::runtime_error);
    s = p.state();
    s.sum.pop_back();
    EXPECT_THROW(p.restore(s), std::runtime_error);
}

}  // namespace
}  // namespace glint
