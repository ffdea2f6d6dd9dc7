// The glTF importer on the scene scripts/make_gltf_scene.py writes (values checked against the
// script's numbers, worked out by hand), .gltf against .glb, and the failure modes.
#include <gtest/gtest.h>

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <fmt/format.h>
#include <fstream>
#include <numbers>
#include <sstream>

#include "glint/builder/build.h"
#include "glint/assets/mesh_import.h"
#include "glint/formats/scene_yaml.h"
#include "testing.h"

namespace glint {
namespace {

constexpr double kPi = std::numbers::pi;

class Gltf : public ::testing::Test {
protected:
    void SetUp() override {
        const std::string cmd = "python3 " + std::string(GLINT_SOURCE_DIR) + "/scripts/make_gltf_scene.py " +
                                dir_.path().string() + " > /dev/null";
        ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
    }
    std::string read(const std::string& name) {
        std::ifstream in(dir_ / name, std::ios::binary);
        std::ostringstream s;
        s << in.rdbuf();
        return s.str();
    }
    void write(const std::string& name, const std::string& text) { std::ofstream(dir_ / name, std::ios::binary) << text; }
    std::string error_of(const std::string& name) {
        try {
            import_gltf(dir_ / name);
        } catch (const IoError& e) {
            return e.what();
        }
        return "(no error)";
    }
    testing::TempDir dir_;
};

const ImportedMaterial& named(const ImportedFile& f, const std::string& name) {
    for (const auto& m : f.materials)
        if (m.name == name) return m;
    throw std::runtime_error("no material " + name);
}

TEST_F(Gltf, MaterialsMapOntoPbrWithTheirTexturesAndExtensions) {
    const ImportedFile f = import_gltf(dir_ / "textured.gltf");
    ASSERT_EQ(f.materials.size(), 5u);
    for (const auto& m : f.materials) EXPECT_EQ(m.desc.kind, MaterialDesc::Kind::kPbr) << m.name;
    // tiles: base colour texture tiled 4 times by KHR_texture_transform, mirrored repeat. In
    // glint's uv (v up): u' = 4u, v' = 1 - 4 (1 - v) = 4v - 3.
    const MaterialDesc& tiles = named(f, "tiles").desc;
    ASSERT_EQ(tiles.color.kind, TextureDesc::Kind::kImage);
    EXPECT_EQ(tiles.color.uv_transform, (std::array<Float, 6>{4, 0, 0, 0, 4, -3}));
    EXPECT_EQ(tiles.color.wrap, WrapMode::kMirror);
    EXPECT_EQ(tiles.color.wrap_v, WrapMode::kMirror);
    ASSERT_TRUE(tiles.color.pixels);
    EXPECT_EQ(tiles.color.pixels->width, 64);
    // Texel (0, 0) is (230, 200, 150) in sRGB: decoded to linear.
    EXPECT_NEAR(tiles.color.pixels->texels[0].r, std::pow((230 / 255.0 + 0.055) / 1.055, 2.4), 1e-5);
    EXPECT_FLOAT_EQ(tiles.roughness, 0.8f);
    // brushed metal: factors, and the metallic-roughness map (linear, clamp in u, repeat in v).
    const MaterialDesc& metal = named(f, "brushed metal").desc;
    EXPECT_FLOAT_EQ(metal.metallic, 1);
    ASSERT_TRUE(metal.metallic_roughness);
    EXPECT_EQ(metal.metallic_roughness->wrap, WrapMode::kClamp);
    EXPECT_EQ(metal.metallic_roughness->wrap_v, WrapMode::kRepeat);
    EXPECT_NEAR(metal.metallic_roughness->pixels->texels[0].g, 38 / 255.0, 1e-6);  // not sRGB-decoded
    EXPECT_FLOAT_EQ(metal.color.value.g, 0.8f);  // a factor alone is a constant
    // glass: KHR_materials_transmission and KHR_materials_ior.
    const MaterialDesc& glass = named(f, "glass").desc;
    EXPECT_FLOAT_EQ(glass.transmission, 1);
    EXPECT_FLOAT_EQ(glass.ior, 1.45f);
    // ... and KHR_materials_volume: what is left after 0.5 units is the attenuation colour.
    ASSERT_TRUE(glass.interior);
    EXPECT_NEAR(std::exp(-glass.interior->sigma_a.r * 0.5f), 0.9f, 1e-6f);
    EXPECT_NEAR(std::exp(-glass.interior->sigma_a.g * 0.5f), 0.5f, 1e-6f);
    EXPECT_NEAR(std::exp(-glass.interior->sigma_a.b * 0.5f), 0.25f, 1e-6f);
    EXPECT_EQ(glass.interior->sigma_s, Color{0});
    EXPECT_FALSE(named(f, "tiles").desc.interior);
    // lamp: emissive factor 1 times KHR_materials_emissive_strength 4, with its texture.
    const MaterialDesc& lamp = named(f, "lamp").desc;
    EXPECT_FLOAT_EQ(lamp.emission.radiance.g, 4);
    EXPECT_TRUE(lamp.emission_map);
    // bumpy: the normal map.
    EXPECT_TRUE(named(f, "bumpy").desc.normal_map);
    EXPECT_FALSE(named(f, "tiles").desc.normal_map);
}

TEST_F(Gltf, DispersionIsAnAbbeNumberAboutTheIor) {
    // KHR_materials_dispersion: dispersion = 20 / V_d, about KHR_materials_ior's index at 587.56 nm.
    std::string text = read("textured.gltf");
    const auto at = text.find("\"KHR_materials_ior\":");  // in the glass material (not extensionsUsed)
    ASSERT_NE(at, std::string::npos);
    text.insert(at, "\"KHR_materials_dispersion\": {\"dispersion\": 0.5}, ");
    write("dispersive.gltf", text);
    const ImportedFile f = import_gltf(dir_ / "dispersive.gltf");
    const MaterialDesc& glass = named(f, "glass").desc;
    ASSERT_TRUE(glass.ior_spectrum);
    const Spectrum& n = *glass.ior_spectrum;
    EXPECT_NEAR(n(587.56f), glass.ior, 1e-5);
    EXPECT_NEAR((glass.ior - 1) / (n(486.13f) - n(656.27f)), 20 / 0.5, 1e-3);
    EXPECT_FALSE(named(f, "tiles").desc.ior_spectrum);
}

TEST_F(Gltf, NodeHierarchyCameraAndLightArePlacedInGlintsFrame) {
    const ImportedFile f = import_gltf(dir_ / "textured.gltf");
    ASSERT_EQ(f.nodes.size(), 5u);
    ASSERT_EQ(f.meshes.size(), 5u);
    // The metal ball: (0.3, 0.5, 0) inside a group rotated 40 degrees about y and scaled 1.2,
    // then z negated: R_y(40) (0.36, 0.6, 0) = (0.36 cos 40, 0.6, -0.36 sin 40) -> z flipped.
    const double c = std::cos(40 * kPi / 180), s = std::sin(40 * kPi / 180);
    int found = 0;
    for (const ImportedNode& n : f.nodes) {
        if (f.meshes[n.mesh].name != "metal ball") continue;
        const Point3 p = n.transform.point({0, 0, 0});
        EXPECT_NEAR(p.x, 0.36 * c, 1e-5);
        EXPECT_NEAR(p.y, 0.6, 1e-5);
        EXPECT_NEAR(p.z, 0.36 * s, 1e-5);
        // The uniform scale 1.2 is kept: a unit vector comes out 1.2 long.
        EXPECT_NEAR(length(n.transform.vector({1, 0, 0})), 1.2, 1e-5);
        ++found;
    }
    EXPECT_EQ(found, 1);
    // The camera at (0, 2.2, -6) turned 180 degrees about y and pitched 12 degrees down: it looks
    // along (0, -sin 12, cos 12) in glTF, (0, -sin 12, -cos 12) in glint.
    ASSERT_TRUE(f.camera);
    EXPECT_EQ(f.camera->name, "main");
    EXPECT_NEAR(f.camera->position.z, 6, 1e-5);
    EXPECT_NEAR(f.camera->direction.y, -std::sin(12 * kPi / 180), 1e-4);
    EXPECT_NEAR(f.camera->direction.z, -std::cos(12 * kPi / 180), 1e-4);
    EXPECT_NEAR(f.camera->yfov_degrees, 0.7 * 180 / kPi, 1e-4);
    // The spot light, a child of the camera: intensity 40 times its colour, cone cosines.
    ASSERT_EQ(f.lights.size(), 1u);
    const auto* spot = std::get_if<SpotLight>(&f.lights[0]);
    ASSERT_TRUE(spot);
    EXPECT_NEAR(spot->intensity.r, 40, 1e-4);
    EXPECT_NEAR(spot->cos_outer, std::cos(0.6), 1e-6);
    EXPECT_NEAR(spot->cos_inner, std::cos(0.3), 1e-6);
}

TEST_F(Gltf, BinaryGlbReadsAsTheTextFile) {
    const ImportedFile a = import_gltf(dir_ / "textured.gltf");
    const ImportedFile b = import_gltf(dir_ / "textured.glb");
    ASSERT_EQ(a.meshes.size(), b.meshes.size());
    for (std::size_t i = 0; i < a.meshes.size(); ++i) {
        EXPECT_EQ(a.meshes[i].positions.size(), b.meshes[i].positions.size());
        EXPECT_EQ(a.meshes[i].indices, b.meshes[i].indices);
        EXPECT_EQ(a.meshes[i].uvs.size(), b.meshes[i].uvs.size());
    }
    EXPECT_EQ(named(a, "tiles").desc.color.pixels->texels, named(b, "tiles").desc.color.pixels->texels);
}

TEST_F(Gltf, BadFilesAreErrorsNamingTheFile) {
    const std::string file = (dir_ / "x.gltf").string();
    EXPECT_EQ(error_of("x.gltf"), file + ": cannot open: no such file");
    write("x.gltf", "{\"asset\": {\"version\": \"2.0\"}, \"meshes\": [");  // truncated JSON
    EXPECT_EQ(error_of("x.gltf").rfind(file + ":1:42: JSON syntax error", 0), 0u) << error_of("x.gltf");
    // An accessor reaching past its buffer.
    std::string text = read("textured.gltf");
    const auto at = text.find("\"count\": 4");
    ASSERT_NE(at, std::string::npos);
    text.replace(at, 10, "\"count\": 400000");
    write("x.gltf", text);
    EXPECT_NE(error_of("x.gltf").find("reaches past the end of its buffer"), std::string::npos) << error_of("x.gltf");
    // A missing texture file.
    std::filesystem::remove(dir_ / "checker.png");
    const std::string missing = error_of("textured.gltf");
    EXPECT_NE(missing.find("checker.png"), std::string::npos) << missing;
    // No camera of that name.
    EXPECT_NE(std::string([&] {
                  try {
                      import_gltf(dir_ / "textured.glb", "side");
                  } catch (const IoError& e) {
                      return std::string(e.what());
                  }
                  return std::string();
              }()).find("no camera named 'side'"),
              std::string::npos);
}

// A one-triangle file, one line per part, so that an error's line and column are known: line k
// of the text is lines[k - 1].
std::vector<std::string> triangle_lines() {
    return {
        "{",
        "  \"asset\": {\"version\": \"2.0\"},",
        "  \"scene\": 0,",
        "  \"scenes\": [{\"nodes\": [0]}],",
        "  \"nodes\": [{\"mesh\": 0}],",
        "  \"meshes\": [{\"name\": \"tri\", \"primitives\": [{\"attributes\": {\"POSITION\": 0}, \"indices\": 1}]}],",
        "  \"accessors\": [",
        "    {\"bufferView\": 0, \"componentType\": 5126, \"count\": 3, \"type\": \"VEC3\"},",
        "    {\"bufferView\": 1, \"componentType\": 5123, \"count\": 3, \"type\": \"SCALAR\"}",
        "  ],",
        "  \"bufferViews\": [",
        "    {\"buffer\": 0, \"byteOffset\": 0, \"byteLength\": 36},",
        "    {\"buffer\": 0, \"byteOffset\": 36, \"byteLength\": 6}",
        "  ],",
        // (0,0,0) (1,0,0) (0,1,0) as floats, then 0 1 2 as uint16 and two bytes of padding.
        "  \"buffers\": [{\"byteLength\": 44, \"uri\": "
        "\"data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAABAAIAAAA=\"}]",
        "}",
    };
}

std::string joined(const std::vector<std::string>& lines) {
    std::string s;
    for (const auto& l : lines) s += l + "\n";
    return s;
}

// The same JSON as a .glb (header and one JSON chunk; the buffer stays a data URI).
std::string as_glb(std::string json) {
    while (json.size() % 4) json += ' ';
    std::string out;
    const auto u32 = [&](std::uint32_t v) {
        for (int k = 0; k < 4; ++k) out.push_back(static_cast<char>(v >> (8 * k)));
    };
    out += "glTF";
    u32(2);
    u32(static_cast<std::uint32_t>(12 + 8 + json.size()));
    u32(static_cast<std::uint32_t>(json.size()));
    out += "JSON";
    return out + json;
}

TEST_F(Gltf, ErrorsPointAtTheLineAndColumnOfTheValue) {
    write("ok.gltf", joined(triangle_lines()));
    // No NORMAL: the winding is turned back after the z mirror, so the face's own normal keeps to
    // glTF's counter-clockwise front.
    ASSERT_EQ(import_gltf(dir_ / "ok.gltf").meshes.at(0).indices, (std::vector<std::uint32_t>{0, 2, 1}));
    const std::string file = (dir_ / "x.gltf").string();
    // Line `line` replaced by `text`: the error, expected at the first `mark` in that line.
    const auto check = [&](int line, const std::string& text, const std::string& mark, const std::string& message) {
        auto lines = triangle_lines();
        lines[line - 1] = text;
        write("x.gltf", joined(lines));
        const std::size_t col = text.find(mark);
        ASSERT_NE(col, std::string::npos);
        EXPECT_EQ(error_of("x.gltf"), fmt::format("{}:{}:{}: {}", file, line, col + 1, message)) << text;
    };
    check(5, "  \"nodes\": [{\"mesh\": 5}],", "5}", "node 0 uses mesh 5 that does not exist");
    check(3, "  \"scene\": 3,", "3", "scene 3 does not exist");
    check(6, "  \"meshes\": [{\"name\": \"tri\", \"primitives\": [{\"attributes\": {\"POSITION\": 7}, \"indices\": 1}]}],",
          "7}", "mesh 'tri' primitive 0: accessor 7 does not exist");
    check(6, "  \"meshes\": [{\"name\": \"tri\", \"primitives\": [{\"attributes\": {\"POSITION\": 0, \"COLOR_0\": 7}}]}],",
          "7}", "mesh 'tri' primitive 0: accessor 7 does not exist");
    check(9, "    {\"bufferView\": 1, \"componentType\": 5123, \"count\": 4, \"type\": \"SCALAR\"}", "4,",
          "mesh 'tri' primitive 0: accessor 1 reaches past the end of its buffer");
    check(9, "    {\"bufferView\": 1, \"componentType\": 5123, \"count\": 3, \"type\": \"VEC2\"}", "\"VEC2",
          "mesh 'tri' primitive 0: accessor 1 has the wrong type");
    // Indices read from the floats' bytes: 1.0f is 0x3f800000.
    check(9, "    {\"bufferView\": 0, \"byteOffset\": 12, \"componentType\": 5125, \"count\": 3, \"type\": \"SCALAR\"}",
          "{", "mesh 'tri' primitive 0: index 1065353216 out of range (3 vertices)");
    check(13, "    {\"buffer\": 4, \"byteOffset\": 36, \"byteLength\": 6}", "4,",
          "mesh 'tri' primitive 0: accessor 1: buffer 4 does not exist");
    check(6,
          "  \"meshes\": [{\"name\": \"tri\", \"primitives\": [{\"attributes\": {\"POSITION\": 0}, \"indices\": 1, "
          "\"material\": 0}]}], \"materials\": [{\"pbrMetallicRoughness\": {\"baseColorTexture\": {\"index\": 3}}}],",
          "3}", "baseColorTexture: texture 3 does not exist");
    // Nodes must form trees.
    check(5, "  \"nodes\": [{\"mesh\": 0, \"children\": [1, 1]}, {\"mesh\": 0}],", "1]",
          "node 1 is a child of node 0 and of node 0; nodes must form trees");
    {  // a cycle: reported where the scene names one of its nodes as a root (line 4)
        auto lines = triangle_lines();
        lines[4] = "  \"nodes\": [{\"children\": [1]}, {\"children\": [0], \"mesh\": 0}],";
        write("x.gltf", joined(lines));
        EXPECT_EQ(error_of("x.gltf"), file + ":4:25: node 0 is a scene root and a child of node 1; nodes must form trees");
    }
    check(4, "  \"scenes\": [{\"nodes\": [0, 9]}],", "9", "node 9 does not exist");
    // KHR_materials_volume values outside their ranges.
    check(6,
          "  \"meshes\": [{\"name\": \"tri\", \"primitives\": [{\"attributes\": {\"POSITION\": 0}, \"indices\": 1, "
          "\"material\": 0}]}], \"materials\": [{\"extensions\": {\"KHR_materials_volume\": "
          "{\"thicknessFactor\": 1, \"attenuationDistance\": -2}}}],",
          "-2", "KHR_materials_volume: attenuationDistance must be positive");
    check(6,
          "  \"meshes\": [{\"name\": \"tri\", \"primitives\": [{\"attributes\": {\"POSITION\": 0}, \"indices\": 1, "
          "\"material\": 0}]}], \"materials\": [{\"extensions\": {\"KHR_materials_volume\": "
          "{\"thicknessFactor\": 1, \"attenuationColor\": [1, 2, 0.5]}}}],",
          "[1, 2", "KHR_materials_volume: attenuationColor must lie in [0, 1]");
    // The same error in a .glb names the file and the node, without a line.
    auto lines = triangle_lines();
    lines[4] = "  \"nodes\": [{\"mesh\": 5}],";
    write("x.glb", as_glb(joined(lines)));
    EXPECT_EQ(error_of("x.glb"), (dir_ / "x.glb").string() + ": node 0 uses mesh 5 that does not exist");
}

// Every camera of the file is listed, orthographic ones too (ymag is half the visible height);
// the first is the one used unless one is named.
TEST_F(Gltf, EveryCameraPerspectiveAndOrthographic) {
    auto lines = triangle_lines();
    lines[3] = "  \"scenes\": [{\"nodes\": [0, 1, 2]}],";
    lines[4] = "  \"nodes\": [{\"mesh\": 0}, {\"camera\": 0, \"translation\": [0, 0, 5]}, "
               "{\"camera\": 1, \"translation\": [1, 2, 3]}],";
    lines[5] += "\n  \"cameras\": [{\"name\": \"persp\", \"type\": \"perspective\", \"perspective\": {\"yfov\": 0.5, \"znear\": 0.1}},"
                " {\"name\": \"ortho\", \"type\": \"orthographic\", \"orthographic\": {\"xmag\": 3, \"ymag\": 1.5, \"znear\": 0.1, \"zfar\": 100}}],";
    write("cameras.gltf", joined(lines));
    const ImportedFile f = import_gltf(dir_ / "cameras.gltf");
    ASSERT_EQ(f.cameras.size(), 2u);
    EXPECT_FALSE(f.cameras[0].orthographic);
    EXPECT_NEAR(f.cameras[0].yfov_degrees, 0.5 * 180 / kPi, 1e-4);
    EXPECT_TRUE(f.cameras[1].orthographic);
    EXPECT_EQ(f.cameras[1].ymag, 1.5f);
    EXPECT_NEAR(f.cameras[1].position.z, -3, 1e-6);  // glTF's +z is glint's -z
    EXPECT_NEAR(f.cameras[1].direction.z, 1, 1e-6);  // looking along glTF's -z
    ASSERT_TRUE(f.camera);
    EXPECT_EQ(f.camera->name, "persp");
    const ImportedFile g = import_gltf(dir_ / "cameras.gltf", "ortho");
    ASSERT_TRUE(g.camera);
    EXPECT_TRUE(g.camera->orthographic);
}

TEST_F(Gltf, SparseAccessorsReplaceTheirElements) {
    // POSITION with one sparse element: vertex 1 becomes (5, 6, 7), z negated on import. The
    // second buffer holds the sparse index (uint16 1, two bytes of padding) and the value.
    const auto sparse_file = [&](const std::string& buffer) {
        auto lines = triangle_lines();
        lines[7] = "    {\"bufferView\": 0, \"componentType\": 5126, \"count\": 3, \"type\": \"VEC3\", \"sparse\": {\"count\": 1,"
                   " \"indices\": {\"bufferView\": 2, \"componentType\": 5123}, \"values\": {\"bufferView\": 3}}},";
        lines[12] += ", {\"buffer\": 1, \"byteLength\": 2}, {\"buffer\": 1, \"byteOffset\": 4, \"byteLength\": 12}";
        lines[14].insert(lines[14].size() - 1,
                         ", {\"byteLength\": 16, \"uri\": \"data:application/octet-stream;base64," + buffer + "\"}");
        write("sparse.gltf", joined(lines));
    };
    sparse_file("AQAAAAAAoEAAAMBAAADgQA==");
    const ImportedFile f = import_gltf(dir_ / "sparse.gltf");
    ASSERT_EQ(f.meshes.size(), 1u);
    const auto& p = f.meshes[0].positions;
    ASSERT_EQ(p.size(), 3u);
    EXPECT_EQ(p[0], (Point3{0, 0, 0}));
    EXPECT_EQ(p[1], (Point3{5, 6, -7}));
    EXPECT_EQ(p[2], (Point3{0, 1, 0}));
    // The same with the index 3, past the accessor's 3 elements.
    sparse_file("AwAAAAAAoEAAAMBAAADgQA==");
    const std::string e = error_of("sparse.gltf");
    EXPECT_NE(e.find(":8:"), std::string::npos) << e;
    EXPECT_NE(e.find("mesh 'tri' primitive 0: accessor 0: sparse index 3 is past its 3 elements"), std::string::npos) << e;
}

TEST_F(Gltf, NodeGraphsThatAreNotTreesEndInAnErrorNotAHang) {
    // 60 nodes, each listing the next twice: visited once per path, 2^60 visits.
    std::string nodes = "  \"nodes\": [";
    for (int k = 0; k < 60; ++k) nodes += fmt::format("{{\"mesh\": 0, \"children\": [{}, {}]}}, ", k + 1, k + 1);
    nodes += "{\"mesh\": 0}],";
    auto lines = triangle_lines();
    lines[4] = nodes;
    write("x.gltf", joined(lines));
    EXPECT_NE(error_of("x.gltf").find("node 1 is a child of node 0 and of node 0; nodes must form trees"), std::string::npos);
    // Without scenes every tree is shown once; a cycle of nodes has no root and is not shown.
    lines = triangle_lines();
    lines[2] = "";
    lines[3] = "";
    lines[4] = "  \"nodes\": [{\"mesh\": 0, \"children\": [3]}, {\"children\": [2], \"mesh\": 0}, {\"children\": [1]}, {\"mesh\": 0}],";
    write("x.gltf", joined(lines));
    EXPECT_EQ(import_gltf(dir_ / "x.gltf").nodes.size(), 2u);  // nodes 0 and 3
}

TEST_F(Gltf, CorruptedNumbersGiveAnErrorOrAModelNeverACrash) {
    // Every integer in the test scene's JSON (indices, counts, offsets, enums) replaced in turn by
    // values that break it: each import ends in a model or an IoError. (ASan in `make sanitize`.)
    const std::string good = read("textured.gltf");
    std::vector<std::pair<std::size_t, std::size_t>> ints;  // offset, length
    for (std::size_t i = 0; i < good.size();) {
        if (std::isdigit(static_cast<unsigned char>(good[i])) &&
            (i == 0 || !(std::isalnum(static_cast<unsigned char>(good[i - 1])) || good[i - 1] == '.' || good[i - 1] == '_'))) {
            std::size_t j = i;
            while (j < good.size() && std::isdigit(static_cast<unsigned char>(good[j]))) ++j;
            if (j < good.size() && good[j] != '.' && good[j] != 'e' && !std::isalpha(static_cast<unsigned char>(good[j])))
                ints.emplace_back(i, j - i);
            i = j;
        } else {
            ++i;
        }
    }
    ASSERT_GT(ints.size(), 150u);
    int errors = 0, models = 0;
    for (const auto& [at, len] : ints)
        for (const char* v : {"-1", "1", "9", "300000000", "18446744073709551615"}) {
            std::string t = good;
            t.replace(at, len, v);
            write("fuzz.gltf", t);
            try {
                const ImportedFile f = import_gltf(dir_ / "fuzz.gltf");
                for (const TriangleMesh& m : f.meshes)
                    for (std::uint32_t i : m.indices) ASSERT_LT(i, m.positions.size());
                ++models;
            } catch (const IoError&) {
                ++errors;
            }
        }
    EXPECT_GT(errors, 100);
    EXPECT_GT(models, 100);
}

TEST_F(Gltf, TexturedEmissionIsTheSameSampledAsSeen) {
    // The lamp's emission is textured: what light sampling returns at a point of the panel must
    // equal what a ray that hits the same point sees (two independent routes to the texture).
    write("scene.yaml", "integrator: {type: path}\nobjects:\n  - {type: mesh, file: textured.glb}\n");
    auto sources = std::make_shared<SourceFiles>();
    const RenderJob job = build(load_scene_file((dir_ / "scene.yaml").string(), sources), {}, sources);
    const Scene& s = job.scene;
    const LightSampler& ls = s.light_sampler();
    const Point3 p{0, 1.0f, -1.0f};  // in front of the panel (its lit face is at z = -1.975)
    int compared = 0, bright = 0, dark = 0;
    for (std::uint32_t l = 0; l < ls.count(); ++l) {
        const auto* area = std::get_if<AreaLight>(&ls.light(l));
        if (!area) continue;
        for (int k = 0; k < 64; ++k) {
            const Sample2 u{(k % 8 + 0.5f) / 8, (k / 8 + 0.5f) / 8};
            const auto sample = ls.sample_li(s, l, p, u);
            if (!sample) continue;
            const Ray r{p, sample->wi};
            const auto hit = s.intersect(r);
            if (!hit || std::abs(hit->t - sample->distance) > 1e-3f * sample->distance) continue;  // blocked
            const SurfaceInteraction si = s.interaction(r, *hit);
            const Color seen = s.emitted(si, -sample->wi);
            EXPECT_NEAR(seen.r, sample->L.r, 1e-3f * (1 + seen.r));
            EXPECT_NEAR(seen.g, sample->L.g, 1e-3f * (1 + seen.g));
            ++compared;
            (seen.r > 2 ? bright : dark)++;
        }
    }
    EXPECT_GT(compared, 100);
    EXPECT_GT(bright, 10);  // both squares of the emissive checker were met
    EXPECT_GT(dark, 10);
}

}  // namespace
}  // namespace glint

