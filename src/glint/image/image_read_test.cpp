// Reading texture images through OpenImageIO: real files written here, then read back.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <fmt/format.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <bit>
#include <tuple>

#include "glint/builder/build.h"
#include "glint/image/image_io.h"
#include "glint/base/limits.h"
#include "glint/formats/scene_yaml.h"
#include "glint/render/render.h"
#include "testing.h"

namespace glint {
namespace {

void write_rgb(const std::filesystem::path& path, int w, int h, OIIO::TypeDesc type,
               const std::vector<float>& rgb, const char* compression = nullptr) {
    auto out = OIIO::ImageOutput::create(path.string());
    ASSERT_TRUE(out);
    OIIO::ImageSpec spec(w, h, 3, type);
    if (compression) spec.attribute("compression", compression);
    ASSERT_TRUE(out->open(path.string(), spec));
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, rgb.data()));
    out->close();
}

// Every format textures come in: values written
// (8-bit ones exactly representable, read as linear), read back within each format's precision.
TEST(ImageRead, EveryFormatByItsExtension) {
    testing::TempDir dir;
    const std::vector<float> rgb{0, 51 / 255.0f, 1, 102 / 255.0f, 153 / 255.0f, 204 / 255.0f,
                                 1, 0, 51 / 255.0f, 204 / 255.0f, 1, 0};  // 2 x 2
    struct Case {
        const char* ext;
        OIIO::TypeDesc type;
        float tolerance;
    };
    for (const Case& c : {Case{".png", OIIO::TypeDesc::UINT8, 1e-6f}, Case{".tga", OIIO::TypeDesc::UINT8, 1e-6f},
                         Case{".tif", OIIO::TypeDesc::UINT8, 1e-6f}, Case{".ppm", OIIO::TypeDesc::UINT8, 1e-6f},
                         Case{".exr", OIIO::TypeDesc::FLOAT, 0}, Case{".hdr", OIIO::TypeDesc::FLOAT, 0.01f}}) {
        SCOPED_TRACE(c.ext);
        const auto path = dir / (std::string("a") + c.ext);
        write_rgb(path, 2, 2, c.type, rgb);
        const Image im = read_image(path, ImageEncoding::kLinear);
        ASSERT_EQ(im.width, 2);
        ASSERT_EQ(im.height, 2);
        for (int i = 0; i < 4; ++i) {
            const Color& t = im.texel(i % 2, i / 2);
            EXPECT_NEAR(t.r, rgb[3 * i], c.tolerance);
            EXPECT_NEAR(t.g, rgb[3 * i + 1], c.tolerance);
            EXPECT_NEAR(t.b, rgb[3 * i + 2], c.tolerance);
        }
    }
    // JPEG (lossy, its colours subsampled): a flat grey, within a level or two.
    write_rgb(dir / "a.jpg", 2, 2, OIIO::TypeDesc::UINT8, std::vector<float>(12, 102 / 255.0f));
    for (const Color& t : read_image(dir / "a.jpg", ImageEncoding::kLinear).texels) EXPECT_NEAR(t.g, 102 / 255.0f, 2 / 255.0f);
}

// Found by fuzz_image: OpenEXR allocates what a header attribute declares, before glint could
// check anything (1.9 GB for a 1.4 KB file). glint checks the sizes against the file first,
// walking the header as OpenEXR does.
class ExrHeaderLies : public ::testing::Test {
protected:
    void SetUp() override {
        write_rgb(dir_ / "ok.exr", 2, 2, OIIO::TypeDesc::HALF, std::vector<float>(12, 0.5f));
        std::ifstream in(dir_ / "ok.exr", std::ios::binary);
        ok_.assign(std::istreambuf_iterator<char>(in), {});
    }
    // An attribute of a type OpenEXR does not know: it allocates `size` bytes for the value.
    static std::string opaque(const std::string& name, std::uint32_t size) {
        std::string a = name + '\0' + "glintjunk" + '\0';
        a.append(reinterpret_cast<const char*>(&size), 4);
        return a;
    }
    std::string refused(const std::string& bytes) {
        std::ofstream(dir_ / "bad.exr", std::ios::binary) << bytes;
        try {
            read_image(dir_ / "bad.exr", ImageEncoding::kLinear);
        } catch (const IoError& e) {
            return e.what();
        }
        return "no error";
    }
    testing::TempDir dir_;
    std::string ok_;
};

