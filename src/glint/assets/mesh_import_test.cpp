// The PLY reader and the OBJ importer on small handwritten files, on every failure mode we know
// of, on corrupted bytes, and on the Stanford bunny in both formats.
#include <gtest/gtest.h>
#include <fmt/format.h>

#include <sys/stat.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <fstream>
#include <random>

#include "glint/assets/mesh_import.h"
#include "testing.h"

namespace glint {
namespace {

std::string error_of(const std::function<void()>& f) {
    try {
        f();
    } catch (const IoError& e) {
        return e.what();
    }
    return "(no error)";
}

void write(const std::filesystem::path& p, const std::string& text) {
    std::ofstream(p, std::ios::binary) << text;
}

const char* kAsciiPly =
    "ply\n"
    "format ascii 1.0\n"
    "comment a unit quad with normals, texture coordinates and colours\n"
    "element vertex 4\n"
    "property float x\nproperty float y\nproperty float z\n"
    "property float nx\nproperty float ny\nproperty float nz\n"
    "property float s\nproperty float t\n"
    "property uchar red\nproperty uchar green\nproperty uchar blue\n"
    "element face 1\n"
    "property list uchar int vertex_indices\n"
    "end_header\n"
    "0 0 0  0 0 -1  0 0  255 0 0\n"
    "1 0 0  0 0 -1  1 0  0 255 0\n"
    "1 1 0  0 0 -1  1 1  0 0 255\n"
    "0 1 0  0 0 -1  0 1  128 128 128\n"
    "4 0 1 2 3\n";

TEST(Ply, AsciiQuadWithEveryAttribute) {
    const ImportedFile f = parse_ply(kAsciiPly, "quad.ply");
    ASSERT_EQ(f.meshes.size(), 1u);
    const TriangleMesh& m = f.meshes[0];
    EXPECT_EQ(m.triangle_count(), 2u);  // the quad as a fan
    EXPECT_EQ(m.indices, (std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3}));
    ASSERT_EQ(m.normals.size(), 4u);
    EXPECT_EQ(m.normals[2].z, -1);
    ASSERT_EQ(m.uvs.size(), 4u);
    EXPECT_EQ(m.uvs[2].x, 1);
    EXPECT_EQ(m.uvs[3].y, 1);
    ASSERT_EQ(m.colors.size(), 4u);
    EXPECT_EQ(m.colors[0].r, 1);  // 8-bit colours are sRGB: 255 -> 1, 0 -> 0
    EXPECT_EQ(m.colors[0].g, 0);
    EXPECT_NEAR(m.colors[3].r, 0.2158605f, 1e-6f);  // ((128/255 + 0.055) / 1.055)^2.4
    EXPECT_EQ(m.material, kNoImportedMaterial);
}

// A binary PLY written here byte by byte (so the reader is checked against an independent
// writer), with an element the reader must skip (with a list in it) before the faces.
std::string binary_ply(bool big_endian) {
    std::string out = std::string("ply\nformat ") + (big_endian ? "binary_big_endian" : "binary_little_endian") +
                      " 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
                      "property double confidence\n"
                      "element edge 1\nproperty list uchar short pair\nproperty int flag\n"
                      "element face 2\nproperty uchar flags\nproperty list uchar uint vertex_indices\nend_header\n";
    const auto put = [&](const void* p, int n) {
        unsigned char b[8];
        std::memcpy(b, p, n);
        if (big_endian == (std::endian::native == std::endian::little)) std::reverse(b, b + n);
        out.append(reinterpret_cast<const char*>(b), n);
    };
    const float v[4][3] = {{0, 0, 0}, {2, 0, 0}, {0, 3, 0}, {0, 0, 4}};
    for (const auto& p : v) {
        for (float c : p) put(&c, 4);
        const double conf = 0.5;
        put(&conf, 8);
    }
    const unsigned char two = 2;
    const std::int16_t e[2] = {0, 1};
    const std::int32_t flag = 7;
    put(&two, 1);
    put(&e[0], 2);
    put(&e[1], 2);
    put(&flag, 4);
    const unsigned char three = 3, flags = 0;
    const std::uint32_t faces[2][3] = {{0, 1, 2}, {0, 2, 3}};
    for (const auto& f : faces) {
        put(&flags, 1);
        put(&three, 1);
        for (std::uint32_t i : f) put(&i, 4);
    }
    return out;
}

TEST(Ply, FloatColoursAreLinear) {
    const ImportedFile f = parse_ply(
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
        "property float red\nproperty float green\nproperty float blue\nelement face 1\n"
        "property list uchar int vertex_indices\nend_header\n"
        "0 0 0 0.5 0.25 1\n1 0 0 0 0 0\n0 1 0 1 1 1\n3 0 1 2\n",
        "float.ply");
    ASSERT_EQ(f.meshes.at(0).colors.size(), 3u);
    EXPECT_EQ(f.meshes[0].colors[0].r, 0.5f);  // as written, not sRGB-decoded
    EXPECT_EQ(f.meshes[0].colors[0].g, 0.25f);
}

TEST(Ply, BinaryLittleAndBigEndianReadTheSame) {
    for (const bool big : {false, true}) {
        const ImportedFile f = parse_ply(binary_ply(big), "tet.ply");
        const TriangleMesh& m = f.meshes.at(0);
        ASSERT_EQ(m.positions.size(), 4u) << big;
        EXPECT_EQ(m.positions[1].x, 2);
        EXPECT_EQ(m.positions[2].y, 3);
        EXPECT_EQ(m.positions[3].z, 4);
        EXPECT_EQ(m.indices, (std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3}));
        EXPECT_TRUE(m.normals.empty());
        EXPECT_TRUE(m.colors.empty());
    }
}

