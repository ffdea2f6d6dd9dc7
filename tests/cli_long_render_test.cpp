// End-to-end tests of the glint command over long renders (see the comment below).
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
#include <vector>

#include <OpenImageIO/imageio.h>

#include "cli_fixture.h"

using namespace glint_cli_test;
// Long renders: progressive passes, interruption, checkpoints, time budgets and the live view,
// each through the real binary in a child process.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>

#include <atomic>
#include <cstring>
#include <map>

#include "glint/session/checkpoint.h"

namespace {

class LongRender : public Cli {
protected:
    // Starts glint in the test's folder (the shell execs it: the pid is glint's).
    pid_t start(const std::string& args) {
        const std::string cmd = std::string("cd '") + dir_.path().string() + "' && exec '" + GLINT_CLI + "' " +
                                args + " >>out.txt 2>>err.txt </dev/null";
        const pid_t pid = ::fork();
        if (pid == 0) {
            ::execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
            ::_exit(127);
        }
        return pid;
    }
    static int wait_for(pid_t pid) {
        int status = 0;
        ::waitpid(pid, &status, 0);
        return WIFEXITED(status) ? WEXITSTATUS(status) : 1000 + WTERMSIG(status);
    }
    // Waits (up to 60 s) until `file` exists with a modification time other than `before`, or
    // the child has exited; true if it did appear.
    bool wait_for_file(pid_t pid, const fs::path& file, fs::file_time_type before) {
        for (int i = 0; i < 6000; ++i) {
            std::error_code ec;
            if (fs::exists(file, ec) && fs::last_write_time(file, ec) != before) return true;
            int status;
            if (::waitpid(pid, &status, WNOHANG) == pid) {
                exited_status_ = WIFEXITED(status) ? WEXITSTATUS(status) : 1000 + WTERMSIG(status);
                return false;
            }
            std::this_thread::sleep_for(std::chrono::milliseconds(10));
        }
        return false;
    }
    static std::vector<float> pixels(const fs::path& file, std::map<std::string, std::string>* meta = nullptr) {
        auto in = OIIO::ImageInput::open(file.string());
        if (!in) return {};
        const OIIO::ImageSpec& spec = in->spec();
        std::vector<float> v(static_cast<std::size_t>(spec.width) * spec.height * spec.nchannels);
        in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, v.data());
        if (meta) {
            for (const auto& p : spec.extra_attribs) (*meta)[p.name().string()] = p.get_string();
        }
        return v;
    }
    int exited_status_ = -1;
    const std::string cornell_ = std::string(GLINT_SOURCE_DIR) + "/scenes/cornell-box.yaml";
};

// The renders these tests stop and resume: long enough to be stopped several times, a quarter of
// the samples under the sanitizers, where each sample costs 5-20 times more.
const std::string kLongSpp = glint::testing::kSanitized ? "64" : "256";
// The one stopped three times needs three checkpoints before the end: passes double, so each
// doubling of the spp adds one. At 256 spp a quiet machine finished after two (2026-11-28, once
// the path tracer was 15 % faster); 1024 leaves two more.
const std::string kThreeStopSpp = glint::testing::kSanitized ? "64" : "1024";

