// The Khronos glTF sample models of tests/data/khronos (provenance and licences in its README):
// what each file holds, as the collection documents it, arrives in glint; and a file without a
// camera is framed whole, whatever its root node does to it, through the real command line.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cmath>
#include <cstdlib>
#include <fmt/format.h>
#include <fstream>
#include <numbers>

#include "glint/image/image_io.h"
#include "glint/assets/mesh_import.h"
#include "testing.h"

namespace glint {
namespace {

std::filesystem::path khronos(const std::string& name) {
    return std::filesystem::path(GLINT_SOURCE_DIR) / "tests/data/khronos" / (name + ".gltf");
}

TEST(Khronos, BoxIsTwelveTrianglesOfARedMaterial) {
    const ImportedFile f = import_gltf(khronos("Box"));
    ASSERT_EQ(f.meshes.size(), 1u);
    EXPECT_EQ(f.meshes[0].triangle_count(), 12u);
    EXPECT_FALSE(f.camera);
    const Bounds3 b = f.meshes[0].bounds();  // a cube of side 1 about the origin
    EXPECT_NEAR(b.lo.x, -0.5f, 1e-6f);
    EXPECT_NEAR(b.hi.z, 0.5f, 1e-6f);
    ASSERT_EQ(f.materials.size(), 1u);
    EXPECT_NEAR(f.materials[0].desc.color.value.r, 0.8f, 1e-6f);
    EXPECT_EQ(f.materials[0].desc.color.value.g, 0);
}

TEST(Khronos, BoxTexturedReadsItsEmbeddedPng) {
    const ImportedFile f = import_gltf(khronos("BoxTextured"));
    ASSERT_EQ(f.materials.size(), 1u);
    const TextureDesc& t = f.materials[0].desc.color;
    ASSERT_EQ(t.kind, TextureDesc::Kind::kImage);
    ASSERT_TRUE(t.pixels);
    EXPECT_EQ(t.pixels->width, 211);  // the PNG's header: 211 x 211, palette
    EXPECT_EQ(t.pixels->height, 211);
    EXPECT_EQ(f.meshes.at(0).uvs.size(), f.meshes[0].positions.size());
}

TEST(Khronos, BoxVertexColorsMultiplyTheBaseColour) {
    const ImportedFile f = import_gltf(khronos("BoxVertexColors"));
    const TriangleMesh& m = f.meshes.at(0);
    EXPECT_EQ(m.colors.size(), 24u);
    // The material is OPAQUE: COLOR_0's alpha (0 at some corners) must not cut anything out.
    EXPECT_FALSE(f.materials.at(0).alpha);
    // Base colour = factor 0.8 x vertex colour.
    const TextureDesc& c = f.materials[0].desc.color;
    ASSERT_EQ(c.kind, TextureDesc::Kind::kScale);
    EXPECT_EQ(c.children.at(1).kind, TextureDesc::Kind::kVertexColor);
}

TEST(Khronos, CamerasListsBothCameras) {
    const ImportedFile f = import_gltf(khronos("Cameras"));
    ASSERT_EQ(f.cameras.size(), 2u);
    EXPECT_FALSE(f.cameras[0].orthographic);
    EXPECT_NEAR(f.cameras[0].yfov_degrees, 0.7 * 180 / std::numbers::pi, 1e-4);
    EXPECT_TRUE(f.cameras[1].orthographic);
    EXPECT_EQ(f.cameras[1].ymag, 1);
    for (const GltfCamera& c : f.cameras) {  // at (0.5, 0.5, 3) looking down glTF's -z: glint's +z
        EXPECT_NEAR(c.position.z, -3, 1e-6);
        EXPECT_NEAR(c.direction.z, 1, 1e-6);
    }
}

TEST(Khronos, UnnamedCamerasArePickedByTheirOrder) {
    const ImportedFile second = import_gltf(khronos("Cameras"), "#1");
    ASSERT_TRUE(second.camera);
    EXPECT_TRUE(second.camera->orthographic);
    const ImportedFile first = import_gltf(khronos("Cameras"), "#0");
    ASSERT_TRUE(first.camera);
    EXPECT_FALSE(first.camera->orthographic);
    try {
        import_gltf(khronos("Cameras"), "#2");
        ADD_FAILURE() << "no error";
    } catch (const IoError& e) {
        EXPECT_NE(std::string(e.what()).find("no camera named '#2' (the file has 2; '#0' to '#1' pick them in order)"),
                  std::string::npos)
            << e.what();
    }
}

TEST(Khronos, SimpleSparseAccessorMovesThreeVertices) {
    // Vertices 8, 10 and 12 of the 2 x 7 grid are replaced by (1, 2), (3, 3) and (5, 4).
    const ImportedFile f = import_gltf(khronos("SimpleSparseAccessor"));
    const TriangleMesh& m = f.meshes.at(0);
    ASSERT_EQ(m.positions.size(), 14u);
    EXPECT_EQ(m.positions[8], (Point3{1, 2, 0}));
    EXPECT_EQ(m.positions[10], (Point3{3, 3, 0}));
    EXPECT_EQ(m.positions[12], (Point3{5, 4, 0}));
    EXPECT_EQ(m.positions[9], (Point3{2, 1, 0}));  // untouched: row y = 1, x = 2
    EXPECT_EQ(m.triangle_count(), 12u);
}

TEST(Khronos, TriangleWithoutIndicesIsOneTriangle) {
    const ImportedFile f = import_gltf(khronos("TriangleWithoutIndices"));
    const TriangleMesh& m = f.meshes.at(0);
    EXPECT_EQ(m.triangle_count(), 1u);
}

// Box.gltf under a new root node of scale s, translation 1000 s (1, -2, 3) and a rotation, rendered
// by `glint render` with no camera: the red cube's pixels never touch the frame's outer 3 pixels
// (frame_box keeps every corner within 90 % of the half-frame), and fill a good part of it.
TEST(Khronos, AFileWithoutACameraIsFramedWholeWhateverItsRootNodeDoes) {
    const std::string box = testing::read_file(khronos("Box"));
    testing::TempDir dir;
    struct Case {
        double scale;
        bool moved;
    };
    for (const Case c : {Case{1e-3, true}, Case{1, false}, Case{1, true}, Case{1e4, true}}) {
        std::string t = box;
        // Node 0 was the root; a new node 2 holds it.
        const std::string scene = "\"nodes\": [\n                0\n            ]";
        ASSERT_NE(t.find(scene), std::string::npos);
        t.replace(t.find(scene), scene.size(), "\"nodes\": [2]");
        const double s = c.scale, d = c.moved ? 1000 * s : 0;
        // 40 degrees about (1, 2, 3) / |.|: q = (sin 20 axis, cos 20).
        const double h = 20 * std::numbers::pi / 180, n = std::sqrt(14.0);
        const std::string root = fmt::format(
            R"(,{{"children": [0], "scale": [{0}, {0}, {0}], "translation": [{1}, {2}, {3}], "rotation": [{4}, {5}, {6}, {7}]}})",
            s, d, -2 * d, 3 * d, c.moved ? std::sin(h) / n : 0, c.moved ? 2 * std::sin(h) / n : 0,
            c.moved ? 3 * std::sin(h) / n : 0, c.moved ? std::cos(h) : 1);
        const std::string nodes_end = "1.0\n            ]\n        }\n    ],\n    \"meshes\"";
        ASSERT_NE(t.find(nodes_end), std::string::npos);
        t.insert(t.find(nodes_end) + std::string("1.0\n            ]\n        }").size(), root);
        std::ofstream(dir / "box.gltf") << t;
        const std::string cmd = fmt::format("'{}' render '{}' -o '{}' --width 96 --height 72 --spp 4 > /dev/null 2>&1", GLINT_CLI,
                                            (dir / "box.gltf").string(), (dir / "box.exr").string());
        ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
        const Image img = read_image(dir / "box.exr", ImageEncoding::kLinear);
        int inside = 0, border = 0;
        for (int y = 0; y < img.height; ++y)
            for (int x = 0; x < img.width; ++x) {
                const Color p = img.texel(x, y);
                if (!(p.r > 3 * p.b + 0.01f)) continue;  // the sky is bluish white, the cube red
                ++inside;
                border += x < 3 || y < 3 || x >= img.width - 3 || y >= img.height - 3;
            }
        EXPECT_EQ(border, 0) << "scale " << s << (c.moved ? " moved and rotated" : "");
        EXPECT_GT(inside, img.width * img.height / 8) << "scale " << s;
    }
}

}  // namespace
}  // namespace glint