namespace glint {
namespace {

TEST_F(Gltf, VolumeMaterialBecomesAnInteriorMediumOfItsSurfaces) {
    write("scene.yaml", "integrator: {type: path}\nmedium: air\nmedia:\n  air: {type: homogeneous, albedo: 1, density: 0.01}\n"
                        "objects:\n  - {type: mesh, file: textured.gltf}\n");
    auto sources = std::make_shared<SourceFiles>();
    const RenderJob job = build(load_scene_file((dir_ / "scene.yaml").string(), sources), {}, sources);
    const Scene& s = job.scene;
    ASSERT_EQ(s.media.size(), 2u);  // the scene's air and the glass's inside
    EXPECT_TRUE(s.has_media());
    int with = 0;
    for (MaterialId m = 0; m < s.materials.size(); ++m) {
        const MediumInterface* mi = s.medium_interface(m);
        if (!mi) continue;
        ++with;
        EXPECT_EQ(mi->interior, 1u);
        EXPECT_EQ(mi->exterior, 0u);  // the scene's medium outside
        const auto& h = std::get<HomogeneousMedium>(s.media[mi->interior]);
        EXPECT_NEAR(std::exp(-h.sigma_a.g * 0.5f), 0.5f, 1e-6f);
    }
    EXPECT_EQ(with, 1);
}

}  // namespace
}  // namespace glint