// Interrupted by SIGINT, then SIGTERM, then SIGKILL, each time resumed from the checkpoint: the
// final image is the uninterrupted one, bit for bit. After SIGINT and SIGTERM the exit status is
// 3 and the image of the completed passes is whole; after SIGKILL the last checkpoint is whole.
TEST_F(LongRender, InterruptedAndResumedRendersEqualTheUninterruptedOne) {
    const std::string scene = cornell_ + " --width 96 --height 72 --spp " + kThreeStopSpp + " --threads 2";
    ASSERT_EQ(run("render " + scene + " -q -o full.exr").status, 0);
    const std::vector<float> full = pixels(dir_ / "full.exr");
    ASSERT_FALSE(full.empty());

    const fs::path ckpt = dir_ / "c.ckpt";
    const int signals[] = {SIGINT, SIGTERM, SIGKILL};
    int interrupted = 0, status = -1;
    for (int round = 0; round < 12; ++round) {
        const fs::file_time_type before = fs::exists(ckpt) ? fs::last_write_time(ckpt) : fs::file_time_type{};
        const std::string resume = round == 0 ? "--checkpoint c.ckpt" : "--resume c.ckpt";
        exited_status_ = -1;
        const pid_t pid = start("render " + scene + " -o part.exr --checkpoint-every 0.15 " + resume);
        if (!wait_for_file(pid, ckpt, before)) {  // it finished before a new checkpoint
            status = exited_status_;
            break;
        }
        const int sig = signals[interrupted % 3];
        ::kill(pid, sig);
        status = wait_for(pid);
        if (status == 0) break;  // it had just finished
        ++interrupted;
        // Whatever the signal, the checkpoint on disk is whole.
        const glint::Checkpoint c = glint::read_checkpoint(ckpt);
        EXPECT_GT(c.state.spp_done, 0);
        const auto temporaries = [&] {
            std::vector<fs::path> t;
            for (const auto& e : fs::directory_iterator(dir_.path()))
                if (e.path().extension() == ".tmp") t.push_back(e.path());
            return t;
        };
        if (sig == SIGKILL) {
            EXPECT_EQ(status, 1000 + SIGKILL);
            // A process killed outright may leave the temporary file it was writing (never a
            // truncated image or checkpoint); cleared here so the check below means something.
            for (const fs::path& t : temporaries()) fs::remove(t);
        } else {
            EXPECT_TRUE(temporaries().empty());
            EXPECT_EQ(status, 3) << read(dir_ / "err.txt");
            std::map<std::string, std::string> meta;
            EXPECT_EQ(pixels(dir_ / "part.exr", &meta).size(), full.size());  // whole, readable
            EXPECT_EQ(meta["glint:spp"], std::to_string(c.state.spp_done));
            EXPECT_EQ(meta["glint:complete"], "no");
        }
    }
    const std::string log = read(dir_ / "err.txt");  // what the interrupted runs said
    // A slow build (the sanitizers') may not finish within the rounds: the last resume runs to the end.
    if (status != 0 && interrupted > 0) status = run("render " + scene + " -q -o part.exr --resume c.ckpt").status;
    EXPECT_EQ(status, 0) << read(dir_ / "err.txt");
    EXPECT_GE(interrupted, 3) << "the render finished too soon to be interrupted by each signal";
    const std::vector<float> part = pixels(dir_ / "part.exr");
    ASSERT_EQ(part.size(), full.size());
    EXPECT_EQ(0, std::memcmp(part.data(), full.data(), full.size() * sizeof(float)));
    for (const auto& e : fs::directory_iterator(dir_.path()))  // no temporary file left behind
        EXPECT_NE(e.path().extension(), ".tmp") << e.path();
    EXPECT_NE(log.find("interrupted by SIGINT"), std::string::npos) << log;
    EXPECT_NE(log.find("interrupted by SIGTERM"), std::string::npos) << log;
}

// An animated scene for the --frames tests: a camera on a smooth path, a sphere moving up, a box
// turning, lit by the sky and path traced.
const char* kAnimatedScene =
    "animation: {fps: 24}\n"
    "camera: {type: look_at, from: {keyframes: [[0, [0, 1, -6]], [2, [2, 1.5, -5]], [5, [3, 1, -5]]], "
    "interpolation: smooth}, to: [0, 0.5, 0], fov: 40}\n"
    "film: {width: 64, height: 48}\n"
    "integrator: {type: path}\n"
    "background: {type: sky}\n"
    "objects:\n"
    "  - {type: plane, point: [0, 0, 0], normal: [0, 1, 0]}\n"
    "  - {type: sphere, center: {keyframes: [[0, [0, 1, 0]], [5, [0, 2, 0]]]}, radius: 1,\n"
    "     material: {type: diffuse, albedo: [0.8, 0.1, 0.1]}}\n"
    "  - {type: box, min: [-0.5, 0, -0.5], max: [0.5, 1, 0.5],\n"
    "     transform: [{rotate: {angle: {keyframes: [[0, 0], [5, 90]]}, axis: [0, 1, 0]}}, {translate: [2, 0, 0]}]}\n";

