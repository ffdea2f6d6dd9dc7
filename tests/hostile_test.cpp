// Hostile inputs, second round (issue 32), met where a user meets them: through the command line.
// Each class: no crash, no hang (every run is killed after 20 s), a non-zero exit with a message
// naming the file and line, nothing written; and the valid-but-extreme renders.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

#include "cli_fixture.h"
#include "glint/image/image_io.h"

namespace glint_cli_test {
namespace {

class Hostile : public Cli {
protected:
    Result run_limited(const std::string& args) { return run(args, 20); }
    // The error must be a clean refusal: exit 1, `message` in stderr, no image.
    void expect_refused(const std::string& args, const std::string& message, int status = 1) {
        const Result r = run_limited(args);
        EXPECT_EQ(r.status, status) << args << "\n" << r.err;
        EXPECT_NE(r.err.find(message), std::string::npos) << args << "\n" << r.err;
        EXPECT_FALSE(fs::exists(dir_ / "out.png")) << args;
    }
    static constexpr const char* kCamera = "camera: {type: look_at, from: [0, 0, -5], to: [0, 0, 0], fov: 40}\n";
    // A real 2 x 2 image written by glint itself (to `out`, any format), for tests that damage it.
    int render_pixel(const std::string& out) {
        write("pixel.yaml", std::string(kCamera) + "film: {width: 2, height: 2}\nsampler: {spp: 1}\n"
                            "objects:\n  - {type: sphere, center: [0, 0, 0], radius: 1}\n");
        return run_limited("render pixel.yaml -o " + out).status;
    }
};

std::string base64(const std::string& bytes) {
    static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (std::size_t i = 0; i < bytes.size(); i += 3) {
        std::uint32_t v = static_cast<unsigned char>(bytes[i]) << 16;
        if (i + 1 < bytes.size()) v |= static_cast<unsigned char>(bytes[i + 1]) << 8;
        if (i + 2 < bytes.size()) v |= static_cast<unsigned char>(bytes[i + 2]);
        out += k[v >> 18 & 63];
        out += k[v >> 12 & 63];
        out += i + 1 < bytes.size() ? k[v >> 6 & 63] : '=';
        out += i + 2 < bytes.size() ? k[v & 63] : '=';
    }
    return out;
}

// One triangle, counter-clockwise seen from +z (glTF's front), positions then indices in one
// buffer; `primitive_extra` and `top_extra` are spliced into the primitive and the top object.
std::string triangle_gltf(const std::string& primitive_extra = "", const std::string& top_extra = "",
                          std::vector<std::uint16_t> indices = {0, 1, 2}, float scale = 1) {
    std::string buffer;
    for (float f : {0.0f, 0.0f, 0.0f, scale, 0.0f, 0.0f, 0.0f, scale, 0.0f}) buffer.append(reinterpret_cast<const char*>(&f), 4);
    for (std::uint16_t i : indices) buffer.append(reinterpret_cast<const char*>(&i), 2);
    while (buffer.size() % 4) buffer += '\0';
    return fmt::format(
        R"({{"asset": {{"version": "2.0"}}{},
 "scenes": [{{"nodes": [0]}}], "nodes": [{{"mesh": 0}}],
 "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0}}, "indices": 1{}}}]}}],
 "accessors": [
  {{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [{}, {}, 0]}},
  {{"bufferView": 1, "componentType": 5123, "count": {}, "type": "SCALAR"}}],
 "bufferViews": [{{"buffer": 0, "byteLength": 36}}, {{"buffer": 0, "byteOffset": 36, "byteLength": {}}}],
 "buffers": [{{"byteLength": {}, "uri": "data:application/octet-stream;base64,{}"}}]}}
)",
        top_extra, primitive_extra, scale, scale, indices.size(), 2 * indices.size(), buffer.size(), base64(buffer));
}

// triangle_gltf with the first `from` replaced by `to`.
std::string triangle_gltf_with(const std::string& from, const std::string& to) {
    std::string g = triangle_gltf();
    g.replace(g.find(from), from.size(), to);
    return g;
}

