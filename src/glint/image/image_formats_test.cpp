// The image formats glint reads and writes itself (image_formats.h), checked against OpenImageIO
// as the independent reader and writer, and against hand-made files whose values follow from the
// format's definition.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <random>

#include <fmt/format.h>

#include "glint/image/image_formats.h"
#include "glint/image/image_io.h"
#include "testing.h"

namespace glint {
namespace {

std::vector<std::uint8_t> test_pattern(int w, int h, unsigned seed) {
    // Half smooth gradients (what renders look like, long matches), half noise (literals).
    std::mt19937 rng(seed);
    std::vector<std::uint8_t> rgb(static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 3);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int k = 0; k < 3; ++k) {
                const std::size_t i = (static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x)) * 3 +
                                      static_cast<std::size_t>(k);
                rgb[i] = y % 2 == 0 ? static_cast<std::uint8_t>((x * (k + 1) + y) & 255) : static_cast<std::uint8_t>(rng());
            }
    return rgb;
}

void write_bytes(const std::filesystem::path& p, const std::vector<std::uint8_t>& bytes) {
    std::ofstream(p, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()),
                                             static_cast<std::streamsize>(bytes.size()));
}

// Every filter, image sizes around the strip boundaries (one row, one pixel, strips that end
// mid-image): OpenImageIO (libpng) decodes exactly the bytes given, and so does glint's reader.
TEST(PngEncoder, OpenImageIOReadsBackEveryByteForEveryFilter) {
    testing::TempDir dir;
    for (const auto [w, h] : {std::pair{1, 1}, std::pair{7, 3}, std::pair{333, 900}, std::pair{3000, 97}}) {
        const auto rgb = test_pattern(w, h, static_cast<unsigned>(w * h));
        for (int filter = 0; filter <= 4; ++filter) {
            SCOPED_TRACE(::testing::Message() << w << "x" << h << " filter " << filter);
            const auto p = dir.path() / "a.png";
            write_bytes(p, encode_png(rgb.data(), w, h, true, {}, PngOptions{1, 0, filter}));
            auto in = OIIO::ImageInput::open(p.string());
            ASSERT_TRUE(in) << OIIO::geterror();
            ASSERT_EQ(in->spec().width, w);
            ASSERT_EQ(in->spec().height, h);
            std::vector<std::uint8_t> back(rgb.size());
            ASSERT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, back.data()));
            EXPECT_EQ(back, rgb);
            const Image mine = read_image(p, ImageEncoding::kLinear);
            ASSERT_EQ(mine.texels.size(), static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
            for (std::size_t i = 0; i < mine.texels.size(); i += 97)
                EXPECT_EQ(mine.texels[i].g, static_cast<float>(rgb[3 * i + 1]) / 255.0f);
        }
    }
}

TEST(PngEncoder, TheBytesDoNotDependOnTheThreadCount) {
    const int w = 1000, h = 700;  // several strips
    const auto rgb = test_pattern(w, h, 5);
    std::vector<std::vector<std::uint8_t>> out;
    for (int threads : {1, 2, 3}) {
        tbb::task_arena arena(threads);
        arena.execute([&] { out.push_back(encode_png(rgb.data(), w, h, false, {{"k", "v"}})); });
    }
    EXPECT_EQ(out[0], out[1]);
    EXPECT_EQ(out[0], out[2]);
}