// A job killed in the middle of an animation (SIGINT, then SIGKILL) goes on where it stopped: the
// frames on disk are whole and skipped, the interrupted frame is not written, and every frame in
// the end is the uninterrupted job's, bit for bit.
TEST_F(LongRender, AnAnimationStoppedMidwayGoesOnWhereItStopped) {
    write("anim.yaml", kAnimatedScene);
    const std::string scene = "anim.yaml --spp " + kLongSpp + " --threads 2";
    ASSERT_EQ(run("render " + scene + " --frames 0:5 -q -o full_%d.exr").status, 0) << read(dir_ / "err.txt");
    std::vector<std::vector<float>> full;
    for (int f = 0; f <= 5; ++f) full.push_back(pixels(dir_ / ("full_" + std::to_string(f) + ".exr")));
    for (int f = 1; f <= 5; ++f) EXPECT_NE(full[0], full[static_cast<std::size_t>(f)]) << "frame " << f << " did not move";

    const auto frames_on_disk = [&] {
        int n = 0;
        for (int f = 0; f <= 5; ++f) n += fs::exists(dir_ / ("part_" + std::to_string(f) + ".exr"));
        return n;
    };
    int stopped = 0;
    for (const int sig : {SIGINT, SIGKILL}) {
        const int before = frames_on_disk();
        if (before == 6) break;
        const pid_t pid = start("render " + scene + " --frames 0:5 -o part_%d.exr");
        // Stopped once the frame after the first it renders has started.
        if (!wait_for_file(pid, dir_ / ("part_" + std::to_string(before) + ".exr"), {})) continue;
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
        ::kill(pid, sig);
        const int status = wait_for(pid);
        EXPECT_TRUE(status == (sig == SIGINT ? 3 : 1000 + SIGKILL) || status == 0) << status;
        ++stopped;
        for (const auto& e : fs::directory_iterator(dir_.path()))
            if (e.path().extension() == ".tmp") {
                EXPECT_EQ(sig, SIGKILL) << "SIGINT left " << e.path();  // only a killed process may leave one
                fs::remove(e.path());
            }
        for (int f = 0; f <= 5; ++f) {  // what is on disk is whole and right
            const fs::path p = dir_ / ("part_" + std::to_string(f) + ".exr");
            if (fs::exists(p)) EXPECT_EQ(pixels(p), full[static_cast<std::size_t>(f)]) << p;
        }
    }
    EXPECT_GE(stopped, 1) << "the animation finished before it could be stopped";
    // The frames already written are skipped (untouched), the rest rendered.
    std::map<int, fs::file_time_type> written;
    for (int f = 0; f <= 5; ++f) {
        const fs::path p = dir_ / ("part_" + std::to_string(f) + ".exr");
        if (fs::exists(p)) written[f] = fs::last_write_time(p);
    }
    EXPECT_LT(written.size(), 6u);
    const Result r = run("render " + scene + " --frames 0:5 -o part_%d.exr");
    EXPECT_EQ(r.status, 0) << r.err;
    const std::size_t left = 6 - written.size();
    EXPECT_NE(r.err.find(std::to_string(left) + (left == 1 ? " frame" : " frames") + " rendered, " +
                         std::to_string(written.size()) + " skipped"),
              std::string::npos)
        << r.err;
    for (int f = 0; f <= 5; ++f) {
        const fs::path p = dir_ / ("part_" + std::to_string(f) + ".exr");
        EXPECT_EQ(pixels(p), full[static_cast<std::size_t>(f)]) << p;
        if (written.count(f)) EXPECT_EQ(fs::last_write_time(p), written[f]) << "frame " << f << " was rendered again";
    }
}

