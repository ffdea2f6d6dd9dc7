// Every scene file shipped in scenes/, and the example scene in README.md, loads and builds:
// the documentation cannot drift from the format.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "glint/builder/build.h"
#include "glint/image/image_io.h"
#include "glint/formats/scene_yaml.h"
#include "testing.h"

namespace glint {
namespace {

namespace fs = std::filesystem;

TEST(Scenes, EveryShippedSceneLoadsAndBuilds) {
    int count = 0;
    for (const auto& entry : fs::recursive_directory_iterator(fs::path(GLINT_SOURCE_DIR) / "scenes")) {
        if (entry.path().extension() != ".yaml") continue;
        auto sources = std::make_shared<SourceFiles>();
        EXPECT_NO_THROW(build(load_scene_file(entry.path().string(), sources), {}, sources))
            << entry.path();
        ++count;
    }
    EXPECT_GE(count, 6);
}

// The first ```yaml block after `marker` in a document of the repository.
std::string yaml_block(const std::string& document, const std::string& marker) {
    std::ifstream in(fs::path(GLINT_SOURCE_DIR) / document);
    std::ostringstream text;
    text << in.rdbuf();
    const std::string doc = text.str();
    const auto at = doc.find(marker);
    if (at == std::string::npos) return "";
    const auto start = doc.find("```yaml\n", at);
    if (start == std::string::npos) return "";
    const auto body = start + 8;
    return doc.substr(body, doc.find("```", body) - body);
}

TEST(Scenes, SceneFormatCompleteExampleLoadsAndBuilds) {
    const std::string yaml = yaml_block("docs/scene-format.md", "## A complete example");
    ASSERT_FALSE(yaml.empty());
    auto sources = std::make_shared<SourceFiles>();
    const RenderJob job = build(parse_scene(yaml, "scene-format.md", sources), {}, sources);
    EXPECT_EQ(job.scene.spheres.size(), 9u);
    EXPECT_EQ(job.scene.planes.size(), 1u);
}

TEST(Scenes, SceneFormatKeyframesExampleLoadsAndBuildsAtEveryFrame) {
    const std::string yaml = yaml_block("docs/scene-format.md", "## Animation: keyframes");
    ASSERT_FALSE(yaml.empty());
    for (double frame : {0.0, 10.5, 24.0, 47.0, 60.0}) {
        auto sources = std::make_shared<SourceFiles>();
        EXPECT_NO_THROW(build(parse_scene(yaml, "scene-format.md", sources, frame), {}, sources)) << frame;
    }
}

TEST(Scenes, ReadmeExampleLoadsAndBuilds) {
    std::ifstream in(fs::path(GLINT_SOURCE_DIR) / "README.md");
    std::ostringstream text;
    text << in.rdbuf();
    const std::string readme = text.str();
    const std::string marker = "A scene is a YAML file:\n\n```yaml\n";
    const auto begin = readme.find(marker);
    ASSERT_NE(begin, std::string::npos);
    const auto start = begin + marker.size();
    const std::string yaml = readme.substr(start, readme.find("```", start) - start);
    auto sources = std::make_shared<SourceFiles>();
    const RenderJob job = build(parse_scene(yaml, "README.md", sources), {}, sources);
    EXPECT_EQ(job.scene.spheres.size(), 1u);
    EXPECT_EQ(job.scene.planes.size(), 1u);
}

// scenes/textures/sky.exr is committed so that scenes/materials.yaml renders from a fresh clone;
// it must be exactly what tools/make_sky.cpp writes.
TEST(Scenes, CommittedSkyIsWhatTheGeneratorWrites) {
    testing::TempDir dir;
    const std::string out = (dir / "sky.exr").string();
    ASSERT_EQ(std::system((std::string(GLINT_MAKE_SKY) + " " + out).c_str()), 0);
    const Image fresh = read_image(out, ImageEncoding::kLinear);
    const Image committed =
        read_image(fs::path(GLINT_SOURCE_DIR) / "scenes/textures/sky.exr", ImageEncoding::kLinear);
    ASSERT_EQ(fresh.width, committed.width);
    ASSERT_EQ(fresh.height, committed.height);
    for (std::size_t i = 0; i < fresh.texels.size(); ++i) {
        for (int k = 0; k < 3; ++k) {
            ASSERT_NEAR(fresh.texels[i][k], committed.texels[i][k], 1e-5f * (1 + fresh.texels[i][k]))
                << "texel " << i;
        }
    }
}

}  // namespace
}  // namespace glint