TEST_F(ExrHeaderLies, AnAttributeLargerThanTheFileIsRefusedAtItsByte) {
    // Inserted before the first attribute (byte 8): the name, the type, then the 4-byte size at 8 + 4 + 10.
    const std::string bytes = ok_.substr(0, 8) + opaque("big", 0x70000000) + ok_.substr(8);
    EXPECT_NE(refused(bytes).find(fmt::format("bad.exr': byte 22: OpenEXR header attribute 'big' claims 1879048192 bytes, "
                                              "more than the {} bytes left in the file",
                                              bytes.size() - 26)),
              std::string::npos)
        << refused(bytes);
    EXPECT_EQ(read_image(dir_ / "ok.exr", ImageEncoding::kLinear).width, 2);  // a good file is untouched
}

TEST_F(ExrHeaderLies, AnAttributeHiddenBehindAChannelListsLyingSizeIsSeen) {
    // OpenEXR reads a channel list up to its empty name, whatever size it declares; the next
    // attribute starts there. A list declaring 32 bytes more than it takes hides, from a walk by
    // declared sizes, an attribute that OpenEXR reads (fuzz/regressions/image/exr-chlist-hides-attribute).
    const std::size_t at = ok_.find(std::string("channels\0chlist\0", 16));
    ASSERT_NE(at, std::string::npos);
    const std::size_t type_end = at + 15;
    std::uint32_t size = 0;
    std::memcpy(&size, ok_.data() + type_end + 1, 4);
    const std::size_t value_end = type_end + 5 + size;
    const std::string hidden = opaque("big", 0x70000000);
    std::string padded = hidden + std::string(32 - hidden.size(), 'x');
    std::string bytes = ok_.substr(0, value_end) + padded + ok_.substr(value_end);
    const std::uint32_t lie = size + 32;
    std::memcpy(bytes.data() + type_end + 1, &lie, 4);
    EXPECT_NE(refused(bytes).find(fmt::format("bad.exr': byte {}: OpenEXR header attribute 'big' claims 1879048192 bytes",
                                              value_end + 4 + 10)),
              std::string::npos)
        << refused(bytes);
}

// Found by fuzz_image's idle hour: OpenEXR's reader allocates its decoding buffers, each a whole
// block of 16 to 256 rows (or a tile) of the data window, when the file is opened, however few
// rows the window has. A ~500-byte header claiming a window millions of pixels wide asked for 2 GB
// before glint's size checks ran (fuzz/regressions/image/exr-wide-window-*). glint reads the
// header first and refuses buffers larger than the image itself (and than 256 MB).
TEST_F(ExrHeaderLies, AWideShortWindowIsRefusedBeforeOpenEXRsBuffers) {
    const std::size_t at = ok_.find(std::string("dataWindow\0box2i\0", 17));
    ASSERT_NE(at, std::string::npos);
    std::string bytes = ok_;
    const std::int32_t window[4] = {0, 0, 3'999'999, 0};  // 4,000,000 x 1: a block of 16 such rows is 384 MB
    std::memcpy(bytes.data() + at + 17 + 4, window, 16);
    const std::string error = refused(bytes);
    EXPECT_NE(error.find("bad.exr': its header claims a 4000000 x 1 data window in blocks of 16 rows; OpenEXR would need"),
              std::string::npos)
        << error;
    // As a tiled file (version flag 0x200, a `tiles` attribute) of 2^13 x 2^13 tiles (a 400 MB tile buffer each): refused alike.
    std::string tiled = ok_;
    tiled[5] = static_cast<char>(tiled[5] | 0x02);
    std::string tiles = std::string("tiles\0tiledesc\0", 15);
    const std::uint32_t size = 9, side = 1u << 13;
    tiles.append(reinterpret_cast<const char*>(&size), 4).append(reinterpret_cast<const char*>(&side), 4);
    tiles.append(reinterpret_cast<const char*>(&side), 4).push_back('\0');
    tiled.insert(8, tiles);
    const std::string tiled_error = refused(tiled);
    EXPECT_NE(tiled_error.find("bad.exr': its header claims a 2 x 2 data window in blocks of 8192 x 8192 tiles"),
              std::string::npos)
        << tiled_error;
    // Real wide images read: one row of 5,000 half pixels (ZIP: blocks of 16 rows, 0.5 MB), and two
    // rows of 100,000 float pixels in PIZ's blocks of 32 rows (38 MB each; on two or more threads
    // OpenEXR's 2 x threads buffers would pass 256 MB: decoded on fewer threads instead).
    for (const auto& [w, h, type, codec] :
         {std::tuple{5000, 1, OIIO::TypeDesc::HALF, "zip"}, std::tuple{100000, 2, OIIO::TypeDesc::FLOAT, "piz"}}) {
        std::vector<float> rgb(3 * static_cast<std::size_t>(w) * h);
        for (std::size_t i = 0; i < rgb.size(); ++i) rgb[i] = static_cast<float>(i % 7) * 0.25f;
        write_rgb(dir_ / "wide.exr", w, h, OIIO::TypeDesc(type), rgb, codec);
        const Image image = read_image(dir_ / "wide.exr", ImageEncoding::kLinear);
        ASSERT_EQ(image.width, w) << codec;
        ASSERT_EQ(image.height, h) << codec;
        EXPECT_EQ(image.texel(w - 1, h - 1).b, rgb.back()) << codec;  // multiples of 1/4: exact in half and float
        EXPECT_EQ(image.texel(w / 2, 0).r, rgb[3 * static_cast<std::size_t>(w / 2)]) << codec;
    }
}

