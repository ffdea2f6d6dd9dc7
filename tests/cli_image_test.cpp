// End-to-end tests of the glint command whose output is read back by OpenImageIO, an independent
// reader (in glint_tests_oiio: tests/CMakeLists.txt says why that binary is apart).
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "testing.h"

#include "cli_fixture.h"

using namespace glint_cli_test;

namespace {

TEST_F(Cli, RendersExrWithLinearValuesAndPrintsASummary) {
    const Result r = run("render " + seed("fig10-diffuse.yaml") +
                         " --width 161 --height 91 -o fig10.exr");
    ASSERT_EQ(r.status, 0) << r.err;
    // Not a terminal: one summary line, then where the image went.
    EXPECT_NE(r.err.find("rendered 161x91 at 1 spp in "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("Mrays/s\nwrote fig10.exr\n"), std::string::npos) << r.err;
    auto in = OIIO::ImageInput::open((dir_ / "fig10.exr").string());
    ASSERT_TRUE(in);
    std::vector<float> px(161 * 91 * 3);
    ASSERT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::FLOAT, px.data()));
    EXPECT_NEAR(px[(45 * 161 + 80) * 3], 0.1 + 1 / std::sqrt(3.0), 2e-6);
}

// The same render to every output format: PFM holds the EXR's floats exactly, HDR within an
// RGBE bin of them, and JPEG the PNG's codes within JPEG's loss (both through the display
// transform); each file is read back by OpenImageIO.
TEST_F(Cli, EveryOutputFormatHoldsTheSameRender) {
    const int w = 96, h = 54;
    std::map<std::string, std::vector<float>> images;
    for (const char* ext : {"exr", "pfm", "hdr", "png", "jpg"}) {
        const std::string name = std::string("f.") + ext;
        const Result r = run("render " + seed("fig10-diffuse.yaml") + " --width 96 --height 54 -q -o " + name);
        ASSERT_EQ(r.status, 0) << ext << ": " << r.err;
        auto in = OIIO::ImageInput::open((dir_ / name).string());
        ASSERT_TRUE(in) << name << ": " << OIIO::geterror();
        ASSERT_EQ(in->spec().width, w);
        ASSERT_EQ(in->spec().height, h);
        std::vector<float> px(w * h * 3);
        ASSERT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::FLOAT, px.data()));
        images[ext] = std::move(px);
    }
    EXPECT_EQ(images["pfm"], images["exr"]);
    double jpeg_error = 0;
    for (std::size_t i = 0; i < images["exr"].size(); ++i) {
        // A bin of the pixel's largest component m, 2^(e-8) <= m / 128: OpenImageIO decodes a
        // mantissa to its bin's floor (Radiance and glint, to its middle).
        const float* px = &images["exr"][i - i % 3];
        const float m = std::max({px[0], px[1], px[2]});
        EXPECT_LE(std::abs(images["hdr"][i] - images["exr"][i]), m / 128) << i;
        jpeg_error += std::abs(images["jpg"][i] - images["png"][i]);
    }
    EXPECT_LT(jpeg_error / static_cast<double>(images["png"].size()), 2.0 / 255);
}

TEST_F(Cli, AovsAreExrChannelsWithHandValues) {
    const Result r = run("render " + seed("fig10-diffuse.yaml") +
                         " --width 161 --height 91 --aovs -q -o aov.exr");
    ASSERT_EQ(r.status, 0) << r.err;
    auto in = OIIO::ImageInput::open((dir_ / "aov.exr").string());
    ASSERT_TRUE(in);
    const auto& spec = in->spec();
    ASSERT_EQ(spec.nchannels, 22);
    // EXR keeps channels by name (files store them sorted): look each one up.
    auto channel = [&spec](const std::string& name) {
        for (int c = 0; c < spec.nchannels; ++c)
            if (spec.channel_name(c) == name) return static_cast<std::size_t>(c);
        ADD_FAILURE() << "no channel " << name;
        return std::size_t{0};
    };
    std::vector<float> px(161 * 91 * 22);
    ASSERT_TRUE(in->read_image(0, 0, 0, 22, OIIO::TypeDesc::FLOAT, px.data()));
    // Centre: the white sphere's front at (0,0,0), distance 1 from the camera at (0,0,-1),
    // normal (0,0,-1), albedo K = 1.
    const float* c = &px[(45 * 161 + 80) * 22];
    EXPECT_NEAR(c[channel("R")], 0.1 + 1 / std::sqrt(3.0), 2e-6);
    EXPECT_EQ(c[channel("albedo.R")], 1.0f);
    EXPECT_EQ(c[channel("albedo.B")], 1.0f);
    EXPECT_NEAR(c[channel("N.Z")], -1, 1e-6);
    EXPECT_NEAR(c[channel("N.X")], 0, 1e-6);
    EXPECT_NEAR(c[channel("Z")], 1, 1e-5);
    // The half images: one sample (the figure's spp) is sample 0, even; the odd half has none.
    EXPECT_EQ(c[channel("even.R")], c[channel("R")]);
    EXPECT_EQ(c[channel("odd.R")], 0.0f);
    EXPECT_EQ(c[channel("albedo.even.R")], 1.0f);  // the albedo's halves, likewise
    EXPECT_EQ(c[channel("albedo.odd.R")], 0.0f);
    // Corner: sky. Albedo is the background colour, normal zero, depth infinite.
    const float* k = &px[0];
    EXPECT_EQ(k[channel("albedo.G")], k[channel("G")]);
    EXPECT_EQ(k[channel("N.Y")], 0.0f);
    EXPECT_TRUE(std::isinf(k[channel("Z")]));
}

