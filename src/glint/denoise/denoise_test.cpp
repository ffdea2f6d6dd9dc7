// The denoiser against what is known without it: noise of a known variance about a known mean,
// an image without noise, an edge in the albedo, the variance of the halves' difference, and the
// same bits for any thread count.
#include "glint/denoise/denoise.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <stdexcept>
#include <vector>

namespace glint {
namespace {

// An image of `truth` (per pixel) with Gaussian noise: each half the mean of half the samples
// (standard deviation `sigma_half` per channel), the image their mean; flat features unless set.
struct Noisy {
    int w, h;
    std::vector<Color> truth, color, even, odd, albedo;
    std::vector<Color> even_albedo, odd_albedo;  // the albedo's halves: none unless set
    std::vector<Normal3> normal;
    std::vector<float> depth;
    Noisy(int w_, int h_, float sigma_half, unsigned seed, const std::vector<Color>& t)
        : w(w_), h(h_), truth(t), color(t.size()), even(t.size()), odd(t.size()), albedo(t.size(), Color{0.5f}),
          normal(t.size(), Normal3{0, 0, 1}), depth(t.size(), 4.0f) {
        std::mt19937 rng(seed);
        std::normal_distribution<float> g(0, sigma_half);
        for (std::size_t i = 0; i < t.size(); ++i) {
            even[i] = t[i] + Color{g(rng), g(rng), g(rng)};
            odd[i] = t[i] + Color{g(rng), g(rng), g(rng)};
            color[i] = (even[i] + odd[i]) * 0.5f;
        }
    }
    DenoiseInput input() const {
        const auto or_null = [](const std::vector<Color>& v) { return v.empty() ? nullptr : v.data(); };
        return {w,          h,           color.data(), even.data(), odd.data(), albedo.data(), normal.data(), depth.data(),
                or_null(even_albedo), or_null(odd_albedo)};
    }
};

double rms(const std::vector<Color>& a, const std::vector<Color>& b) {
    double s = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        const Color d = a[i] - b[i];
        s += (d.r * d.r + d.g * d.g + d.b * d.b) / 3.0;
    }
    return std::sqrt(s / static_cast<double>(a.size()));
}

// A grey of 0.5 with noise of standard deviation 0.1 in the image (0.1 sqrt 2 in each half): the
// denoised image's mean is 0.5 within its standard error, and its error is a small share of the
// noise (an 11 x 11 window averages up to 121 pixels: at best 1/11 of it).
TEST(Denoise, ConstantColourWithNoiseGivesItsMean) {
    const int w = 64, h = 48;
    const float sigma = 0.1f;
    const Noisy img(w, h, sigma * std::sqrt(2.0f), 1, std::vector<Color>(static_cast<std::size_t>(w * h), Color{0.5f}));
    EXPECT_NEAR(rms(img.color, img.truth), sigma, 0.005);
    DenoiseStats stats;
    const std::vector<Color> out = denoise(img.input(), {}, &stats);
    double mean = 0;
    for (const Color& c : out) mean += (c.r + c.g + c.b) / 3.0;
    mean /= static_cast<double>(out.size());
    // Neighbouring pixels share most of their windows, so the image mean's error is at most that
    // of one window's mean: 0.1 / sqrt(121 * 3) = 0.0052; four of them.
    EXPECT_NEAR(mean, 0.5, 0.02);
    EXPECT_LT(rms(out, img.truth), 0.25 * sigma) << "candidates won: " << stats.chosen[0] << " " << stats.chosen[1]
                                                 << " " << stats.chosen[2];
}

// A curved surface in a white furnace: every normal sees the same uniform light, so the colour is
// the same grey whatever the normal, which turns by 0.25 radians per pixel along x (a cylinder
// 4 pixels in radius). Neighbouring normals differ by more than the strict bandwidth (0.2), so
// feature weights alone average little more than a column of the window; the loose set's wider
// normal bandwidth lets the colour decide. Measured: 0.223 sigma with the loose set's normal
// bandwidth equal to the strict one's, 0.166 sigma as it is.
TEST(Denoise, ACurvedSurfaceOfOneColourIsAveragedAcrossItsNormals) {
    const int w = 64, h = 48;
    const float sigma = 0.1f;
    Noisy img(w, h, sigma * std::sqrt(2.0f), 11, std::vector<Color>(static_cast<std::size_t>(w * h), Color{0.5f}));
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const float theta = 0.25f * static_cast<float>(x - w / 2);
            img.normal[static_cast<std::size_t>(y * w + x)] = Normal3{std::sin(theta), 0, std::cos(theta)};
        }
    const std::vector<Color> out = denoise(img.input(), {});
    EXPECT_LT(rms(out, img.truth), 0.19 * sigma);
}

