// Compressed glTF meshes: KHR_draco_mesh_compression and EXT_meshopt_compression. The compressed
// files come from the libraries' own encoders (Draco's draco_transcoder, meshoptimizer's
// meshopt_encode*), so the importer's decoding is checked against data it did not produce: every
// decoded vertex must carry the attributes the source gave that position.
#include <gtest/gtest.h>

#include <meshoptimizer.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fmt/format.h>
#include <fstream>

#include "glint/assets/mesh_import.h"
#include "testing.h"

namespace glint {
namespace {

std::string base64(const void* bytes, std::size_t n) {
    static const char* kDigits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    const auto* p = static_cast<const unsigned char*>(bytes);
    std::string out;
    for (std::size_t i = 0; i < n; i += 3) {
        const unsigned v = p[i] << 16 | (i + 1 < n ? p[i + 1] << 8 : 0) | (i + 2 < n ? p[i + 2] : 0);
        out += kDigits[v >> 18 & 63];
        out += kDigits[v >> 12 & 63];
        out += i + 1 < n ? kDigits[v >> 6 & 63] : '=';
        out += i + 2 < n ? kDigits[v & 63] : '=';
    }
    return out;
}

// A 4 x 4 grid of quads in z = 0 (25 vertices, 32 triangles), x and y from 0 to 4; the test's
// texture coordinate of the vertex at (x, y) is (x / 4, y / 8), its normal (0, 0, 1).
struct Grid {
    std::vector<float> positions, uvs;
    std::vector<std::uint32_t> indices;
    Grid() {
        for (int y = 0; y <= 4; ++y)
            for (int x = 0; x <= 4; ++x) {
                positions.insert(positions.end(), {float(x), float(y), 0});
                uvs.insert(uvs.end(), {x / 4.0f, y / 8.0f});
            }
        for (int y = 0; y < 4; ++y)
            for (int x = 0; x < 4; ++x) {
                const std::uint32_t a = y * 5 + x;
                indices.insert(indices.end(), {a, a + 1, a + 6, a, a + 6, a + 5});
            }
    }
};

// Every imported vertex has the uv the grid gave its position (glint: z and v mirrored).
void expect_grid(const ImportedFile& f) {
    ASSERT_EQ(f.meshes.size(), 1u);
    const TriangleMesh& m = f.meshes[0];
    EXPECT_EQ(m.triangle_count(), 32u);
    ASSERT_EQ(m.uvs.size(), m.positions.size());
    double area = 0;
    for (std::uint32_t t = 0; t < m.triangle_count(); ++t) {
        const auto [a, b, c] = m.vertices(t);
        area += 0.5 * length(cross(b - a, c - a));
    }
    EXPECT_NEAR(area, 16, 1e-4);
    for (std::size_t i = 0; i < m.positions.size(); ++i) {
        const Point3 p = m.positions[i];
        EXPECT_NEAR(m.uvs[i].x, p.x / 4, 1e-3) << i;
        EXPECT_NEAR(m.uvs[i].y, 1 - p.y / 8, 1e-3) << i;
        EXPECT_NEAR(p.z, 0, 1e-6);
        if (!m.normals.empty()) {
            EXPECT_NEAR(m.normals[i].z, -1, 0.02) << i;  // glTF +z is glint's -z
        }
    }
}

// Draco's own glTF transcoder (Debian's `draco` package) compresses two Khronos sample models;
// glint's import of the result must give the original's triangles and, at every decoded vertex,
// the attributes of the original vertex at that position and normal (within the quantisation).
TEST(GltfCompression, DracoTranscodedSampleModelsDecodeToTheOriginals) {
    if (std::system("command -v draco_transcoder > /dev/null") != 0)
        GTEST_SKIP() << "draco_transcoder not installed (scripts/install-deps.sh installs Debian's draco)";
    testing::TempDir dir;
    for (const std::string name : {"Box", "BoxVertexColors"}) {
        const std::string source = std::string(GLINT_SOURCE_DIR) + "/tests/data/khronos/" + name + ".gltf";
        const std::string out = (dir / (name + "-draco.gltf")).string();
        const std::string cmd = fmt::format("draco_transcoder -i {} -o {} -qp 16 -qn 12 -qc 12 -qt 14 > /dev/null", source, out);
        ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
        ASSERT_NE(testing::read_file(out).find("KHR_draco_mesh_compression"), std::string::npos);
        const ImportedFile original = import_gltf(source), draco = import_gltf(out);
        ASSERT_EQ(original.meshes.size(), 1u);
        ASSERT_EQ(draco.meshes.size(), 1u);
        const TriangleMesh& a = original.meshes[0];
        const TriangleMesh& b = draco.meshes[0];
        EXPECT_EQ(a.triangle_count(), b.triangle_count()) << name;
        const auto area = [](const TriangleMesh& m) {
            double s = 0;
            for (std::uint32_t t = 0; t < m.triangle_count(); ++t) {
                const auto [p, q, r] = m.vertices(t);
                s += 0.5 * length(cross(q - p, r - p));
            }
            return s;
        };
        EXPECT_NEAR(area(a), area(b), 1e-3 * area(a)) << name;
        ASSERT_EQ(b.normals.size(), b.positions.size()) << name;
        EXPECT_EQ(a.colors.empty(), b.colors.empty()) << name;
        EXPECT_EQ(a.uvs.empty(), b.uvs.empty()) << name;
        for (std::size_t i = 0; i < b.positions.size(); ++i) {
            // The original vertex at this position with this normal (a cube's corners have three).
            std::size_t best = 0;
            float best_d = 1e30f;
            for (std::size_t j = 0; j < a.positions.size(); ++j) {
                const Normal3 na = a.normals[j], nb = b.normals[i];
                const float d = length(a.positions[j] - b.positions[i]) + length(Vector3{na.x - nb.x, na.y - nb.y, na.z - nb.z});
                if (d < best_d) best_d = d, best = j;
            }
            EXPECT_LT(best_d, 2e-3f) << name << " vertex " << i;
            if (!a.colors.empty()) {
                for (int k = 0; k < 3; ++k) EXPECT_NEAR(a.colors[best][k], b.colors[i][k], 1e-3) << name << " vertex " << i;
            }
            if (!a.uvs.empty()) {
                EXPECT_NEAR(a.uvs[best].x, b.uvs[i].x, 1e-3) << name << " vertex " << i;
                EXPECT_NEAR(a.uvs[best].y, b.uvs[i].y, 1e-3) << name << " vertex " << i;
            }
        }
    }
    // Corrupted Draco bytes: an error naming the file and Draco, or (if the bitstream's checks
    // cannot tell) a mesh, never a crash.
    const std::string bin = (dir / "Box-draco.bin").string();
    std::string bytes = testing::read_file(bin);
    for (std::size_t i = 8; i < bytes.size() && i < 60; ++i) bytes[i] = static_cast<char>(bytes[i] ^ 0x5a);
    std::ofstream(bin, std::ios::binary) << bytes;
    try {
        import_gltf(dir / "Box-draco.gltf");
    } catch (const IoError& e) {
        EXPECT_NE(std::string(e.what()).find("Box-draco.gltf"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("Draco"), std::string::npos) << e.what();
    }
}

TEST(GltfCompression, MeshoptBufferViewsDecodeWithTheirFilters) {
    const Grid g;
    const std::size_t nv = g.positions.size() / 3;
    // Positions and uvs as float vertex streams, normals as octahedral bytes (the OCTAHEDRAL
    // filter, 4 bytes per vertex), indices as a meshopt index buffer: all in buffer 0, which the
    // compressed views read; buffer 1 is gltfpack's fallback (no data, only a length).
    std::vector<unsigned char> bytes;
    struct View {
        std::size_t offset, length, stride, count;
        std::string mode, filter;
    };
    std::vector<View> views;
    const auto vertices = [&](const void* data, std::size_t stride, const std::string& filter) {
        std::vector<unsigned char> out(meshopt_encodeVertexBufferBound(nv, stride));
        out.resize(meshopt_encodeVertexBuffer(out.data(), out.size(), data, nv, stride));
        views.push_back({bytes.size(), out.size(), stride, nv, "ATTRIBUTES", filter});
        bytes.insert(bytes.end(), out.begin(), out.end());
        while (bytes.size() % 4) bytes.push_back(0);
    };
    vertices(g.positions.data(), 12, "NONE");
    vertices(g.uvs.data(), 8, "NONE");
    std::vector<float> normals;
    for (std::size_t i = 0; i < nv; ++i) normals.insert(normals.end(), {0, 0, 1, 0});
    std::vector<std::int8_t> oct(4 * nv);
    meshopt_encodeFilterOct(oct.data(), nv, 4, 8, normals.data());
    vertices(oct.data(), 4, "OCTAHEDRAL");
    std::vector<unsigned char> ib(meshopt_encodeIndexBufferBound(g.indices.size(), nv));
    ib.resize(meshopt_encodeIndexBuffer(ib.data(), ib.size(), g.indices.data(), g.indices.size()));
    views.push_back({bytes.size(), ib.size(), 4, g.indices.size(), "TRIANGLES", "NONE"});
    bytes.insert(bytes.end(), ib.begin(), ib.end());
    while (bytes.size() % 4) bytes.push_back(0);

    std::string view_json;
    std::size_t fallback = 0;
    for (const View& v : views) {
        view_json += fmt::format(
            R"({}{{"buffer": 1, "byteOffset": {}, "byteLength": {}{}, "extensions": {{"EXT_meshopt_compression": {{"buffer": 0, "byteOffset": {}, "byteLength": {}, "byteStride": {}, "count": {}, "mode": "{}", "filter": "{}"}}}}}})",
            view_json.empty() ? "" : ",\n    ", fallback, v.stride * v.count,
            v.mode == "ATTRIBUTES" ? fmt::format(R"(, "byteStride": {})", v.stride) : "", v.offset, v.length, v.stride,
            v.count, v.mode, v.filter);
        fallback += v.stride * v.count;
    }
    const std::string gltf = fmt::format(R"({{
  "asset": {{"version": "2.0"}},
  "extensionsUsed": ["EXT_meshopt_compression", "KHR_mesh_quantization"],
  "extensionsRequired": ["EXT_meshopt_compression", "KHR_mesh_quantization"],
  "scenes": [{{"nodes": [0]}}], "nodes": [{{"mesh": 0}}],
  "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0, "TEXCOORD_0": 1, "NORMAL": 2}}, "indices": 3}}]}}],
  "accessors": [
    {{"bufferView": 0, "componentType": 5126, "count": {0}, "type": "VEC3", "min": [0, 0, 0], "max": [4, 4, 0]}},
    {{"bufferView": 1, "componentType": 5126, "count": {0}, "type": "VEC2"}},
    {{"bufferView": 2, "componentType": 5120, "normalized": true, "count": {0}, "type": "VEC3"}},
    {{"bufferView": 3, "componentType": 5125, "count": 96, "type": "SCALAR"}}],
  "bufferViews": [{1}],
  "buffers": [{{"byteLength": {2}, "uri": "data:application/octet-stream;base64,{3}"}},
              {{"byteLength": {4}, "extensions": {{"EXT_meshopt_compression": {{"fallback": true}}}}}}]
}})",
                                         nv, view_json, bytes.size(), base64(bytes.data(), bytes.size()), fallback);
    testing::TempDir dir;
    std::ofstream(dir / "meshopt.gltf") << gltf;
    const ImportedFile f = import_gltf(dir / "meshopt.gltf");
    expect_grid(f);
    ASSERT_EQ(f.meshes.at(0).normals.size(), nv);