// triangle_gltf with a COLOR_0 of `rgb` at every corner and no material.
std::string colored_triangle_gltf(float r, float g, float b) {
    std::string buffer;
    for (float f : {0.0f, 0.0f, 0.0f, 1.0f, 0.0f, 0.0f, 0.0f, 1.0f, 0.0f}) buffer.append(reinterpret_cast<const char*>(&f), 4);
    for (int k = 0; k < 3; ++k)
        for (float f : {r, g, b}) buffer.append(reinterpret_cast<const char*>(&f), 4);
    return fmt::format(
        R"({{"asset": {{"version": "2.0"}}, "scenes": [{{"nodes": [0]}}], "nodes": [{{"mesh": 0}}],
 "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0, "COLOR_0": 1}}}}]}}],
 "accessors": [
  {{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}},
  {{"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC3"}}],
 "bufferViews": [{{"buffer": 0, "byteLength": 36}}, {{"buffer": 0, "byteOffset": 36, "byteLength": 36}}],
 "buffers": [{{"byteLength": 72, "uri": "data:application/octet-stream;base64,{}"}}]}}
)",
        base64(buffer));
}

// --- recursion an input controls -----------------------------------------------------------------

TEST_F(Hostile, YamlAliasInsideItsOwnAnchorIsALocatedError) {
    write("cycle.yaml", std::string(kCamera) + "objects:\n  - &a {type: sphere, center: [0, 0, 0], radius: 1, children: [*a]}\n");
    expect_refused("render cycle.yaml -o out.png", "cycle.yaml:3:");
    write("cycle2.yaml", std::string(kCamera) + "materials:\n  m: &a [1, *a]\n");
    expect_refused("render cycle2.yaml -o out.png", "the value would contain itself");
}

TEST_F(Hostile, AChainOfTenThousandAliasesIsRefusedByTheNestingLimit) {
    std::string text = std::string(kCamera) + "materials:\n  a0: &a0 {color: [1, 1, 1]}\n";
    for (int i = 1; i < 10000; ++i) text += fmt::format("  a{}: &a{} [*a{}]\n", i, i, i - 1);
    write("chain.yaml", text);
    expect_refused("render chain.yaml -o out.png", "levels of nesting exceed the limit of 256 (raise it with --limit nesting=N)");
}

TEST_F(Hostile, BlockNestingDeeperThanTheLimitIsRefusedAsSuch) {
    // Indentation, not brackets: 300 levels reach glint's own check, 3000 yaml-cpp's guard (which
    // says only "bad file"); both are the nesting limit's error.
    for (const int levels : {300, 3000}) {
        std::string text = std::string(kCamera) + "materials:\n  m:";
        for (int i = 0; i < levels; ++i) text += "\n" + std::string(2 * i + 4, ' ') + fmt::format("k{}:", i);
        write("deep.yaml", text + " 1\n");
        expect_refused("render deep.yaml -o out.png", "levels of nesting exceed the limit of 256 (raise it with --limit nesting=N)");
    }
}

TEST_F(Hostile, TheNestingLimitCountsAsTheFlowPrescanDoes) {
    // Every collection counts, block or flow: the document, `materials`, `m` and 253 lists are 256
    // levels, within the limit (the value is wrong for its key, not for its depth); 254 lists
    // are 257, refused although their brackets alone (255) pass the text's pre-scan.
    for (const int levels : {253, 254}) {
        write("n.yaml", std::string(kCamera) + "materials:\n  m: {color: " + std::string(levels, '[') + "1" +
                            std::string(levels, ']') + "}\n");
        const Result r = run_limited("render n.yaml -o out.png");
        EXPECT_EQ(r.status, 1);
        EXPECT_EQ(r.err.find("257 levels of nesting exceed") != std::string::npos, levels == 254) << levels << "\n" << r.err;
    }
}

TEST_F(Hostile, ABillionLaughsOfTexturesIsRefusedAtOnceUsedOrNot) {
    for (const bool used : {false, true}) {
        std::string text = std::string(kCamera) + "materials:\n  l0: {color: &t0 {type: mix, a: [1, 1, 1], b: [0, 0, 0], amount: 0.5}}\n";
        for (int i = 1; i < 60; ++i)
            text += fmt::format("  l{}: {{color: &t{} {{type: mix, a: *t{}, b: *t{}, amount: 0.5}}}}\n", i, i, i - 1, i - 1);
        if (used) text += "objects:\n  - {type: sphere, center: [0, 0, 0], radius: 1, material: l59}\n";
        write("laughs.yaml", text);
        expect_refused("render laughs.yaml -o out.png", "values, the limit (raise it with --limit nodes=N)");
    }
}