// Rows announced as a render would (bands in any order, from several threads at once, some
// strips never announced) give encode_png's bytes; and Image8Writer writes them (and a PPM of
// the same codes) to disk.
TEST(PngEncoder, StripsEncodedAsRowsArriveGiveTheSameFile) {
    const int w = 700, h = 1003;  // strips of 125 rows; the dictionary of each reaches into the last
    const auto rgb = test_pattern(w, h, 9);
    const auto whole = encode_png(rgb.data(), w, h, true, {{"k", "v"}});
    const std::size_t row = static_cast<std::size_t>(w) * 3;
    const auto rows = [&](int y, std::uint8_t* out) { std::memcpy(out, &rgb[static_cast<std::size_t>(y) * row], row); };
    std::mt19937 rng(3);
    for (const int band : {1, 7, 64, h}) {
        SCOPED_TRACE(band);
        std::vector<std::pair<int, int>> bands;
        for (int y = 0; y < h; y += band) bands.emplace_back(y, std::min(h, y + band));
        std::shuffle(bands.begin(), bands.end(), rng);
        if (band == 7) bands.resize(bands.size() / 2);  // half never announced: finish() does the rest
        PngStrips strips(rows, w, h);
        tbb::task_arena arena(3);
        arena.execute([&] {
            tbb::parallel_for(std::size_t{0}, bands.size(), [&](std::size_t i) { strips.rows_ready(bands[i].first, bands[i].second); });
        });
        EXPECT_EQ(strips.finish(true, {{"k", "v"}}), whole);
    }
    testing::TempDir dir;
    for (const char* name : {"w.png", "w.ppm"}) {
        const auto p = dir.path() / name;
        Image8Writer writer(p, w, h, true);
        std::memcpy(writer.rgb(), rgb.data(), rgb.size());
        writer.rows_ready(0, h / 2);
        writer.finish({{"k", "v"}});
        const Image back = read_image(p, ImageEncoding::kLinear);
        ASSERT_EQ(back.texels.size(), static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
        for (std::size_t i = 0; i < back.texels.size(); i += 101)
            ASSERT_EQ(std::lround(back.texels[i].b * 255.0f), rgb[3 * i + 2]) << name << " " << i;
        if (std::string(name) == "w.png") {
            std::ifstream in(p, std::ios::binary);
            const std::vector<std::uint8_t> file{std::istreambuf_iterator<char>(in), {}};
            EXPECT_EQ(file, whole);
        }
    }
    EXPECT_THROW(Image8Writer(dir.path() / "x.exr", 2, 2, false), IoError);
}

TEST(PngEncoder, MetadataAndEncodingAreInTheHeader) {
    testing::TempDir dir;
    const std::vector<std::uint8_t> rgb(3 * 4, 128);
    const auto p = dir.path() / "m.png";
    write_bytes(p, encode_png(rgb.data(), 2, 2, true, {{"glint:spp", "64"}, {"glint:scene", "scènes/été.yaml"}}));
    auto in = OIIO::ImageInput::open(p.string());
    ASSERT_TRUE(in);
    EXPECT_EQ(in->spec().get_string_attribute("glint:spp"), "64");
    EXPECT_EQ(in->spec().get_string_attribute("glint:scene"), "scènes/été.yaml");  // iTXt, UTF-8
    EXPECT_EQ(in->spec().get_string_attribute("oiio:ColorSpace"), "sRGB");
    const auto q = dir.path() / "l.png";
    write_bytes(q, encode_png(rgb.data(), 2, 2, false, {}));
    auto lin = OIIO::ImageInput::open(q.string());
    ASSERT_TRUE(lin);
    EXPECT_FLOAT_EQ(lin->spec().get_float_attribute("oiio:Gamma"), 1.0f);  // gAMA 1.0
}

// Radiance HDR by hand: RGBE (m + 0.5) 2^(e - 136), rows "-Y" top first or "+Y" bottom first,
// flat pixels with the old encoding's repeat, and a run past the row's end refused at its byte.
TEST(HdrReader, DecodesFlatOldRunsAndBothRowOrders) {
    testing::TempDir dir;
    const std::string header = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n";
    // 3 x 2: row one (128,64,0,129) then "repeat x2" (1,1,1,2); row two (255,0,0,130) x 1, (0,0,0,0) x 2.
    const std::string pixels = std::string("\x80\x40\x00\x81", 4) + std::string("\x01\x01\x01\x02", 4) +
                               std::string("\xff\x00\x00\x82", 4) + std::string("\x00\x00\x00\x00", 4) +
                               std::string("\x00\x00\x00\x00", 4);
    for (const char* order : {"-Y", "+Y"}) {
        const auto p = dir.path() / "a.hdr";
        std::ofstream(p, std::ios::binary) << header << order << " 2 +X 3\n" << pixels;
        const Image im = read_image(p, ImageEncoding::kAuto);
        ASSERT_EQ(im.width, 3);
        ASSERT_EQ(im.height, 2);
        const std::size_t first = order[0] == '-' ? 0 : 3, second = order[0] == '-' ? 3 : 0;
        const float f1 = std::ldexp(1.0f, 129 - 136), f2 = std::ldexp(1.0f, 130 - 136);
        for (std::size_t x = 0; x < 3; ++x) {
            EXPECT_EQ(im.texels[first + x].r, 128.5f * f1);
            EXPECT_EQ(im.texels[first + x].g, 64.5f * f1);
            EXPECT_EQ(im.texels[first + x].b, 0.5f * f1);
        }
        EXPECT_EQ(im.texels[second].r, 255.5f * f2);
        EXPECT_EQ(im.texels[second + 1].r, 0.0f);  // exponent 0: black
    }
    const auto bad = dir.path() / "bad.hdr";
    // New RLE, width 8: a run of 9 (0x89) in the first component passes the row's end.
    // (Padded to the 8 bytes an 8-pixel row needs at least, which the reader checks first.)
    std::ofstream(bad, std::ios::binary) << header << "-Y 1 +X 8\n" << std::string("\x02\x02\x00\x08\x89\x10\x00\x00", 8);
    try {
        read_image(bad, ImageEncoding::kAuto);
        ADD_FAILURE() << "no error";
    } catch (const IoError& e) {
        const std::size_t at = header.size() + 10 + 4;  // the count byte, after the resolution line and 2 2 0 8
        EXPECT_NE(std::string(e.what()).find(fmt::format("byte {}: row 0: a run of 9 past the row's end", at)),
                  std::string::npos) << e.what();
    }
}

// The new RLE against OpenImageIO's writer (which run-length encodes): the same values.
TEST(HdrReader, AgreesWithOpenImageIO) {
    testing::TempDir dir;
    const int w = 40, h = 3;
    std::vector<float> rgb(static_cast<std::size_t>(w * h * 3));
    for (std::size_t i = 0; i < rgb.size(); ++i) rgb[i] = i % 7 == 0 ? 0.25f : 0.01f * static_cast<float>(i % 13);
    const auto p = dir.path() / "o.hdr";
    auto out = OIIO::ImageOutput::create(p.string());
    ASSERT_TRUE(out && out->open(p.string(), OIIO::ImageSpec(w, h, 3, OIIO::TypeDesc::FLOAT)));
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, rgb.data()));
    out->close();
    auto in = OIIO::ImageInput::open(p.string());
    ASSERT_TRUE(in);
    std::vector<float> theirs(rgb.size());
    ASSERT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::FLOAT, theirs.data()));
    const Image mine = read_image(p, ImageEncoding::kLinear);
    for (std::size_t i = 0; i < mine.texels.size(); ++i) {
        // Both decode one RGBE code; they may differ by half a bin (Radiance's m + 0.5 against
        // OpenImageIO's m), and a pixel's bin is set by its largest component: at most max/256.
        const float biggest = std::max({theirs[3 * i], theirs[3 * i + 1], theirs[3 * i + 2]});
        for (int k = 0; k < 3; ++k)
            EXPECT_NEAR(mine.texels[i][k], theirs[3 * i + static_cast<std::size_t>(k)], biggest / 256 + 1e-7f) << i;
    }
}

