#include "glint/io/image_io.h"

#include "glint/io/diagnostics.h"
#include "glint/io/limits.h"

#include <unistd.h>

#include <OpenImageIO/imageio.h>
#include <fmt/core.h>

#include <algorithm>
#include <fstream>
#include <bit>
#include <cstdio>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <system_error>
#include <vector>

namespace glint {

namespace fs = std::filesystem;

ImageFormat image_format_for(const fs::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (ext == ".png") return ImageFormat::kPng;
    if (ext == ".exr") return ImageFormat::kExr;
    if (ext == ".ppm") return ImageFormat::kPpm;
    throw IoError(fmt::format("{}: unsupported output format '{}' (supported: .png, .exr, .ppm)",
                              path.string(), ext.empty() ? std::string("no extension") : ext));
}

float srgb_decode(float v) {
    return v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f);
}

namespace {

// Portable float maps (pbrt's PFM textures; OpenImageIO here has no reader for them): "PF"
// (RGB) or "Pf" (grey), "width height", a scale whose sign gives the byte order (negative:
// little endian) and whose magnitude multiplies the values, then the rows bottom to top.
struct RawImage {
    int width = 0, height = 0, channels = 0;
    bool is_float = false;
    std::vector<float> data;  ///< top row first
};

RawImage read_pfm(const fs::path& path, long long max_pixels) {
    std::FILE* f = std::fopen(path.c_str(), "rb");
    if (!f) throw IoError(fmt::format("cannot read image '{}': {}", path.string(), std::strerror(errno)));
    // Nothing is read beyond what the largest allowed map needs (the header is checked below).
    std::error_code size_error;
    const auto file_size = fs::file_size(path, size_error);
    if (!size_error && static_cast<double>(file_size) > static_cast<double>(max_pixels) * 12 + 4096) {
        std::fclose(f);
        throw IoError(fmt::format("cannot read image '{}': {} bytes is more than a map of the limit of {} pixels "
                                  "can hold", path.string(), file_size, max_pixels));
    }
    if (const std::string e = charge_memory(static_cast<long long>(file_size) * 2, "image '" + path.string() + "'"); !e.empty()) {
        std::fclose(f);
        throw IoError(e);
    }
    std::string bytes;
    char buf[65536];
    for (std::size_t n; (n = std::fread(buf, 1, sizeof buf, f)) > 0;) bytes.append(buf, n);
    std::fclose(f);
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

RawImage read_oiio(const fs::path& path, long long max_pixels) {
    auto in = OIIO::ImageInput::open(path.string());
    if (!in) {
        std::string why = OIIO::geterror();
        if (why.empty()) why = "cannot open it";
        throw IoError(fmt::format("cannot read image '{}': {}", path.string(), why));
    }
    const OIIO::ImageSpec& spec = in->spec();
    const long long pixels = static_cast<long long>(spec.width) * spec.height;
    if (spec.width <= 0 || spec.height <= 0 || pixels > max_pixels) {
        throw IoError(fmt::format("image '{}' is {} x {} pixels: {}", path.string(), spec.width, spec.height,
                                  over_limit(Limit::kTexturePixels, pixels, max_pixels)));
    }
    if (const std::string e = charge_memory(pixels * 4 * std::max(spec.nchannels, 3), "image '" + path.string() + "'"); !e.empty())
        throw IoError(e);
    RawImage raw;
    raw.width = spec.width;
    raw.height = spec.height;
    raw.channels = spec.nchannels;
    raw.data.resize(static_cast<std::size_t>(pixels) * static_cast<std::size_t>(raw.channels));
    if (!in->read_image(0, 0, 0, raw.channels, OIIO::TypeDesc::FLOAT, raw.data.data())) {
        throw IoError(fmt::format("cannot read image '{}': {}", path.string(), in->geterror()));
    }
    raw.is_float = spec.format.basetype == OIIO::TypeDesc::FLOAT ||
                   spec.format.basetype == OIIO::TypeDesc::HALF ||
                   spec.format.basetype == OIIO::TypeDesc::DOUBLE;
    return raw;
}

// An OpenEXR file's header attributes, checked before OpenEXR reads them: OpenEXR 3.1 allocates
// whatever size an attribute declares (found by fuzz_image: a 1.4 KB file asked for 1.9 GB).
// Each attribute is a name, a type name (both NUL-terminated) and a 4-byte little-endian size;
// a size beyond the file's end is refused at its byte offset. Files that are not EXR (by their
// magic number) are left alone; only the first megabyte is looked at.
std::string exr_header_error(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::string head(8, '\0');
    in.read(head.data(), 8);
    if (in.gcount() < 8 || head.compare(0, 4, "\x76\x2f\x31\x01") != 0) return {};
    head.resize(1 << 20);  // an EXR: its header, up to a megabyte
    in.read(head.data() + 8, static_cast<std::streamsize>(head.size() - 8));
    head.resize(8 + static_cast<std::size_t>(in.gcount()));
    std::error_code ec;
    const auto file_size = static_cast<std::uint64_t>(fs::file_size(path, ec));
    if (ec) return {};
    const bool multipart = (static_cast<unsigned char>(head[5]) & 0x10) != 0;
    std::size_t at = 8;
    for (bool header_start = true;;) {
        if (at >= head.size()) return {};  // beyond what was read: OpenEXR's checks apply
        if (head[at] == '\0') {            // the end of a header (or, for multipart, of all)
            if (!multipart || header_start) return {};
            ++at;
            header_start = true;
            continue;
        }
        header_start = false;
        const std::size_t name_end = head.find('\0', at);
        const std::size_t type_end = name_end == std::string::npos ? name_end : head.find('\0', name_end + 1);
        if (type_end == std::string::npos || type_end + 4 >= head.size()) return {};
        std::uint32_t size = 0;
        for (int k = 3; k >= 0; --k) size = (size << 8) | static_cast<unsigned char>(head[type_end + 1 + static_cast<std::size_t>(k)]);
        const std::uint64_t value_at = type_end + 5;
        if (size > file_size - std::min(file_size, value_at))
            return fmt::format("byte {}: OpenEXR header attribute '{}' claims {} bytes, more than the {} bytes left in the file",
                               type_end + 1, head.substr(at, std::min<std::size_t>(name_end - at, 64)), size,
                               file_size - std::min(file_size, value_at));
        at = static_cast<std::size_t>(value_at) + size;
    }
}

}  // namespace

Image read_image(const fs::path& path, ImageEncoding encoding, long long max_pixels) {
    if (max_pixels <= 0) max_pixels = limit(Limit::kTexturePixels);
    if (const std::string why = why_not_readable(path); !why.empty())
        throw IoError(fmt::format("cannot read image '{}': it {}", path.string(), why));
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (const std::string why = exr_header_error(path); !why.empty())
        throw IoError(fmt::format("cannot read image '{}': {}", path.string(), why));
    const RawImage raw = ext == ".pfm" ? read_pfm(path, max_pixels) : read_oiio(path, max_pixels);
    const long long pixels = static_cast<long long>(raw.width) * raw.height;
    const int channels = raw.channels;
    const std::vector<float>& data = raw.data;
    const bool is_float = raw.is_float;
    const bool decode = encoding == ImageEncoding::kSrgb ||
                        (encoding == ImageEncoding::kAuto && !is_float);
    Image image;
    image.width = raw.width;
    image.height = raw.height;
    image.texels.resize(static_cast<std::size_t>(pixels));
    for (std::size_t i = 0; i < image.texels.size(); ++i) {
        const float* px = &data[i * static_cast<std::size_t>(channels)];
        float rgb[3];
        for (int k = 0; k < 3; ++k) {
            float v = px[channels >= 3 ? k : 0];
            if (!std::isfinite(v) || v < 0) v = 0;  // texels are reflectances or radiances
            rgb[k] = decode ? srgb_decode(std::min(v, 1.0f)) : v;
        }
        image.texels[i] = {rgb[0], rgb[1], rgb[2]};
    }
    return image;
}

void check_writable(const fs::path& path) {
    image_format_for(path);
    const fs::path dir = path.parent_path().empty() ? fs::path(".") : path.parent_path();
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) {
        throw IoError(fmt::format("{}: cannot write: folder '{}' does not exist", path.string(),
                                  dir.string()));
    }
    if (fs::is_directory(path, ec)) {
        throw IoError(fmt::format("{}: cannot write: it is a folder", path.string()));
    }
    if (::access(dir.c_str(), W_OK) != 0) {
        throw IoError(fmt::format("{}: cannot write to folder '{}': {}", path.string(),
                                  dir.string(), std::strerror(errno)));
    }
}

