// End-to-end tests of the glint command: exit status, messages, and that nothing is lost.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <thread>
#include <sstream>
#include <vector>

#include "testing.h"

#include "cli_fixture.h"

using namespace glint_cli_test;

namespace {

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

// Every format --list-formats names works: each image extension is written by a render, each
// scene or mesh extension is read as its kind (a mesh renders directly; a scene file's reader is
// the one named: an empty file of it is an error of that reader).
TEST_F(Cli, ListFormatsNamesWhatGlintReadsAndWrites) {
    const Result r = run("render --list-formats");
    ASSERT_EQ(r.status, 0) << r.err;
    std::istringstream lines(r.out);
    std::string line, section;
    int images = 0, scenes = 0;
    while (std::getline(lines, line)) {
        if (line.rfind("  ", 0) != 0) {
            section = line;
            continue;
        }
        std::istringstream words(line);
        std::vector<std::string> w;
        for (std::string x; words >> x;) w.push_back(x);
        if (section.rfind("Images written", 0) == 0) {
            for (const std::string& ext : w) {
                if (ext[0] != '.') break;
                const Result out = run("render " + seed("fig07-sphere.yaml") + " --width 8 --height 8 -q -o x" + ext);
                EXPECT_EQ(out.status, 0) << ext << ": " << out.err;
                EXPECT_TRUE(fs::exists(dir_ / ("x" + ext))) << ext;
                ++images;
            }
        } else if (section.rfind("Scene and mesh files", 0) == 0 && w.size() > 2 && w[1][0] == '.') {
            ++scenes;
            if (w[0] == "yaml" || w[0] == "json") {  // glint's reader: an empty file is "empty"
                write("empty" + w[1], "");
                EXPECT_NE(run("render empty" + w[1]).err.find("the scene file is empty"), std::string::npos) << w[1];
            } else if (w[0] == "pbrt") {  // pbrt-v4's reader: a stray token is not a directive
                write("x.pbrt", "42\n");
                EXPECT_NE(run("render x.pbrt").err.find("expected a directive"), std::string::npos);
            }
        }
    }
    EXPECT_EQ(images, 7);  // .png .exr .jpg .jpeg .hdr .pfm .ppm
    EXPECT_EQ(scenes, 7);  // yaml json pbrt gltf glb obj ply
    // Another extension: a PLY known by its first bytes renders as a mesh.
    write("triangle.data",
          "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
          "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
    const Result mesh = run("render triangle.data --width 8 --height 8 --spp 1 -q -o t.png");
    EXPECT_EQ(mesh.status, 0) << mesh.err;
    EXPECT_TRUE(fs::exists(dir_ / "t.png"));
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
    r = run("render " + seed("fig07-sphere.yaml") + " --width 65536 --height 2 -o wide.jpg");
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("wide.jpg: JPEG holds at most 65500 x 65500 pixels; the image is 65536 x 2"), std::string::npos)
        << r.err;
    EXPECT_EQ(r.err.find("rendered"), std::string::npos);  // refused before the render
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


// Inputs that used to hang or be misread (issue 16's findings): devices and FIFOs named as
// scene, texture or mesh files are refused, not read for ever; values outside the documented
// ranges are errors at the value; a UTF-8 byte-order mark is dropped, UTF-16 refused by name.
namespace {

class HostileInput : public Cli {
protected:
    Result run_limited(const std::string& args) { return run(args, 20); }
};

TEST_F(HostileInput, DevicesAndFifosAreRefusedNotRead) {
    ASSERT_EQ(::mkfifo((dir_ / "scene.yaml").c_str(), 0600), 0);
    Result r = run_limited("render scene.yaml -o a.png");
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("scene.yaml: error: cannot read scene file: it is not a regular file (a device, FIFO or socket)"),
              std::string::npos) << r.err;
    fs::create_symlink("/dev/zero", dir_ / "zero.png");
    fs::create_symlink("/dev/zero", dir_ / "zero.ply");
    write("texture.yaml", "film: {width: 8, height: 6}\nmaterials:\n  m: {color: {type: image, filename: zero.png}}\n"
                          "objects:\n  - {type: sphere, center: [0, 0, 3], radius: 1, material: m}\n");
    r = run_limited("render texture.yaml -o a.png");
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("zero.png': it is not a regular file"), std::string::npos) << r.err;
    write("mesh.yaml", "film: {width: 8, height: 6}\nobjects:\n  - {type: mesh, file: zero.ply}\n");
    r = run_limited("render mesh.yaml -o a.png");
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("zero.ply: cannot read: it is not a regular file"), std::string::npos) << r.err;
    r = run_limited("render zero.ply -o a.png");
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("not a regular file"), std::string::npos) << r.err;
    // A glTF buffer whose uri names a FIFO (tinygltf's own reader opened it and blocked).
    ASSERT_EQ(::mkfifo((dir_ / "buf.bin").c_str(), 0600), 0);
    write("fifo.gltf", R"({"asset": {"version": "2.0"}, "buffers": [{"uri": "buf.bin", "byteLength": 36}],
 "bufferViews": [{"buffer": 0, "byteLength": 36}],
 "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}],
 "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}], "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}], "scene": 0})");
    r = run_limited("render fifo.gltf -o a.png");
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("fifo.gltf: cannot read './buf.bin': it is not a regular file"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "a.png"));
}