TEST_F(Hostile, GltfExtrasNestedFortyThousandDeepIsALocatedError) {
    const std::string deep = std::string(40000, '[') + std::string(40000, ']');
    write("deep.gltf", triangle_gltf("", ", \"extras\": {\"x\": " + deep + "}"));
    expect_refused("render deep.gltf -o out.png", "deep.gltf:");
    expect_refused("render deep.gltf -o out.png", "levels of nesting exceed the limit of 256");
    // On a node too, in a .gltf the user's scene names.
    std::string node_deep = triangle_gltf();
    node_deep.replace(node_deep.find("{\"mesh\": 0}"), 11, "{\"mesh\": 0, \"extras\": " + deep + "}");
    write("node.gltf", node_deep);
    expect_refused("render node.gltf -o out.png", "node.gltf:2:");
}

// --- extreme values ------------------------------------------------------------------------------

TEST_F(Hostile, ASphereOfRadiusNearFloatMaxRendersBesideOthers) {
    write("huge.yaml", std::string(kCamera) +
                           "objects:\n"
                           "  - {type: sphere, center: [0, 0, 0], radius: 1.8e38}\n"
                           "  - {type: sphere, center: [0, 0, 3], radius: 1}\n"
                           "  - {type: sphere, center: [3e38, -3e38, 1e38], radius: 1e30}\n"
                           "  - {type: triangle, vertices: [[-3e38, 0, 0], [3e38, 0, 0], [0, 3e38, 1]]}\n");
    const Result r = run_limited("render huge.yaml -o out.png --width 32 --height 24");
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(fs::exists(dir_ / "out.png"));
}

TEST_F(Hostile, ASphereWhoseBoundsLeaveFloatsRangeIsRefusedAtItsRadius) {
    write("far.yaml", std::string(kCamera) + "objects:\n  - {type: sphere, center: [1e38, 0, 0], radius: 3e38}\n");
    expect_refused("render far.yaml -o out.png", "far.yaml:3:50: error: sphere: centre ± radius reaches past float's range");
}

TEST_F(Hostile, AVectorTooLongForFloatIsSaidSoNotCalledZeroLength) {
    write("long.yaml", std::string(kCamera) +
                           "objects:\n  - {type: quad, corner: [0, 0, 10], edge1: [3.4e38, 0, 0], edge2: [0, 1, 0]}\n");
    expect_refused("render long.yaml -o out.png", "long.yaml:3:45: error: edge1 is too long for float arithmetic");
}

// --- allocations a header can lie about ----------------------------------------------------------

