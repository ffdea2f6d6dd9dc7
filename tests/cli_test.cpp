// End-to-end tests of the glint command: exit status, messages, and that nothing is lost.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <thread>
#include <vector>

#include "testing.h"

namespace {

namespace fs = std::filesystem;

struct Result {
    int status;
    std::string out, err;
};

class Cli : public ::testing::Test {
protected:
    static std::string read(const fs::path& p) { return glint::testing::read_file(p); }
    Result run(const std::string& args) {
        const std::string cmd = std::string("cd '") + dir_.path().string() + "' && '" + GLINT_CLI + "' " +
                                args + " >out.txt 2>err.txt </dev/null";
        const int raw = std::system(cmd.c_str());
        Result r{WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, read(dir_ / "out.txt"),
                 read(dir_ / "err.txt")};
        fs::remove(dir_ / "out.txt");
        fs::remove(dir_ / "err.txt");
        return r;
    }
    void write(const std::string& name, const std::string& text) { std::ofstream(dir_ / name) << text; }
    static std::string seed(const std::string& name) {
        return std::string(GLINT_SOURCE_DIR) + "/scenes/seed/" + name;
    }
    glint::testing::TempDir dir_;
};

TEST_F(Cli, VersionAndHelp) {
    Result r = run("--version");
    EXPECT_EQ(r.status, 0);
    EXPECT_EQ(r.out, std::string("glint ") + GLINT_VERSION + "\n");
    r = run("render --help");
    EXPECT_EQ(r.status, 0);
    for (const char* flag : {"--output", "--width", "--height", "--spp", "--threads", "--seed",
                             "--max-depth", "--aovs", "--quiet"})
        EXPECT_NE(r.out.find(flag), std::string::npos) << flag;
}

TEST_F(Cli, BadSceneFailsAndLeavesTheExistingImageUntouched) {
    write("old.png", "precious bytes");
    write("bad.yaml", "objects:\n  - {type: sphere, center: [0, 0, 1], radius: -2}\n");
    const Result r = run("render bad.yaml -o old.png");
    EXPECT_EQ(r.status, 1);
    EXPECT_EQ(r.err,
              "bad.yaml:2:47: error: radius must be > 0, got -2\n"
              "      - {type: sphere, center: [0, 0, 1], radius: -2}\n"
              "                                                  ^~\n"
              "glint: 1 error; no image written\n");
    EXPECT_EQ(read(dir_ / "old.png"), "precious bytes");
    EXPECT_EQ(dir_.file_count(), 2u);  // nothing else appeared
}

TEST_F(Cli, MissingSceneFileIsAnError) {
    const Result r = run("render nowhere.yaml");
    EXPECT_EQ(r.status, 1);
    EXPECT_EQ(r.err,
              "nowhere.yaml: error: cannot open scene file: No such file or directory\n"
              "glint: 1 error; no image written\n");
}

TEST_F(Cli, AbsurdFilmIsRefusedWithoutAllocating) {
    const Result r = run("render " + seed("fig07-sphere.yaml") +
                         " --width 1000000 --height 1000000 -o big.png");
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("--width must be in [1, 65536], got 1000000"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "big.png"));
    const Result r2 = run("render " + seed("fig07-sphere.yaml") + " --spp 0");
    EXPECT_EQ(r2.status, 1);
    EXPECT_NE(r2.err.find("--spp must be in [1, 1048576], got 0"), std::string::npos) << r2.err;
}

TEST_F(Cli, UnwritableOutputIsRefusedBeforeRendering) {
    Result r = run("render " + seed("fig07-sphere.yaml") + " -o picture.gif");
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("unsupported output format '.gif'"), std::string::npos) << r.err;
    r = run("render " + seed("fig07-sphere.yaml") + " -o missing/dir/a.png");
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("does not exist"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("rendered"), std::string::npos);  // refused before the render
}

TEST_F(Cli, NonNumericFlagIsAnError) {
    const Result r = run("render " + seed("fig07-sphere.yaml") + " --width abc");
    EXPECT_NE(r.status, 0);
    EXPECT_NE(r.err.find("--width"), std::string::npos) << r.err;
}

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