TEST(ImageRead, SrgbDecodeInvertsTheEncoding) {
    for (float v : {0.0f, 0.001f, 0.2f, 0.5f, 1.0f}) EXPECT_NEAR(srgb_decode(srgb_encode(v)), v, 1e-5);
    EXPECT_NEAR(srgb_decode(0.5f), 0.21404, 1e-4);
}

TEST(ImageRead, EightBitIsSrgbAndFloatIsLinearByDefault) {
    testing::TempDir dir;
    // 188/255 = 0.7373 encodes 0.5 linear within 8-bit precision.
    write_rgb(dir / "a.png", 1, 1, OIIO::TypeDesc::UINT8, {188 / 255.0f, 0, 1});
    write_rgb(dir / "a.exr", 1, 1, OIIO::TypeDesc::FLOAT, {0.5f, 2.5f, 0});
    const Image png = read_image(dir / "a.png", ImageEncoding::kAuto);
    EXPECT_NEAR(png.texel(0, 0).r, srgb_decode(188 / 255.0f), 1e-6);
    EXPECT_NEAR(png.texel(0, 0).r, 0.5, 0.003);
    EXPECT_EQ(png.texel(0, 0).b, 1.0f);
    EXPECT_NEAR(read_image(dir / "a.png", ImageEncoding::kLinear).texel(0, 0).r, 188 / 255.0f, 1e-6);
    const Image exr = read_image(dir / "a.exr", ImageEncoding::kAuto);
    EXPECT_EQ(exr.texel(0, 0).r, 0.5f);
    EXPECT_EQ(exr.texel(0, 0).g, 2.5f);  // linear, unclamped
}