// --frames: one frame alone is that frame of the sequence; the pattern, the range and the
// options that do not go with it are refused before anything renders.
TEST_F(LongRender, FramesOneFrameAloneAndBadArguments) {
    write("anim.yaml", kAnimatedScene);
    ASSERT_EQ(run("render anim.yaml --spp 4 --frames 1:3 -q -o f%02d.exr").status, 0);
    for (const char* f : {"f01.exr", "f02.exr", "f03.exr"}) EXPECT_TRUE(fs::exists(dir_ / f)) << f;
    ASSERT_EQ(run("render anim.yaml --spp 4 --frames 2 -q -o two.exr").status, 0);
    EXPECT_EQ(pixels(dir_ / "two.exr"), pixels(dir_ / "f02.exr"));
    EXPECT_NE(pixels(dir_ / "f01.exr"), pixels(dir_ / "f02.exr"));
    // Frame 0 without --frames is the scene's first frame.
    ASSERT_EQ(run("render anim.yaml --spp 4 --frames 0 -q -o a.exr").status, 0);
    ASSERT_EQ(run("render anim.yaml --spp 4 -q -o b.exr").status, 0);
    EXPECT_EQ(pixels(dir_ / "a.exr"), pixels(dir_ / "b.exr"));
    const std::size_t files = dir_.file_count();
    const std::pair<const char*, const char*> bad[] = {
        {"--frames 3:1 -o f%d.exr", "--frames 3:1: expected FIRST:LAST"},
        {"--frames x -o f%d.exr", "--frames x: expected FIRST:LAST"},
        {"--frames 0:2 -o f.exr", "-o f.exr: several frames need the frame number in the name"},
        {"--frames 0:2 -o f%d%d.exr", "the frame number may appear once"},
        {"--frames 0:2 -o f%s.exr", "must be %d, %0Nd"},
        {"--frames 0:2", "--frames needs -o"},
        {"--frames 0:2 -o f%d.exr --checkpoint c.ckpt", "--checkpoint and --resume are for one image"},
        {"--frames 0:2 -o f%d.exr --fps 0", "--fps 0: must be a number above 0"},
    };
    for (const auto& [args, message] : bad) {
        const Result r = run(std::string("render anim.yaml ") + args);
        EXPECT_EQ(r.status, 1) << args;
        EXPECT_NE(r.err.find(message), std::string::npos) << args << ": " << r.err;
    }
    EXPECT_EQ(dir_.file_count(), files);  // nothing written
}

// A second SIGINT exits at once (status 130), removes the temporary files and leaves the old
// image as it was.
TEST_F(LongRender, SecondSigintAbortsAtOnceWithoutATruncatedFile) {
    write("old.exr", "precious bytes");
    const pid_t pid = start("render " + cornell_ + " --width 1000 --height 1000 --spp 64 -q -o old.exr "
                            "--checkpoint c.ckpt --checkpoint-every 0");
    ASSERT_TRUE(wait_for_file(pid, dir_ / "c.ckpt", {}));
    ::kill(pid, SIGINT);
    // Two signals sent back to back can merge into one: the second follows once the first has
    // been taken, while the render winds down (abandoning the pass, writing 1000x1000 pixels).
    std::this_thread::sleep_for(std::chrono::milliseconds(30));
    ::kill(pid, SIGINT);
    EXPECT_EQ(wait_for(pid), 130);
    EXPECT_TRUE(read(dir_ / "old.exr") == "precious bytes");
    for (const auto& e : fs::directory_iterator(dir_.path()))
        EXPECT_NE(e.path().extension(), ".tmp") << e.path();
    EXPECT_NO_THROW(glint::read_checkpoint(dir_ / "c.ckpt"));
}