TEST(PnmReader, AsciiAndSixteenBitMaps) {
    testing::TempDir dir;
    const auto a = dir.path() / "a.ppm";
    std::ofstream(a) << "P3\n# a comment\n2 1\n10\n0 5 10  10 0 1\n";
    const Image im = read_image(a, ImageEncoding::kLinear);
    ASSERT_EQ(im.width, 2);
    EXPECT_EQ(im.texels[0].g, 0.5f);
    EXPECT_EQ(im.texels[1].r, 1.0f);
    EXPECT_EQ(im.texels[1].b, 0.1f);
    const auto g = dir.path() / "g.pgm";
    std::ofstream(g, std::ios::binary) << "P5 2 1 65535\n" << std::string("\x80\x00\xff\xff", 4);  // big endian
    const Image grey = read_image(g, ImageEncoding::kLinear);
    EXPECT_EQ(grey.texels[0].r, 32768.0f / 65535.0f);
    EXPECT_EQ(grey.texels[0].b, 32768.0f / 65535.0f);  // grey replicated
    EXPECT_EQ(grey.texels[1].g, 1.0f);
    const auto short_file = dir.path() / "s.ppm";
    std::ofstream(short_file, std::ios::binary) << "P6 4 4 255\n" << std::string(10, 'x');
    EXPECT_THROW(read_image(short_file, ImageEncoding::kLinear), IoError);
}