// Without noise (both halves equal to the image) every pixel comes back as it was, edges and
// gradients included: every candidate filter that could blur has a larger error estimate.
TEST(Denoise, ANoiseFreeImageComesBackUnchanged) {
    const int w = 40, h = 30;
    std::vector<Color> t(static_cast<std::size_t>(w * h));
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            t[static_cast<std::size_t>(y * w + x)] = Color{x < 20 ? 0.2f : 0.9f, 0.01f * static_cast<float>(y), 0.3f + 0.01f * static_cast<float>(x)};
    const Noisy img(w, h, 0, 1, t);
    const std::vector<Color> out = denoise(img.input());
    for (std::size_t i = 0; i < t.size(); ++i) {
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(out[i][c], t[i][c], 1e-5f * (1 + t[i][c])) << "pixel " << i;
    }
}

// An albedo edge (0.2 | 0.8) under white light with noise: the columns beside the edge keep
// their own side's value, and the noise falls. Averaged over the 48 rows, a column's noise is
// about 0.057 / sqrt(48) = 0.008 where it is left as it was (the edge's own columns keep most of
// theirs); a blur across the edge that moved them a tenth of the way would be 0.06.
TEST(Denoise, AnAlbedoEdgeIsNotBlurredAcross) {
    const int w = 48, h = 48;
    std::vector<Color> t(static_cast<std::size_t>(w * h));
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) t[static_cast<std::size_t>(y * w + x)] = Color{x < 24 ? 0.2f : 0.8f};
    Noisy img(w, h, 0.08f, 2, t);
    img.albedo = t;
    const std::vector<Color> out = denoise(img.input());
    for (const int x : {22, 23, 24, 25}) {
        double mean = 0;
        for (int y = 0; y < h; ++y) mean += out[static_cast<std::size_t>(y * w + x)].g;
        mean /= h;
        EXPECT_NEAR(mean, x < 24 ? 0.2 : 0.8, 0.035) << "column " << x;
    }
    EXPECT_LT(rms(out, t), 0.5 * rms(img.color, t));
}

// A ramp (0.3 + 0.02 x) that ends at an albedo edge, with noise: the columns beside the edge see
// only their own side, so a weighted mean of their window would sit below the ramp (the window's
// pixels are to one side, up to 5 pixels, 0.1, lower); the plane fit follows the ramp. Averaged
// over 200 rows a column's noise is under 0.04 / sqrt(200) = 0.003; 0.006 allowed. The weighted
// mean alone (the filter before plane fits) missed columns 29 and 30 by 0.016 and 0.027.
TEST(Denoise, ARampBesideAnEdgeKeepsItsLevel) {
    const int w = 48, h = 200;
    std::vector<Color> t(static_cast<std::size_t>(w * h)), albedo(t.size());
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const auto i = static_cast<std::size_t>(y * w + x);
            t[i] = Color{x < 32 ? 0.3f + 0.02f * static_cast<float>(x) : 0.2f};
            albedo[i] = Color{x < 32 ? 0.8f : 0.2f};
        }
    Noisy img(w, h, 0.04f * std::sqrt(2.0f), 6, t);
    img.albedo = albedo;
    const std::vector<Color> out = denoise(img.input());
    for (const int x : {29, 30, 31}) {
        double err = 0;
        for (int y = 0; y < h; ++y) {
            const auto i = static_cast<std::size_t>(y * w + x);
            err += (out[i].r + out[i].g + out[i].b) / 3.0 - t[i].g;
        }
        EXPECT_NEAR(err / h, 0.0, 0.006) << "column " << x;
    }
    EXPECT_LT(rms(out, t), 0.5 * rms(img.color, t));
}

// The half images' difference estimates the variance of the image's mean: over a flat noisy
// image its average is sigma^2 (here sigma = 0.05), within the estimate's sampling error.
TEST(Denoise, HalfBufferVarianceMatchesTheNoise) {
    const int w = 64, h = 64;
    const float sigma = 0.05f;
    const Noisy img(w, h, sigma * std::sqrt(2.0f), 3, std::vector<Color>(static_cast<std::size_t>(w * h), Color{1.0f}));
    const std::vector<Color> v = denoise_variance(img.input());
    double mean = 0;
    for (const Color& c : v) mean += (c.r + c.g + c.b) / 3.0;
    mean /= static_cast<double>(v.size());
    // (even - odd)^2 / 4 per pixel and channel is sigma^2 times a chi-square of one degree of
    // freedom: relative standard error sqrt(2 / 12288) = 1.3 % for the mean; 5 % allowed.
    EXPECT_NEAR(mean / (sigma * sigma), 1.0, 0.05);
}

TEST(Denoise, TheSameBitsForAnyThreadCount) {
    const int w = 70, h = 53;  // bands of 16 rows that do not divide the height
    std::vector<Color> t(static_cast<std::size_t>(w * h));
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) t[static_cast<std::size_t>(y * w + x)] = Color{(x / 8 + y / 8) % 2 ? 0.7f : 0.1f, 0.4f, 0.2f};
    Noisy img(w, h, 0.1f, 4, t);
    for (std::size_t i = 0; i < t.size(); ++i) img.depth[i] = 2 + 0.01f * static_cast<float>(i % static_cast<std::size_t>(w));
    std::vector<std::vector<Color>> outs;
    for (const int threads : {1, 2, 3}) outs.push_back(denoise(img.input(), {6, threads}));
    for (std::size_t k = 1; k < outs.size(); ++k)
        EXPECT_EQ(std::memcmp(outs[0].data(), outs[k].data(), outs[0].size() * sizeof(Color)), 0) << "threads " << k + 1;
}