fs::path temporary_path(const fs::path& target) {
    const fs::path dir = target.parent_path().empty() ? fs::path(".") : target.parent_path();
    return dir / fmt::format(".{}.glint-{}.tmp", target.filename().string(), ::getpid());
}

void write_image(const fs::path& path, const Film& film, const DisplaySettings& display,
                 const ImageMetadata& metadata) {
    const ImageFormat format = image_format_for(path);
    const int w = film.width(), h = film.height();
    const fs::path tmp = temporary_path(path);
    const auto annotate = [&metadata](OIIO::ImageSpec& spec) {
        for (const auto& [name, value] : metadata) spec.attribute(name, value);
    };

    auto out = OIIO::ImageOutput::create(path.string());
    if (!out) {
        throw IoError(fmt::format("{}: cannot create an image writer: {}", path.string(),
                                  OIIO::geterror()));
    }
    bool ok = false;
    std::vector<float> floats;
    std::vector<std::uint8_t> bytes;
    const auto n = static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
    if (format == ImageFormat::kExr) {
        // R, G, B, then with AOVs: albedo.R/G/B, N.X/Y/Z and Z (depth), OpenEXR's names, then
        // the sample counts.
        const bool counts = film.has_sample_counts();
        const int channels = (film.has_aovs() ? 10 : 3) + (counts ? 1 : 0);
        OIIO::ImageSpec spec(w, h, channels, OIIO::TypeDesc::FLOAT);
        spec.attribute("compression", "zip");
        spec.channelnames = {"R", "G", "B"};
        if (film.has_aovs()) {
            spec.channelnames.insert(spec.channelnames.end(),
                                     {"albedo.R", "albedo.G", "albedo.B", "N.X", "N.Y", "N.Z", "Z"});
            spec.z_channel = 9;
        }
        if (counts) spec.channelnames.push_back("spp");
        annotate(spec);
        const auto stride = static_cast<std::size_t>(channels);
        floats.resize(n * stride);
        for (std::size_t i = 0; i < n; ++i) {
            float* px = &floats[i * stride];
            const Color c = film.pixels()[i];
            px[0] = c.r, px[1] = c.g, px[2] = c.b;
            if (film.has_aovs()) {
                const Color a = film.albedo()[i];
                const Normal3 nn = film.normal()[i];
                px[3] = a.r, px[4] = a.g, px[5] = a.b;
                px[6] = nn.x, px[7] = nn.y, px[8] = nn.z;
                px[9] = film.depth()[i];
            }
            if (counts) px[channels - 1] = film.sample_counts()[i];
        }
        ok = out->open(tmp.string(), spec) &&
             out->write_image(OIIO::TypeDesc::FLOAT, floats.data());
    } else {
        OIIO::ImageSpec spec(w, h, 3, OIIO::TypeDesc::UINT8);
        spec.attribute("oiio:ColorSpace", display.encoding == Encoding::kSrgb ? "sRGB" : "Linear");
        annotate(spec);
        bytes.resize(n * 3);
        for (std::size_t i = 0; i < n; ++i) {
            const Color c = film.pixels()[i];
            for (int k = 0; k < 3; ++k) bytes[3 * i + k] = encode_8bit(c[k], display);
        }
        ok = out->open(tmp.string(), spec) &&
             out->write_image(OIIO::TypeDesc::UINT8, bytes.data());
    }
    ok = out->close() && ok;
    if (!ok) {
        const std::string why = out->geterror();
        std::error_code ec;
        fs::remove(tmp, ec);
        throw IoError(fmt::format("{}: writing the image failed: {}", path.string(), why));
    }
    std::error_code ec;
    fs::rename(tmp, path, ec);
    if (ec) {
        std::error_code ignored;
        fs::remove(tmp, ignored);
        throw IoError(fmt::format("{}: cannot move the finished image into place: {}",
                                  path.string(), ec.message()));
    }
}

}  // namespace glint
