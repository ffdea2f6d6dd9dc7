// The vocabulary table (vocabulary.h) against its three users: the YAML reader must accept
// exactly the table's types, values and keys (each of its "unknown ..." messages lists what it
// knows: the test compares that list with the table's); docs/scene-format.md must name every
// type, value and key in backticks in the section of its kind; the writer's output must read back.
#include "glint/description/vocabulary.h"

#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <tuple>

#include "glint/base/diagnostics.h"
#include "glint/formats/scene_writer.h"
#include "glint/formats/scene_yaml.h"
#include "glint/image/image_io.h"
#include "glint/session/formats.h"

namespace glint {
namespace {

std::string join(const std::vector<std::string>& names) {
    std::string out;
    for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
    return out;
}

// The reader's error text for a scene, or "" if it reads.
std::string errors_of(const std::string& text) {
    try {
        parse_scene(text, "scene.yaml", std::make_shared<SourceFiles>());
    } catch (const SceneError& e) {
        return e.what();
    }
    return "";
}

// "(known: a, b, c)" after the first message matching `start`.
std::string known_after(const std::string& errors, const std::string& start) {
    const std::size_t at = errors.find(start);
    if (at == std::string::npos) return "<no message '" + start + "' in:\n" + errors + ">";
    const std::size_t open = errors.find("(known: ", at);
    const std::size_t close = errors.find(')', open);
    if (open == std::string::npos || close == std::string::npos) return "<no known list in: " + errors + ">";
    return errors.substr(open + 8, close - open - 8);
}

// A scene whose map of `kind` (of type `type`) holds the key `bogus_key`, so that the reader
// lists the keys it knows there.
std::string with_bogus_key(const std::string& kind, const std::string& type) {
    const std::string t = type.empty() ? "" : "type: " + type + ", ";
    if (kind == "scene") return "bogus_key: 1\n";
    if (kind == "animation") return "animation: {bogus_key: 1}\n";
    if (kind == "keyframes") return "camera: {near: {keyframes: [[0, 1]], bogus_key: 1}}\n";
    if (kind == "camera") return "camera: {" + t + "bogus_key: 1}\n";
    if (kind == "film") return "film: {bogus_key: 1}\n";
    if (kind == "filter") return "film: {filter: {" + t + "bogus_key: 1}}\n";
    if (kind == "sampler") return "sampler: {bogus_key: 1}\n";
    if (kind == "integrator") return "integrator: {" + t + "bogus_key: 1}\n";
    if (kind == "background") return "background: {" + t + "bogus_key: 1}\n";
    if (kind == "light") return "lights: [{" + t + "bogus_key: 1}]\n";
    if (kind == "material") return "materials: {m: {" + t + "bogus_key: 1}}\n";
    if (kind == "texture") return "materials: {m: {type: diffuse, albedo: {" + t + "bogus_key: 1}}}\n";
    if (kind == "medium") return "media: {f: {" + t + "bogus_key: 1}}\n";
    if (kind == "object") return "objects: [{" + t + "bogus_key: 1}]\n";
    if (kind == "transform") return "objects: [{type: sphere, transform: {" + type + ": {bogus_key: 1}}}]\n";
    return "";
}

// A scene giving a value set's setting the value `bogus`, and the start of the reader's message.
std::pair<std::string, std::string> with_bogus_value(const std::string& kind) {
    if (kind == "interpolation")
        return {"camera: {near: {keyframes: [[0, 1]], interpolation: bogus}}\n", "unknown interpolation"};
    if (kind == "encoding") return {"film: {encoding: bogus}\n", "unknown encoding"};
    if (kind == "tone_curve") return {"film: {tonemap: bogus}\n", "unknown tonemap"};
    if (kind == "sampler_type") return {"sampler: {type: bogus}\n", "unknown sampler type"};
    if (kind == "strategy") return {"integrator: {type: path, strategy: bogus}\n", "unknown strategy"};
    if (kind == "light_sampler")
        return {"integrator: {type: path, light_sampler: bogus}\n", "unknown light_sampler"};
    if (kind == "texture_filter")
        return {"integrator: {type: path, texture_filter: bogus}\n", "unknown texture_filter"};
    if (kind == "metal") return {"materials: {m: {type: conductor, metal: bogus}}\n", "unknown metal"};
    if (kind == "texture_encoding")
        return {"materials: {m: {type: diffuse, albedo: {type: image, filename: x.png, encoding: bogus}}}\n",
                "unknown encoding"};
    if (kind == "wrap")
        return {"materials: {m: {type: diffuse, albedo: {type: image, filename: x.png, wrap: bogus}}}\n", "unknown wrap"};
    if (kind == "transform")
        return {"objects: [{type: sphere, center: [0, 0, 0], radius: 1, transform: {bogus: 1}}]\n",
                "unknown transform step"};
    if (kind == "alpha_mode")
        return {"objects: [{type: mesh, file: x.ply, alpha: 0.5, alpha_mode: bogus}]\n", "unknown alpha_mode"};
    return {"", ""};
}

std::set<std::string> kinds() {
    std::set<std::string> out;
    for (const VocabularyEntry& e : vocabulary()) out.emplace(e.kind);
    return out;
}

TEST(Vocabulary, TheReaderKnowsExactlyTheTablesKeys) {
    int checked = 0;
    for (const VocabularyEntry& e : vocabulary()) {
        if (e.keys.empty()) continue;
        const std::string text = with_bogus_key(std::string(e.kind), std::string(e.type));
        ASSERT_FALSE(text.empty()) << "no test scene for kind " << e.kind;
        EXPECT_EQ(known_after(errors_of(text), "unknown key 'bogus_key'"),
                  join(vocabulary_keys(e.kind, e.type)))
            << e.kind << " " << e.type << "\n" << text;
        ++checked;
    }
    EXPECT_GE(checked, 50);
}

TEST(Vocabulary, TheReaderKnowsExactlyTheTablesTypesAndValues) {
    for (const std::string& kind : kinds()) {
        const std::vector<std::string> types = vocabulary_types(kind);
        if (types.size() == 1 && types[0].empty()) continue;  // a map without types
        std::string text, start;
        if (const auto [t, s] = with_bogus_value(kind); !t.empty()) {
            text = t;
            start = s;
        } else {
            text = with_bogus_key(kind, "bogus");
            start = "unknown " + kind + " type 'bogus'";
        }
        EXPECT_EQ(known_after(errors_of(text), start), join(types)) << kind << "\n" << text;
    }
}

// The text of docs/scene-format.md from the heading that starts with `heading` to the next
// heading of the same level.
std::string section(const std::string& doc, const std::string& heading) {
    const std::size_t at = doc.find("\n" + heading);
    if (at == std::string::npos) return "";
    const std::size_t level = heading.find(' ');
    const std::size_t end = doc.find("\n" + heading.substr(0, level) + " ", at + 1);
    return doc.substr(at, end == std::string::npos ? std::string::npos : end - at);
}

TEST(Vocabulary, EveryTypeValueAndKeyIsDocumentedInItsSection) {
    std::ifstream in(std::string(GLINT_SOURCE_DIR) + "/docs/scene-format.md");
    ASSERT_TRUE(in) << "docs/scene-format.md";
    std::stringstream ss;
    ss << in.rdbuf();
    const std::string doc = ss.str();
    // Where each kind is documented.
    const std::map<std::string, std::string> where{
        {"scene", "# Scene file format"},  // the whole document: the top-level keys head its sections
        {"animation", "## Animation"},     {"keyframes", "## Animation"},   {"interpolation", "## Animation"},
        {"camera", "## `camera`"},         {"film", "## `film`"},           {"encoding", "## `film`"},
        {"tone_curve", "## `film`"},       {"filter", "## `film`"},         {"sampler", "## `sampler`"},
        {"sampler_type", "## `sampler`"},  {"integrator", "## `integrator`"}, {"strategy", "## `integrator`"},
        {"light_sampler", "## `integrator`"}, {"texture_filter", "## `integrator`"},
        {"background", "## `background`"}, {"light", "## `lights`"},       {"material", "## `materials`"},
        {"metal", "## `materials`"},       {"texture", "## `materials`"},   {"texture_encoding", "## `materials`"},
        {"wrap", "## `materials`"},        {"medium", "## `media`"},        {"object", "## `objects`"},
        {"alpha_mode", "## `objects`"},    {"transform", "### `transform`"},
    };
    for (const VocabularyEntry& e : vocabulary()) {
        const auto w = where.find(std::string(e.kind));
        ASSERT_NE(w, where.end()) << "no section named for kind " << e.kind;
        const std::string text = w->first == "scene" ? doc : section(doc, w->second);
        ASSERT_FALSE(text.empty()) << "docs/scene-format.md has no section '" << w->second << "'";
        // In code: `name`, or an example starting with it (`name: value`, `type: name`).
        const auto named = [&text](std::string_view name) {
            const std::string n(name);
            return text.find("`" + n + "`") != std::string::npos || text.find("`" + n + ":") != std::string::npos ||
                   text.find("`type: " + n + "`") != std::string::npos;
        };
        if (!e.type.empty()) {
            EXPECT_TRUE(named(e.type)) << e.kind << " '" << e.type << "' is not in " << w->second;
        }
        for (std::string_view key : e.keys)
            EXPECT_TRUE(named(key)) << e.kind << " " << e.type << ": key '" << key << "' is not in " << w->second;
    }
}

TEST(Vocabulary, NamesOfEnumerationsFollowTheirOrder) {
    EXPECT_EQ(vocabulary_name(SamplerType::kSobol), "sobol");
    EXPECT_EQ(vocabulary_name(SamplerType::kStratified), "stratified");
    EXPECT_EQ(vocabulary_name(SamplerType::kIndependent), "independent");
    EXPECT_EQ(vocabulary_name(FilterType::kBox), "box");
    EXPECT_EQ(vocabulary_name(FilterType::kTent), "tent");
    EXPECT_EQ(vocabulary_name(FilterType::kGaussian), "gaussian");
    EXPECT_EQ(vocabulary_name(FilterType::kBlackmanHarris), "blackman_harris");
    EXPECT_EQ(vocabulary_name(ToneCurve::kClamp), "clamp");
    EXPECT_EQ(vocabulary_name(ToneCurve::kReinhard), "reinhard");
    EXPECT_EQ(vocabulary_name(ToneCurve::kAces), "aces");
    EXPECT_EQ(vocabulary_name(Encoding::kSrgb), "srgb");
    EXPECT_EQ(vocabulary_name(Encoding::kRaw), "raw");
}

// What the writer writes, the reader reads: every scene of the repository (YAML and pbrt), written
// back as YAML, parses without an error (an unknown key or type would be one).
TEST(Vocabulary, TheWritersOutputReadsBack) {
    const std::filesystem::path root = std::filesystem::path(GLINT_SOURCE_DIR) / "scenes";
    int written = 0;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(root)) {
        const std::string ext = entry.path().extension().string();
        if (ext != ".yaml" && ext != ".pbrt") continue;
        auto sources = std::make_shared<SourceFiles>();
        SceneDescription d;
        try {
            d = read_scene_file(entry.path().string(), sources);
        } catch (const SceneError&) {
            continue;  // a scene that needs files not here (models on the search path) is not the subject
        }
        const std::filesystem::path out = std::filesystem::temp_directory_path() / "glint-vocabulary-test" /
                                          (entry.path().stem().string() + ".yaml");
        std::filesystem::create_directories(out.parent_path());
        WrittenScene w;
        try {
            w = write_scene_yaml(d, out);
        } catch (const IoError&) {
            continue;  // what the writer says it cannot write yet (pbrt's equal-area maps)
        }
        EXPECT_EQ(errors_of(w.yaml), "") << entry.path() << " written as:\n" << w.yaml;
        ++written;
    }
    std::filesystem::remove_all(std::filesystem::temp_directory_path() / "glint-vocabulary-test");
    EXPECT_GE(written, 10);
}

// Keys the writer used to leave out (a YAML scene converted lost its tone curve, a flat integrator
// became whitted, a pbr material its glTF layers): each written and read back to the same value.
TEST(Vocabulary, TheWriterKeepsWhatTheReaderRead) {
    const std::string text =
        "film: {width: 32, height: 16, encoding: raw, tonemap: aces, exposure: 1.5, aovs: true}\n"
        "integrator: {type: path, max_depth: 7, rr_depth: 3, clamp: 10, strategy: light}\n"
        "materials:\n"
        "  p: {type: pbr, base_color: [0.5, 0.5, 0.5], clearcoat: 0.5, clearcoat_roughness: 0.25,\n"
        "      sheen: [0.2, 0.3, 0.4], sheen_roughness: 0.5, specular: 0.7, specular_color: [1, 0.5, 0.25]}\n"
        "objects:\n"
        "  - {type: sphere, center: [0, 0, 3], radius: 1, material: p}\n";
    const auto round_trip = [](const std::string& yaml) {
        const SceneDescription d = parse_scene(yaml, "scene.yaml", std::make_shared<SourceFiles>());
        const std::filesystem::path out = std::filesystem::temp_directory_path() / "glint-writer-test.yaml";
        const std::string written = write_scene_yaml(d, out).yaml;
        return std::pair{d, parse_scene(written, "written.yaml", std::make_shared<SourceFiles>())};
    };
    const auto [a, b] = round_trip(text);
    EXPECT_EQ(b.film.display.encoding, Encoding::kRaw);
    EXPECT_EQ(b.film.display.curve, ToneCurve::kAces);
    EXPECT_EQ(b.film.display.exposure, 1.5f);
    EXPECT_TRUE(b.film.aovs);
    EXPECT_EQ(b.integrator.kind, IntegratorKind::kPath);
    EXPECT_EQ(b.integrator.max_depth.value, 7);
    EXPECT_EQ(b.integrator.path.rr_depth, 3);
    EXPECT_EQ(b.integrator.path.clamp, 10.0f);
    EXPECT_EQ(b.integrator.path.strategy, LightStrategy::kLight);
    ASSERT_EQ(b.materials.size(), 1u);
    const MaterialDesc& m = b.materials[0].material;
    for (const auto& [name, layer, want] :
         {std::tuple{"clearcoat", &m.clearcoat, Color{0.5f}}, {"clearcoat_roughness", &m.clearcoat_roughness, Color{0.25f}},
          {"sheen", &m.sheen, Color{0.2f, 0.3f, 0.4f}}, {"sheen_roughness", &m.sheen_roughness, Color{0.5f}},
          {"specular", &m.specular, Color{0.7f}}, {"specular_color", &m.specular_color, Color{1, 0.5f, 0.25f}}}) {
        ASSERT_TRUE(layer->has_value()) << name;
        EXPECT_EQ((*layer)->value, want) << name;
    }
    for (const char* kind : {"flat", "normals"}) {
        const auto [c, d] = round_trip(std::string("integrator: {type: ") + kind + "}\n");
        EXPECT_EQ(d.integrator.kind, c.integrator.kind) << kind;
    }
    // A checker on uv (pbrt-v4's 2D checkerboard) keeps its space, scales and offsets.
    const auto [u, v] = round_trip(
        "materials:\n  m: {type: diffuse, albedo: {type: checker, size: 0.5, even: [1, 1, 1], odd: [0, 0, 0],\n"
        "      space: uv, uv_scale: [8, 4], uv_offset: [0.25, -0.5]}}\n");
    ASSERT_EQ(v.materials.size(), 1u);
    const CheckerTexture& k = v.materials[0].material.color.checker;
    EXPECT_TRUE(k.on_uv);
    EXPECT_EQ(k.size, 0.5f);
    EXPECT_EQ(k.u_scale, 8.0f);
    EXPECT_EQ(k.v_scale, 4.0f);
    EXPECT_EQ(k.u_offset, 0.25f);
    EXPECT_EQ(k.v_offset, -0.5f);
}

}  // namespace
}  // namespace glint