// PFM (pbrt's float textures), written here byte by byte: both byte orders, the scale's
// magnitude multiplying, rows stored bottom to top, and a grey "Pf" map.
TEST(ImageRead, PortableFloatMaps) {
    const testing::TempDir dir;
    const auto write = [&](const std::string& name, const std::string& header, const std::vector<float>& values, bool little) {
        std::string bytes = header;
        for (float v : values) {
            const auto u = std::bit_cast<std::uint32_t>(v);
            for (int k = 0; k < 4; ++k) {
                const int shift = little ? 8 * k : 8 * (3 - k);
                bytes.push_back(static_cast<char>((u >> shift) & 0xff));
            }
        }
        std::ofstream(dir.path() / name, std::ios::binary) << bytes;
        return dir.path() / name;
    };
    // 2 x 2, bottom row first in the file: (1,2,3) (4,5,6) / top row (7,8,9) (10,11,12).
    const std::vector<float> rgb{1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12};
    const Image big = read_image(write("big.pfm", "PF\n2 2\n1.0\n", rgb, false), ImageEncoding::kAuto, limit(Limit::kTexturePixels));
    const Image little = read_image(write("little.pfm", "PF\n2 2\n-2.0\n", rgb, true), ImageEncoding::kAuto, limit(Limit::kTexturePixels));
    ASSERT_EQ(big.width, 2);
    EXPECT_EQ(big.texel(0, 0).r, 7);  // the top-left texel is the last row's first
    EXPECT_EQ(big.texel(1, 1).b, 6);
    EXPECT_EQ(little.texel(1, 0).g, 22);  // 11 x |scale|
    const Image grey = read_image(write("grey.pfm", "Pf\n3 1\n-1\n", {0.25f, 0.5f, 0.75f}, true), ImageEncoding::kAuto, limit(Limit::kTexturePixels));
    EXPECT_EQ(grey.texel(2, 0).g, 0.75f);
    EXPECT_EQ(grey.texel(1, 0).r, 0.5f);
    const auto message = [&](const std::filesystem::path& p) {
        try {
            read_image(p, ImageEncoding::kAuto, limit(Limit::kTexturePixels));
        } catch (const IoError& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    EXPECT_NE(message(write("short.pfm", "PF\n2 2\n1\n", {1, 2, 3}, false)).find("byte 9: 12 bytes of data for 12 floats"),
              std::string::npos);
    EXPECT_NE(message(write("magic.pfm", "P6\n2 2\n1\n", {}, false)).find("not a PFM file"), std::string::npos);
    EXPECT_NE(message(write("huge.pfm", "PF\n100000 100000\n1\n", {}, false)).find("exceed the limit of"), std::string::npos);
}

TEST(ImageRead, TooLargeIsRefusedFromTheHeader) {
    testing::TempDir dir;
    write_rgb(dir / "big.png", 4, 4, OIIO::TypeDesc::UINT8, std::vector<float>(48, 0.5f));
    try {
        read_image(dir / "big.png", ImageEncoding::kAuto, 10);
        FAIL();
    } catch (const IoError& e) {
        EXPECT_NE(std::string(e.what()).find("is 4 x 4 pixels: 16 image pixels exceed the limit of 10"), std::string::npos);
    }
}

TEST(ImageRead, MissingTextureIsASceneErrorAtTheFilename) {
    testing::TempDir dir;
    const std::string scene =
        "objects:\n"
        "  - {type: sphere, center: [0, 0, 1], radius: 1,\n"
        "     material: {color: {type: image, filename: nope.png}}}\n";
    std::ofstream(dir / "s.yaml") << scene;
    auto sources = std::make_shared<SourceFiles>();
    const std::string path = (dir / "s.yaml").string();
    try {
        build(load_scene_file(path, sources), {}, sources);
        FAIL();
    } catch (const SceneError& e) {
        const std::string msg = e.what();
        // Column of "nope.png" on line 3, resolved relative to the scene file's folder.
        EXPECT_EQ(msg.rfind(path + ":3:48: error: cannot read image '" + (dir / "nope.png").string() + "'", 0), 0u) << msg;
    }
}

TEST(ImageRead, TexturedQuadRendersTheImage) {
    // A 2 x 1 image, red | blue, on a quad filling the view: with bilinear filtering the outer
    // quarters are pure red and pure blue.
    testing::TempDir dir;
    write_rgb(dir / "rb.exr", 2, 1, OIIO::TypeDesc::FLOAT, {1, 0, 0, 0, 0, 1});
    std::ofstream(dir / "s.yaml") <<
        "camera: {position: [0, 0, -1], direction: [0, 0, 1], viewport_width: 2, viewport_height: 2, near: 1}\n"
        "film: {width: 16, height: 16}\n"
        "integrator: {type: flat}\n"
        "objects:\n"
        "  - {type: quad, corner: [-1, -1, 0], edge1: [2, 0, 0], edge2: [0, 2, 0],\n"
        "     material: {color: {type: image, filename: rb.exr, wrap: clamp}}}\n";
    auto sources = std::make_shared<SourceFiles>();
    const RenderJob job = build(load_scene_file((dir / "s.yaml").string(), sources), {}, sources);
    Film film(job.film_width, job.film_height);
    render(job.scene, job.camera, *job.integrator, job.options, film);
    EXPECT_EQ(film.at(1, 8), (Color{1, 0, 0}));
    EXPECT_EQ(film.at(14, 8), (Color{0, 0, 1}));
    EXPECT_NEAR(film.at(7, 8).r + film.at(8, 8).r, 1, 1e-5);  // the blend in the middle
}

}  // namespace
}  // namespace glint