TEST(Ply, EveryFailureNamesTheFileAndThePlace) {
    const auto err = [](const std::string& text) { return error_of([&] { parse_ply(text, "bad.ply"); }); };
    EXPECT_EQ(err("PLY\n"), "bad.ply:1: not a PLY file (the first line must be 'ply')");
    EXPECT_EQ(err("ply\nformat ascii 1.0\nelement vertex 1\n"), "bad.ply:3: the header has no 'end_header'");
    EXPECT_EQ(err("ply\nformat utf8 1.0\nend_header\n"),
              "bad.ply:2: unknown format 'utf8' (known: ascii, binary_little_endian, binary_big_endian)");
    EXPECT_EQ(err("ply\nformat ascii 1.0\nproperty float x\nend_header\n"), "bad.ply:3: a property before any element");
    EXPECT_EQ(err("ply\nformat ascii 1.0\nelement vertex 1\nproperty quad x\nend_header\n"),
              "bad.ply:4: unknown property type 'quad'");
    // A count the file cannot hold is refused before anything is allocated.
    EXPECT_EQ(err("ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\nproperty float x\n"
                  "property float y\nproperty float z\nend_header\nabcd"),
              "bad.ply:3: element 'vertex' claims 4000000000 entries, more than the 4 bytes after the header can hold");
    // Counts past every integer type (the fuzzer's finds, undefined behaviour before): a vertex
    // count beyond long long is over the limit, an ASCII list count of 1e23 is compared as a number.
    EXPECT_EQ(err("ply\nformat binary_little_endian 1.0\nelement vertex 13018374452099416065\nend_header\nab").rfind(
                  "bad.ply:3: ", 0),
              0u);
    EXPECT_EQ(err("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty list uchar int junk\n"
                  "property float y\nproperty float z\nend_header\n0 1e23 1 2 3\n"),
              "bad.ply:9: vertex 0: list 'junk' claims 1e+23 entries past the end of the file");
    EXPECT_EQ(err("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\n"
                  "end_header\n0 0 zero\n"),
              "bad.ply:8: vertex 0: expected a number, got 'zero'");
    EXPECT_EQ(err("ply\nformat ascii 1.0\nelement vertex 1\nproperty float y\nend_header\n0\n"),
              "bad.ply:3: the vertex element needs properties x, y and z");
    EXPECT_EQ(err("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                  "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n"),
              "bad.ply:13: face 0: vertex index 7 out of range (3 vertices)");
    std::string truncated = binary_ply(false);
    truncated.resize(truncated.size() - 5);
    // The byte where the value being read starts (the last face's count, a uchar, at 386), and the element.
    EXPECT_EQ(err(truncated), "bad.ply: byte 386: face 1: list 'vertex_indices' claims 3 entries past the end of the file");
    for (std::size_t cut = 1; cut < 14; ++cut) {  // every cut into the last face: the byte and the face are named
        std::string t = binary_ply(false);
        t.resize(t.size() - cut);
        EXPECT_EQ(err(t).rfind("bad.ply: byte ", 0), 0u) << err(t);
        EXPECT_NE(err(t).find(": face 1: "), std::string::npos) << err(t);
    }
    EXPECT_EQ(error_of([] { import_ply("/nonexistent/x.ply"); }), "/nonexistent/x.ply: cannot open: No such file or directory");
}

TEST(Ply, CorruptedBytesGiveAnErrorOrAMeshNeverACrash) {
    // Every single-byte change and every truncation of a small binary file, and random byte
    // noise: each parse ends in a mesh or an IoError. (Run under ASan by `make sanitize`.)
    const std::string good = binary_ply(false);
    std::mt19937 g(1);
    int errors = 0, meshes = 0;
    const auto attempt = [&](const std::string& bytes) {
        try {
            const ImportedFile f = parse_ply(bytes, "fuzz.ply");
            for (const TriangleMesh& m : f.meshes)
                for (std::uint32_t i : m.indices) ASSERT_LT(i, m.positions.size());
            ++meshes;
        } catch (const IoError&) {
            ++errors;
        }
    };
    for (std::size_t n = 0; n < good.size(); ++n) attempt(good.substr(0, n));
    for (std::size_t i = 0; i < good.size(); ++i)
        for (const unsigned char v : {0x00, 0xff, 0x7f, 0x80}) {
            std::string b = good;
            b[i] = static_cast<char>(v);
            attempt(b);
        }
    for (int k = 0; k < 2000; ++k) {
        std::string b = good;
        for (int j = 0; j < 4; ++j) b[g() % b.size()] = static_cast<char>(g());
        attempt(b);
    }
    EXPECT_GT(errors, 100);
    EXPECT_GT(meshes, 100);
}

TEST(Obj, GroupsMaterialsAndTheirMapping) {
    testing::TempDir dir;
    write(dir / "scene.mtl",
          "newmtl matte\nKd 0.8 0.2 0.1\n"
          "newmtl shiny\nKd 0.1 0.1 0.7\nKs 0.5 0.5 0.5\nNs 98\nNi 1.4\n"
          "newmtl glass\nKd 1 1 1\nd 0.2\nNi 1.33\n"
          "newmtl lamp\nKd 0 0 0\nKe 5 4 3\n");
    write(dir / "scene.obj",
          "mtllib scene.mtl\n"
          "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\n"
          "vn 0 0 -1\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
          "g floor\nusemtl matte\nf 1/1/1 2/2/1 3/3/1 4/4/1\n"
          "g side\nusemtl shiny\nf 1 2 5\nusemtl glass\nf 2 3 5\nusemtl lamp\nf 3 4 5\n");
    const ImportedFile f = import_obj(dir / "scene.obj");
    ASSERT_EQ(f.materials.size(), 4u);
    EXPECT_EQ(f.materials[0].desc.kind, MaterialDesc::Kind::kDiffuse);
    EXPECT_EQ(f.materials[0].desc.color.value.r, 0.8f);
    EXPECT_EQ(f.materials[1].desc.kind, MaterialDesc::Kind::kPlastic);
    EXPECT_FLOAT_EQ(f.materials[1].desc.ior, 1.4f);
    EXPECT_FLOAT_EQ(f.materials[1].desc.roughness, std::pow(2.0f / 100, 0.25f));
    EXPECT_EQ(f.materials[2].desc.kind, MaterialDesc::Kind::kDielectric);
    EXPECT_FLOAT_EQ(f.materials[2].desc.ior, 1.33f);
    EXPECT_EQ(f.materials[3].desc.emission.radiance.r, 5);
    ASSERT_EQ(f.meshes.size(), 2u);
    const TriangleMesh& floor = f.meshes[0];
    EXPECT_EQ(floor.name, "floor");
    EXPECT_EQ(floor.triangle_count(), 2u);
    EXPECT_EQ(floor.normals.size(), floor.positions.size());
    EXPECT_EQ(floor.uvs.size(), floor.positions.size());
    EXPECT_EQ(floor.material_of(0), 0u);
    const TriangleMesh& side = f.meshes[1];
    EXPECT_EQ(side.triangle_count(), 3u);
    EXPECT_EQ(side.face_materials, (std::vector<MaterialId>{1, 2, 3}));
    EXPECT_TRUE(side.normals.empty());
    EXPECT_EQ(side.positions.size(), 5u);  // welded: each of vertices 1 to 5 once
}

TEST(Obj, MissingFilesAndBadFacesAreErrorsNamingThem) {
    testing::TempDir dir;
    write(dir / "a.obj", "mtllib nowhere.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    EXPECT_NE(error_of([&] { import_obj(dir / "a.obj"); }).find("nowhere.mtl"), std::string::npos)
        << error_of([&] { import_obj(dir / "a.obj"); });
    write(dir / "b.mtl", "newmtl wood\nKd 1 1 1\nmap_Kd planks.png\n");
    write(dir / "b.obj", "mtllib b.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl wood\nf 1 2 3\n");
    const std::string missing_texture = error_of([&] { import_obj(dir / "b.obj"); });
    EXPECT_NE(missing_texture.find("material 'wood'"), std::string::npos) << missing_texture;
    EXPECT_NE(missing_texture.find("planks.png"), std::string::npos) << missing_texture;
    write(dir / "c.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\ng a\nf 1 2 3\ng b\n\nf 1 3 2\nf 1 2 9\n");
    EXPECT_EQ(error_of([&] { import_obj(dir / "c.obj"); }),
              (dir / "c.obj").string() + ":9:7: vertex index 9 is out of range (3 vertices)");
    write(dir / "c.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//4\n");
    EXPECT_EQ(error_of([&] { import_obj(dir / "c.obj"); }),
              (dir / "c.obj").string() + ":5:16: normal index 4 is out of range (1 normals)");
    EXPECT_EQ(error_of([&] { import_obj(dir / "none.obj"); }), (dir / "none.obj").string() + ": cannot open: no such file");
    write(dir / "d.obj", "# nothing\n");
    EXPECT_EQ(error_of([&] { import_obj(dir / "d.obj"); }), (dir / "d.obj").string() + ": no faces");
}

TEST(Obj, NormMapsBecomeNormalMapsAndHeightBumpsANote) {
    testing::TempDir dir;
    std::filesystem::copy_file(std::filesystem::path(GLINT_SOURCE_DIR) / "scenes/textures/uv-grid.png", dir / "n.png");
    write(dir / "m.mtl", "newmtl a\nKd 1 1 1\nnorm n.png\nnewmtl b\nKd 1 1 1\nmap_Bump n.png\n"
                         "newmtl c\nKd 1 1 1\nmap_Bump -bm 0.5 n.png\n");
    write(dir / "m.obj", "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\n");
    const ImportedFile f = import_obj(dir / "m.obj");
    ASSERT_EQ(f.materials.size(), 3u);
    ASSERT_TRUE(f.materials[0].desc.normal_map);
    EXPECT_EQ(f.materials[0].desc.normal_map->encoding, ImageEncoding::kLinear);
    EXPECT_FALSE(f.materials[1].desc.normal_map);  // a height map: not applied, and said
    ASSERT_EQ(f.notes.size(), 1u);
    EXPECT_NE(f.notes[0].find("bump (height) map 'n.png' is not applied"), std::string::npos) << f.notes[0];
    ASSERT_TRUE(f.materials[2].desc.normal_map);  // -bm marks a normal map exported as map_Bump
    EXPECT_FLOAT_EQ(f.materials[2].desc.normal_scale, 0.5f);
    write(dir / "m.mtl", "newmtl a\nnorm gone.png\n");
    const std::string e = error_of([&] { import_obj(dir / "m.obj"); });
    EXPECT_NE(e.find("normal map 'gone.png' not found"), std::string::npos) << e;
}

TEST(MeshFiles, TheBunnyReadsTheSameFromPlyAndObj) {
    const std::filesystem::path models = GLINT_TEST_MODEL_DIR;
    if (!std::filesystem::exists(models / "stanford-bunny.ply")) GTEST_SKIP() << "no " << models;
    const ImportedFile ply = import_ply(models / "stanford-bunny.ply");
    const ImportedFile obj = import_obj(models / "stanford-bunny.obj");
    // The models' README: 35,947 vertices and 69,451 triangles, the PLY converted from the OBJ
    // with vertex order and indices unchanged.
    ASSERT_EQ(ply.meshes.size(), 1u);
    ASSERT_EQ(obj.meshes.size(), 1u);
    EXPECT_EQ(ply.meshes[0].positions.size(), 35947u);
    EXPECT_EQ(ply.meshes[0].triangle_count() + ply.dropped_triangles, 69451u);
    EXPECT_EQ(obj.meshes[0].triangle_count() + obj.dropped_triangles, 69451u);
    const Bounds3 a = ply.meshes[0].bounds(), b = obj.meshes[0].bounds();
    for (int k = 0; k < 3; ++k) {
        EXPECT_NEAR(a.lo[k], b.lo[k], 1e-6f);
        EXPECT_NEAR(a.hi[k], b.hi[k], 1e-6f);
    }
}

}  // namespace
}  // namespace glint