TEST_F(LongRender, ACheckpointOfAnotherRenderIsRefused) {
    const std::string scene = cornell_ + " --width 16";
    ASSERT_EQ(run("render " + scene + " --height 12 --spp 8 -q -o a.exr --checkpoint c.ckpt").status, 0);
    for (const std::string other : {"--height 12 --spp 16", "--height 12 --spp 8 --seed 3", "--height 13 --spp 8",
                                    "--height 12 --spp 8 --aovs",
                                    "--height 12 --spp 8 --noise-threshold 0.1"}) {
        const Result r = run("render " + scene + " " + other + " -o b.exr --resume c.ckpt");
        EXPECT_EQ(r.status, 1) << other;
        EXPECT_NE(r.err.find("c.ckpt: a checkpoint of another scene or other options"), std::string::npos)
            << other << ": " << r.err;
        EXPECT_FALSE(fs::exists(dir_ / "b.exr")) << other;
    }
    // Another scene file (the same scene, one colour changed).
    std::string text = read(cornell_);
    text.replace(text.find("0.63"), 4, "0.64");
    write("edited.yaml", text);
    Result r = run("render edited.yaml --width 16 --height 12 --spp 8 -o b.exr --resume c.ckpt");
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("a checkpoint of another scene"), std::string::npos) << r.err;
    // Not a checkpoint at all; and a missing one.
    write("junk.ckpt", "GLINTCKP but not really");
    r = run("render " + scene + " --height 12 --spp 8 -o b.exr --resume junk.ckpt");
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("junk.ckpt: "), std::string::npos) << r.err;
    r = run("render " + scene + " --height 12 --spp 8 -o b.exr --resume none.ckpt");
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("none.ckpt: no such checkpoint"), std::string::npos) << r.err;
    // The same render resumes: a complete checkpoint just writes its image again.
    r = run("render " + scene + " --height 12 --spp 8 -q -o b.exr --resume c.ckpt");
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(pixels(dir_ / "a.exr"), pixels(dir_ / "b.exr"));
}

TEST_F(LongRender, ATimeBudgetStopsAtAPassAndSaysHowFarItGot) {
    const Result r = run("render " + cornell_ + " --width 64 --height 48 --spp 100000 --time 1s -o t.exr");
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.err.find("(time budget reached)"), std::string::npos) << r.err;
    std::map<std::string, std::string> meta;
    ASSERT_FALSE(pixels(dir_ / "t.exr", &meta).empty());
    EXPECT_EQ(meta["glint:complete"], "no");
    EXPECT_EQ(meta["glint:spp_target"], "100000");
    const int spp = std::stoi(meta["glint:spp"]);
    EXPECT_GT(spp, 0);
    EXPECT_LT(spp, 100000);
    EXPECT_NE(r.err.find("at " + std::to_string(spp) + " spp of 100000"), std::string::npos) << r.err;
    // PNG carries the same metadata.
    ASSERT_EQ(run("render " + cornell_ + " --width 8 --height 6 --spp 4 -q -o t.png").status, 0);
    meta.clear();
    pixels(dir_ / "t.png", &meta);
    EXPECT_EQ(meta["glint:spp"], "4");
    EXPECT_EQ(meta["glint:complete"], "yes");
    // Bad values are refused before rendering.
    EXPECT_EQ(run("render " + cornell_ + " --time 10x -o u.png").status, 1);
    EXPECT_EQ(run("render " + cornell_ + " --noise-threshold -1 -o u.png").status, 1);
    EXPECT_EQ(run("render " + cornell_ + " --min-spp 4 -o u.png").status, 1);
    EXPECT_FALSE(fs::exists(dir_ / "u.png"));
}