TEST_F(Hostile, AnHdrHeaderClaimingMorePixelsThanItsBytesIsRefusedBeforeAllocating) {
    std::string hdr = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 11000 +X 11000\n";
    hdr += std::string(56 - hdr.size(), '\x01');
    ASSERT_EQ(hdr.size(), 56u);
    write("lie.hdr", hdr);
    write("env.yaml", std::string(kCamera) + "background: {type: environment, filename: lie.hdr}\n");
    // The message is the row check's, which runs before the pixels are allocated.
    const Result r = run_limited("render env.yaml -o out.png");
    EXPECT_EQ(r.status, 1) << r.err;
    EXPECT_NE(r.err.find("lie.hdr"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("11000 rows need at least"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("env.yaml:2:"), std::string::npos) << r.err;
}

// OpenEXR allocates its decoding buffers, whole blocks of the data window, when it opens a file:
// a window claimed 4 million pixels wide and one row high was gigabytes before glint could look
// (found by fuzz_image). Refused from the header, as an environment map and to `glint denoise`.
TEST_F(Hostile, AnExrHeaderClaimingAWideWindowIsRefusedBeforeOpenEXRAllocates) {
    ASSERT_EQ(render_pixel("ok.exr"), 0);
    std::string bytes = read(dir_ / "ok.exr");
    const std::size_t at = bytes.find(std::string("dataWindow\0box2i\0", 17));
    ASSERT_NE(at, std::string::npos);
    const std::int32_t window[4] = {0, 0, 3'999'999, 0};
    std::memcpy(bytes.data() + at + 17 + 4, window, 16);
    write("lie.exr", bytes);
    write("env.yaml", std::string(kCamera) + "background: {type: environment, filename: lie.exr}\n");
    const std::string claim = "lie.exr': its header claims a 4000000 x 1 data window in blocks of 16 rows";
    expect_refused("render env.yaml -o out.png", claim);
    expect_refused("render env.yaml -o out.png", "env.yaml:2:");
    const Result r = run_limited("denoise lie.exr -o out.exr");
    EXPECT_EQ(r.status, 1) << r.err;
    EXPECT_NE(r.err.find(claim), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "out.exr"));
}

TEST_F(Hostile, AGltfAccessorOfMillionsWithNoDataIsRefusedNamingTheFile) {
    std::string g = triangle_gltf_with("\"count\": 3", "\"count\": 89000000");
    g.replace(g.find("{\"bufferView\": 0, "), 18, "{");
    write("zeros.gltf", g);
    expect_refused("render zeros.gltf -o out.png", "zeros.gltf:");
}

TEST_F(Hostile, ANegativeGltfAccessorCountIsLocated) {
    write("negative.gltf", triangle_gltf_with("\"count\": 3", "\"count\": -3"));
    expect_refused("render negative.gltf -o out.png", "negative.gltf:5:");
    expect_refused("render negative.gltf -o out.png", "accessors[0].count: -3 is not an integer of at least 1");
}

// --- real files refused no more --------------------------------------------------------------------

TEST_F(Hostile, ObjFacesOf360CornersRender) {
    std::string obj;
    for (int k = 0; k < 360; ++k)
        obj += fmt::format("v {} {} 0\n", std::cos(k * 3.14159265 / 180), std::sin(k * 3.14159265 / 180));
    obj += "f";
    for (int k = 1; k <= 360; ++k) obj += fmt::format(" {}", k);
    obj += "\n";
    write("circle.obj", obj);
    write("circle.yaml", std::string(kCamera) + "objects:\n  - {type: mesh, file: circle.obj}\n");
    const Result r = run_limited("info circle.yaml");
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("358"), std::string::npos) << r.out;  // 360 - 2 triangles
}

// --- errors that point at the spot -----------------------------------------------------------------

TEST_F(Hostile, MissingMaterialLibrariesAndMapsNameTheirFileAndLine) {
    write("a.obj", "# a quad\nmtllib missing.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 3\n");
    expect_refused("render a.obj -o out.png", "a.obj:2: material library 'missing.mtl'");
    write("b.obj", "mtllib b.mtl\nusemtl red\nv 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 3\n");
    write("b.mtl", "newmtl other\nKd 1 1 1\n\nnewmtl red\nKd 1 0 0\nmap_Kd nowhere.png\n");
    expect_refused("render b.obj -o out.png", "b.mtl:6: material 'red': texture map_Kd 'nowhere.png' not found");
    write("b.mtl", "newmtl red\nKd 1 0 0\nnorm bumps.png\n");
    expect_refused("render b.obj -o out.png", "b.mtl:3: material 'red': normal map 'bumps.png' not found");
}

TEST_F(Hostile, APngNamedExrIsRefusedInGlintsWordsAtTheSceneLine) {
    ASSERT_EQ(render_pixel("env.png"), 0);
    fs::rename(dir_ / "env.png", dir_ / "env.exr");
    write("env.yaml", std::string(kCamera) + "background: {type: environment, filename: env.exr}\n");
    expect_refused("render env.yaml -o out.png", "it is a PNG file, not OpenEXR as its extension says");
    expect_refused("render env.yaml -o out.png", "env.yaml:2:");
}

TEST_F(Hostile, ANulByteFurtherInIsReportedAtItsLine) {
    std::string text = std::string(kCamera) + "objects:\n  - {type: sphere, center: [0, 0, 0], ";
    text += '\0';
    text += " radius: 1}\n";
    std::ofstream(dir_ / "nul.yaml", std::ios::binary) << text;
    expect_refused("render nul.yaml -o out.png", "nul.yaml:3:39: error: a NUL byte");
}

// --- the command line's edges --------------------------------------------------------------------

