// The library's layers (docs/architecture.md, "Layers"): a file may include files of its own
// folder and of lower layers only. The exceptions are listed here, each with its reason; a new
// upward include fails this test, naming the file and what it includes.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <string>

namespace {

namespace fs = std::filesystem;

// Lowest first. Folders of src/glint/, and the headers at its top by file name.
const std::map<std::string, int> kLayer{
    {"base", 0},       {"math", 0},        {"spectra", 1},    {"ray.h", 1},      {"interaction.h", 1}, {"samplers", 2},
    {"shapes", 3},     {"textures", 3},    {"film", 3},       {"denoise", 3},       {"media", 4},
    {"materials", 5},
    {"lights", 5},     {"cameras", 5},     {"background.h", 5}, {"accel", 6},       {"scene.h", 7},
    {"integrators", 8}, {"render", 9},     {"image", 10},     {"description", 11},  {"assets", 12},
    {"formats", 13},   {"demo_scene.h", 13}, {"builder", 14}, {"session", 15},
};

// The upward includes kept, and why (docs/architecture.md says the same).
const std::set<std::pair<std::string, std::string>> kKept{
    // Embree's scene is built from the render-time scene's arrays, and its filter callback asks
    // Scene::alpha_keeps whether a cut-out mesh is there.
    {"accel/embree.cpp", "scene.h"},
    // The light sampler's build walks the scene's emitters (shapes whose material emits).
    {"lights/light_sampler.cpp", "scene.h"},
    // make_bsdf evaluates a material's textures, which the scene owns (images by id).
    {"materials/make_bsdf.h", "scene.h"},
};

// The layer of a path relative to src/glint: its folder's, or (at the top) its file's.
int layer_of(const fs::path& rel, std::string& unit) {
    const std::string first = rel.begin()->string();
    unit = std::distance(rel.begin(), rel.end()) > 1 ? first : rel.filename().string();
    if (unit == "background.cpp") unit = "background.h";
    // The scene's sources beside scene.h: scene.cpp, scene_motion.cpp (and its test).
    if (unit == "scene.cpp" || unit == "scene_motion.cpp" || unit == "scene_motion_test.cpp") unit = "scene.h";
    const auto it = kLayer.find(unit);
    return it == kLayer.end() ? -1 : it->second;
}

TEST(SourceLayers, NoFileIncludesAHigherLayer) {
    const fs::path root = fs::path(GLINT_SOURCE_DIR) / "src" / "glint";
    const std::regex include(R"re(^#include "glint/([^"]+)")re");
    int files = 0;
    std::set<std::pair<std::string, std::string>> kept_seen;
    for (const auto& entry : fs::recursive_directory_iterator(root)) {
        if (!entry.is_regular_file()) continue;
        const fs::path rel = fs::relative(entry.path(), root);
        const std::string name = rel.filename().string();
        if (name.find("_test.") != std::string::npos) continue;  // tests may use anything
        const std::string ext = rel.extension().string();
        if (ext != ".h" && ext != ".cpp" && ext != ".inl") continue;
        std::string unit;
        const int from = layer_of(rel, unit);
        ASSERT_GE(from, 0) << rel << " is in no layer: add its folder to kLayer and to docs/architecture.md";
        ++files;
        std::ifstream in(entry.path());
        for (std::string line; std::getline(in, line);) {
            std::smatch m;
            if (!std::regex_search(line, m, include)) continue;
            std::string to_unit;
            const int to = layer_of(fs::path(m[1].str()), to_unit);
            ASSERT_GE(to, 0) << rel << " includes " << m[1] << ", in no layer";
            if (to_unit == unit || to <= from) continue;
            const std::pair<std::string, std::string> edge{rel.generic_string(), m[1].str()};
            if (kKept.count(edge)) {
                kept_seen.insert(edge);
                continue;
            }
            ADD_FAILURE() << rel.generic_string() << " (" << unit << ", layer " << from << ") includes "
                          << m[1] << " (" << to_unit << ", layer " << to << ")";
        }
    }
    EXPECT_GT(files, 150);
    EXPECT_EQ(kept_seen, kKept) << "an exception no longer needed: remove it here and in docs/architecture.md";
}

}  // namespace
