// glTF alpha modes, texture-coordinate sets, KHR_mesh_quantization and required extensions, on the
// model scripts/make_gltf_alpha.py writes (its docstring gives every number checked here).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <cstdlib>
#include <fstream>
#include <random>
#include <sstream>

#include "glint/builder/build.h"
#include "glint/assets/mesh_import.h"
#include "glint/formats/scene_yaml.h"
#include "testing.h"

namespace glint {
namespace {

class GltfAlpha : public ::testing::TestWithParam<AccelKind> {
protected:
    void SetUp() override {
        const std::string cmd = "python3 " + std::string(GLINT_SOURCE_DIR) + "/scripts/make_gltf_alpha.py " +
                                dir_.path().string() + " > /dev/null";
        ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
    }
    RenderJob load(const std::string& yaml_extra = "") {
        std::ofstream(dir_ / "scene.yaml") << "integrator: {type: path}\nobjects:\n  - {type: mesh, file: alpha.gltf"
                                           << yaml_extra << "}\n";
        auto sources = std::make_shared<SourceFiles>();
        Overrides o;
        o.accel = GetParam();
        return build(load_scene_file((dir_ / "scene.yaml").string(), sources), o, sources);
    }
    testing::TempDir dir_;
};

// A ray straight down the z axis through (x, y) of the plane z = 0 (the quads' plane: glint's
// mirror of the glTF frame keeps it).
Ray down(float x, float y) { return Ray{{x, y, 5}, {0, 0, -1}}; }

TEST_P(GltfAlpha, MaskCutsTheTexturesHolesForCameraAndShadowRays) {
    const RenderJob job = load();
    const Scene& s = job.scene;
    for (int i = 0; i < 4; ++i) {
        for (int j = 0; j < 4; ++j) {
            const Ray r = down(i + 0.5f, 3.5f - j);  // texel (i, j)'s centre
            const bool opaque = (i + j) % 2 == 0;
            const auto hit = s.intersect(r);
            EXPECT_EQ(hit.has_value(), opaque) << i << "," << j;
            if (hit) {
                EXPECT_NEAR(hit->t, 5, 1e-4);
            }
            EXPECT_EQ(s.occluded(r), opaque) << i << "," << j;  // shadow rays see the same holes
            EXPECT_EQ(s.intersect_brute_force(r).has_value(), opaque);
        }
    }
}

TEST_P(GltfAlpha, VertexAlphaIsCutAtTheCutoff) {
    // fade: alpha = (x - 20) / 4 from COLOR_0, cut at 0.5 (x = 22).
    const RenderJob job = load();
    for (const float x : {20.3f, 21.0f, 21.9f, 22.1f, 23.0f, 23.7f}) {
        EXPECT_EQ(job.scene.intersect(down(x, 2)).has_value(), x > 22) << x;
        EXPECT_EQ(job.scene.occluded(down(x, 2)), x > 22) << x;
    }
}

TEST_P(GltfAlpha, BlendLetsThroughOneMinusAlphaOfTheRays) {
    // veil: BLEND with alpha 0.25. Over n random rays the hits are binomial(n, 0.25): sd
    // sqrt(n p (1 - p)); 5 sd bounds a correct renderer fails once in 3 million runs.
    const RenderJob job = load();
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(0.01f, 0.99f);
    const int n = 20000;
    int hits = 0, blocked = 0;
    for (int k = 0; k < n; ++k) {
        // Through a random point of the quad, from a random direction above it.
        const Point3 target{10 + 4 * u(rng), 4 * u(rng), 0};
        const Vector3 d = normalize(Vector3{u(rng) - 0.5f, u(rng) - 0.5f, -1});
        const Ray r{target - d * 5, d};
        hits += job.scene.intersect(r).has_value();
        blocked += job.scene.occluded(r);
    }
    const double sd = std::sqrt(n * 0.25 * 0.75);
    EXPECT_NEAR(hits, 0.25 * n, 5 * sd);
    EXPECT_NEAR(blocked, 0.25 * n, 5 * sd);
}

TEST_P(GltfAlpha, TexturesReadTheTexCoordSetTheyName) {
    // second: TEXCOORD_0 is (0, 0) everywhere; the texture reads TEXCOORD_1, so each texel shows
    // where it is: (i % 2, j % 2, 1) (0 and 255 decode to 0 and 1 exactly).
    const RenderJob job = load();
    const Scene& s = job.scene;
    for (int i = 0; i < 4; ++i) {
        for (int j = 0; j < 4; ++j) {
            const Ray r = down(30 + i + 0.5f, 3.5f - j);
            const auto hit = s.intersect(r);
            ASSERT_TRUE(hit);
            const SurfaceInteraction si = s.interaction(r, *hit);
            const auto* pbr = std::get_if<PbrMaterial>(&s.materials[si.material]);
            ASSERT_TRUE(pbr);
            const Color c = s.texture(pbr->base_color, si);
            EXPECT_NEAR(c.r, i % 2, 1e-5) << i << "," << j;
            EXPECT_NEAR(c.g, j % 2, 1e-5) << i << "," << j;
            EXPECT_NEAR(c.b, 1, 1e-5);
        }
    }
}

TEST_P(GltfAlpha, QuantizedPositionsAreScaledByTheirNode) {
    // packed: unsigned shorts (80 + 2 cx, 2 cy) scaled by 0.5: the quad x in [40, 44], y in [0, 4].
    const RenderJob job = load();
    EXPECT_TRUE(job.scene.intersect(down(40.2f, 0.2f)));
    EXPECT_TRUE(job.scene.intersect(down(43.8f, 3.8f)));
    EXPECT_FALSE(job.scene.intersect(down(44.2f, 2)));
    EXPECT_FALSE(job.scene.intersect(down(42, 4.2f)));
}

TEST_P(GltfAlpha, AnObjectsOwnMaterialReplacesTheFilesAlphaAndItsOwnAlphaWins) {
    // A scene material replaces the file's materials, and with them their cut-outs: every texel
    // of the fence is solid. An object `alpha` applies to every mesh of the file.
    const RenderJob solid = load(", material: {type: diffuse}");
    EXPECT_TRUE(solid.scene.intersect(down(1.5f, 3.5f)));  // texel (1, 0): a hole in the file's material
    const RenderJob gone = load(", alpha: 0");
    for (const float x : {0.5f, 12.0f, 32.0f, 42.0f}) EXPECT_FALSE(gone.scene.intersect(down(x, 3.5f))) << x;
}

#if GLINT_EMBREE
INSTANTIATE_TEST_SUITE_P(Backends, GltfAlpha, ::testing::Values(AccelKind::kBvh, AccelKind::kEmbree));
#else
INSTANTIATE_TEST_SUITE_P(Backends, GltfAlpha, ::testing::Values(AccelKind::kBvh));
#endif

TEST(GltfExtensions, ARequiredExtensionGlintLacksIsALocatedErrorAndAUsedOneANote) {
    testing::TempDir dir;
    const std::string cmd = "python3 " + std::string(GLINT_SOURCE_DIR) + "/scripts/make_gltf_alpha.py " +
                            dir.path().string() + " > /dev/null";
    ASSERT_EQ(std::system(cmd.c_str()), 0);
    const ImportedFile ok = import_gltf(dir / "alpha.gltf");  // KHR_mesh_quantization is required and known
    EXPECT_TRUE(ok.notes.empty());
    std::string text = testing::read_file(dir / "alpha.gltf");
    const auto write = [&](const std::string& name, const std::string& t) { std::ofstream(dir / name) << t; };
    // extensionsRequired is written before extensionsUsed (make_gltf_alpha.py keeps key order).
    std::string required = text;
    const auto at = required.find("\"extensionsRequired\"");
    ASSERT_NE(at, std::string::npos);
    const auto q = required.find("KHR_mesh_quantization", at);
    required.replace(q, std::string("KHR_mesh_quantization").size(), "KHR_texture_basisu");
    write("required.gltf", required);
    try {
        import_gltf(dir / "required.gltf");
        ADD_FAILURE() << "no error";
    } catch (const IoError& e) {
        const std::string m = e.what();
        // The line of the entry in the file.
        const int line = 1 + static_cast<int>(std::count(required.begin(), required.begin() + q, '\n'));
        EXPECT_NE(m.find(fmt::format("required.gltf:{}:", line)), std::string::npos) << m;
        EXPECT_NE(m.find("requires the extension KHR_texture_basisu"), std::string::npos) << m;
    }
    std::string used = text;
    const auto u = used.find("\"extensionsUsed\": [");
    ASSERT_NE(u, std::string::npos);
    used.insert(u + std::string("\"extensionsUsed\": [").size(), "\"KHR_materials_variants\", ");
    write("used.gltf", used);
    const ImportedFile f = import_gltf(dir / "used.gltf");
    ASSERT_EQ(f.notes.size(), 1u);
    EXPECT_NE(f.notes[0].find("uses the extension KHR_materials_variants, which glint ignores"), std::string::npos);
    std::string mode = text;
    const auto b = mode.find("\"BLEND\"");
    mode.replace(b, 7, "\"SOFT\"");
    write("mode.gltf", mode);
    try {
        import_gltf(dir / "mode.gltf");
        ADD_FAILURE() << "no error";
    } catch (const IoError& e) {
        // Refused by the specification's rules, at the value, before the material is read.
        EXPECT_NE(std::string(e.what()).find("].alphaMode: \"SOFT\" is not one of the values glTF allows"), std::string::npos)
            << e.what();
    }
}

}  // namespace
}  // namespace glint