// A value out of its range is CLI11's validation error, status 105 (docs/cli.md).
TEST_F(Hostile, SeedsOutOfRangeAreRefused) {
    write("s.yaml", std::string(kCamera) + "film: {width: 4, height: 4}\nobjects:\n  - {type: sphere, center: [0, 0, 0], radius: 1}\n");
    expect_refused("render s.yaml -o out.png --seed -1", "--seed: '-1' is not a whole number from 0 to 18446744073709551615", 105);
    expect_refused("render s.yaml -o out.png --seed 18446744073709551616", "--seed: 18446744073709551616 is out of range", 105);
    expect_refused("render s.yaml -o out.png --seed 12abc", "is not a whole number", 105);
    const Result r = run_limited("render s.yaml -o out.png --seed 18446744073709551615");
    EXPECT_EQ(r.status, 0) << r.err;
}

TEST_F(Hostile, EmptyArgumentsAreErrorsNotDefaults) {
    write("s.yaml", std::string(kCamera) + "film: {width: 4, height: 4}\nobjects:\n  - {type: sphere, center: [0, 0, 0], radius: 1}\n");
    expect_refused("render s.yaml -o ''", "--output: an empty argument", 105);
    EXPECT_FALSE(fs::exists(dir_ / "s.png"));
    EXPECT_FALSE(fs::exists(dir_ / "glint.png"));
    expect_refused("render ''", "SCENE: an empty argument", 105);
    EXPECT_FALSE(fs::exists(dir_ / "glint.png"));
}

TEST_F(Hostile, AnUnknownCommandIsNamedWithTheNearest) {
    // Status 106, as CLI11 gives for a missing command.
    expect_refused("draw s.yaml", "unknown command 'draw'", 106);
    expect_refused("draw s.yaml", "commands: render, info, bench, convert", 106);
    expect_refused("rendr s.yaml", "did you mean 'render'?", 106);
    write("s.yaml", "");
    expect_refused("s.yaml", "to render that file: glint render s.yaml", 106);
}

// --- glTF as its specification says --------------------------------------------------------------

TEST_F(Hostile, AGltfSyntaxErrorQuotingALongStretchIsALocatedErrorNotAStackOverflow) {
    // Found by fuzz_gltf (fuzz/regressions/gltf/): tinygltf's message quoted a 20 KB literal, and
    // libstdc++'s std::regex, matching it, recursed per character until the stack overflowed.
    write("long.gltf", "{\n  \"accessors\": [\n    {\n      \"buffe" + std::string(20000, 'A') + "A/ \"x\"}]}\n");
    expect_refused("render long.gltf -o out.png", "long.gltf:4:");
    expect_refused("render long.gltf -o out.png", "JSON syntax error");
}

TEST_F(Hostile, GltfVersionsAGlint20ReaderCannotReadAreRefused) {
    write("min.gltf", triangle_gltf_with("{\"version\": \"2.0\"}", "{\"version\": \"2.0\", \"minVersion\": \"2.1\"}"));
    expect_refused("render min.gltf -o out.png", "min.gltf:1:");
    expect_refused("render min.gltf -o out.png", "asset.minVersion: the file needs glTF 2.1; glint reads glTF 2.0");
    write("three.gltf", triangle_gltf_with("\"2.0\"", "\"3.0\""));
    expect_refused("render three.gltf -o out.png", "asset.version: the file needs glTF 3.0");
}

TEST_F(Hostile, GltfPropertiesOfTheWrongTypeAreLocatedErrors) {
    const auto with = triangle_gltf_with;
    write("a.gltf", with("\"count\": 3", "\"count\": \"3\""));
    expect_refused("render a.gltf -o out.png", "a.gltf:5:");
    expect_refused("render a.gltf -o out.png", "accessors[0].count: \"3\" is not an integer of at least 1");
    write("b.gltf", with("\"mesh\": 0", "\"mesh\": {\"index\": 0}"));
    expect_refused("render b.gltf -o out.png", "nodes[0].mesh: {\"index\":0} is not an integer of at least 0");
    write("c.gltf", with("\"componentType\": 5126", "\"componentType\": 5127"));
    expect_refused("render c.gltf -o out.png", "accessors[0].componentType: 5127 is not one of the values glTF allows");
    write("d.gltf", with("\"type\": \"VEC3\"", "\"type\": \"VEC5\""));
    expect_refused("render d.gltf -o out.png", "accessors[0].type: \"VEC5\" is not one of the values glTF allows");
}

