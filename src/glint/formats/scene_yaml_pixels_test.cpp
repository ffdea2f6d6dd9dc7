// Image textures and grid media given in the scene itself (`pixels`, `voxels`): the numbers land
// where the docs say (row 0 at the top, x fastest), sRGB is decoded by its formula, an image given
// as pixels renders as the same image read from a file, and mistakes are located.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>

#include "glint/builder/build.h"
#include "glint/formats/scene_yaml.h"
#include "glint/render/render.h"

#include "testing.h"

namespace glint {
namespace {

SceneDescription parsed(const std::string& text, const InlineArrays* arrays = nullptr) {
    return parse_scene(text, "scene.yaml", std::make_shared<SourceFiles>(), 0, arrays);
}

std::string errors_of(const std::string& text, const InlineArrays* arrays = nullptr) {
    auto sources = std::make_shared<SourceFiles>();
    try {
        build(parse_scene(text, "scene.yaml", sources, 0, arrays), {}, sources);
    } catch (const SceneError& e) {
        return e.what();
    }
    return "";
}

const Image& first_pixels(const SceneDescription& d) {
    const TextureDesc& t = d.materials.at(0).material.color;
    EXPECT_EQ(t.kind, TextureDesc::Kind::kImage);
    EXPECT_TRUE(t.pixels);
    return *t.pixels;
}

TEST(SceneYamlPixels, RowsFromTheTopAndChannelsInOrder) {
    // 2 rows of 3 RGB pixels: pixel (x, y) = (x, y, x + y) / 10.
    const SceneDescription d = parsed(
        "materials:\n"
        "  m: {color: {type: image, pixels: [[[0, 0, 0], [0.1, 0, 0.1], [0.2, 0, 0.2]],\n"
        "                                     [[0, 0.1, 0.1], [0.1, 0.1, 0.2], [0.2, 0.1, 0.3]]]}}\n");
    const Image& im = first_pixels(d);
    ASSERT_EQ(im.width, 3);
    ASSERT_EQ(im.height, 2);
    EXPECT_TRUE(im.alpha.empty());
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 3; ++x) {
            EXPECT_EQ(im.texel(x, y).r, static_cast<float>(x * 0.1)) << x << "," << y;
            EXPECT_EQ(im.texel(x, y).g, static_cast<float>(y * 0.1)) << x << "," << y;
            EXPECT_EQ(im.texel(x, y).b, static_cast<float>((x + y) * 0.1)) << x << "," << y;
        }
}

// Grey (rows of numbers) is replicated; RGBA keeps its alpha; `encoding: srgb` decodes the colour
// by the sRGB transfer function (IEC 61966-2-1), written out here, and leaves alpha linear.
TEST(SceneYamlPixels, GreyRgbaAndSrgbDecoding) {
    const SceneDescription greys = parsed("materials: {m: {color: {type: image, pixels: [[0.25, 0.5]]}}}\n");
    const Image& grey = first_pixels(greys);
    EXPECT_EQ(grey.width, 2);
    EXPECT_EQ(grey.texel(1, 0).g, 0.5f);
    EXPECT_EQ(grey.texel(0, 0).b, 0.25f);
    const SceneDescription rgba = parsed(
        "materials: {m: {color: {type: image, encoding: srgb, pixels: [[[0.5, 0.02, 1, 0.5]]]}}}\n");
    const Image& im = first_pixels(rgba);
    const auto srgb = [](double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); };
    EXPECT_NEAR(im.texel(0, 0).r, srgb(0.5), 1e-6);
    EXPECT_NEAR(im.texel(0, 0).g, srgb(0.02), 1e-7);
    EXPECT_NEAR(im.texel(0, 0).b, 1.0, 1e-6);
    ASSERT_EQ(im.alpha.size(), 1u);
    EXPECT_EQ(im.alpha[0], 0.5f);
}

// An array handed over beside the text (a numpy array's memory) reads as the nested list does.
TEST(SceneYamlPixels, AnArrayBesideTheTextIsTheList) {
    const float px[] = {0, 0, 0, 0.1f, 0, 0.1f, 0.2f, 0, 0.2f, 0, 0.1f, 0.1f, 0.1f, 0.1f, 0.2f, 0.2f, 0.1f, 0.3f};
    ArrayView v{px, nullptr, 2, 9};
    v.shape = {2, 3, 3};
    v.dims = 3;
    const InlineArrays arrays{v};
    const SceneDescription d = parsed("materials: {m: {color: {type: image, pixels: '<array 0>'}}}\n", &arrays);
    const Image& a = first_pixels(d);
    ASSERT_EQ(a.width, 3);
    ASSERT_EQ(a.height, 2);
    EXPECT_EQ(a.texel(2, 1).b, 0.3f);
    EXPECT_EQ(a.texel(1, 0).r, 0.1f);
}