    // The same as a .glb: buffer 0 is the binary chunk.
    {
        std::string json = gltf;
        const std::string uri = fmt::format(R"(, "uri": "data:application/octet-stream;base64,{}")", base64(bytes.data(), bytes.size()));
        json.erase(json.find(uri), uri.size());
        while (json.size() % 4) json += ' ';
        std::string glb = "glTF";
        const auto u32 = [&](std::uint32_t v) { glb.append(reinterpret_cast<const char*>(&v), 4); };
        u32(2);
        u32(static_cast<std::uint32_t>(12 + 8 + json.size() + 8 + bytes.size()));
        u32(static_cast<std::uint32_t>(json.size()));
        glb += "JSON" + json;
        u32(static_cast<std::uint32_t>(bytes.size()));
        glb += std::string("BIN\0", 4);
        glb.append(reinterpret_cast<const char*>(bytes.data()), bytes.size());
        std::ofstream(dir / "meshopt.glb", std::ios::binary) << glb;
        expect_grid(import_gltf(dir / "meshopt.glb"));
    }

    // A truncated compressed stream is an error at that view, never a crash.
    std::string broken = gltf;
    const std::string key = "\"byteLength\": " + std::to_string(views[0].length) + ", \"byteStride\": 12, \"count\"";
    const auto at = broken.find(key);
    ASSERT_NE(at, std::string::npos);
    broken.replace(at, key.size(), "\"byteLength\": 5, \"byteStride\": 12, \"count\"");
    std::ofstream(dir / "broken.gltf") << broken;
    try {
        import_gltf(dir / "broken.gltf");
        ADD_FAILURE() << "no error";
    } catch (const IoError& e) {
        EXPECT_NE(std::string(e.what()).find("EXT_meshopt_compression"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("broken.gltf:"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace glint