TEST_F(HostileInput, ValuesOutsideTheirRangesAreErrorsAtTheValue) {
    write("fov.yaml", "camera: {type: look_at, from: [0, 0, -4], to: [0, 0, 0], fov: 180}\n");
    Result r = run_limited("render fov.yaml -o a.png");
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("fov.yaml:1:63: error: fov must be in (0, 180), got 180"), std::string::npos) << r.err;
    // A glTF perspective camera with yfov 0 (the specification requires > 0).
    write("cam.gltf", R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
  "nodes": [{"camera": 0}],
  "cameras": [{"type": "perspective", "perspective": {"yfov": 0, "znear": 0.1}}]})");
    r = run_limited("render cam.gltf -o a.png");
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("cam.gltf:3:"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("yfov must be in (0, pi) radians, got 0"), std::string::npos) << r.err;
}

TEST_F(HostileInput, ByteOrderMarks) {
    const std::string scene = "film: {width: 8, height: 6}\n";
    write("bom8.yaml", "\xEF\xBB\xBF" + scene);
    EXPECT_EQ(run_limited("render bom8.yaml -q -o a.png").status, 0);
    std::string utf16 = "\xFF\xFE";
    for (char c : scene) utf16 += std::string{c, '\0'};
    write("bom16.yaml", utf16);
    Result r = run_limited("render bom16.yaml -o b.png");
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("bom16.yaml:1:1: error: the file is UTF-16; glint reads scene files as UTF-8: save it as UTF-8"),
              std::string::npos) << r.err;
    write("nul.yaml", utf16.substr(2));
    r = run_limited("render nul.yaml -o b.png");
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("not text (it holds NUL bytes"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "b.png"));
}

}  // namespace

// Issue 16: --restrict-paths keeps every read under the scene's folder and the model search path;
// the limits on what a scene may ask for name the flag that raises them.
namespace {

class UntrustedScene : public Cli {
protected:
    Result run_limited(const std::string& args) { return run(args, 20); }
};

TEST_F(UntrustedScene, RestrictPathsRefusesFilesOutsideTheScenesFolder) {
    fs::create_directories(dir_ / "sub");
    const float tri[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    write("outside.bin", std::string(reinterpret_cast<const char*>(tri), sizeof tri));
    const auto gltf = [](const std::string& uri) {
        return R"({"asset": {"version": "2.0"}, "buffers": [{"uri": ")" + uri + R"(", "byteLength": 36}],
 "bufferViews": [{"buffer": 0, "byteLength": 36}],
 "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}],
 "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}], "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}], "scene": 0})";
    };
    write("sub/up.gltf", gltf("../outside.bin"));
    const std::string small = " --width 16 --height 12 --spp 1";
    EXPECT_EQ(run_limited("render sub/up.gltf -q -o a.png" + small).status, 0);  // by default glint reads it
    Result r = run_limited("render sub/up.gltf --restrict-paths -o b.png");
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("sub/up.gltf: cannot read 'sub/../outside.bin': it is outside the folders --restrict-paths allows ("),
              std::string::npos) << r.err;
    // A symbolic link inside the folder is followed to where it leads.
    fs::create_symlink(dir_ / "outside.bin", dir_ / "sub" / "link.bin");
    write("sub/link.gltf", gltf("link.bin"));
    r = run_limited("render sub/link.gltf --restrict-paths -o b.png");
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("is outside the folders --restrict-paths allows"), std::string::npos) << r.err;
    // A texture named by a YAML scene, by absolute path.
    write("sub/tex.yaml", "film: {width: 8, height: 6}\nmaterials:\n  m: {color: {type: image, filename: " +
                              (dir_ / "outside.png").string() + "}}\n"
                              "objects:\n  - {type: sphere, center: [0, 0, 3], radius: 1, material: m}\n");
    write("outside.png", "not read");
    r = run_limited("render sub/tex.yaml --restrict-paths -o b.png");
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("is outside the folders --restrict-paths allows"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "b.png"));
    // Inside the folder, all is as before.
    fs::copy_file(dir_ / "outside.bin", dir_ / "sub" / "inside.bin");
    write("sub/in.gltf", gltf("inside.bin"));
    EXPECT_EQ(run_limited("render sub/in.gltf --restrict-paths -q -o c.png" + small).status, 0);
}

TEST_F(UntrustedScene, LimitsNameTheFlagThatRaisesThem) {
    write("quad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 3\n");
    Result r = run_limited("render quad.obj --limit triangles=1 -o a.png");
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("2 triangles exceed the limit of 1 (raise it with --limit triangles=N)"), std::string::npos) << r.err;
    EXPECT_EQ(run_limited("render quad.obj --limit triangles=2 -q -o a.png --width 16 --height 12 --spp 1").status, 0);
    r = run_limited("render quad.obj --limit vertices=3 -o b.png");
    EXPECT_NE(r.err.find("4 vertices exceed the limit of 3 (raise it with --limit vertices=N)"), std::string::npos) << r.err;
    // The memory budget: the mesh (4 x 44 + 2 x 80 bytes) fits in 1 kB, the film (64 bytes a pixel) does not.
    r = run_limited("render quad.obj --width 32 --height 32 --limit memory=1KiB -o b.png");
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("the film needs 0.1 MB; with the 0.0 MB asked for before it, that exceeds the memory limit of "
                         "0.0 MB (raise it with --limit memory=N)"),
              std::string::npos) << r.err;
    r = run_limited("render quad.obj --limit frobs=3 -o b.png");
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("unknown limit 'frobs' (known: film-pixels, texture-pixels, triangles, vertices, grid-voxels, "
                         "nesting, includes, memory, nodes)"), std::string::npos) << r.err;
    r = run_limited("render quad.obj --limit triangles=lots -o b.png");
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("'lots' is not a whole number of at least 1"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "b.png"));
}

}  // namespace
