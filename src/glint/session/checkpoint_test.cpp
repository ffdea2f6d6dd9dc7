#include "glint/session/checkpoint.h"

#include <gtest/gtest.h>

#include <cstring>
#include <fstream>

#include "glint/image/image_io.h"
#include "glint/formats/scene_yaml.h"
#include "testing.h"

namespace glint {
namespace {

ProgressiveState small_state(bool adaptive, bool aovs) {
    ProgressiveState s;
    s.width = 3;
    s.height = 2;
    s.spp_target = 16;
    s.spp_done = 4;
    s.passes = 3;
    s.adaptive = adaptive;
    s.aovs = aovs;
    s.seconds = 1.5;
    s.rays = 12345;
    s.allocate();
    for (std::size_t i = 0; i < s.pixels(); ++i) {
        s.sum[i] = Color{0.1f * i, 0.2f, -0.0f};
        s.weight[i] = 4.0f + i;
        if (adaptive) s.samples[i] = static_cast<std::uint32_t>(i), s.active[i] = i % 2;
        if (aovs) s.depth[i] = 1.0f / (i + 1), s.odd_albedo[i] = Color{0.25f, 0.01f * i, 0.5f};
        if (s.halves()) s.odd_sum[i] = Color{0.05f * i, 0.1f, 0.0f}, s.odd_weight[i] = 2.0f + i;
    }
    return s;
}

std::string bytes_of(const std::filesystem::path& p) { return glint::testing::read_file(p); }
void put_bytes(const std::filesystem::path& p, const std::string& b) {
    std::ofstream(p, std::ios::binary) << b;
}

TEST(Checkpoint, RoundTripsEveryPlaneBitForBit) {
    glint::testing::TempDir dir;
    for (bool adaptive : {false, true}) {
        for (bool aovs : {false, true}) {
            const ProgressiveState s = small_state(adaptive, aovs);
            write_checkpoint(dir / "c.ckpt", 0xfeedULL, s);
            const Checkpoint c = read_checkpoint(dir / "c.ckpt");
            EXPECT_EQ(c.fingerprint, 0xfeedULL);
            const ProgressiveState& r = c.state;
            EXPECT_EQ(r.width, 3);
            EXPECT_EQ(r.spp_done, 4);
            EXPECT_EQ(r.passes, 3);
            EXPECT_EQ(r.adaptive, adaptive);
            EXPECT_EQ(r.aovs, aovs);
            EXPECT_EQ(r.seconds, 1.5);
            EXPECT_EQ(r.rays, 12345u);
            EXPECT_EQ(0, std::memcmp(r.sum.data(), s.sum.data(), s.sum.size() * sizeof(Color)));
            EXPECT_EQ(r.odd_weight, s.odd_weight);
            ASSERT_EQ(r.odd_sum.size(), s.odd_sum.size());
            if (!s.odd_sum.empty())  // (memcmp of two null pointers is undefined, even for 0 bytes)
                EXPECT_EQ(0, std::memcmp(r.odd_sum.data(), s.odd_sum.data(), s.odd_sum.size() * sizeof(Color)));
            EXPECT_EQ(r.samples, s.samples);
            EXPECT_EQ(r.active, s.active);
            EXPECT_EQ(r.depth, s.depth);
            ASSERT_EQ(r.odd_albedo.size(), s.odd_albedo.size());
            if (!s.odd_albedo.empty())
                EXPECT_EQ(0, std::memcmp(r.odd_albedo.data(), s.odd_albedo.data(), s.odd_albedo.size() * sizeof(Color)));
            // 72-byte header, 16 bytes a pixel (+16 odd samples with either, +5 adaptive, +44 AOVs), 8-byte checksum.
            EXPECT_EQ(bytes_of(dir / "c.ckpt").size(), 72 + 6 * (16 + (adaptive || aovs ? 16 : 0) + (adaptive ? 5 : 0) + (aovs ? 44 : 0)) + 8);
            EXPECT_EQ(dir.file_count(), 1u);  // no temporary file left
        }
    }
}

TEST(Checkpoint, DamagedOrForeignFilesAreLocatedErrors) {
    glint::testing::TempDir dir;
    write_checkpoint(dir / "c.ckpt", 1, small_state(true, false));
    const std::string good = bytes_of(dir / "c.ckpt");
    const auto error_of = [&](const std::string& bytes) {
        put_bytes(dir / "x.ckpt", bytes);
        try {
            read_checkpoint(dir / "x.ckpt");
        } catch (const IoError& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    std::string flipped = good;
    flipped[100] ^= 0x10;  // inside the planes
    EXPECT_NE(error_of(flipped).find("byte " + std::to_string(good.size() - 8) + ": checksum mismatch"),
              std::string::npos)
        << error_of(flipped);
    EXPECT_NE(error_of(good.substr(0, good.size() - 1)).find("truncated or damaged"), std::string::npos);
    EXPECT_NE(error_of(good.substr(0, 40)).find("too short"), std::string::npos);
    EXPECT_NE(error_of("P6\n" + good.substr(3)).find("byte 0: not a glint checkpoint"), std::string::npos);
    std::string version = good;
    version[8] = 9;
    EXPECT_NE(error_of(version).find("byte 8: checkpoint version 9"), std::string::npos);
    // A header claiming a 2^20 x 2^20 film: refused from the sizes, before any allocation.
    std::string huge = good;
    const std::int32_t big = 1 << 20;
    std::memcpy(&huge[24], &big, 4);
    std::memcpy(&huge[28], &big, 4);
    EXPECT_NE(error_of(huge).find("byte 64:"), std::string::npos) << error_of(huge);
    std::string zero = good;
    std::memset(&zero[24], 0, 4);
    EXPECT_NE(error_of(zero).find("byte 24: film 0x2 out of range"), std::string::npos);
    EXPECT_NE(error_of("").find("too short"), std::string::npos);
    EXPECT_THROW(read_checkpoint(dir / "missing.ckpt"), IoError);
    EXPECT_THROW(read_checkpoint(dir.path()), IoError);  // a folder
}

TEST(Checkpoint, DurationsParse) {
    EXPECT_EQ(parse_duration("90", "t"), 90);
    EXPECT_EQ(parse_duration("90s", "t"), 90);
    EXPECT_EQ(parse_duration("10m", "t"), 600);
    EXPECT_EQ(parse_duration("1h30m", "t"), 5400);
    EXPECT_EQ(parse_duration("2.5h", "t"), 9000);
    EXPECT_EQ(parse_duration("1d", "t"), 86400);
    EXPECT_EQ(parse_duration("0.25", "t"), 0.25);
    for (const char* bad : {"", "-5", "10x", "1h30", "m", "nan", "inf", "1e999", " 5", "5 m"})
        EXPECT_THROW(parse_duration(bad, "--time"), IoError) << bad;
    try {
        parse_duration("ten", "--time");
    } catch (const IoError& e) {
        EXPECT_STREQ(e.what(), "--time: 'ten' is not a duration (examples: 90, 90s, 10m, 1h30m, 2.5h)");
    }
}

// The fingerprint follows what changes the image: the settings text, the scene text, a mesh's
// vertices, the camera; not the path the scene was read from.
TEST(Checkpoint, FingerprintFollowsTheSceneAndTheSettings) {
    glint::testing::TempDir dir;
    const std::string scene =
        "film: {width: 8, height: 6}\n"
        "camera: {position: [0, 0, -3], direction: [0, 0, 1]}\n"
        "objects:\n  - {type: triangle, vertices: [[0, 0, 0], [1, 0, 0], [0, 1, 0]]}\n";
    const auto fingerprint = [&](const std::string& text, const std::string& name, const std::string& settings) {
        std::ofstream(dir / name) << text;
        auto sources = std::make_shared<SourceFiles>();
        const RenderJob job = build(load_scene_file((dir / name).string(), sources), {}, sources);
        return render_fingerprint(job, settings);
    };
    const std::uint64_t base = fingerprint(scene, "a.yaml", "spp 4");
    EXPECT_EQ(base, fingerprint(scene, "a.yaml", "spp 4"));
    EXPECT_EQ(base, fingerprint(scene, "b.yaml", "spp 4"));  // moved: the same render
    EXPECT_NE(base, fingerprint(scene, "a.yaml", "spp 5"));
    std::string moved = scene;
    moved.replace(moved.find("[1, 0, 0]"), 9, "[1, 0, 1]");
    EXPECT_NE(base, fingerprint(moved, "a.yaml", "spp 4"));
    std::string camera = scene;
    camera.replace(camera.find("-3"), 2, "-4");
    EXPECT_NE(base, fingerprint(camera, "a.yaml", "spp 4"));
}

TEST(Checkpoint, HashSeesEveryByte) {
    std::string s(37, 'a');
    const std::uint64_t h = hash_bytes(s.data(), s.size());
    for (std::size_t i = 0; i < s.size(); ++i) {
        std::string t = s;
        t[i] = 'b';
        EXPECT_NE(h, hash_bytes(t.data(), t.size())) << i;
    }
    EXPECT_NE(h, hash_bytes(s.data(), s.size() - 1));
    EXPECT_NE(h, hash_bytes(s.data(), s.size(), 1));
}

}  // namespace
}  // namespace glint