TEST_F(LongRender, AdaptiveSamplingWritesTheSampleCounts) {
    const Result r = run("render " + cornell_ +
                         " --width 48 --height 36 --spp 512 --noise-threshold 0.05 --min-spp 8 -o a.exr");
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.err.find("converged"), std::string::npos) << r.err;
    auto in = OIIO::ImageInput::open((dir_ / "a.exr").string());
    ASSERT_TRUE(in);
    const OIIO::ImageSpec spec = in->spec();
    ASSERT_EQ(spec.nchannels, 4);
    EXPECT_EQ(spec.channelnames[3], "spp");
    std::vector<float> v(static_cast<std::size_t>(spec.width) * spec.height * 4);
    in->read_image(0, 0, 0, 4, OIIO::TypeDesc::FLOAT, v.data());
    float lo = 1e9f, hi = 0;
    for (std::size_t i = 3; i < v.size(); i += 4) lo = std::min(lo, v[i]), hi = std::max(hi, v[i]);
    EXPECT_EQ(lo, 8.0f);
    EXPECT_GT(hi, 8.0f);

    // The same from the scene file's sampler; out of range is an error at the value.
    std::string text = read(cornell_);
    const auto at = text.find("sampler:");
    ASSERT_NE(at, std::string::npos);
    text.erase(at, text.find('\n', at) - at);
    write("adaptive.yaml", text + "sampler: {spp: 512, noise_threshold: 0.05, min_spp: 8}\n");
    EXPECT_EQ(run("render adaptive.yaml --width 48 --height 36 -q -o b.exr").status, 0);
    std::vector<float> w(v.size());
    auto again = OIIO::ImageInput::open((dir_ / "b.exr").string());
    ASSERT_TRUE(again);
    ASSERT_EQ(again->spec().nchannels, 4);
    again->read_image(0, 0, 0, 4, OIIO::TypeDesc::FLOAT, w.data());
    EXPECT_EQ(w, v);  // the same render as the flags gave
    write("bad.yaml", text + "sampler: {spp: 512, noise_threshold: 2}\n");
    const Result bad = run("render bad.yaml -o c.exr");
    EXPECT_EQ(bad.status, 1);
    EXPECT_NE(bad.err.find("noise_threshold must be in [0, 1], got 2"), std::string::npos) << bad.err;
}

// A viewer: tev's side of the protocol, decoded here from the bytes (independently of glint's
// encoder), serving one connection.
struct TevReceiver {
    int listener = -1, port = 0;
    std::thread thread;
    std::map<std::string, std::vector<float>> images;  // RGB
    std::map<std::string, std::pair<int, int>> sizes;
    int creates = 0, updates = 0, closes = 0;
    bool hang_up_after_first = false;
    std::string error;

    TevReceiver() {
        listener = ::socket(AF_INET, SOCK_STREAM, 0);
        sockaddr_in a{};
        a.sin_family = AF_INET;
        a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
        ::bind(listener, reinterpret_cast<sockaddr*>(&a), sizeof a);
        ::listen(listener, 1);
        socklen_t len = sizeof a;
        ::getsockname(listener, reinterpret_cast<sockaddr*>(&a), &len);
        port = ntohs(a.sin_port);
    }
    void serve() {
        thread = std::thread([this] {
            const int fd = ::accept(listener, nullptr, nullptr);
            if (fd < 0) return;
            std::vector<char> buf;
            char chunk[65536];
            for (;;) {
                const ssize_t n = ::recv(fd, chunk, sizeof chunk, 0);
                if (n <= 0) break;
                buf.insert(buf.end(), chunk, chunk + n);
                while (buf.size() >= 4) {
                    std::uint32_t size;
                    std::memcpy(&size, buf.data(), 4);
                    if (size < 5) {
                        error = "bad packet size";
                        ::close(fd);
                        return;
                    }
                    if (buf.size() < size) break;
                    decode(std::vector<char>(buf.begin(), buf.begin() + size));
                    buf.erase(buf.begin(), buf.begin() + size);
                    if (hang_up_after_first) {
                        ::close(fd);
                        return;
                    }
                }
            }
            ::close(fd);
        });
    }
    void decode(const std::vector<char>& p) {
        std::size_t at = 5;
        const auto str = [&] {
            std::string s;
            while (at < p.size() && p[at] != '\0') s += p[at++];
            ++at;
            return s;
        };
        const auto i32 = [&] {
            std::int32_t v;
            std::memcpy(&v, p.data() + at, 4);
            at += 4;
            return v;
        };
        const auto i64 = [&] {
            std::int64_t v;
            std::memcpy(&v, p.data() + at, 8);
            at += 8;
            return v;
        };
        switch (p[4]) {
            case 2: ++closes, str(); break;
            case 4: {
                ++creates;
                ++at;  // grab focus
                const std::string name = str();
                const int w = i32(), h = i32(), c = i32();
                for (int k = 0; k < c; ++k) str();
                sizes[name] = {w, h};
                images[name].assign(static_cast<std::size_t>(w) * h * 3, -1.0f);
                break;
            }
            case 6: {
                ++updates;
                ++at;
                const std::string name = str();
                const int c = i32();
                std::vector<std::string> names;
                for (int k = 0; k < c; ++k) names.push_back(str());
                const int x = i32(), y = i32(), w = i32(), h = i32();
                std::vector<std::int64_t> offset(c), stride(c);
                for (auto& o : offset) o = i64();
                for (auto& s : stride) s = i64();
                const float* data = reinterpret_cast<const float*>(p.data() + at);
                const int width = sizes[name].first;
                for (int k = 0; k < c; ++k) {
                    const int ch = names[k] == "R" ? 0 : names[k] == "G" ? 1 : 2;
                    for (int j = 0; j < h; ++j)
                        for (int i = 0; i < w; ++i) {
                            float v;
                            std::memcpy(&v, data + offset[k] + (static_cast<std::int64_t>(j) * w + i) * stride[k], 4);
                            images[name][(static_cast<std::size_t>(y + j) * width + x + i) * 3 + ch] = v;
                        }
                }
                break;
            }
            default: error = "unknown packet type " + std::to_string(p[4]);
        }
    }
    ~TevReceiver() {
        if (thread.joinable()) thread.join();
        ::close(listener);
    }
};

