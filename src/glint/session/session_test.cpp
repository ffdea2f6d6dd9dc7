// The render session as a second front end uses it (session.h): no command line, no signals,
// hooks for messages, passes and cancellation.
#include "glint/session/session.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <string>

#include "glint/image/image_io.h"
#include "glint/render/render.h"
#include "testing.h"

namespace glint {
namespace {

std::string scene(const std::string& name) { return std::string(GLINT_SOURCE_DIR) + "/scenes/" + name; }

struct Recorder {
    std::string text;
    int passes = 0;
    std::atomic<bool> cancel{false};
    int cancel_after = -1;  ///< set the cancel flag after this many passes
    SessionHooks hooks() {
        SessionHooks h;
        h.print = [this](const std::string& t) { text += t; };
        h.cancel = &cancel;
        h.pass_done = [this](const ProgressiveRender& r, double) {
            ++passes;
            EXPECT_EQ(r.passes(), passes);
            if (passes == cancel_after) cancel = true;
        };
        return h;
    }
};

SessionOptions small(const std::string& name, const std::filesystem::path& out) {
    SessionOptions o;
    o.scene = scene(name);
    o.output = out.string();
    o.width = 32;
    o.height = 24;
    o.spp = 16;
    o.progress = ProgressMode::kQuiet;
    return o;
}

// The session's image is the image of the pieces it is made of: the job load_job builds, rendered
// in one go and written (the progressive passes sum to the one-pass floats: progressive.h).
TEST(Session, RendersWhatItsPiecesRender) {
    testing::TempDir dir;
    Recorder rec;
    const SessionOptions o = small("cornell-box.yaml", dir / "a.exr");
    ASSERT_EQ(RenderSession(o, rec.hooks()).run(), SessionResult::kComplete);
    EXPECT_GE(rec.passes, 1);
    EXPECT_NE(rec.text.find("wrote " + (dir / "a.exr").string()), std::string::npos) << rec.text;

    RenderJob job = load_job(o);
    Film film(job.film_width, job.film_height);
    render(job.scene, job.camera, *job.integrator, job.options, film);
    write_image(dir / "b.exr", film, job.display);
    const Image a = read_image(dir / "a.exr", ImageEncoding::kLinear);
    const Image b = read_image(dir / "b.exr", ImageEncoding::kLinear);
    ASSERT_EQ(a.texels.size(), b.texels.size());
    for (std::size_t i = 0; i < a.texels.size(); ++i) ASSERT_EQ(a.texels[i], b.texels[i]) << i;
}

// In memory (the Python module): a scene read once, rendered twice with the image handed over,
// gives the floats the written file holds, and nothing is written.
TEST(Session, AnImageInMemoryIsTheImageWritten) {
    testing::TempDir dir;
    Recorder rec;
    SessionOptions o = small("cornell-box.yaml", dir / "a.exr");
    ASSERT_EQ(RenderSession(o, rec.hooks()).run(), SessionResult::kComplete);
    const Image written = read_image(dir / "a.exr", ImageEncoding::kLinear);

    o.loaded = std::make_shared<const LoadedScene>(read_scene(o));
    o.output = (dir / "not-written.exr").string();
    for (int run = 0; run < 2; ++run) {
        SessionHooks h = rec.hooks();
        std::vector<Color> pixels;
        ImageMetadata meta;
        h.pass_done = nullptr;
        h.image = [&](const Film& film, const DisplaySettings&, const ImageMetadata& m) {
            pixels.assign(film.pixels().begin(), film.pixels().end());
            meta = m;
        };
        ASSERT_EQ(RenderSession(o, h).run(), SessionResult::kComplete);
        ASSERT_EQ(pixels.size(), written.texels.size());
        for (std::size_t i = 0; i < pixels.size(); ++i) ASSERT_EQ(pixels[i], written.texels[i]) << i;
        EXPECT_NE(std::find(meta.begin(), meta.end(), std::pair<std::string, std::string>("glint:spp", "16")), meta.end());
    }
    EXPECT_FALSE(std::filesystem::exists(dir / "not-written.exr"));
}

TEST(Session, ACancelledSessionWritesNothingBeforeItsFirstPass) {
    testing::TempDir dir;
    Recorder rec;
    rec.cancel = true;
    EXPECT_EQ(RenderSession(small("cornell-box.yaml", dir / "a.exr"), rec.hooks()).run(), SessionResult::kInterrupted);
    EXPECT_FALSE(std::filesystem::exists(dir / "a.exr"));
    EXPECT_EQ(rec.passes, 0);
    EXPECT_NE(rec.text.find("interrupted by a cancellation: no pass completed; nothing written"), std::string::npos)
        << rec.text;
}

TEST(Session, ACancelAfterAPassKeepsThePassesDone) {
    testing::TempDir dir;
    Recorder rec;
    rec.cancel_after = 1;
    SessionOptions o = small("cornell-box.yaml", dir / "a.exr");
    o.spp = 256;  // several passes: the first is small (progressive.h's schedule)
    EXPECT_EQ(RenderSession(o, rec.hooks()).run(), SessionResult::kInterrupted);
    EXPECT_EQ(rec.passes, 1);
    ASSERT_TRUE(std::filesystem::exists(dir / "a.exr"));
    EXPECT_NE(rec.text.find("the image holds 1 passes"), std::string::npos) << rec.text;
}

TEST(Session, ErrorsAreThrownNotPrinted) {
    testing::TempDir dir;
    Recorder rec;
    SessionOptions o = small("cornell-box.yaml", dir / "a.exr");
    o.scene = (dir / "missing.yaml").string();
    EXPECT_THROW(RenderSession(o, rec.hooks()).run(), SceneError);
    EXPECT_EQ(rec.text, "");
}

TEST(Session, ConvertWritesAYamlSceneThatReadsBack) {
    testing::TempDir dir;
    std::string notes;
    const WrittenScene w =
        convert_scene(scene("pbrt/cornell-box.pbrt"), dir / "c.yaml", false, [&](const std::string& n) { notes += n; });
    ASSERT_TRUE(std::filesystem::exists(dir / "c.yaml"));
    SessionOptions o = small("cornell-box.yaml", dir / "c.exr");
    o.scene = (dir / "c.yaml").string();
    EXPECT_NO_THROW(load_job(o));
    EXPECT_THROW(convert_scene(std::string(GLINT_SOURCE_DIR) + "/tests/data/none.ply", dir / "m.yaml", false, nullptr),
                 IoError);
}

}  // namespace
}  // namespace glint