namespace glint {

// Issue 16: a broken .glb container is reported by glint at its byte offset, and what tinygltf
// still reports comes in glint's form.
TEST(GltfHardening, BrokenBinaryContainersAreReportedAtTheirByte) {
    testing::TempDir dir;
    const auto u32 = [](std::uint32_t v) { return std::string(reinterpret_cast<const char*>(&v), 4); };
    const std::string json = R"({"asset": {"version": "2.0"}}   )";  // 32 bytes: a multiple of 4
    ASSERT_EQ(json.size() % 4, 0u);
    const auto glb = [&](std::uint32_t version, std::int64_t length, std::uint32_t json_length, const std::string& type,
                         const std::string& tail) {
        std::string body = u32(json_length) + type + json + tail;
        const std::uint32_t total = length >= 0 ? static_cast<std::uint32_t>(length) : static_cast<std::uint32_t>(12 + body.size());
        return "glTF" + u32(version) + u32(total) + body;
    };
    const auto err = [&](const std::string& bytes) {
        std::ofstream(dir / "x.glb", std::ios::binary) << bytes;
        try {
            import_gltf(dir / "x.glb");
        } catch (const IoError& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    const std::string f = (dir / "x.glb").string() + ": ";
    EXPECT_EQ(err("glTF"), f + "byte 0: 4 bytes, too short for the 12-byte header of a binary glTF");
    EXPECT_EQ(err("GLTF" + u32(2) + u32(12)), f + "byte 0: not a binary glTF (it does not start with 'glTF')");
    EXPECT_EQ(err(glb(1, -1, 32, "JSON", "")), f + "byte 4: version 1; glint reads glTF 2");
    EXPECT_EQ(err(glb(2, 1000, 32, "JSON", "")), f + "byte 8: the header gives the length as 1000 bytes; the file has 52");
    EXPECT_EQ(err(glb(2, -1, 32, "JSOX", "")), f + "byte 16: the first chunk must be of type 'JSON'");
    EXPECT_EQ(err(glb(2, -1, 36, "JSON", "")), f + "byte 12: the JSON chunk's length 36 runs past the end of the file (52 bytes)");
    EXPECT_EQ(err(glb(2, -1, 32, "JSON", u32(8) + "BIX" + std::string(1, '\0') + "12345678")),
              f + "byte 56: the second chunk must be of type 'BIN'");
    EXPECT_EQ(err(glb(2, -1, 32, "JSON", u32(800) + "BIN" + std::string(1, '\0') + "12345678")),
              f + "byte 52: the BIN chunk's length 800 runs past the end of the file (68 bytes)");
    // A well-formed container with nothing to draw is not a container error.
    EXPECT_EQ(err(glb(2, -1, 32, "JSON", "")).find("byte"), std::string::npos);
}

}  // namespace glint