// OpenEXR: a luminance-only file reads as grey; a data window that does not start at the origin
// is read from its own corner.
TEST(ExrReader, LuminanceAndOffsetDataWindows) {
    testing::TempDir dir;
    const auto y = dir.path() / "y.exr";
    {
        OIIO::ImageSpec spec(2, 1, 1, OIIO::TypeDesc::HALF);
        spec.channelnames = {"Y"};
        auto out = OIIO::ImageOutput::create(y.string());
        ASSERT_TRUE(out && out->open(y.string(), spec));
        const float v[2] = {0.5f, 2.0f};
        ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, v));
        out->close();
    }
    const Image grey = read_image(y, ImageEncoding::kAuto);
    EXPECT_EQ(grey.texels[0].g, 0.5f);
    EXPECT_EQ(grey.texels[1].r, 2.0f);  // floats are linear: no sRGB decoding, no clamp
    const auto o = dir.path() / "o.exr";
    {
        OIIO::ImageSpec spec(2, 2, 3, OIIO::TypeDesc::FLOAT);
        spec.x = 100, spec.y = -7;
        spec.full_x = 0, spec.full_y = 0, spec.full_width = 300, spec.full_height = 300;
        auto out = OIIO::ImageOutput::create(o.string());
        ASSERT_TRUE(out && out->open(o.string(), spec));
        const float v[12] = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12};
        ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, v));
        out->close();
    }
    const Image off = read_image(o, ImageEncoding::kAuto);
    ASSERT_EQ(off.width, 2);
    EXPECT_EQ(off.texels[0].r, 1.0f);
    EXPECT_EQ(off.texels[3].b, 12.0f);
}

TEST(JpegReader, GreyscaleIsReplicated) {
    testing::TempDir dir;
    const auto p = dir.path() / "g.jpg";
    OIIO::ImageSpec spec(8, 8, 1, OIIO::TypeDesc::UINT8);
    auto out = OIIO::ImageOutput::create(p.string());
    ASSERT_TRUE(out && out->open(p.string(), spec));
    const std::vector<std::uint8_t> v(64, 200);
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::UINT8, v.data()));
    out->close();
    const Image im = read_image(p, ImageEncoding::kLinear);
    ASSERT_EQ(im.width, 8);
    EXPECT_NEAR(im.texels[9].r, 200 / 255.0f, 1.5f / 255);  // a flat block survives JPEG
    EXPECT_EQ(im.texels[9].r, im.texels[9].b);
}

// The RGBE bytes of values worked by hand from Ward's definition: the largest component v is
// m 2^e with m in [0.5, 1); each component c is stored as floor(c 2^(8-e)), and e as e + 128.
TEST(HdrWriter, RgbeBytesByHand) {
    std::uint8_t b[4];
    rgbe_encode(1.0f, 1.0f, 1.0f, b);  // 1 = 0.5 2^1: 1 * 2^7 = 128
    EXPECT_EQ(std::vector<int>(b, b + 4), (std::vector<int>{128, 128, 128, 129}));
    rgbe_encode(0.5f, 0.25f, 0.0f, b);  // 0.5 = 0.5 2^0: 0.5 * 256, 0.25 * 256
    EXPECT_EQ(std::vector<int>(b, b + 4), (std::vector<int>{128, 64, 0, 128}));
    rgbe_encode(3.0f, 1.0f, 0.1f, b);  // 3 = 0.75 2^2: 3 * 64 = 192, 64, floor(6.4) = 6
    EXPECT_EQ(std::vector<int>(b, b + 4), (std::vector<int>{192, 64, 6, 130}));
    rgbe_encode(-1.0f, std::nanf(""), 0.0f, b);  // nothing positive: RGBE's zero
    EXPECT_EQ(std::vector<int>(b, b + 4), (std::vector<int>{0, 0, 0, 0}));
    rgbe_encode(std::numeric_limits<float>::infinity(), 0.0f, 0.0f, b);  // clamped to 1e38 < 2^127
    EXPECT_EQ(b[3], 127 + 128);
}

