// Distributed rendering under Open MPI's real mpirun (distributed.h): the image of any number of
// ranks is the single process's to the bit; a stalled rank loses its tiles to the others and the
// image stays the same; a rank that cannot load the scene, or loaded another one, is an error on
// rank 0, never a hang; a rank without the scene's files gets them from rank 0; a job stopped
// by its time budget resumes on another number of ranks; an animation's frames are the single
// process's and the frames written are skipped when the job runs again.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

#include "testing.h"

namespace {

namespace fs = std::filesystem;

struct Result {
    int status;
    std::string err;
};

class Mpi : public ::testing::Test {
protected:
    void SetUp() override {
        if (std::system("command -v mpirun >/dev/null 2>&1") != 0)
            GTEST_SKIP() << "mpirun not found: scripts/install-deps.sh installs Open MPI (openmpi-bin)";
    }
    // Runs `command` in the test's folder with glint's path for {glint}, under a time limit so that
    // a hang fails the test. mpirun refuses root without the first two variables (CI runs as
    // root). For the sanitizer build, two settings let LeakSanitizer tell Open MPI's leftovers
    // from glint's leaks at a fair price: full stacks (fast_unwind_on_malloc=0), in which
    // fuzz/lsan.supp finds an Open MPI library under the frames of components unloaded by then; and
    // PMIx's client library preloaded in every rank. Open MPI 4.1 unloads it at MPI_Finalize with
    // its component (it has no parameter to keep components loaded), and the 3,300 blocks its
    // globals still point to then looked leaked: each a suppression to match through frames of
    // no known library, every lookup a fresh read of /proc/self/maps. Preloaded, it stays mapped,
    // its blocks stay reachable, and a 2-rank render costs 1.6 s instead of 2.3 s (docs/robustness.md).
    Result run(std::string command, int limit = 120) {
        for (std::size_t at; (at = command.find("{glint}")) != std::string::npos;)
            command.replace(at, 7, std::string("'") + GLINT_CLI + "'");
        if (glint::testing::kSanitized)
            for (std::size_t at = 0; (at = command.find("mpirun ", at)) != std::string::npos; at += 7)
                command.insert(at + 7, "-x LD_PRELOAD=libpmix.so.2 ");
        const std::string cmd = "cd '" + dir_.path().string() +
                                "' && export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 "
                                "ASAN_OPTIONS=\"${ASAN_OPTIONS:-}:fast_unwind_on_malloc=0\" && timeout " +
                                std::to_string(limit) + " env " + command + " >/dev/null 2>err.txt </dev/null";
        const int raw = std::system(cmd.c_str());
        Result r{WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, glint::testing::read_file(dir_ / "err.txt")};
        fs::remove(dir_ / "err.txt");
        return r;
    }
    // Every channel of an EXR, as floats.
    std::vector<float> pixels(const std::string& name) {
        auto in = OIIO::ImageInput::open((dir_ / name).string());
        if (!in) return {};
        const OIIO::ImageSpec& spec = in->spec();
        std::vector<float> px(static_cast<std::size_t>(spec.width) * spec.height * spec.nchannels);
        if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, px.data())) return {};
        return px;
    }
    // An EXR's glint:spp attribute (the samples per pixel it holds), or -1.
    long spp_of(const std::string& name) {
        auto in = OIIO::ImageInput::open((dir_ / name).string());
        if (!in) return -1;
        const std::string spp = in->spec().get_string_attribute("glint:spp");
        return spp.empty() ? -1 : std::stol(spp);
    }
    static std::string scene(const std::string& name) { return std::string(GLINT_SOURCE_DIR) + "/scenes/" + name; }
    // anim.yaml: a camera and a sphere moving over frames 0 to 3.
    void write_animation() {
        std::ofstream out(dir_ / "anim.yaml");
        out << "camera: {type: look_at, from: {keyframes: [[0, [0, 1.5, -6]], [3, [3, 1.5, -5]]], interpolation: smooth},\n"
               "         to: [0, 0.8, 0], fov: 40}\n"
               "integrator: {type: path, max_depth: 4}\n"
               "background: {type: constant, color: [0.6, 0.7, 0.9]}\n"
               "objects:\n"
               "  - {type: plane, point: [0, 0, 0], normal: [0, 1, 0]}\n"
               "  - {type: sphere, center: {keyframes: [[0, [0, 1, 0]], [3, [0, 2, 0]]]}, radius: 1,\n"
               "     material: {color: [0.8, 0.2, 0.2]}}\n";
    }
    // The frames rank `rank` rendered, from rank 0's report of an animation by whole frames.
    static long frames_of(const std::string& err, int rank) {
        std::smatch m;
        return std::regex_search(err, m, frame_row(rank)) ? std::stol(m[1]) : -1;
    }
    // Rank `rank`'s busy seconds in rank 0's report of an animation by whole frames.
    static double frame_busy_of(const std::string& err, int rank) {
        std::smatch m;
        return std::regex_search(err, m, frame_row(rank)) ? std::stod(m[2]) : -1;
    }
    // "rank  frames   share   busy (s)   idle (s)": a row's frames and busy seconds.
    static std::regex frame_row(int rank) {
        return std::regex("\n\\s*" + std::to_string(rank) + "\\s+(\\d+)\\s+[\\d.]+ %\\s+([\\d.]+)\\s+[\\d.]+\n");
    }
    // The tiles rank `rank` rendered, from rank 0's report.
    static long tiles_of(const std::string& err, int rank) {
        std::smatch m;
        const std::regex line("\n\\s*" + std::to_string(rank) + "\\s+\\S+\\s+\\d+\\s+(\\d+)\\s");
        return std::regex_search(err, m, line) ? std::stol(m[1]) : -1;
    }
    glint::testing::TempDir dir_;
};

