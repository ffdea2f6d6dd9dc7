// Every scene file shipped in scenes/, and the example scene in README.md, loads and builds:
// the documentation cannot drift from the format.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "glint/io/build.h"
#include "glint/io/scene_yaml.h"

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

}  // namespace
}  // namespace glint
