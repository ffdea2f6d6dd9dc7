// Structure-aware: the input is not a file but the choices that build one, so that every run is
// a well-formed attack of the classes issue 32 names, which byte-level mutation reaches rarely:
//   0  YAML alias graphs: anchors whose values repeat earlier anchors (or themselves) any number
//      of times, at any nesting: cycles, long chains, billion laughs, used or unused;
//   1  glTF JSON nested deep (in extras, on the asset or a node) with accessor counts and buffer
//      sizes that lie (negative, huge, no bufferView, a view shorter than its accessor);
//   2  image headers that lie about their size (HDR, PFM, PPM, PNG IHDR) over a few real bytes;
//   3  OBJ polygons of any corner count, concave, with extreme coordinates.
// A located error or a clean result is the right answer; anything else is a finding.
#include <fmt/format.h>

#include <cmath>
#include <cstring>

#include "fuzz_common.h"
#include "glint/assets/mesh_import.h"
#include "glint/formats/scene_yaml.h"

namespace {

// The input as a stream of choices; past its end every choice is 0.
class Choices {
public:
    Choices(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}
    std::uint32_t byte() { return at_ < size_ ? data_[at_++] : 0; }
    std::uint32_t u16() { return byte() | byte() << 8; }
    std::uint32_t u32() { return u16() | u16() << 16; }
    std::uint32_t below(std::uint32_t n) { return n == 0 ? 0 : u16() % n; }
    double number() {  // ordinary, tiny, huge, negative, non-finite
        static const double kSpecial[] = {0, 1, -1, 0.5, 1e-38, 1e38, 3.4e38, -3.4e38, 1e300, NAN, INFINITY, -INFINITY};
        const std::uint32_t pick = byte();
        return pick < 200 ? (static_cast<double>(u16()) - 32768) / 256 : kSpecial[pick % std::size(kSpecial)];
    }

private:
    const std::uint8_t* data_;
    std::size_t size_, at_ = 0;
};

std::string yaml_number(double x) {
    if (std::isnan(x)) return ".nan";
    if (std::isinf(x)) return x > 0 ? ".inf" : "-.inf";
    return fmt::format("{}", x);
}

void alias_graph(Choices& c) {
    std::string text = "camera: {type: look_at, from: [0, 0, -5], to: [0, 0, 0], fov: 40}\nfilm: {width: 4, height: 4}\n"
                       "sampler: {spp: 1}\nmaterials:\n";
    const std::uint32_t anchors = 1 + c.below(64);
    for (std::uint32_t i = 0; i < anchors; ++i) {
        const std::uint32_t repeats = c.below(12), depth = c.below(8);
        std::string value = std::string(depth, '[') + "{type: mix, a: [1, 1, 1], b: [0, 0, 0], amount: 0.5}";
        for (std::uint32_t k = 0; k < repeats; ++k) value += fmt::format(", *a{}", c.below(i + 1));  // i: itself
        value += std::string(depth, ']');
        text += fmt::format("  m{}: {{color: &a{} {}}}\n", i, i, depth == 0 && repeats == 0 ? value : "[" + value + "]");
    }
    if (c.byte() % 2)
        text += fmt::format("objects:\n  - {{type: sphere, center: [0, 0, 0], radius: {}, material: m{}}}\n",
                            yaml_number(c.number()), c.below(anchors));
    glint::fuzz::expect_located_errors([&] {
        auto sources = std::make_shared<glint::SourceFiles>();
        glint::parse_scene(text, "structure.yaml", sources);
    });
}

void lying_gltf(Choices& c) {
    const std::uint32_t depth = c.u16() % 50000;
    const std::string deep = std::string(depth, '[') + std::string(depth, ']');
    const bool on_node = c.byte() % 2;
    const long long count = static_cast<std::int32_t>(c.u32());
    const std::uint32_t length = c.u16(), offset = c.u16();
    const bool view = c.byte() % 3 != 0;
    const std::string buffer = "AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAABAAIAAAA=";  // 3 floats x 3, 3 u16
    const std::string json = fmt::format(
        R"({{"asset": {{"version": "2.0"{}}}, "scenes": [{{"nodes": [0]}}], "nodes": [{{"mesh": 0{}}}],
"meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0}}}}]}}],
"accessors": [{{{}"componentType": 5126, "count": {}, "type": "VEC3"}}],
"bufferViews": [{{"buffer": 0, "byteOffset": {}, "byteLength": {}}}],
"buffers": [{{"byteLength": 44, "uri": "data:application/octet-stream;base64,{}"}}]}})",
        on_node ? "" : ", \"extras\": " + (deep.empty() ? std::string("0") : deep), on_node && !deep.empty() ? ", \"extras\": " + deep : "",
        view ? "\"bufferView\": 0, " : "", count, offset, length, buffer);
    const auto path = glint::fuzz::put("structure.gltf", json);
    glint::fuzz::expect_located_errors([&] { glint::import_gltf(path); });
}

void lying_image(Choices& c) {
    const std::uint32_t w = c.u32(), h = c.u32(), kind = c.byte() % 4, data = c.below(256);
    std::string bytes;
    const char* ext = ".hdr";
    if (kind == 0) {
        bytes = fmt::format("#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y {} +X {}\n", h, w);
    } else if (kind == 1) {
        bytes = fmt::format("PF\n{} {}\n-1.0\n", w, h);
        ext = ".pfm";
    } else if (kind == 2) {
        bytes = fmt::format("P6\n{} {}\n255\n", w, h);
        ext = ".ppm";
    } else {  // a PNG signature and an IHDR claiming w x h (its CRC unchecked by the claim)
        bytes = std::string("\x89PNG\r\n\x1a\n\0\0\0\x0dIHDR", 16);
        for (std::uint32_t v : {w, h}) {
            for (int k = 3; k >= 0; --k) bytes += static_cast<char>(v >> (8 * k));
        }
        bytes += std::string("\x08\x02\0\0\0", 5);
        ext = ".png";
    }
    for (std::uint32_t i = 0; i < data; ++i) bytes += static_cast<char>(c.byte());
    const auto path = glint::fuzz::put(std::string("structure") + ext, bytes);
    glint::fuzz::expect_located_errors([&] { glint::read_image(path, glint::ImageEncoding::kAuto, 1 << 22); });
}

void polygon(Choices& c) {
    const std::uint32_t corners = 3 + c.below(1000);
    std::string obj;
    for (std::uint32_t i = 0; i < corners; ++i) {
        const double a = 2 * 3.14159265358979 * i / corners, r = 1 + (c.byte() % 2 ? c.number() : 0);
        obj += fmt::format("v {} {} {}\n", yaml_number(r * std::cos(a)), yaml_number(r * std::sin(a)),
                           c.byte() % 8 == 0 ? yaml_number(c.number()) : "0");
    }
    obj += "f";
    for (std::uint32_t i = 1; i <= corners; ++i) obj += fmt::format(" {}", i);
    obj += "\n";
    glint::fuzz::expect_located_errors([&] { glint::parse_obj(obj, "structure.obj", glint::fuzz::scratch()); });
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    glint::fuzz::scratch();
    Choices c(data, size);
    switch (c.byte() % 4) {
        case 0: alias_graph(c); break;
        case 1: lying_gltf(c); break;
        case 2: lying_image(c); break;
        default: polygon(c); break;
    }
    return 0;
}