TEST_F(Hostile, AnEmissiveGltfTriangleWithoutNormalsShinesToItsFront) {
    // Counter-clockwise seen from +z, which is glTF's front: glint's frame mirrors z, so the front
    // faces glint's -z. Black, one-sided emission 1, on black: seen from the front the triangle
    // glows (1), from the back it is black.
    write("lamp.gltf", triangle_gltf(", \"material\": 0",
                                     ", \"materials\": [{\"emissiveFactor\": [1, 1, 1], \"pbrMetallicRoughness\": "
                                     "{\"baseColorFactor\": [0, 0, 0, 1], \"metallicFactor\": 0}}]"));
    const auto brightest = [&](float z) {
        write("lamp.yaml", fmt::format("camera: {{type: look_at, from: [0.3, 0.3, {}], to: [0.3, 0.3, 0], fov: 40}}\n"
                                       "film: {{width: 24, height: 24}}\nsampler: {{spp: 4}}\nintegrator: {{type: path}}\n"
                                       "background: {{type: constant, color: [0, 0, 0]}}\n"
                                       "objects:\n  - {{type: mesh, file: lamp.gltf}}\n", z));
        const Result r = run_limited("render lamp.yaml -o lamp.pfm");
        EXPECT_EQ(r.status, 0) << r.err;
        float most = 0;
        for (const glint::Color& c : glint::read_image(dir_ / "lamp.pfm", glint::ImageEncoding::kLinear).texels)
            most = std::max(most, c.g);
        return most;
    };
    EXPECT_GT(brightest(-3), 0.9f) << "from glTF's front";
    EXPECT_LT(brightest(3), 0.01f) << "from its back";
}

TEST_F(Hostile, VertexColoursTintAPrimitiveWithoutAMaterial) {
    // The spec's default material (white, metallic 1, roughness 1) times COLOR_0 red, under a white
    // sky: a rough red metal, so the triangle is red, not the grey of glint's default material.
    write("red.gltf", colored_triangle_gltf(1, 0, 0));
    write("red.yaml", "camera: {type: look_at, from: [0.3, 0.3, -3], to: [0.3, 0.3, 0], fov: 20}\n"
                      "film: {width: 8, height: 8}\nsampler: {spp: 16}\nintegrator: {type: path}\n"
                      "background: {type: constant, color: [1, 1, 1]}\nobjects:\n  - {type: mesh, file: red.gltf}\n");
    const Result r = run_limited("render red.yaml -o red.pfm");
    ASSERT_EQ(r.status, 0) << r.err;
    const glint::Image im = glint::read_image(dir_ / "red.pfm", glint::ImageEncoding::kLinear);
    const glint::Color c = im.texels[4 * 8 + 3];  // inside the triangle, near the frame's centre
    EXPECT_GT(c.r, 0.2f);
    EXPECT_LT(c.g, 0.2f * c.r);
    EXPECT_LT(c.b, 0.2f * c.r);
}

TEST_F(Hostile, GltfPrimitiveRestartIndicesAreRefused) {
    write("restart.gltf", triangle_gltf("", "", {0, 1, 2, 65535, 0, 1}));
    expect_refused("render restart.gltf -o out.png", "index 65535 is the primitive restart value");
}

TEST_F(Hostile, AGltfTextureFileThatIsNotThereIsNotFound) {
    std::string g = triangle_gltf(", \"material\": 0",
                                  ", \"materials\": [{\"pbrMetallicRoughness\": {\"baseColorTexture\": {\"index\": 0}}}],"
                                  " \"textures\": [{\"source\": 0}], \"images\": [{\"uri\": \"gone.png\"}]");
    write("tex.gltf", g);
    expect_refused("render tex.gltf -o out.png", "image 0: 'gone.png' not found");
}

TEST_F(Hostile, AMeshOfOnlyDegenerateTrianglesIsAnErrorAsAnEmptySceneIs) {
    write("inf.obj", "v 0 0 0\nv inf 0 0\nv 0 1 0\nf 1 2 3\n");
    expect_refused("render inf.obj -o out.png", "all 1 of its triangles are degenerate");
    write("flat.gltf", triangle_gltf("", "", {0, 0, 1}));
    expect_refused("render flat.gltf -o out.png", "all 1 of its triangles are degenerate");
}

}  // namespace
}  // namespace glint_cli_test
