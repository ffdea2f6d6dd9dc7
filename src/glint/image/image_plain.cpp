// The formats simple enough to read and write directly: Radiance HDR (RGBE), PFM (pbrt's float
// maps) and the binary and ASCII Netpbm maps (PGM, PPM; read only here, PPM is written in
// image_io.cpp).
#include <fmt/core.h>

#include <algorithm>
#include <bit>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "glint/image/image_formats.h"
#include "glint/base/limits.h"

namespace glint {

namespace fs = std::filesystem;

namespace {

// The whole file, if it is at most `max_bytes` long (what an image of `max_pixels` can take) (checked from its size, before reading) and
// the memory budget allows it.
std::string file_bytes(const fs::path& path, double max_bytes, long long max_pixels) {
    std::FILE* f = std::fopen(path.c_str(), "rb");
    if (!f) throw IoError(fmt::format("cannot read image '{}': {}", path.string(), std::strerror(errno)));
    std::error_code size_error;
    const auto file_size = fs::file_size(path, size_error);
    if (!size_error && static_cast<double>(file_size) > max_bytes) {
        std::fclose(f);
        throw IoError(fmt::format("cannot read image '{}': {} bytes is more than an image of the limit of {} "
                                  "pixels can hold", path.string(), file_size, max_pixels));
    }
    if (const std::string e = charge_memory(static_cast<long long>(file_size), "image '" + path.string() + "'");
        !e.empty()) {
        std::fclose(f);
        throw IoError(e);
    }
    std::string bytes;
    char buf[65536];
    for (std::size_t n; (n = std::fread(buf, 1, sizeof buf, f)) > 0;) bytes.append(buf, n);
    std::fclose(f);
    return bytes;
}

// Whitespace-separated header fields, with PNM's '#' comments, and where they stop.
struct Tokens {
    const std::string& bytes;
    std::size_t pos = 0;
    bool comments = false;
    std::string next() {
        for (;;) {
            while (pos < bytes.size() && std::isspace(static_cast<unsigned char>(bytes[pos]))) ++pos;
            if (!comments || pos >= bytes.size() || bytes[pos] != '#') break;
            while (pos < bytes.size() && bytes[pos] != '\n') ++pos;
        }
        const std::size_t start = pos;
        while (pos < bytes.size() && !std::isspace(static_cast<unsigned char>(bytes[pos]))) ++pos;
        return bytes.substr(start, pos - start);
    }
    long long integer(long long lo, long long hi) {
        const std::string t = next();
        if (t.empty() || t.size() > 18 || !std::all_of(t.begin(), t.end(), [](char c) { return c >= '0' && c <= '9'; }))
            return -1;
        const long long v = std::stoll(t);
        return v < lo || v > hi ? -1 : v;
    }
};

}  // namespace

// Portable float maps (pbrt's PFM textures): "PF" (RGB) or "Pf" (grey), "width height", a scale
// whose sign gives the byte order (negative: little endian) and whose magnitude multiplies the
// values, then the rows bottom to top.
RawImage read_pfm(const fs::path& path, long long max_pixels) {
    // Nothing is read beyond what the largest allowed map needs (the header is checked below);
    // the file's bytes and the floats decoded from them are charged to the memory budget.
    const std::string bytes = file_bytes(path, static_cast<double>(max_pixels) * 12 + 4096, max_pixels);
    if (const std::string e = charge_memory(static_cast<long long>(bytes.size()), "image '" + path.string() + "'");
        !e.empty())
        throw IoError(e);
    std::size_t pos = 0;
    const auto token = [&]() {
        while (pos < bytes.size() && std::isspace(static_cast<unsigned char>(bytes[pos]))) ++pos;
        const std::size_t start = pos;
        while (pos < bytes.size() && !std::isspace(static_cast<unsigned char>(bytes[pos]))) ++pos;
        return bytes.substr(start, pos - start);
    };
    const auto bad = [&](const std::string& why) {
        return IoError(fmt::format("cannot read image '{}': byte {}: {}", path.string(), pos, why));
    };
    const std::string magic = token();
    if (magic != "PF" && magic != "Pf") throw bad("not a PFM file (expected 'PF' or 'Pf')");
    RawImage raw;
    raw.channels = magic == "PF" ? 3 : 1;
    raw.is_float = true;
    long long w = 0, h = 0;
    double scale = 0;
    try {
        std::size_t used = 0;
        std::string t = token();
        w = std::stoll(t, &used);
        if (used != t.size()) throw std::invalid_argument(t);
        t = token();
        h = std::stoll(t, &used);
        if (used != t.size()) throw std::invalid_argument(t);
        t = token();
        scale = std::stod(t, &used);
        if (used != t.size()) throw std::invalid_argument(t);
    } catch (const std::exception&) {
        throw bad("the header needs a width, a height and a scale");
    }
    if (w <= 0 || h <= 0 || static_cast<double>(w) * static_cast<double>(h) > static_cast<double>(max_pixels))
        throw bad(fmt::format("{} x {} pixels: {}", w, h,
                              over_limit(Limit::kTexturePixels, static_cast<long long>(std::min(9.0e18, double(w) * double(h))), max_pixels)));
    if (!(scale != 0) || !std::isfinite(scale)) throw bad("the scale must be a finite non-zero number");
    ++pos;  // the single whitespace byte that ends the header
    const std::size_t count = static_cast<std::size_t>(w * h) * static_cast<std::size_t>(raw.channels);
    if (bytes.size() < pos || bytes.size() - pos < count * 4)
        throw bad(fmt::format("{} bytes of data for {} floats", bytes.size() < pos ? 0 : bytes.size() - pos, count));
    raw.width = static_cast<int>(w);
    raw.height = static_cast<int>(h);
    raw.data.resize(count);
    const bool little = scale < 0;
    const float factor = static_cast<float>(std::abs(scale));
    const std::size_t row = static_cast<std::size_t>(w) * static_cast<std::size_t>(raw.channels);
    for (std::size_t i = 0; i < count; ++i) {
        unsigned char b[4];
        std::memcpy(b, bytes.data() + pos + 4 * i, 4);
        if (!little) std::swap(b[0], b[3]), std::swap(b[1], b[2]);  // the file is big endian
        std::uint32_t u = 0;
        for (int k = 3; k >= 0; --k) u = (u << 8) | b[k];
        const float v = std::bit_cast<float>(u) * factor;
        const std::size_t y = i / row, x = i % row;  // rows bottom to top
        raw.data[(static_cast<std::size_t>(h) - 1 - y) * row + x] = v;
    }
    return raw;
}

RawImage read_hdr(const fs::path& path, long long max_pixels) {
    // A flat RGBE file is 4 bytes a pixel; run-length encoding adds at most a count byte per 128
    // literal bytes and 4 bytes per row of 8 or more pixels: under 5 bytes a pixel in all.
    const std::string bytes = file_bytes(path, 5.0 * static_cast<double>(max_pixels) + 65536, max_pixels);
    std::size_t pos = 0;
    const auto bad = [&](const std::string& why) {
        return IoError(fmt::format("cannot read image '{}': byte {}: {}", path.string(), pos, why));
    };
    const auto line = [&]() {
        const std::size_t end = bytes.find('\n', pos);
        if (end == std::string::npos) throw bad("the header does not end");
        std::string l = bytes.substr(pos, end - pos);
        pos = end + 1;
        return l;
    };
    if (bytes.compare(0, 2, "#?") != 0) throw bad("not a Radiance HDR file (it must start with '#?')");
    line();
    for (std::string l; !(l = line()).empty();) {
        if (l.rfind("FORMAT=", 0) == 0 && l != "FORMAT=32-bit_rle_rgbe")
            throw bad(fmt::format("format '{}' (glint reads 32-bit_rle_rgbe)", l.substr(7)));
    }
    // The resolution line: "-Y height +X width" (rows top first) or "+Y height +X width".
    const std::size_t res_at = pos;
    const std::string res = line();
    char ysign = 0, xsign = 0;
    long long h = 0, w = 0;
    {
        char yaxis = 0, xaxis = 0;
        int used = 0;
        if (std::sscanf(res.c_str(), " %c%c %lld %c%c %lld%n", &ysign, &yaxis, &h, &xsign, &xaxis, &w, &used) != 6 ||
            static_cast<std::size_t>(used) != res.size() || yaxis != 'Y' || xaxis != 'X' || xsign != '+' ||
            (ysign != '-' && ysign != '+')) {
            pos = res_at;
            throw bad(fmt::format("resolution line '{}' (glint reads '-Y height +X width' and '+Y height +X width')",
                                  res.substr(0, 64)));
        }
    }
    admit_image(path, w, h, max_pixels, 3 * 4 + 4, 0);
    const auto W = static_cast<std::size_t>(w), H = static_cast<std::size_t>(h);
    {
        // The fewest bytes a row of W pixels can take: one 4-byte pixel, then the old encoding's
        // repeat codes (4 bytes each; three in a row repeat at most 255 + 255 << 8 + 255 << 16
        // times) and a literal pixel after each three. Checked for all rows before allocating.
        const std::size_t chains = (W - 1 + 16777214) / 16777215;  // a literal + up to 3 repeats each
        const std::size_t rest = W - 1 - (chains > 0 ? (chains - 1) * 16777215 : 0);
        const std::size_t last = chains == 0 ? 0 : rest <= 255 ? 1 : rest <= 65535 ? 2 : 3;
        const double min_row = 4.0 + (chains == 0 ? 0.0 : 16.0 * static_cast<double>(chains - 1) + 4.0 * static_cast<double>(last));
        if (static_cast<double>(bytes.size() - pos) < min_row * static_cast<double>(H))
            throw bad(fmt::format("the header claims {} x {} pixels; {} rows need at least {:.0f} bytes, and {} are left",
                                  w, h, h, min_row * static_cast<double>(H), bytes.size() - pos));
    }
    std::vector<unsigned char> rgbe(W * 4);
    RawImage raw;
    raw.width = static_cast<int>(w);
    raw.height = static_cast<int>(h);
    raw.channels = 3;
    raw.is_float = true;
    raw.data.resize(W * H * 3);
    const auto byte = [&]() -> unsigned char {
        if (pos >= bytes.size()) throw bad("the pixel data ends early");
        return static_cast<unsigned char>(bytes[pos++]);
    };
    for (std::size_t y = 0; y < H; ++y) {
        const bool rle = W >= 8 && W < 32768 && pos + 4 <= bytes.size() && bytes[pos] == 2 && bytes[pos + 1] == 2 &&
                         (static_cast<unsigned char>(bytes[pos + 2]) & 0x80) == 0;
        if (rle) {  // the new run-length encoding: each component's row in runs
            const std::size_t row_at = pos;
            pos += 2;
            const std::size_t n = static_cast<std::size_t>(byte()) << 8 | byte();
            if (n != W) {
                pos = row_at;
                throw bad(fmt::format("row {} declares {} pixels; the image is {} wide", y, n, W));
            }
            for (std::size_t c = 0; c < 4; ++c) {
                for (std::size_t x = 0; x < W;) {
                    const std::size_t count_at = pos;
                    unsigned count = byte();
                    const bool run = count > 128;
                    if (run) count -= 128;
                    if (count == 0 || x + count > W) {
                        pos = count_at;
                        throw bad(fmt::format("row {}: a run of {} past the row's end", y, count));
                    }
                    if (run) {
                        const unsigned char v = byte();
                        for (unsigned k = 0; k < count; ++k) rgbe[4 * (x++) + c] = v;
                    } else {
                        for (unsigned k = 0; k < count; ++k) rgbe[4 * (x++) + c] = byte();
                    }
                }
            }
        } else {  // flat pixels, with the old encoding's repeats (1, 1, 1, n: the previous pixel n times)
            int shift = 0;
            for (std::size_t x = 0; x < W;) {
                unsigned char p[4] = {byte(), byte(), byte(), byte()};
                if (p[0] == 1 && p[1] == 1 && p[2] == 1) {
                    if (x == 0 || shift > 16) throw bad(fmt::format("row {}: a repeat with no pixel before it", y));
                    const std::size_t count = static_cast<std::size_t>(p[3]) << shift;
                    if (x + count > W) throw bad(fmt::format("row {}: a repeat past the row's end", y));
                    for (std::size_t k = 0; k < count; ++k, ++x) std::memcpy(&rgbe[4 * x], &rgbe[4 * (x - 1)], 4);
                    shift += 8;
                } else {
                    std::memcpy(&rgbe[4 * x], p, 4);
                    ++x;
                    shift = 0;
                }
            }
        }
        const std::size_t out_row = ysign == '-' ? y : H - 1 - y;
        for (std::size_t x = 0; x < W; ++x) {
            const unsigned char* p = &rgbe[4 * x];
            // Radiance's convention: a mantissa m stands for the middle of its bin, (m + 0.5) 2^(e-136).
            const float f = p[3] == 0 ? 0.0f : std::ldexp(1.0f, static_cast<int>(p[3]) - 136);
            for (std::size_t k = 0; k < 3; ++k)
                raw.data[(out_row * W + x) * 3 + k] = p[3] == 0 ? 0.0f : (static_cast<float>(p[k]) + 0.5f) * f;
        }
    }
    return raw;
}

RawImage read_pnm(const fs::path& path, long long max_pixels) {
    const std::string bytes = file_bytes(path, 6.0 * static_cast<double>(max_pixels) * 8 + 65536, max_pixels);
    Tokens t{bytes, 0, true};
    const auto bad = [&](const std::string& why) {
        return IoError(fmt::format("cannot read image '{}': byte {}: {}", path.string(), t.pos, why));
    };
    const std::string magic = t.next();
    if (magic != "P2" && magic != "P3" && magic != "P5" && magic != "P6")
        throw bad(fmt::format("'{}' is not a greymap or pixmap glint reads (P2, P3, P5, P6)", magic.substr(0, 8)));
    const long long w = t.integer(1, 1LL << 40), h = t.integer(1, 1LL << 40), maxval = t.integer(1, 65535);
    if (w < 0 || h < 0 || maxval < 0) throw bad("the header needs a width, a height and a maximum value (1 to 65535)");
    const bool ascii = magic == "P2" || magic == "P3";
    const std::size_t channels = magic == "P3" || magic == "P6" ? 3 : 1;
    admit_image(path, w, h, max_pixels, 3 * 4, 0);
    RawImage raw;
    raw.width = static_cast<int>(w);
    raw.height = static_cast<int>(h);
    raw.channels = static_cast<int>(channels);
    const std::size_t count = static_cast<std::size_t>(w * h) * channels;
    // Each value takes at least a byte (a digit, or a binary sample): checked before allocating.
    if (count > bytes.size() - std::min(bytes.size(), t.pos))
        throw bad(fmt::format("the header claims {} x {} pixels ({} values); only {} bytes follow it", w, h, count,
                              bytes.size() - std::min(bytes.size(), t.pos)));
    raw.data.resize(count);
    const float scale = 1.0f / static_cast<float>(maxval);
    if (ascii) {
        for (std::size_t i = 0; i < count; ++i) {
            const long long v = t.integer(0, maxval);
            if (v < 0) throw bad(fmt::format("value {} of {}: expected an integer from 0 to {}", i, count, maxval));
            raw.data[i] = static_cast<float>(v) * scale;
        }
        return raw;
    }
    const std::size_t start = t.pos + 1;  // one whitespace byte ends the header
    const std::size_t size = maxval > 255 ? 2 : 1;
    if (bytes.size() < start || (bytes.size() - start) / size < count) {
        t.pos = std::min(bytes.size(), start);
        throw bad(fmt::format("{} bytes of data for {} values", bytes.size() < start ? 0 : bytes.size() - start, count));
    }
    for (std::size_t i = 0; i < count; ++i) {
        const auto* p = reinterpret_cast<const unsigned char*>(bytes.data() + start + i * size);
        const unsigned v = size == 2 ? (unsigned{p[0]} << 8 | p[1]) : p[0];  // 16-bit values are big endian
        raw.data[i] = static_cast<float>(std::min<unsigned>(v, static_cast<unsigned>(maxval))) * scale;
    }
    return raw;
}

void rgbe_encode(float r, float g, float b, std::uint8_t out[4]) {
    const auto clean = [](float c) { return c > 0 ? std::min(c, 1e38f) : 0.0f; };  // NaN fails c > 0
    r = clean(r), g = clean(g), b = clean(b);
    const float v = std::max({r, g, b});
    if (v < 1e-32f) {
        out[0] = out[1] = out[2] = out[3] = 0;
        return;
    }
    int e = 0;
    std::frexp(v, &e);  // v = m 2^e with m in [0.5, 1)
    // Scaling by the power of two 2^(8-e) is exact, so the largest component lands in [128, 256).
    const float scale = std::ldexp(1.0f, 8 - e);
    out[0] = static_cast<std::uint8_t>(r * scale);
    out[1] = static_cast<std::uint8_t>(g * scale);
    out[2] = static_cast<std::uint8_t>(b * scale);
    out[3] = static_cast<std::uint8_t>(e + 128);
}

namespace {

// One component of a row in the new run-length encoding: runs of 4 to 127 equal bytes as
// (128 + n, byte), everything between as literals of at most 128 bytes (n, bytes...).
void rle_component(const std::uint8_t* row, std::size_t width, std::vector<std::uint8_t>& out) {
    const auto at = [row](std::size_t x) { return row[4 * x]; };
    const auto literals = [&](std::size_t from, std::size_t to) {
        while (from < to) {
            const std::size_t n = std::min<std::size_t>(to - from, 128);
            out.push_back(static_cast<std::uint8_t>(n));
            for (std::size_t k = 0; k < n; ++k) out.push_back(at(from + k));
            from += n;
        }
    };
    std::size_t pending = 0;  // the first byte not yet written
    for (std::size_t x = 0; x < width;) {
        std::size_t run = 1;
        while (x + run < width && run < 127 && at(x + run) == at(x)) ++run;
        if (run >= 4) {
            literals(pending, x);
            out.push_back(static_cast<std::uint8_t>(128 + run));
            out.push_back(at(x));
            pending = x + run;
        }
        x += run;
    }
    literals(pending, width);
}

std::string header_value(std::string v) {  // a header line cannot hold a line break
    std::replace(v.begin(), v.end(), '\n', ' ');
    std::replace(v.begin(), v.end(), '\r', ' ');
    return v;
}

}  // namespace

std::vector<std::uint8_t> encode_hdr(const float* rgb, int width, int height, const ImageMetadata& metadata) {
    std::string header = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n";
    for (const auto& [name, value] : metadata) header += header_value(name) + "=" + header_value(value) + "\n";
    header += fmt::format("\n-Y {} +X {}\n", height, width);
    std::vector<std::uint8_t> out(header.begin(), header.end());
    const auto W = static_cast<std::size_t>(width);
    const bool rle = width >= 8 && width < 32768;
    std::vector<std::uint8_t> row(W * 4);
    out.reserve(out.size() + W * static_cast<std::size_t>(height) * 4);
    for (std::size_t y = 0; y < static_cast<std::size_t>(height); ++y) {
        for (std::size_t x = 0; x < W; ++x) {
            const float* p = rgb + (y * W + x) * 3;
            rgbe_encode(p[0], p[1], p[2], &row[4 * x]);
        }
        if (!rle) {
            out.insert(out.end(), row.begin(), row.end());
            continue;
        }
        out.insert(out.end(), {2, 2, static_cast<std::uint8_t>(W >> 8), static_cast<std::uint8_t>(W & 255)});
        for (std::size_t c = 0; c < 4; ++c) rle_component(&row[c], W, out);
    }
    return out;
}

std::vector<std::uint8_t> encode_pfm(const float* rgb, int width, int height) {
    const std::string header = fmt::format("PF\n{} {}\n-1\n", width, height);
    std::vector<std::uint8_t> out(header.begin(), header.end());
    const std::size_t row = static_cast<std::size_t>(width) * 3;
    out.reserve(out.size() + row * static_cast<std::size_t>(height) * 4);
    for (std::size_t y = static_cast<std::size_t>(height); y-- > 0;) {  // bottom row first
        for (std::size_t i = 0; i < row; ++i) {
            const auto u = std::bit_cast<std::uint32_t>(rgb[y * row + i]);
            for (int k = 0; k < 4; ++k) out.push_back(static_cast<std::uint8_t>(u >> (8 * k)));  // little endian
        }
    }
    return out;
}

}  // namespace glint