TEST_F(Cli, AovsAreExrChannelsWithHandValues) {
    const Result r = run("render " + seed("fig10-diffuse.yaml") +
                         " --width 161 --height 91 --aovs -q -o aov.exr");
    ASSERT_EQ(r.status, 0) << r.err;
    auto in = OIIO::ImageInput::open((dir_ / "aov.exr").string());
    ASSERT_TRUE(in);
    const auto& spec = in->spec();
    ASSERT_EQ(spec.nchannels, 10);
    // EXR keeps channels by name (files store them sorted): look each one up.
    auto channel = [&spec](const std::string& name) {
        for (int c = 0; c < spec.nchannels; ++c)
            if (spec.channel_name(c) == name) return static_cast<std::size_t>(c);
        ADD_FAILURE() << "no channel " << name;
        return std::size_t{0};
    };
    std::vector<float> px(161 * 91 * 10);
    ASSERT_TRUE(in->read_image(0, 0, 0, 10, OIIO::TypeDesc::FLOAT, px.data()));
    // Centre: the white sphere's front at (0,0,0), distance 1 from the camera at (0,0,-1),
    // normal (0,0,-1), albedo K = 1.
    const float* c = &px[(45 * 161 + 80) * 10];
    EXPECT_NEAR(c[channel("R")], 0.1 + 1 / std::sqrt(3.0), 2e-6);
    EXPECT_EQ(c[channel("albedo.R")], 1.0f);
    EXPECT_EQ(c[channel("albedo.B")], 1.0f);
    EXPECT_NEAR(c[channel("N.Z")], -1, 1e-6);
    EXPECT_NEAR(c[channel("N.X")], 0, 1e-6);
    EXPECT_NEAR(c[channel("Z")], 1, 1e-5);
    // Corner: sky. Albedo is the background colour, normal zero, depth infinite.
    const float* k = &px[0];
    EXPECT_EQ(k[channel("albedo.G")], k[channel("G")]);
    EXPECT_EQ(k[channel("N.Y")], 0.0f);
    EXPECT_TRUE(std::isinf(k[channel("Z")]));
}

TEST_F(Cli, AovsNeedAnExrOutput) {
    const Result r = run("render " + seed("fig10-diffuse.yaml") + " --aovs -o a.png");
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("AOVs (albedo, normal, depth) are written as EXR channels; use an .exr output"),
              std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "a.png"));
}

TEST_F(Cli, QuietPrintsNothing) {
    const Result r = run("render " + seed("fig07-sphere.yaml") + " --width 32 --height 18 -q -o a.png");
    EXPECT_EQ(r.status, 0);
    EXPECT_EQ(r.err, "");
    EXPECT_EQ(r.out, "");
    EXPECT_TRUE(fs::exists(dir_ / "a.png"));
}

TEST_F(Cli, DemoRendersTheBuiltInFigure14) {
    const Result r = run("render --width 64 --height 36 -q");
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(fs::exists(dir_ / "glint.png"));
    // The demo is the fig14 file: same pixels.
    ASSERT_EQ(run("render " + seed("fig14-reflections.yaml") + " --width 64 --height 36 -q -o f.png").status, 0);
    EXPECT_EQ(read(dir_ / "glint.png"), read(dir_ / "f.png"));
}

TEST_F(Cli, OutputDefaultsToTheSceneName) {
    write("tiny.yaml", "film: {width: 8, height: 4}\n");
    const Result r = run("render tiny.yaml -q");
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(fs::exists(dir_ / "tiny.png"));
}

TEST_F(Cli, KilledRenderLeavesTheExistingImageUntouched) {
    write("old.png", "precious bytes");
    const pid_t pid = ::fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
        // A render far too long to finish before the kill: 4096x4096 at 64 spp.
        if (::chdir(dir_.path().c_str()) != 0) ::_exit(126);
        ::execl(GLINT_CLI, GLINT_CLI, "render", "--width", "4096", "--height", "4096", "--spp",
                "64", "-q", "-o", "old.png", static_cast<char*>(nullptr));
        ::_exit(127);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    ::kill(pid, SIGKILL);
    int status = 0;
    ::waitpid(pid, &status, 0);
    ASSERT_TRUE(WIFSIGNALED(status));
    EXPECT_EQ(read(dir_ / "old.png"), "precious bytes");
}

}  // namespace

