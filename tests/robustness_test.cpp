// Bad input never crashes: thousands of random mutations of the shipped scene files either build
// or fail with a SceneError carrying diagnostics; nothing else escapes, and scenes that do build
// render finite pixels. (A seeded, deterministic fuzz run; fast enough for every `make test`.)
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "glint/builder/build.h"
#include "glint/formats/scene_yaml.h"
#include "glint/render/render.h"
#include "glint/samplers/hash.h"
#include "testing.h"

namespace glint {
namespace {

namespace fs = std::filesystem;

std::string mutate(std::string text, std::uint32_t seed) {
    std::uint32_t n = 0;
    auto next = [&] { return hash_combine(seed, n++); };
    static const char* const kTokens[] = {
        ":", "-", "[", "]", "{", "}", ",", "#", "\"", "'", " ", "\n", "\t", "0", "-1", "1e39",
        ".nan", ".inf", "-0", "1e-39", "999999999999", "type", "sphere", "plane", "radius",
        "material", "&a", "*a", "!!str", "null", "~", "true", "65536", "1e400"};
    const int edits = 1 + static_cast<int>(next() % 4);
    for (int e = 0; e < edits && !text.empty(); ++e) {
        const std::size_t at = next() % text.size();
        switch (next() % 5) {
            case 0: text.erase(at, 1 + next() % 8); break;
            case 1: text.insert(at, kTokens[next() % std::size(kTokens)]); break;
            case 2: text[at] = static_cast<char>(next() % 128); break;
            case 3: {  // duplicate a line
                const std::size_t begin = text.rfind('\n', at) == std::string::npos ? 0 : text.rfind('\n', at) + 1;
                const std::size_t end = text.find('\n', at);
                text.insert(begin, text.substr(begin, (end == std::string::npos ? text.size() : end + 1) - begin));
                break;
            }
            default: {  // replace a number with an extreme one
                const std::size_t digit = text.find_first_of("0123456789", at);
                if (digit != std::string::npos)
                    text.replace(digit, 1, kTokens[13 + next() % 8]);
                break;
            }
        }
    }
    return text;
}

TEST(Robustness, MutatedScenesBuildOrFailCleanly) {
    std::vector<std::string> originals;
    for (const auto& entry : fs::recursive_directory_iterator(fs::path(GLINT_SOURCE_DIR) / "scenes")) {
        if (entry.path().extension() != ".yaml") continue;
        std::ifstream in(entry.path());
        std::ostringstream s;
        s << in.rdbuf();
        originals.push_back(s.str());
    }
    ASSERT_FALSE(originals.empty());
    int failed = 0, built = 0;
    for (std::uint32_t i = 0; i < static_cast<std::uint32_t>(testing::scaled(3000)); ++i) {
        const std::string text = mutate(originals[i % originals.size()], i);
        auto sources = std::make_shared<SourceFiles>();
        try {
            Overrides small;  // keep renders of whatever survives tiny and quick
            small.width = 8;
            small.height = 4;
            small.spp = 1;
            small.max_depth = 3;
            const RenderJob job = build(parse_scene(text, "fuzz.yaml", sources), small, sources);
            Film film(job.film_width, job.film_height);
            render(job.scene, job.camera, *job.integrator, job.options, film);
            // Huge but representable inputs (a colour of 999999999999, or 0.1e39 where a
            // digit of 0.9 became 1e39) may legitimately overflow float arithmetic; every other
            // scene that builds renders finite pixels.
            if (text.find("999999999999") == std::string::npos && text.find("e39") == std::string::npos) {
                for (const Color& c : film.pixels()) ASSERT_TRUE(is_finite(c)) << text;
            }
            ++built;
        } catch (const SceneError& e) {
            ASSERT_FALSE(e.diagnostics().empty());
            ++failed;
        } catch (const std::exception& e) {
            FAIL() << "unexpected exception: " << e.what() << "\n--- scene ---\n" << text;
        }
    }
    EXPECT_GT(failed, testing::scaled(300));  // the mutations do produce errors...
    EXPECT_GT(built, testing::scaled(300));   // ...and plenty of valid variants
}

}  // namespace
}  // namespace glint