TEST_F(Cli, DemoRendersTheBuiltInFigure14) {
    const Result r = run("render --width 64 --height 36 -q");
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(fs::exists(dir_ / "glint.png"));
    // The demo is the fig14 file: same pixels (the headers differ: scene name, render time).
    ASSERT_EQ(run("render " + seed("fig14-reflections.yaml") + " --width 64 --height 36 -q -o f.png").status, 0);
    const auto pixels = [](const fs::path& p) {
        auto in = OIIO::ImageInput::open(p.string());
        std::vector<unsigned char> v(64 * 36 * 3);
        if (in) in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, v.data());
        return v;
    };
    EXPECT_EQ(pixels(dir_ / "glint.png"), pixels(dir_ / "f.png"));
}

}  // namespace

namespace {

// The shared objects the dynamic loader reports loading while glint runs `args` in `dir`
// (LD_DEBUG=files names each one as it is opened, dlopen included).
std::string libraries_loaded(const fs::path& dir, const std::string& args) {
    const std::string cmd = "cd '" + dir.string() + "' && LD_DEBUG=files '" + GLINT_CLI + "' " + args +
                            " >/dev/null 2>ld.txt </dev/null";
    EXPECT_EQ(std::system(cmd.c_str()), 0) << glint::testing::read_file(dir / "ld.txt").substr(0, 2000);
    return glint::testing::read_file(dir / "ld.txt");
}

}  // namespace

// Issue 17's lean start: OpenImageIO, OpenVDB and Embree are loaded only by the processes that
// need them: not by --version or a render to PNG/EXR, yes by a TGA texture (OpenImageIO), a .vdb
// grid (OpenVDB) and --accel embree.
TEST_F(Cli, HeavyLibrariesAreLoadedOnlyWhenNeeded) {
    const auto loads = [](const std::string& log, const char* lib) { return log.find(lib) != std::string::npos; };
    for (const std::string args : {std::string("--version"), "render " + seed("fig14-reflections.yaml") +
                                                                 " --width 32 --height 18 -q -o a.png",
                                   "render " + seed("fig14-reflections.yaml") + " --width 32 --height 18 -q -o a.exr"}) {
        const std::string log = libraries_loaded(dir_.path(), args);
        EXPECT_FALSE(loads(log, "libOpenImageIO")) << args;
        EXPECT_FALSE(loads(log, "libopenvdb")) << args;
        EXPECT_FALSE(loads(log, "libmpi")) << args;  // only under mpirun (mpi_test.cpp)
#if !GLINT_EMBREE_LINKED  // the sanitizer build links Embree (src/CMakeLists.txt says why)
        EXPECT_FALSE(loads(log, "libembree")) << args;
#endif
        EXPECT_TRUE(loads(log, "libtbb")) << args;  // the log is real: a library glint does load
    }
    {
        OIIO::ImageSpec spec(2, 2, 3, OIIO::TypeDesc::UINT8);
        auto out = OIIO::ImageOutput::create((dir_ / "t.tga").string());
        ASSERT_TRUE(out && out->open((dir_ / "t.tga").string(), spec));
        const std::uint8_t px[12] = {255, 0, 0, 0, 255, 0, 0, 0, 255, 255, 255, 255};
        ASSERT_TRUE(out->write_image(OIIO::TypeDesc::UINT8, px));
        out->close();
    }
    write("tga.yaml",
          "camera: {position: [0, 0, -3], direction: [0, 0, 1]}\n"
          "materials:\n  m: {color: {type: image, filename: t.tga}}\n"
          "lights: [{type: directional, direction: [0, 0, 1], intensity: [1, 1, 1]}]\n"
          "objects: [{type: sphere, center: [0, 0, 0], radius: 1, material: m}]\n");
    EXPECT_TRUE(loads(libraries_loaded(dir_.path(), "render tga.yaml --width 8 --height 8 -q -o t.png"), "libOpenImageIO"));
#if GLINT_EMBREE
    EXPECT_TRUE(loads(libraries_loaded(dir_.path(), "render " + seed("fig14-reflections.yaml") +
                                                        " --width 8 --height 8 --accel embree -q -o e.png"),
                      "libembree3"));
#endif
    EXPECT_TRUE(loads(libraries_loaded(dir_.path(), "render " + std::string(GLINT_SOURCE_DIR) +
                                                        "/scenes/volumes/cloud.yaml --width 8 --height 8 --spp 1 -q -o v.png"),
                      "libopenvdb"));
}