// A PFM written byte by byte here (its format: "PF", size, -1 for little-endian, rows from the
// bottom) and the same pixels in the scene render the same image, bit for bit.
TEST(SceneYamlPixels, PixelsRenderAsTheSameImageFromAFile) {
    const testing::TempDir tmp;
    const float rows[2][3][3] = {{{0.9f, 0.1f, 0.1f}, {0.1f, 0.8f, 0.2f}, {0.3f, 0.3f, 0.9f}},
                                 {{1.0f, 1.0f, 0.0f}, {0.0f, 0.5f, 0.5f}, {0.7f, 0.2f, 0.6f}}};  // row 0 = top
    {
        std::ofstream f(tmp.path() / "tex.pfm", std::ios::binary);
        f << "PF\n3 2\n-1.0\n";
        for (int y = 1; y >= 0; --y) f.write(reinterpret_cast<const char*>(rows[y]), sizeof rows[y]);
    }
    const std::string pixels = "[[[0.9, 0.1, 0.1], [0.1, 0.8, 0.2], [0.3, 0.3, 0.9]], "
                               "[[1.0, 1.0, 0.0], [0.0, 0.5, 0.5], [0.7, 0.2, 0.6]]]";
    const auto render_with = [&](const std::string& texture) {
        const std::string text =
            "camera: {type: look_at, from: [0, 0, -3], to: [0, 0, 0], fov: 40}\n"
            "film: {width: 24, height: 16}\n"
            "integrator: {type: flat}\n"
            "materials: {m: {color: {type: image, encoding: linear, " + texture + "}}}\n"
            "objects: [{type: quad, corner: [-1.5, -1, 0], edge1: [3, 0, 0], edge2: [0, 2, 0], material: m}]\n";
        auto sources = std::make_shared<SourceFiles>();
        const RenderJob job = build(parse_scene(text, (tmp.path() / "scene.yaml").string(), sources), {}, sources);
        Film film(job.film_width, job.film_height);
        RenderOptions o = job.options;
        o.spp = 4;
        render(job.scene, job.camera, *job.integrator, o, film);
        return film;
    };
    const Film a = render_with("filename: tex.pfm"), b = render_with("pixels: " + pixels);
    int differ = 0;
    for (int y = 0; y < a.height(); ++y)
        for (int x = 0; x < a.width(); ++x)
            for (int c = 0; c < 3; ++c) differ += a.at(x, y)[c] != b.at(x, y)[c];
    EXPECT_EQ(differ, 0);
    // The picture is the texture (not blank): the top-left quadrant is reddish, the bottom-left yellow.
    EXPECT_GT(b.at(2, 2).r, 2 * b.at(2, 2).g);
    EXPECT_GT(b.at(2, 13).g, 0.5f);
}

TEST(SceneYamlPixels, MistakesAreLocated) {
    const auto has = [](const std::string& errors, const std::string& what) {
        EXPECT_NE(errors.find(what), std::string::npos) << errors;
    };
    has(errors_of("materials: {m: {color: {type: image, pixels: [[[1, 0], [0, 1]]]}}}\n"),
        "scene.yaml:1:46: error: image texture: 'pixels' must have 1, 3 or 4 channels");
    has(errors_of("materials: {m: {color: {type: image, pixels: [[1, 0], [0]]}}}\n"),
        "scene.yaml:1:55: error: image texture: 'pixels': expected a list of 2 here (the shape is 2 x 2), got 1");
    has(errors_of("materials: {m: {color: {type: image, pixels: [[1, .nan]]}}}\n"),
        "scene.yaml:1:51: error: expected a finite number, got '.nan'");
    const float bad[] = {1, 2, std::nanf("")};
    ArrayView v{bad, nullptr, 1, 3};
    v.shape = {1, 3, 0};
    v.dims = 2;
    const InlineArrays arrays{v};
    has(errors_of("materials: {m: {color: {type: image, pixels: '<array 0>'}}}\n", &arrays),
        "scene.yaml:1:46: error: image texture: 'pixels': every value must be finite and non-negative; number 2 "
        "(counting from 0) is nan");
    has(errors_of("materials: {m: {color: {type: image, pixels: [[1, -1]]}}}\n"), "number 1 (counting from 0) is -1");
    has(errors_of("materials: {m: {color: {type: image, filename: a.png, pixels: [[1]]}}}\n"),
        "give 'filename' or 'pixels', not both");
    has(errors_of("materials: {m: {color: {type: image, pixels: 3}}}\n"), "'pixels' must be a list of numbers");
    has(errors_of("materials: {m: {color: {type: image, pixels: [[[[1]]]]}}}\n"), "must be a list nested 2 to 3 deep");
    has(errors_of("materials: {m: {color: {type: image, pixels: '<array 0>'}}}\n"), "(no array 0 was given");
    has(errors_of("materials: {m: {color: {type: image}}}\n"), "missing required key 'filename'");
    // Voxels
    has(errors_of("media: {s: {type: grid, voxels: [[1, 2]]}}\n"), "'voxels' must be a list nested 3 deep");
    has(errors_of("media: {s: {type: grid, voxels: [[[1]]], file: a.vdb}}\n"),
        "'file' names a grid in a file; with 'voxels' give none");
    has(errors_of("media: {s: {type: grid, voxels: [[[1]]], min: [0, 0, 0], max: [1, 0, 1]}}\n"),
        "'max' must exceed 'min' on every axis");
    has(errors_of("media: {s: {type: grid, file: a.vdb, min: [0, 0, 0]}}\n"), "'min' places 'voxels', which are not given");
    has(errors_of("media: {s: {type: grid, voxels: [[[1, -2]]]}}\n"), "number 1 (counting from 0) is -2");
}

}  // namespace
}  // namespace glint