// The run-length encoding by hand: a 300-pixel row of one colour is, per component, runs of
// 127, 127 and 46 (128 + n, byte), after the row's marker 2 2 1 44 (300 = 1 * 256 + 44).
TEST(HdrWriter, ARowOfOneColourIsThreeRunsPerComponent) {
    const std::vector<float> rgb(300 * 3, 1.0f);  // RGBE 128 128 128 129
    const auto bytes = encode_hdr(rgb.data(), 300, 1, {});
    const std::string header = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 1 +X 300\n";
    ASSERT_EQ(std::string(bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(header.size())), header);
    std::vector<int> want = {2, 2, 1, 44};
    for (const int v : {128, 128, 128, 129}) want.insert(want.end(), {128 + 127, v, 128 + 127, v, 128 + 46, v});
    EXPECT_EQ(std::vector<int>(bytes.begin() + static_cast<std::ptrdiff_t>(header.size()), bytes.end()), want);
}

// Values over eleven decades, zeros, negatives, NaN and rows of equal pixels (runs), written in
// the run-length encoding (width >= 8) and flat (width < 8): glint's reader gives every component
// back within half a bin, 2^(e-9), of what was written, OpenImageIO's within a bin.
TEST(HdrWriter, EveryValueComesBackWithinItsBinInGlintAndOpenImageIO) {
    testing::TempDir dir;
    std::mt19937 rng(17);
    std::uniform_real_distribution<float> exponent(-5.0f, 6.0f);
    for (const auto [w, h] : {std::pair{37, 5}, std::pair{5, 3}, std::pair{300, 2}}) {
        SCOPED_TRACE(::testing::Message() << w << "x" << h);
        std::vector<float> rgb(static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 3);
        for (std::size_t i = 0; i < rgb.size(); ++i) rgb[i] = std::pow(10.0f, exponent(rng));
        for (std::size_t i = 0; i < static_cast<std::size_t>(w) * 3; ++i) rgb[i] = i % 3 == 0 ? 0.75f : 0.25f;  // a run
        rgb[3] = -2.0f;
        rgb[4] = std::nanf("");
        rgb[rgb.size() - 3] = rgb[rgb.size() - 2] = rgb[rgb.size() - 1] = 0.0f;
        const auto p = dir.path() / "a.hdr";
        write_bytes(p, encode_hdr(rgb.data(), w, h, {{"glint:spp", "16"}}));
        const RawImage mine = read_hdr(p, 1 << 20);
        auto in = OIIO::ImageInput::open(p.string());
        ASSERT_TRUE(in) << OIIO::geterror();
        ASSERT_EQ(in->spec().width, w);
        ASSERT_EQ(in->spec().height, h);
        std::vector<float> theirs(rgb.size());
        ASSERT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::FLOAT, theirs.data()));
        for (std::size_t i = 0; i < rgb.size(); i += 3) {
            float v = 0;
            for (int k = 0; k < 3; ++k) v = std::max(v, rgb[i + static_cast<std::size_t>(k)] > 0 ? rgb[i + static_cast<std::size_t>(k)] : 0.0f);
            const float half_bin = v > 0 ? std::ldexp(1.0f, std::ilogb(v) + 1 - 9) : 0.0f;
            for (std::size_t k = i; k < i + 3; ++k) {
                const float want = rgb[k] > 0 ? rgb[k] : 0.0f;
                EXPECT_LE(std::abs(mine.data[k] - want), half_bin * 1.0001f) << k << ": " << rgb[k];
                // OpenImageIO decodes a mantissa to its bin's floor, m 2^(e-136): within a bin.
                EXPECT_LE(std::abs(theirs[k] - want), 2 * half_bin * 1.0001f) << k << ": " << rgb[k];
            }
        }
    }
}