TEST_F(LongRender, TheLiveViewStreamsTheImageAsItForms) {
    TevReceiver tev;
    tev.serve();
    const Result r = run("render " + cornell_ + " --width 40 --height 30 --spp 16 -q -o v.exr --display 127.0.0.1:" +
                         std::to_string(tev.port));
    EXPECT_EQ(r.status, 0) << r.err;
    tev.thread.join();
    EXPECT_EQ(tev.error, "");
    EXPECT_EQ(tev.creates, 1);
    EXPECT_EQ(tev.closes, 1);  // any earlier image of the name, before creating it
    EXPECT_GE(tev.updates, 5);  // passes of 1, 1, 2, 4, 8 samples: one update each
    ASSERT_EQ(tev.images.count("cornell-box.yaml"), 1u);
    const std::vector<float> shown = tev.images["cornell-box.yaml"];
    const std::vector<float> file = pixels(dir_ / "v.exr");
    ASSERT_EQ(shown.size(), file.size());
    EXPECT_EQ(0, std::memcmp(shown.data(), file.data(), file.size() * sizeof(float)));
}

TEST_F(LongRender, AMissingOrVanishingViewerNeverStopsTheRender) {
    TevReceiver closed;  // bound, never accepting: a port with nothing behind it once closed
    const int port = closed.port;
    ::close(closed.listener);
    closed.listener = ::socket(AF_INET, SOCK_STREAM, 0);
    Result r = run("render " + cornell_ + " --width 16 --height 12 --spp 4 -o a.exr --display 127.0.0.1:" +
                   std::to_string(port));
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.err.find("glint: note: display 127.0.0.1:" + std::to_string(port)), std::string::npos) << r.err;
    EXPECT_TRUE(fs::exists(dir_ / "a.exr"));

    TevReceiver rude;
    rude.hang_up_after_first = true;
    rude.serve();
    r = run("render " + cornell_ + " --width 200 --height 150 --spp 8 -o b.exr --display 127.0.0.1:" +
            std::to_string(rude.port));
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.err.find("rendering on without it"), std::string::npos) << r.err;
    EXPECT_TRUE(fs::exists(dir_ / "b.exr"));

    r = run("render " + cornell_ + " --width 16 --height 12 --spp 4 -o c.exr --display nonsense");
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.err.find("expected HOST:PORT"), std::string::npos) << r.err;
}

}  // namespace