namespace glint {
namespace {

// KHR_materials_clearcoat, _sheen and _specular on the Khronos Box (its one material extended):
// factors land in the material's textures, out-of-range values are located errors.
TEST(GltfExtensions, ClearcoatSheenAndSpecularMapOntoThePbrMaterial) {
    testing::TempDir dir;
    const std::string box = testing::read_file(std::filesystem::path(GLINT_SOURCE_DIR) / "tests/data/khronos/Box.gltf");
    const auto with = [&](const std::string& extensions) {
        std::string t = box;
        const std::string key = "\"pbrMetallicRoughness\": {";
        t.insert(t.find(key), "\"extensions\": {" + extensions + "},\n            ");
        std::ofstream(dir / "box.gltf") << t;
        return dir / "box.gltf";
    };
    const ImportedFile f = import_gltf(with(
        R"("KHR_materials_clearcoat": {"clearcoatFactor": 0.75, "clearcoatRoughnessFactor": 0.25},
           "KHR_materials_sheen": {"sheenColorFactor": [0.5, 0.25, 1], "sheenRoughnessFactor": 0.4},
           "KHR_materials_specular": {"specularFactor": 0.3, "specularColorFactor": [2, 1, 0.5]})"));
    const MaterialDesc& d = f.materials.at(0).desc;
    ASSERT_TRUE(d.clearcoat && d.clearcoat_roughness && d.sheen && d.sheen_roughness && d.specular && d.specular_color);
    EXPECT_EQ(d.clearcoat->value, Color{0.75f});
    EXPECT_EQ(d.clearcoat_roughness->value, Color{0.25f});
    EXPECT_EQ(d.sheen->value, (Color{0.5f, 0.25f, 1}));
    EXPECT_EQ(d.sheen_roughness->value, Color{0.4f});
    EXPECT_EQ(d.specular->value, Color{0.3f});
    EXPECT_EQ(d.specular_color->value, (Color{2, 1, 0.5f}));
    // A zero clear coat or black sheen is no layer at all.
    const ImportedFile none = import_gltf(with(R"("KHR_materials_clearcoat": {}, "KHR_materials_sheen": {})"));
    EXPECT_FALSE(none.materials.at(0).desc.clearcoat);
    EXPECT_FALSE(none.materials.at(0).desc.sheen);
    // A texCoord far outside int's range, or not a whole number: an error at it, not a cast.
    // (On BoxTextured, which has a texture 0.)
    const std::string textured =
        testing::read_file(std::filesystem::path(GLINT_SOURCE_DIR) / "tests/data/khronos/BoxTextured.gltf");
    for (const char* tc : {"1e300", "2.5", "-3"}) {
        std::string t = textured;
        const std::string key = "\"pbrMetallicRoughness\": {";
        t.insert(t.find(key), fmt::format(R"("extensions": {{"KHR_materials_clearcoat": {{"clearcoatFactor": 1, "clearcoatTexture": {{"index": 0, "texCoord": {}}}}}}},)", tc));
        std::ofstream(dir / "textured.gltf") << t;
        try {
            import_gltf(dir / "textured.gltf");
            ADD_FAILURE() << "no error for texCoord " << tc;
        } catch (const IoError& e) {
            EXPECT_NE(std::string(e.what()).find("texCoord"), std::string::npos) << e.what();
        }
    }
    try {
        import_gltf(with(R"("KHR_materials_clearcoat": {"clearcoatFactor": 1.5})"));
        ADD_FAILURE() << "no error";
    } catch (const IoError& e) {
        EXPECT_NE(std::string(e.what()).find("clearcoatFactor must be a number in [0, 1]"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("box.gltf:"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace glint