bool same_bits(const std::vector<float>& a, const std::vector<float>& b) {
    return !a.empty() && a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

// The Cornell box by the path tracer (8 spp in passes of 1, 1, 2 and 4), adaptive sampling (its
// per-pixel counts and active flags travel with each pass) and AOVs: 1 to 4 ranks of one
// thread, 12 tiles shared however the ranks asked for them, the same floats as one process.
TEST_F(Mpi, EveryRankCountGivesTheSingleProcessImage) {
    struct Case {
        const char* options;
        std::vector<int> ranks;
    };
    // Under the sanitizers, where each mpirun costs seconds more (LeakSanitizer's scan of Open
    // MPI's leftovers), one rank and an uneven three.
    const Case cases[] = {{"--spp 8", glint::testing::kSanitized ? std::vector<int>{1, 3} : std::vector<int>{1, 2, 3, 4}},
                          {"--spp 64 --noise-threshold 0.05 --min-spp 4", {3}},
                          {"--spp 4 --aovs", {2}},
                          {"--spp 4 --denoise", {2}}};  // rank 0 denoises
    for (const Case& c : cases) {
        SCOPED_TRACE(c.options);
        const std::string render = "{glint} render '" + scene("cornell-box.yaml") + "' --width 64 --height 48 " +
                                   c.options + " --threads 1 -q";
        Result r = run(render + " -o single.exr");
        ASSERT_EQ(r.status, 0) << r.err;
        const std::vector<float> single = pixels("single.exr");
        ASSERT_FALSE(single.empty());
        for (const int n : c.ranks) {
            const std::string out = "ranks" + std::to_string(n) + ".exr";
            r = run("mpirun -np " + std::to_string(n) + " --oversubscribe " + render + " -o " + out);
            ASSERT_EQ(r.status, 0) << n << " ranks: " << r.err;
            EXPECT_TRUE(same_bits(single, pixels(out))) << n << " ranks";
        }
    }
}

// Rank 1 sleeps two seconds before returning its first tiles (GLINT_TEST_STALL, a test-only
// hook); after the 0.2 s timeout rank 0 renders them itself. The image is the same, rank 1's
// share is smaller than rank 0's, and the report says so.
TEST_F(Mpi, AStalledRankGetsFewerTilesAndTheImageIsTheSame) {
    const std::string render = "{glint} render '" + scene("cornell-box.yaml") +
                               "' --width 64 --height 48 --spp 8 --threads 1";
    Result r = run(render + " -q -o single.exr");
    ASSERT_EQ(r.status, 0) << r.err;
    r = run("GLINT_TEST_STALL=1:2 mpirun -np 2 --oversubscribe " + render + " --rank-timeout 0.2 -o stalled.exr");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(same_bits(pixels("single.exr"), pixels("stalled.exr")));
    const long zero = tiles_of(r.err, 0), one = tiles_of(r.err, 1);
    ASSERT_GE(zero, 0) << r.err;
    ASSERT_GE(one, 0) << r.err;
    EXPECT_LT(one, zero) << r.err;
    EXPECT_EQ(zero + one, 4 * 12) << r.err;  // 4 passes of 12 tiles, each counted once
}

// A job stopped by its time budget leaves a checkpoint of the completed passes; another job with
// another number of ranks resumes it, and the image is the single uninterrupted process's.
TEST_F(Mpi, AJobStoppedByItsTimeBudgetResumesOnAnyRankCountToTheSameImage) {
    const std::string render = "{glint} render '" + scene("cornell-box.yaml") +
                               "' --width 64 --height 48 --spp 256 --threads 1";
    Result r = run(render + " -q -o full.exr");
    ASSERT_EQ(r.status, 0) << r.err;
    r = run("mpirun -np 2 --oversubscribe " + render + " --time 0.3 --checkpoint c.ckpt -q -o part.exr");
    ASSERT_EQ(r.status, 0) << r.err;
    const long part = spp_of("part.exr");
    EXPECT_GT(part, 0);
    EXPECT_LT(part, 256) << "the budget did not stop the render, so nothing was resumed";
    r = run("mpirun -np 3 --oversubscribe " + render + " --resume c.ckpt -q -o final.exr");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(spp_of("final.exr"), 256);
    EXPECT_TRUE(same_bits(pixels("full.exr"), pixels("final.exr")));
}

// A scene only rank 0 can read: rank 1 starts in an empty folder, asks rank 0 for the files it
// read (the scene, an image texture, a mesh found through rank 0's GLINT_MODEL_PATH) and renders
// from its copy of them; the image is the single process's and rank 1 took part.
TEST_F(Mpi, ARankWithoutTheFilesGetsThemFromRankZero) {
    const fs::path zero = dir_ / "zero";
    fs::create_directories(zero / "maps");
    fs::create_directories(zero / "models");
    fs::create_directories(dir_ / "one");
    fs::create_directories(dir_ / "tmp1");
    fs::copy_file(fs::path(GLINT_SOURCE_DIR) / "scenes/textures/uv-grid.png", zero / "maps/grid.png");
    const auto write = [](const fs::path& p, const std::string& text) {
        std::ofstream out(p, std::ios::binary);
        out << text;
    };
    write(zero / "models/pyramid.ply",
          "ply\nformat ascii 1.0\nelement vertex 5\nproperty float x\nproperty float y\nproperty float z\n"
          "element face 4\nproperty list uchar int vertex_indices\nend_header\n"
          "-1 0 -1\n1 0 -1\n1 0 1\n-1 0 1\n0 1.5 0\n3 0 1 4\n3 1 2 4\n3 2 3 4\n3 3 0 4\n");
    write(zero / "scene.yaml", R"(camera: {type: look_at, from: [0, 2, -6], to: [0, 0.8, 0], fov: 40}
sampler: {spp: 4}
integrator: {type: path, max_depth: 4}
background: {type: constant, color: [0.6, 0.7, 0.9]}
materials:
  grid: {color: {type: image, filename: maps/grid.png}}
  white: {color: [0.8, 0.8, 0.8]}
objects:
  - {type: plane, point: [0, 0, 0], normal: [0, 1, 0], material: white}
  - {type: sphere, center: [-1.4, 1, 0.5], radius: 1, material: grid}
  - {type: mesh, file: pyramid.ply, material: grid, transform: [{translate: [1.2, 0, 0]}]}
)");
    const std::string options = " render scene.yaml --width 64 --height 48 --spp 512 --threads 1";
    const std::string models = "GLINT_MODEL_PATH='" + (zero / "models").string() + "' ";
    Result r = run("sh -c \"cd zero && " + models + "'" + GLINT_CLI + "'" + options + " -q -o ../single.exr\"");
    ASSERT_EQ(r.status, 0) << r.err;
    r = run("mpirun --oversubscribe -np 1 --wdir zero env " + models + "{glint}" + options +
            " -o ../both.exr : -np 1 --wdir one env TMPDIR='" + (dir_ / "tmp1").string() + "' {glint}" + options + " -o ../both.exr");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(same_bits(pixels("single.exr"), pixels("both.exr")));
    EXPECT_GT(tiles_of(r.err, 1), 0) << r.err;
    EXPECT_TRUE(fs::is_empty(dir_ / "one"));
    EXPECT_TRUE(fs::is_empty(dir_ / "tmp1"));  // rank 1's copy of the files, removed at its end
}

// An animation across ranks: every frame is the single process's, bit for bit, whether frames go
// out whole (at least as many frames as ranks) or each is shared by tiles (fewer); frames already
// written are skipped when the job is run again (here on 3 ranks, one of which has no files and
// loads rank 0's copy for each frame); a stalled rank's frame is rendered again by another; a
// rank with another scene ends the job with its error.
TEST_F(Mpi, AnAnimationAcrossRanksGivesTheSingleProcessFramesAndSkipsWrittenOnes) {
    fs::create_directories(dir_ / "one");
    write_animation();
    // Enough samples that a rank which must first fetch rank 0's files still finds tiles left
    // (below): under the sanitizers' -O2 build, 16 samples were rendered before it was ready.
    const std::string options = std::string(" render anim.yaml --width 48 --height 32 --spp ") +
                                (glint::testing::kSanitized ? "32" : "64") + " --threads 1 --frames 0:3";
    Result r = run("{glint}" + options + " -q -o s_%d.exr");
    ASSERT_EQ(r.status, 0) << r.err;
    // 4 frames, 2 ranks: whole frames.
    r = run("mpirun --oversubscribe -np 2 {glint}" + options + " -o m_%d.exr");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_GT(frames_of(r.err, 1), 0) << r.err;
    EXPECT_EQ(frames_of(r.err, 0) + frames_of(r.err, 1), 4) << r.err;
    for (int f = 0; f <= 3; ++f) {
        const std::string n = std::to_string(f);
        EXPECT_TRUE(same_bits(pixels("s_" + n + ".exr"), pixels("m_" + n + ".exr"))) << "frame " << f;
    }
    EXPECT_FALSE(same_bits(pixels("m_0.exr"), pixels("m_3.exr")));
    // Two frames lost: a job of 3 ranks renders only those (fewer frames than ranks: by tiles),
    // rank 2 from rank 0's files.
    fs::remove(dir_ / "m_1.exr");
    fs::remove(dir_ / "m_3.exr");
    const auto kept = fs::last_write_time(dir_ / "m_2.exr");
    r = run("mpirun --oversubscribe -np 2 {glint}" + options + " -o m_%d.exr : -np 1 --wdir one {glint}" + options +
            " -o m_%d.exr");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.err.find("2 frames rendered, 2 skipped"), std::string::npos) << r.err;
    EXPECT_GT(tiles_of(r.err, 2), 0) << r.err;
    EXPECT_EQ(fs::last_write_time(dir_ / "m_2.exr"), kept);
    for (int f = 0; f <= 3; ++f) {
        const std::string n = std::to_string(f);
        EXPECT_TRUE(same_bits(pixels("s_" + n + ".exr"), pixels("m_" + n + ".exr"))) << "frame " << f;
    }
    EXPECT_TRUE(fs::is_empty(dir_ / "one"));
    // Rank 1 stalls on its first whole frame: rank 0 renders its frames and that one too.
    r = run("mpirun --oversubscribe -np 2 env GLINT_TEST_STALL=1:4 {glint}" + options + " -o d_%d.exr");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_GE(frames_of(r.err, 0), 3) << r.err;
    EXPECT_GE(frame_busy_of(r.err, 1), 4.0) << r.err;  // the stall counts as rank 1's time on its frame
    for (int f = 0; f <= 3; ++f) {
        const std::string n = std::to_string(f);
        EXPECT_TRUE(same_bits(pixels("s_" + n + ".exr"), pixels("d_" + n + ".exr"))) << "frame " << f;
    }
    // Whole frames on a rank without the files: it renders them from rank 0's copy.
    r = run("mpirun --oversubscribe -np 1 {glint}" + options + " -o w_%d.exr : -np 1 --wdir one {glint}" + options +
            " -o w_%d.exr");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_GT(frames_of(r.err, 1), 0) << r.err;
    for (int f = 0; f <= 3; ++f) {
        const std::string n = std::to_string(f);
        EXPECT_TRUE(same_bits(pixels("s_" + n + ".exr"), pixels("w_" + n + ".exr"))) << "frame " << f;
    }
    EXPECT_TRUE(fs::is_empty(dir_ / "one"));
    // A rank with another scene: rank 0 reports it and the job ends (no hang between frames);
    // the frames rank 0 wrote meanwhile are its own, right ones.
    fs::create_directories(dir_ / "other");
    {
        std::ofstream out(dir_ / "other/anim.yaml");
        out << "objects: [{type: sphere, center: [0, 0, 0], radius: 1}]\n";
    }
    r = run("mpirun --oversubscribe -np 1 {glint}" + options + " -o x_%d.exr : -np 1 --wdir other {glint}" + options +
            " -o x_%d.exr", 60);
    EXPECT_EQ(r.status, 1) << r.err;
    EXPECT_NE(r.err.find("glint: error: rank 1: frame "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("differ from rank 0's"), std::string::npos) << r.err;
    for (int f = 0; f <= 3; ++f) {
        const std::string n = std::to_string(f);
        if (fs::exists(dir_ / ("x_" + n + ".exr")))
            EXPECT_TRUE(same_bits(pixels("s_" + n + ".exr"), pixels("x_" + n + ".exr"))) << "frame " << f;
    }
    // Fewer frames than ranks (by tiles): the same error, from the frame's fingerprint.
    const std::string two = std::regex_replace(options, std::regex("0:3"), "0:1");
    r = run("mpirun --oversubscribe -np 1 {glint}" + two + " -o y_%d.exr : -np 3 --wdir other {glint}" + two +
            " -o y_%d.exr", 60);
    EXPECT_EQ(r.status, 1) << r.err;
    EXPECT_NE(r.err.find("differ from rank 0's"), std::string::npos) << r.err;
}

// SIGUSR1 to mpirun (forwarded to every rank) stops an animation rendered by whole frames: the
// frames finished are written, rank 0's frame in flight is not, the exit status is 3; the same
// command run again renders only the rest, and every frame is the single process's.
TEST_F(Mpi, AnAnimationStoppedBySigusr1GoesOnWhereItStopped) {
    write_animation();
    // Long enough to be stopped after a frame; a quarter of the samples under the sanitizers.
    const std::string options = std::string(" render anim.yaml --width 48 --height 32 --spp ") +
                                (glint::testing::kSanitized ? "128" : "512") + " --threads 1 --frames 0:7";
    Result r = run("{glint}" + options + " -q -o s_%d.exr", 300);
    ASSERT_EQ(r.status, 0) << r.err;
    // The signal goes as soon as a frame has been written (mpirun's stderr is watched for it).
    r = run("sh -c \"mpirun --oversubscribe -np 2 {glint}" + options +
                " -o m_%d.exr 2>job.txt & p=\\$!; until grep -q 'written by rank' job.txt || ! kill -0 \\$p; do sleep 0.1; done; "
                "kill -USR1 \\$p; wait \\$p; s=\\$?; cat job.txt >&2; exit \\$s\"",
            300);
    EXPECT_EQ(r.status, 3) << r.err;
    EXPECT_NE(r.err.find("interrupted by SIGUSR1"), std::string::npos) << r.err;
    int written = 0;
    for (int f = 0; f <= 7; ++f) written += fs::exists(dir_ / ("m_" + std::to_string(f) + ".exr")) ? 1 : 0;
    EXPECT_GE(written, 1);
    EXPECT_LT(written, 8) << r.err;
    r = run("mpirun --oversubscribe -np 2 {glint}" + options + " -o m_%d.exr", 300);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.err.find(std::to_string(8 - written) + " frame"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(std::to_string(written) + " skipped"), std::string::npos) << r.err;
    for (int f = 0; f <= 7; ++f) {
        const std::string n = std::to_string(f);
        EXPECT_TRUE(same_bits(pixels("s_" + n + ".exr"), pixels("m_" + n + ".exr"))) << "frame " << f;
    }
    for (const auto& e : fs::directory_iterator(dir_.path()))
        EXPECT_EQ(e.path().string().find(".tmp"), std::string::npos) << e.path();
}

// Each rank loads the scene itself: a rank that cannot (here: another file, missing) or that
// loaded a different render (another seed) is reported by rank 0, which writes nothing and exits
// with an error; the job ends instead of waiting for the rank.
TEST_F(Mpi, ARankWithoutTheSceneOrWithAnotherOneIsAnErrorNotAHang) {
    const std::string good = "{glint} render '" + scene("cornell-box.yaml") + "' --width 64 --height 48 --spp 4 --threads 1";
    Result r = run("mpirun -np 1 " + good + " -o a.exr : -np 1 {glint} render nowhere.yaml --threads 1 -o a.exr", 60);
    EXPECT_NE(r.status, 0);
    EXPECT_NE(r.err.find("glint: error: rank 1: "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("nowhere.yaml"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "a.exr"));

    r = run("mpirun -np 1 " + good + " -o b.exr : -np 1 " + good + " --seed 7 -o b.exr", 60);
    EXPECT_NE(r.status, 0);
    EXPECT_NE(r.err.find("differ from rank 0's"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "b.exr"));
}

}  // namespace