namespace glint {

// Issue 16: OBJ indices are checked by glint before tinyobjloader sees them, as written (64-bit:
// tinyobjloader's int overflowed, 4000000000 was reported as -294967292), at line and column.
TEST(Obj, IndicesAreCheckedAsWrittenAtTheirColumn) {
    const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    const auto err = [&](const std::string& faces) {
        return error_of([&] { parse_obj(tri + faces, "big.obj", "."); });
    };
    EXPECT_EQ(err("f 1 2 4000000000\n"), "big.obj:4:7: vertex index 4000000000 is out of range (3 vertices)");
    EXPECT_EQ(err("f 1 2 99999999999999999999\n"), "big.obj:4:7: vertex index 99999999999999999999 is out of range");
    EXPECT_EQ(err("f 1 2 0\n"), "big.obj:4:7: vertex index 0: OBJ indices start at 1");
    EXPECT_EQ(err("f -1 -2 -4\n"), "big.obj:4:9: vertex index -4 is out of range (3 vertices before this line)");
    EXPECT_EQ(err("f 1 2 x3\n"), "big.obj:4:7: 'x3' is not a vertex index");
    EXPECT_EQ(err("vt 0 0\nf 1/1 2/1 3/2\n"), "big.obj:5:13: texture coordinate index 2 is out of range (1 texture coordinates)");
    EXPECT_EQ(err("vt 0 0\nvn 0 0 1\nf 1/1/1/1 2 3\n"), "big.obj:6:7: a corner has more than three indices");
    EXPECT_EQ(err("l 1 5\n"), "big.obj:4:5: vertex index 5 is out of range (3 vertices)");
    // A face of 300 corners (more than tinyobjloader's byte holds) is read whole: 298 triangles.
    std::string circle;
    for (int i = 0; i < 300; ++i) circle += fmt::format("v {} {} 0\n", std::cos(i * 0.0209), std::sin(i * 0.0209));
    std::string face = "f";
    for (int i = 1; i <= 300; ++i) face += " " + std::to_string(i);
    const ImportedFile disc = parse_obj(circle + face + "\n", "big.obj", ".");
    ASSERT_EQ(disc.meshes.size(), 1u);
    EXPECT_EQ(disc.meshes[0].indices.size(), 3u * 298);
    EXPECT_EQ(disc.dropped_triangles, 0u);
    // Indices written before the vertices they name are fine (OBJ allows it), negative ones count back.
    const ImportedFile ok = parse_obj("f 1 2 3\n" + tri + "f -3 -2 -1\n", "ok.obj", ".");
    ASSERT_EQ(ok.meshes.size(), 1u);
    EXPECT_EQ(ok.meshes[0].indices.size(), 6u);
}

TEST(Obj, MaterialLibrariesAreReadOnlyWhenTheyAreRegularFiles) {
    testing::TempDir dir;
    ASSERT_EQ(::mkfifo((dir / "m.mtl").c_str(), 0600), 0);
    write(dir / "a.obj", "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    const std::string e = error_of([&] { import_obj(dir / "a.obj"); });
    EXPECT_NE(e.find("material library 'm.mtl'"), std::string::npos) << e;
    EXPECT_NE(e.find("it is not a regular file"), std::string::npos) << e;
}

}  // namespace glint

namespace glint {

// Found by fuzz_ply: an element with no properties and a huge count was skipped entry by entry
// (2^63 of them: for ever). It holds no bytes, so it is not read at all.
TEST(Ply, AnElementOfNoPropertiesIsNotLoopedOver) {
    std::string ply = "ply\nformat binary_little_endian 1.0\nelement junk 9223372036854775807\nelement vertex 3\n"
                      "property float x\nproperty float y\nproperty float z\nelement face 1\n"
                      "property list uchar int vertex_indices\nend_header\n";
    const float v[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const std::int32_t f[3] = {0, 1, 2};
    ply.append(reinterpret_cast<const char*>(v), sizeof v);
    ply += '\3';
    ply.append(reinterpret_cast<const char*>(f), sizeof f);
    const ImportedFile file = parse_ply(ply, "junk.ply");
    ASSERT_EQ(file.meshes.size(), 1u);
    EXPECT_EQ(file.meshes[0].indices, (std::vector<std::uint32_t>{0, 1, 2}));
}

}  // namespace glint