// PFM bytes by hand: the header, then the bottom row first, each float little-endian and exactly
// as given (NaN and negatives too); glint's reader and OpenImageIO's read the floats back.
TEST(PfmWriter, BottomRowFirstEveryFloatExact) {
    const std::vector<float> rgb = {1, 2, 3, 4, 5, 6,            // top row
                                    -0.5f, 1e-30f, 7, 8, 9, 1e30f};  // bottom row
    const auto bytes = encode_pfm(rgb.data(), 2, 2);
    const std::string header = "PF\n2 2\n-1\n";
    ASSERT_EQ(bytes.size(), header.size() + 12 * 4);
    EXPECT_EQ(std::string(bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(header.size())), header);
    const auto float_at = [&](std::size_t i) {
        std::uint32_t u = 0;
        for (int k = 3; k >= 0; --k) u = (u << 8) | bytes[header.size() + 4 * i + static_cast<std::size_t>(k)];
        return std::bit_cast<float>(u);
    };
    EXPECT_EQ(float_at(0), -0.5f);  // the bottom-left pixel comes first
    EXPECT_EQ(float_at(5), 1e30f);
    EXPECT_EQ(float_at(6), 1.0f);   // then the top row
    testing::TempDir dir;
    write_bytes(dir.path() / "a.pfm", bytes);
    const RawImage mine = read_pfm(dir.path() / "a.pfm", 100);
    EXPECT_EQ(mine.data, rgb);
    auto in = OIIO::ImageInput::open((dir.path() / "a.pfm").string());
    ASSERT_TRUE(in) << OIIO::geterror();
    std::vector<float> theirs(rgb.size());
    ASSERT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::FLOAT, theirs.data()));
    EXPECT_EQ(theirs, rgb);
}

// A JPEG of a smooth image (what renders mostly are) decodes, by OpenImageIO and by glint's
// reader, within a few codes of what was written; chroma is not subsampled; the metadata is in
// the comment marker.
TEST(JpegWriter, DecodesCloseToTheCodesWithFullChromaAndTheMetadata) {
    const int w = 96, h = 64;
    std::vector<std::uint8_t> rgb(static_cast<std::size_t>(w) * h * 3);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            std::uint8_t* p = &rgb[(static_cast<std::size_t>(y) * w + static_cast<std::size_t>(x)) * 3];
            p[0] = static_cast<std::uint8_t>(x * 255 / (w - 1));
            p[1] = static_cast<std::uint8_t>(y * 255 / (h - 1));
            p[2] = static_cast<std::uint8_t>(128 + 100 * std::sin(0.1 * (x + y)));
        }
    testing::TempDir dir;
    const auto p = dir.path() / "a.jpg";
    write_bytes(p, encode_jpeg(rgb.data(), w, h, {{"glint:spp", "4"}, {"Software", "glint"}}));
    auto in = OIIO::ImageInput::open(p.string());
    ASSERT_TRUE(in) << OIIO::geterror();
    EXPECT_EQ(in->spec().get_string_attribute("jpeg:subsampling"), "4:4:4");
    EXPECT_NE(in->spec().get_string_attribute("ImageDescription").find("glint:spp=4\n"), std::string::npos)
        << in->spec().get_string_attribute("ImageDescription");
    std::vector<std::uint8_t> theirs(rgb.size());
    ASSERT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, theirs.data()));
    const Image mine = read_image(p, ImageEncoding::kLinear);
    double sum = 0;
    int worst = 0;
    for (std::size_t i = 0; i < rgb.size(); ++i) {
        const int d = std::abs(int{theirs[i]} - int{rgb[i]});
        sum += d;
        worst = std::max(worst, d);
        const Color c = mine.texels[i / 3];
        EXPECT_EQ(std::lround((i % 3 == 0 ? c.r : i % 3 == 1 ? c.g : c.b) * 255.0f), theirs[i]);
    }
    EXPECT_LT(sum / static_cast<double>(rgb.size()), 1.0);
    EXPECT_LE(worst, 8);
}

}  // namespace
}  // namespace glint