// A fine texture (albedo 0.45 to 0.55 at random per pixel, known exactly: its halves agree)
// under smooth light, with noise. The albedo differs between neighbours by less than the albedo
// feature's bandwidth, so filtering the colour blurs the texture; with the albedo's halves the
// filter can also filter the shading (colour / albedo) and multiply the pixel's albedo back.
TEST(Denoise, AFineTextureSurvivesThroughTheShading) {
    const int w = 64, h = 64;
    std::vector<Color> t(static_cast<std::size_t>(w * h)), albedo(t.size());
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(0.45f, 0.55f);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const auto i = static_cast<std::size_t>(y * w + x);
            albedo[i] = Color{u(rng)};
            t[i] = albedo[i] * (0.8f + 0.2f * std::sin(0.1f * static_cast<float>(x + y)));
        }
    Noisy img(w, h, 0.03f * std::sqrt(2.0f), 8, t);
    img.albedo = albedo;
    const double without = rms(denoise(img.input()), t);
    img.even_albedo = img.odd_albedo = albedo;
    const double with = rms(denoise(img.input()), t);
    EXPECT_LT(with, 0.5 * without);
}

// Noise the albedo shares: each pixel's samples see albedo 0.2 or 0.8 (a sub-pixel edge), the
// colour is the albedo (white light, nothing else random). The shading is then exact and the
// shading candidates return each pixel's raw colour, noise and all; their error estimate must
// see that the albedo's noise is the colour's (the covariance from the halves), or it would
// choose them everywhere. With the halves the result may not be worse than without them.
TEST(Denoise, NoiseTheAlbedoSharesIsNotTakenForSignal) {
    const int w = 64, h = 64, spp = 16;
    std::vector<Color> truth(static_cast<std::size_t>(w * h), Color{0.5f});
    Noisy img(w, h, 0, 9, truth);
    std::mt19937 rng(9);
    std::bernoulli_distribution coin(0.5);
    img.even_albedo.resize(truth.size()), img.odd_albedo.resize(truth.size());
    for (std::size_t i = 0; i < truth.size(); ++i) {
        float half[2] = {0, 0};
        for (int s = 0; s < spp; ++s) half[s & 1] += (coin(rng) ? 0.8f : 0.2f) / (spp / 2);
        img.even[i] = img.even_albedo[i] = Color{half[0]};
        img.odd[i] = img.odd_albedo[i] = Color{half[1]};
        img.color[i] = img.albedo[i] = Color{(half[0] + half[1]) / 2};
    }
    const double with = rms(denoise(img.input()), truth);
    img.even_albedo.clear(), img.odd_albedo.clear();
    const double without = rms(denoise(img.input()), truth);
    EXPECT_LT(with, 1.05 * without);
    EXPECT_LT(with, 0.7 * rms(img.color, truth));
}

// The image filtered in strips of rows, each with the rows it depends on, has the bits of the
// image filtered whole (the halo is wide enough), for strips that do not divide the height.
TEST(Denoise, StripsGiveTheWholeImagesBits) {
    const int w = 61, h = 57;
    std::vector<Color> t(static_cast<std::size_t>(w * h)), albedo(t.size());
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const auto i = static_cast<std::size_t>(y * w + x);
            albedo[i] = Color{(x / 7 + y / 5) % 2 ? 0.7f : 0.3f, 0.5f, 0.4f};
            t[i] = albedo[i] * (0.5f + 0.01f * static_cast<float>(y));
        }
    Noisy img(w, h, 0.1f, 10, t);
    img.albedo = albedo;
    Noisy halves(w, h, 0.05f, 11, albedo);  // noisy albedo halves
    img.even_albedo = halves.even, img.odd_albedo = halves.odd;
    for (std::size_t i = 0; i < t.size(); ++i) img.depth[i] = 3 + 0.02f * static_cast<float>(i / static_cast<std::size_t>(w));
    DenoiseOptions whole;
    whole.strip_rows = h;
    const std::vector<Color> ref = denoise(img.input(), whole);
    for (const int rows : {1, 5, 16, 30}) {
        DenoiseOptions o;
        o.strip_rows = rows;
        const std::vector<Color> out = denoise(img.input(), o);
        EXPECT_EQ(std::memcmp(ref.data(), out.data(), ref.size() * sizeof(Color)), 0) << "strips of " << rows << " rows";
    }
}

TEST(Denoise, BadInputsAreErrorsThatNameThePixel) {
    Noisy img(8, 6, 0.1f, 5, std::vector<Color>(48, Color{0.5f}));
    DenoiseInput in = img.input();
    in.odd = nullptr;
    EXPECT_THROW(denoise(in), std::invalid_argument);
    in = img.input();
    in.width = 0;
    EXPECT_THROW(denoise(in), std::invalid_argument);
    img.color[3 * 8 + 5].g = std::nanf("");
    try {
        denoise(img.input());
        FAIL() << "a NaN was accepted";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("pixel (5, 3) of the image"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace glint
