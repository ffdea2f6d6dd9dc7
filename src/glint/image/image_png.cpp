// PNG: read through libspng; written by glint's own strip-parallel encoder over zlib (the PNG
// container is a handful of chunks; the cost is all in filtering and deflating, which libpng and
// libspng do on one thread). Both checked against OpenImageIO's reader in the tests.
#include <fmt/core.h>
#include <spng.h>
#include <tbb/parallel_for.h>
#include <zlib.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>

#include "glint/image/image_formats.h"

namespace glint {

namespace fs = std::filesystem;

RawImage read_png(const fs::path& path, long long max_pixels) {
    const auto fail = [&](const std::string& why) {
        return IoError(fmt::format("cannot read image '{}': {}", path.string(), why));
    };
    std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"), &std::fclose);
    if (!file) throw fail(std::strerror(errno));
    std::unique_ptr<spng_ctx, void (*)(spng_ctx*)> ctx(spng_ctx_new(0), &spng_ctx_free);
    if (!ctx) throw fail("out of memory");
    // Ancillary chunks (text, ICC profiles) are skipped past a megabyte; the image's size is
    // checked against the limits below, before any pixel is decoded.
    spng_set_chunk_limits(ctx.get(), 1u << 20, 1u << 22);
    if (int e = spng_set_png_file(ctx.get(), file.get()); e != 0) throw fail(spng_strerror(e));
    spng_ihdr ihdr{};
    if (int e = spng_get_ihdr(ctx.get(), &ihdr); e != 0) throw fail(spng_strerror(e));
    admit_image(path, ihdr.width, ihdr.height, max_pixels, 4 * 3 + (ihdr.bit_depth > 8 ? 8 : 4), kPngPixelsPerByte);
    const bool wide = ihdr.bit_depth > 8;
    const int fmt = wide ? SPNG_FMT_RGBA16 : SPNG_FMT_RGBA8;
    std::size_t size = 0;
    if (int e = spng_decoded_image_size(ctx.get(), fmt, &size); e != 0) throw fail(spng_strerror(e));
    std::vector<unsigned char> pixels(size);
    if (int e = spng_decode_image(ctx.get(), pixels.data(), size, fmt, SPNG_DECODE_TRNS); e != 0)
        throw fail(spng_strerror(e));
    RawImage raw;
    raw.width = static_cast<int>(ihdr.width);
    raw.height = static_cast<int>(ihdr.height);
    raw.channels = 3;
    const std::size_t n = static_cast<std::size_t>(raw.width) * static_cast<std::size_t>(raw.height);
    raw.data.resize(n * 3);
    for (std::size_t i = 0; i < n; ++i) {
        for (std::size_t k = 0; k < 3; ++k) {
            if (wide) {
                std::uint16_t v;
                std::memcpy(&v, &pixels[(4 * i + k) * 2], 2);  // SPNG_FMT_RGBA16 is host-endian
                raw.data[3 * i + k] = static_cast<float>(v) / 65535.0f;
            } else {
                raw.data[3 * i + k] = static_cast<float>(pixels[4 * i + k]) / 255.0f;
            }
        }
    }
    return raw;
}

namespace {

void put32(std::vector<std::uint8_t>& out, std::uint32_t v) {
    for (int s = 24; s >= 0; s -= 8) out.push_back(static_cast<std::uint8_t>(v >> s));
}

void chunk(std::vector<std::uint8_t>& out, const char type[4], const std::uint8_t* data, std::size_t size) {
    put32(out, static_cast<std::uint32_t>(size));
    const std::size_t start = out.size();
    out.insert(out.end(), type, type + 4);
    out.insert(out.end(), data, data + size);
    put32(out, static_cast<std::uint32_t>(
                   crc32_z(0, out.data() + start, static_cast<z_size_t>(out.size() - start))));
}

void chunk(std::vector<std::uint8_t>& out, const char type[4], const std::string& data) {
    chunk(out, type, reinterpret_cast<const std::uint8_t*>(data.data()), data.size());
}

std::uint8_t paeth(int a, int b, int c) {
    const int p = a + b - c, pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
    return static_cast<std::uint8_t>(pa <= pb && pa <= pc ? a : pb <= pc ? b : c);
}

// One scanline: the filter type byte, then each byte minus its predictor (a: the byte one pixel
// to the left, b: the byte above, c: above-left; 0 outside the image, so the first row's `prev` is
// a row of zeros). One loop per filter.
void filter_row(const std::uint8_t* x, const std::uint8_t* prev, std::size_t n, int filter, std::uint8_t* out) {
    out[0] = static_cast<std::uint8_t>(filter);
    ++out;
    constexpr std::size_t bpp = 3;
    const std::size_t head = std::min(bpp, n);
    switch (filter) {
        case 1:
            std::memcpy(out, x, head);
            for (std::size_t i = bpp; i < n; ++i) out[i] = static_cast<std::uint8_t>(x[i] - x[i - bpp]);
            break;
        case 2:
            for (std::size_t i = 0; i < n; ++i) out[i] = static_cast<std::uint8_t>(x[i] - prev[i]);
            break;
        case 3:
            for (std::size_t i = 0; i < head; ++i) out[i] = static_cast<std::uint8_t>(x[i] - prev[i] / 2);
            for (std::size_t i = bpp; i < n; ++i) out[i] = static_cast<std::uint8_t>(x[i] - (x[i - bpp] + prev[i]) / 2);
            break;
        case 4:
            for (std::size_t i = 0; i < head; ++i) out[i] = static_cast<std::uint8_t>(x[i] - prev[i]);  // Paeth(0, b, 0) = b
            for (std::size_t i = bpp; i < n; ++i)
                out[i] = static_cast<std::uint8_t>(x[i] - paeth(x[i - bpp], prev[i], prev[i - bpp]));
            break;
        default: std::memcpy(out, x, n); break;
    }
}

bool is_ascii(const std::string& s) {
    return std::all_of(s.begin(), s.end(), [](char c) { return c >= 0x20 && c < 0x7f; });
}

}  // namespace

std::size_t png_strip_rows(int width) {
    const std::size_t line = static_cast<std::size_t>(width) * 3 + 1;
    return std::max<std::size_t>(1, (kPngStripBytes + line - 1) / line);
}

std::vector<std::uint8_t> encode_png(const std::uint8_t* rgb, int width, int height, bool srgb,
                                     const ImageMetadata& metadata, const PngOptions& options) {
    const std::size_t row = static_cast<std::size_t>(width) * 3;
    return encode_png([&](int y, std::uint8_t* out) { std::memcpy(out, rgb + static_cast<std::size_t>(y) * row, row); },
                      width, height, srgb, metadata, options);
}

namespace {

// A thread's deflate state, kept from strip to strip (and image to image) and reset between
// them: zlib's state is some 270 KB, which malloc takes fresh from the kernel (and gives back)
// at each deflateInit/deflateEnd, page faults and all.
class Deflater {
public:
    Deflater() = default;
    Deflater(const Deflater&) = delete;
    Deflater& operator=(const Deflater&) = delete;
    ~Deflater() {
        if (ready_) deflateEnd(&zs_);
    }
    /// A stream ready for a new raw deflate stream at these settings, or null (status: zlib's error).
    z_stream* get(int level, int strategy, int& status) {
        if (ready_ && (level != level_ || strategy != strategy_)) {
            deflateEnd(&zs_);
            ready_ = false;
        }
        if (ready_) {
            status = deflateReset(&zs_);
        } else {
            zs_ = z_stream{};
            status = deflateInit2(&zs_, level, Z_DEFLATED, -15, 8, strategy);
            ready_ = status == Z_OK;
            level_ = level, strategy_ = strategy;
        }
        return status == Z_OK ? &zs_ : nullptr;
    }

private:
    z_stream zs_{};
    bool ready_ = false;
    int level_ = 0, strategy_ = 0;
};

}  // namespace

PngStrips::PngStrips(PngRows rows, int width, int height, const PngOptions& options)
    : rows_(std::move(rows)), width_(width), height_(height), options_(options),
      row_(static_cast<std::size_t>(width) * 3), line_(row_ + 1), strip_rows_(png_strip_rows(width)),
      count_((static_cast<std::size_t>(height) + strip_rows_ - 1) / strip_rows_), parts_(count_),
      adlers_(count_), status_(count_, Z_OK), claimed_(count_), left_(count_) {
    for (std::size_t s = 0; s < count_; ++s) left_[s].store(static_cast<int>(end_row(s) - s * strip_rows_));
}

std::size_t PngStrips::end_row(std::size_t s) const {
    return std::min(static_cast<std::size_t>(height_), (s + 1) * strip_rows_);
}

std::size_t PngStrips::first_row_read(std::size_t s) const {
    const std::size_t y0 = s * strip_rows_;
    const std::size_t dict = std::min<std::size_t>(32768, y0 * line_);  // primed as one stream would be
    const std::size_t r0 = (y0 * line_ - dict) / line_;  // the first row the dictionary reaches into
    return r0 == 0 ? 0 : r0 - 1;                         // and the row above it, its predictor
}

void PngStrips::rows_ready(int y0, int y1) {
    const auto first = static_cast<std::size_t>(y0) / strip_rows_;
    for (std::size_t s = first; s < count_ && s * strip_rows_ < static_cast<std::size_t>(y1); ++s) {
        const std::size_t a = std::max(s * strip_rows_, static_cast<std::size_t>(y0));
        const std::size_t b = std::min(end_row(s), static_cast<std::size_t>(y1));
        if (left_[s].fetch_sub(static_cast<int>(b - a), std::memory_order_acq_rel) != static_cast<int>(b - a)) continue;
        // Strip s is complete: it and the strips that wait for it may now be encodable.
        for (std::size_t t = s; t < count_ && first_row_read(t) < end_row(s); ++t) try_encode(t);
    }
}

bool PngStrips::ready(std::size_t s) const {
    for (std::size_t t = first_row_read(s) / strip_rows_; t <= s; ++t)
        if (left_[t].load(std::memory_order_acquire) != 0) return false;
    return true;
}

void PngStrips::try_encode(std::size_t s) {
    if (ready(s) && !claimed_[s].exchange(true, std::memory_order_acq_rel)) encode(s);
}

// A strip is made whole by one task: its rows (and the few before it that its dictionary covers)
// produced, filtered and deflated in buffers the thread keeps, so that nothing the size of the
// image is allocated or touched.
void PngStrips::encode(std::size_t s) {
    const std::size_t row = row_, line = line_;
    const std::size_t y0 = s * strip_rows_, y1 = end_row(s);
    const std::size_t dict = std::min<std::size_t>(32768, y0 * line);
    const std::size_t r0 = (y0 * line - dict) / line;
    // raw holds rows r0 - 1 .. y1 - 1, the first being the predictor of row r0 (zeros above the
    // image).
    thread_local std::vector<std::uint8_t> raw, filtered, deflated;
    raw.resize((y1 - r0 + 1) * row);
    filtered.resize((y1 - r0) * line);
    if (r0 == 0) {
        std::fill_n(raw.begin(), row, std::uint8_t{0});
    } else {
        rows_(static_cast<int>(r0 - 1), raw.data());
    }
    for (std::size_t y = r0; y < y1; ++y) rows_(static_cast<int>(y), &raw[(y - r0 + 1) * row]);
    for (std::size_t y = r0; y < y1; ++y)
        filter_row(&raw[(y - r0 + 1) * row], &raw[(y - r0) * row], row, options_.filter, &filtered[(y - r0) * line]);
    const std::uint8_t* begin = &filtered[(y0 - r0) * line];
    const std::size_t size = (y1 - y0) * line;
    adlers_[s] = adler32_z(adler32_z(0, nullptr, 0), begin, size);
    thread_local Deflater deflater;
    z_stream* stream = deflater.get(options_.level, options_.strategy, status_[s]);
    if (!stream) return;
    z_stream& zs = *stream;
    if (dict > 0) deflateSetDictionary(&zs, begin - dict, static_cast<uInt>(dict));
    deflated.resize(deflateBound(&zs, size) + 64);
    zs.next_in = const_cast<Bytef*>(begin);
    zs.avail_in = static_cast<uInt>(size);
    zs.next_out = deflated.data();
    zs.avail_out = static_cast<uInt>(deflated.size());
    const bool last = s + 1 == count_;
    const int r = deflate(&zs, last ? Z_FINISH : Z_SYNC_FLUSH);
    status_[s] = (last ? r == Z_STREAM_END : r == Z_OK && zs.avail_in == 0 && zs.avail_out > 0) ? Z_OK : Z_BUF_ERROR;
    parts_[s].assign(deflated.data(), deflated.data() + zs.total_out);
}

std::vector<std::uint8_t> PngStrips::finish(bool srgb, const ImageMetadata& metadata) {
    // The strips not encoded yet (all of them when no rows were announced), in parallel.
    tbb::parallel_for(std::size_t{0}, count_, [&](std::size_t s) {
        if (!claimed_[s].exchange(true, std::memory_order_acq_rel)) encode(s);
    });
    return assemble(srgb, metadata);
}

std::vector<std::uint8_t> encode_png(const PngRows& rows, int width, int height, bool srgb,
                                     const ImageMetadata& metadata, const PngOptions& options) {
    PngStrips strips(rows, width, height, options);
    return strips.finish(srgb, metadata);
}

std::vector<std::uint8_t> PngStrips::assemble(bool srgb, const ImageMetadata& metadata) const {
    const int width = width_, height = height_;
    const std::size_t line = line_, strips = count_, strip_rows = strip_rows_;
    const auto h = static_cast<std::size_t>(height);
    const auto& parts = parts_;
    const auto& adlers = adlers_;
    for (int st : status_)
        if (st != Z_OK) throw IoError(fmt::format("PNG encoding failed (zlib error {})", st));
    uLong adler = strips ? adlers[0] : adler32_z(0, nullptr, 0);
    for (std::size_t s = 1; s < strips; ++s) {
        const std::size_t rows = std::min(h, (s + 1) * strip_rows) - s * strip_rows;
        adler = adler32_combine(adler, adlers[s], static_cast<z_off_t>(rows * line));
    }

    std::vector<std::uint8_t> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    std::vector<std::uint8_t> ihdr;
    put32(ihdr, static_cast<std::uint32_t>(width));
    put32(ihdr, static_cast<std::uint32_t>(height));
    ihdr.insert(ihdr.end(), {8, 2, 0, 0, 0});  // 8 bits, RGB, deflate, adaptive filtering, no interlace
    chunk(png, "IHDR", ihdr.data(), ihdr.size());
    std::vector<std::uint8_t> gamma;
    put32(gamma, srgb ? 45455 : 100000);  // 1/2.2 beside the sRGB chunk, as the PNG spec advises; 1.0: linear
    if (srgb) chunk(png, "sRGB", std::string(1, '\0'));  // rendering intent: perceptual
    chunk(png, "gAMA", gamma.data(), gamma.size());
    for (const auto& [key, value] : metadata) {
        const std::string k = key.substr(0, 79);  // keywords are 1-79 Latin-1 characters
        if (k.empty() || !is_ascii(k)) continue;
        if (is_ascii(value)) {
            chunk(png, "tEXt", k + '\0' + value);
        } else {  // UTF-8 (a scene path, say): uncompressed iTXt, no language tag
            chunk(png, "iTXt", k + std::string("\0\0\0\0\0", 5) + value);
        }
    }
    std::size_t zsize = 2 + 4;
    for (const auto& p : parts) zsize += p.size();
    std::vector<std::uint8_t> z;
    z.reserve(zsize);
    z.insert(z.end(), {0x78, 0x01});  // deflate, 32 KiB window, no dictionary, "fastest"
    for (const auto& p : parts) z.insert(z.end(), p.begin(), p.end());
    put32(z, static_cast<std::uint32_t>(adler));
    png.reserve(png.size() + z.size() + 32);
    chunk(png, "IDAT", z.data(), z.size());
    chunk(png, "IEND", nullptr, 0);
    return png;
}

}  // namespace glint