namespace {

TEST_F(Cli, MeshFilesRenderDirectlyAndInfoAndBenchReportThem) {
    const std::string make = "python3 " + std::string(GLINT_SOURCE_DIR) + "/scripts/make_gltf_scene.py '" +
                             dir_.path().string() + "' > /dev/null";
    ASSERT_EQ(std::system(make.c_str()), 0);
    // A glTF file with its own camera, rendered directly.
    Result r = run("render textured.glb --spp 1 --width 48 --height 32 -o direct.png");
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(fs::exists(dir_ / "direct.png"));
    EXPECT_NE(r.err.find("note: textured.glb: dropped 184 degenerate triangles"), std::string::npos) << r.err;
    // A camera chosen by a name the file does not have: an error, no image.
    r = run("render textured.glb --camera side -o side.png");
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("no camera named 'side'"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "side.png"));
    // info: the numbers of the generated scene (5 meshes of 4,634 triangles, 184 dropped).
    r = run("info textured.gltf");
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("triangles    4450 rendered, 4450 stored"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("meshes       5 (2502 vertices), 5 instances"), std::string::npos) << r.out;
    // The generator's camera: yfov 0.7 rad, at (0, 2.2, -6) in glTF, so z = 6 in glint's frame.
    EXPECT_NE(r.out.find("cameras      main (perspective, 40.1 degrees) at [0, 2.2, 6]"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("(used)"), std::string::npos) << r.out;
    // Khronos' Cameras: two unnamed cameras at one place, perspective then orthographic; only
    // the first is used.
    r = run("info '" + std::string(GLINT_SOURCE_DIR) + "/tests/data/khronos/Cameras.gltf'");
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("(perspective, 40.1 degrees) at [0.5, 0.5, -3] looking [0, 0, 1] (used)\n"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("(orthographic, 2 high) at [0.5, 0.5, -3] looking [0, 0, 1]\n"), std::string::npos) << r.out;
    // bench: one line per backend built in, with the same hit counts.
    r = run("bench textured.glb --width 32 --height 24 --runs 1 --threads 1");
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("\nbvh "), std::string::npos) << r.out;
#if GLINT_EMBREE
    EXPECT_NE(r.out.find("\nembree "), std::string::npos) << r.out;
#endif
    // --accel all adds spatial splits; every backend finds the same hits.
    r = run("bench textured.glb --width 32 --height 24 --runs 1 --threads 1 --accel all");
    EXPECT_EQ(r.status, 0) << r.err;
    const auto hits_of = [&](const std::string& backend) {
        const std::size_t line = r.out.find("\n" + backend + " ");
        if (line == std::string::npos) return std::string("(no line)");
        const std::size_t h = r.out.find("(hits:", line);
        return r.out.substr(h, r.out.find('\n', h) - h);
    };
    EXPECT_EQ(hits_of("sbvh"), hits_of("bvh")) << r.out;
    EXPECT_NE(r.out.find("mesh bvh: "), std::string::npos) << r.out;
    r = run("info textured.gltf --accel sbvh");
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("acceleration (sbvh)"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find(" kernel, depth "), std::string::npos) << r.out;
    // GLINT_ISA picks a lower kernel, and names the choices when it is not one of them.
    ::setenv("GLINT_ISA", "sse4", 1);
    r = run("info textured.gltf");
    EXPECT_NE(r.out.find("4-wide, sse4 kernel"), std::string::npos) << r.out;
    ::setenv("GLINT_ISA", "avx9", 1);
    r = run("info textured.gltf");
    ::unsetenv("GLINT_ISA");
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("GLINT_ISA=avx9: expected sse4, avx2 or avx512"), std::string::npos) << r.err;
    r = run("render textured.glb --accel rtx");
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("--accel: unknown backend 'rtx' (known: bvh, sbvh, embree)"), std::string::npos) << r.err;
}

}  // namespace
