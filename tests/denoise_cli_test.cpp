// Denoising where a user meets it: `glint render --denoise` and `glint denoise`. The denoised
// image is closer to a converged render than the noisy one; an EXR keeps the image before, the
// features and the half images; `glint denoise` of an --aovs EXR gives the render's own denoised
// bits on any thread count; what cannot be denoised is a clear error and writes nothing.
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <vector>

#include "cli_fixture.h"
#include "glint/image/image_formats.h"
#include "glint/image/image_io.h"

namespace glint_cli_test {
namespace {

class DenoiseCli : public Cli {
protected:
    // A channel of an EXR in the test's folder (empty when missing).
    std::vector<float> channel(const std::string& file, const std::string& name) {
        return glint::read_exr_channels(dir_ / file, {name}, 1 << 24).planes[0];
    }
    // Relative MSE over R, G, B against a reference: (x - ref)^2 / (ref^2 + 0.01), the mean.
    double rel_mse(const std::string& file, const std::string& prefix, const std::string& ref) {
        double sum = 0;
        std::size_t n = 0;
        for (const char* c : {"R", "G", "B"}) {
            const std::vector<float> x = channel(file, prefix + c), r = channel(ref, c);
            EXPECT_EQ(x.size(), r.size());
            for (std::size_t i = 0; i < x.size() && i < r.size(); ++i, ++n)
                sum += (x[i] - r[i]) * (x[i] - r[i]) / (r[i] * r[i] + 0.01);
        }
        return n ? sum / static_cast<double>(n) : 1e9;
    }
    static std::string cornell() { return std::string("'") + GLINT_SOURCE_DIR + "/scenes/cornell-box.yaml' --width 64 --height 48"; }
};

TEST_F(DenoiseCli, TheDenoisedImageIsCloserToTheConvergedOneAndTheExrKeepsTheRest) {
    // The reference's own noise adds 1/128 (1/32 under the sanitizers) of the 8-spp image's.
    ASSERT_EQ(run("render " + cornell() + (glint::testing::kSanitized ? " --spp 256" : " --spp 1024") + " -q -o ref.exr").status, 0);
    Result r = run("render " + cornell() + " --spp 8 --denoise -o d.exr");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.err.find("denoised in"), std::string::npos) << r.err;
    for (const char* name : {"R", "noisy.R", "albedo.G", "N.Z", "Z", "even.B", "odd.B"})
        EXPECT_FALSE(channel("d.exr", name).empty()) << name;
    const double noisy = rel_mse("d.exr", "noisy.", "ref.exr"), denoised = rel_mse("d.exr", "", "ref.exr");
    EXPECT_LT(denoised, 0.5 * noisy) << "relative MSE: noisy " << noisy << ", denoised " << denoised;
    // The image before is the render without --denoise, to the bit.
    ASSERT_EQ(run("render " + cornell() + " --spp 8 -q -o plain.exr").status, 0);
    const std::vector<float> plain = channel("plain.exr", "R"), before = channel("d.exr", "noisy.R");
    ASSERT_EQ(plain.size(), before.size());
    EXPECT_EQ(std::memcmp(plain.data(), before.data(), plain.size() * sizeof(float)), 0);
    // A spp that is not a power of two is denoised, with a note saying why 2^k is better.
    r = run("render " + cornell() + " --spp 12 --denoise -o d12.png");
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.err.find("12 samples per pixel is not a power of two"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("power of two"), r.err.rfind("power of two")) << "once: " << r.err;
    // A PNG gets the denoised image alone.
    r = run("render " + cornell() + " --spp 8 --denoise -q -o d.png");
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(fs::exists(dir_ / "d.png"));
}

// `glint denoise` of the --aovs EXR of the same render gives the same bits as --denoise did,
// whatever the number of threads.
TEST_F(DenoiseCli, TheDenoiseCommandGivesTheRendersBitsOnAnyThreadCount) {
    ASSERT_EQ(run("render " + cornell() + " --spp 8 --denoise -q -o d.exr").status, 0);
    ASSERT_EQ(run("render " + cornell() + " --spp 8 --aovs -q -o a.exr").status, 0);
    const std::vector<float> want = channel("d.exr", "G");
    for (const char* threads : {"1", "2", "3"}) {
        const Result r = run(std::string("denoise a.exr -o b.exr --threads ") + threads);
        ASSERT_EQ(r.status, 0) << r.err;
        const std::vector<float> got = channel("b.exr", "G");
        ASSERT_EQ(got.size(), want.size());
        EXPECT_EQ(std::memcmp(got.data(), want.data(), got.size() * sizeof(float)), 0) << threads << " threads";
        EXPECT_FALSE(channel("b.exr", "noisy.G").empty());
    }
}

// The half images' difference, (even - odd)^2 / 4, estimates the variance of the pixel's mean:
// against the variance over 16 renders with different seeds (brute force), on Figure 14 soft
// (area light, glossy spheres, sky) at 32 spp. With a Sobol permutation that made each half a
// random subset of the samples, the estimate was 5.3 times the truth here (it measured
// unstratified sampling's error); with halves that are nets it is 1.15 times.
TEST_F(DenoiseCli, TheHalfImagesMeasureTheVarianceOfManyRenders) {
    const int renders = 16;
    std::vector<std::vector<float>> mean, even, odd;
    for (int seed = 1; seed <= renders; ++seed) {
        const std::string file = "s" + std::to_string(seed) + ".exr";
        const Result r = run(std::string("render '") + GLINT_SOURCE_DIR + "/scenes/seed/fig14-soft.yaml' " +
                             "--width 40 --height 24 --spp 32 --aovs -q --seed " + std::to_string(seed) + " -o " + file);
        ASSERT_EQ(r.status, 0) << r.err;
        mean.push_back(channel(file, "R"));
        even.push_back(channel(file, "even.R"));
        odd.push_back(channel(file, "odd.R"));
    }
    double truth = 0, estimate = 0;
    const std::size_t pixels = mean[0].size();
    ASSERT_EQ(pixels, 40u * 24u);
    for (std::size_t p = 0; p < pixels; ++p) {
        double m = 0;
        for (int k = 0; k < renders; ++k) m += mean[k][p];
        m /= renders;
        for (int k = 0; k < renders; ++k) {
            truth += (mean[k][p] - m) * (mean[k][p] - m) / (renders - 1);
            estimate += (even[k][p] - odd[k][p]) * (even[k][p] - odd[k][p]) / 4 / renders;
        }
    }
    // Halves of a net are coarser nets, so the estimate runs a little high for smooth integrands
    // (at most 2x for an error falling as 1/N^2); below the truth it would under-filter.
    EXPECT_GT(estimate / truth, 0.8) << "estimate " << estimate << ", variance over renders " << truth;
    EXPECT_LT(estimate / truth, 1.6) << "estimate " << estimate << ", variance over renders " << truth;
}

// In fog the features are those of the first surface along the camera ray, wherever the path
// scattered: Figure 14 in fog so dense that every sample scatters before the floor (density 3:
// transmittance e^-30 across the box) has the albedo of the same fog so thin that none does, to
// the bit, and the same depth; the sample positions are the same in both (docs/denoising.md).
TEST_F(DenoiseCli, FeaturesInFogAreThoseOfTheSurfaceBehindIt) {
    std::ifstream in(std::string(GLINT_SOURCE_DIR) + "/scenes/volumes/fig14-fog.yaml");
    const std::string text((std::istreambuf_iterator<char>(in)), {});
    const std::size_t at = text.find("density: 0.06");
    ASSERT_NE(at, std::string::npos);
    for (const char* density : {"3", "1e-9"}) {
        std::string scene = text;
        scene.replace(at, 13, std::string("density: ") + density);
        write(std::string("fog-") + density + ".yaml", scene);
        const Result r = run(std::string("render fog-") + density + ".yaml --width 48 --height 27 --spp 4 --aovs -q -o fog-" +
                             density + ".exr");
        ASSERT_EQ(r.status, 0) << r.err;
    }
    for (const char* c : {"albedo.R", "albedo.G", "N.Y"}) {
        const std::vector<float> dense = channel("fog-3.exr", c), clear = channel("fog-1e-9.exr", c);
        ASSERT_EQ(dense.size(), 48u * 27u);
        ASSERT_EQ(dense.size(), clear.size());
        EXPECT_EQ(std::memcmp(dense.data(), clear.data(), dense.size() * sizeof(float)), 0) << c;
    }
    const std::vector<float> dense = channel("fog-3.exr", "Z"), clear = channel("fog-1e-9.exr", "Z");
    int floor = 0;
    for (std::size_t i = 0; i < dense.size(); ++i) {
        if (std::isinf(clear[i])) {
            EXPECT_TRUE(std::isinf(dense[i])) << i;
            continue;
        }
        EXPECT_NEAR(dense[i], clear[i], 1e-4f * clear[i]) << i;
        ++floor;
    }
    EXPECT_GT(floor, 48 * 27 / 2);  // most pixels see the floor or a sphere
    // The image itself is another: the dense fog hides the floor.
    EXPECT_NE(channel("fog-3.exr", "R"), channel("fog-1e-9.exr", "R"));
}

TEST_F(DenoiseCli, WhatCannotBeDenoisedIsAnErrorAndNothingIsWritten) {
    // One sample: no two halves to estimate the noise from.
    Result r = run("render " + cornell() + " --spp 1 --denoise -o one.png");
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("--denoise: the render has 1 sample per pixel"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "one.png"));
    // An EXR without the half images, a PNG, a missing file, the input as output.
    ASSERT_EQ(run("render " + cornell() + " --spp 4 -q -o plain.exr").status, 0);
    r = run("denoise plain.exr -o out.exr");
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("plain.exr: no channel even.R"), std::string::npos) << r.err;
    ASSERT_EQ(run("render " + cornell() + " --spp 4 -q -o plain.png").status, 0);
    r = run("denoise plain.png -o out.exr");
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("plain.png: glint denoise reads OpenEXR files"), std::string::npos) << r.err;
    r = run("denoise nowhere.exr -o out.exr");
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("nowhere.exr': not found"), std::string::npos) << r.err;
    ASSERT_EQ(run("render " + cornell() + " --spp 4 --aovs -q -o a.exr").status, 0);
    const std::string before = read(dir_ / "a.exr");
    r = run("denoise a.exr -o a.exr");
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("the output would replace the input"), std::string::npos) << r.err;
    EXPECT_EQ(read(dir_ / "a.exr"), before);
    // A NaN in a channel: named by pixel and plane.
    const int w = 4, h = 3;
    const std::vector<std::string> names = {"R", "G", "B", "even.R", "even.G", "even.B", "odd.R", "odd.G", "odd.B"};
    std::vector<float> px(static_cast<std::size_t>(w * h) * names.size(), 0.5f);
    px[(1 * w + 2) * names.size() + 7] = std::nanf("");  // odd.G of pixel (2, 1)
    glint::write_exr(dir_ / "nan.exr", w, h, names, px.data(), {});
    r = run("denoise nan.exr -o out.exr");
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("nan.exr: pixel (2, 1) of the odd half is not a finite number"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "out.exr"));
}

}  // namespace
}  // namespace glint_cli_test
