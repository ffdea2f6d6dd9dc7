#include "glint/image/image_io.h"
#include "glint/base/atomic_file.h"

#include "glint/base/diagnostics.h"
#include "glint/image/image_formats.h"
#include "glint/base/module.h"
#include "glint/image/oiio_module.h"
#include "glint/base/limits.h"

#include <unistd.h>
#include <string_view>

#include <tbb/parallel_for.h>
#include <fmt/core.h>

#include <algorithm>
#include <fstream>
#include <cstdio>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <optional>
#include <system_error>
#include <vector>

namespace glint {

namespace fs = std::filesystem;

namespace {

std::string lower_extension(const fs::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext;
}

}  // namespace

std::span<const ImageFormatInfo> image_formats() {
    // The order of the "supported" list in image_format_for's message.
    static const ImageFormatInfo formats[] = {
        {ImageFormat::kPng, {".png"}, "PNG, 8-bit sRGB (libspng); rows encoded as they render"},
        {ImageFormat::kExr, {".exr"}, "OpenEXR, 32-bit float linear RGB, with AOVs and sample counts as channels"},
        {ImageFormat::kJpeg, {".jpg", ".jpeg"}, "JPEG, 8-bit sRGB (libjpeg-turbo)"},
        {ImageFormat::kHdr, {".hdr"}, "Radiance RGBE, linear"},
        {ImageFormat::kPfm, {".pfm"}, "Portable float map, linear"},
        {ImageFormat::kPpm, {".ppm"}, "Portable pixmap, 8-bit"},
    };
    return formats;
}

ImageFormat image_format_for(const fs::path& path) {
    const std::string ext = lower_extension(path);
    std::string known;
    for (const ImageFormatInfo& f : image_formats()) {
        for (std::string_view e : f.extensions)
            if (ext == e) return f.format;
        known += (known.empty() ? "" : ", ") + std::string(f.extensions.front());
    }
    throw IoError(fmt::format("{}: unsupported output format '{}' (supported: {})", path.string(),
                              ext.empty() ? std::string("no extension") : ext, known));
}

float srgb_decode(float v) {
    return v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f);
}

namespace {

// The bytes OpenEXR 3.1 reads for the value of an attribute of a type it knows, whatever size the
// attribute declares (0: it reads the declared size). Fixed-size types read their own size;
// `chlist` and `preview` are handled by exr_value_end.
std::uint64_t exr_fixed_size(std::string_view type) {
    static constexpr std::pair<std::string_view, std::uint64_t> kSizes[] = {
        {"box2i", 16}, {"box2f", 16}, {"chromaticities", 32}, {"compression", 1}, {"deepImageState", 1},
        {"double", 8}, {"envmap", 1}, {"float", 4}, {"int", 4}, {"keycode", 28}, {"lineOrder", 1},
        {"m33f", 36}, {"m33d", 72}, {"m44f", 64}, {"m44d", 128}, {"rational", 8}, {"tiledesc", 9},
        {"timecode", 8}, {"v2i", 8}, {"v2f", 8}, {"v2d", 16}, {"v3i", 12}, {"v3f", 12}, {"v3d", 24}};
    for (const auto& [name, size] : kSizes)
        if (name == type) return size;
    return 0;
}

std::uint32_t read_u32(const std::string& head, std::size_t at) {
    std::uint32_t v = 0;
    for (int k = 3; k >= 0; --k) v = (v << 8) | static_cast<unsigned char>(head[at + static_cast<std::size_t>(k)]);
    return v;
}

// Where OpenEXR's reading of an attribute's value ends (an offset into head), or npos when that is
// beyond what was read; `error` is set when the value asks for more than the file holds.
std::size_t exr_value_end(const std::string& head, std::string_view type, std::size_t value_at, std::uint32_t size,
                          std::uint64_t file_size, std::string& error) {
    const std::uint64_t left = file_size - std::min<std::uint64_t>(file_size, value_at);
    if (type == "chlist") {  // channels until an empty name, each a name and 16 bytes: not `size`
        std::size_t at = value_at;
        while (at < head.size() && head[at] != '\0') {
            const std::size_t end = head.find('\0', at);
            if (end == std::string::npos) return std::string::npos;
            at = end + 17;
        }
        return at < head.size() ? at + 1 : std::string::npos;
    }
    if (type == "preview") {  // width, height, then 4 bytes a pixel, allocated before they are read
        if (value_at + 8 > head.size()) return std::string::npos;
        const std::uint64_t w = read_u32(head, value_at), h = read_u32(head, value_at + 4);
        const std::uint64_t room = (left - std::min<std::uint64_t>(left, 8)) / 4;  // pixels the file can hold
        if (w != 0 && h > room / w) {
            error = fmt::format("is a preview image of {} x {} pixels, more than the {} bytes left in the file hold", w, h, left);
            return std::string::npos;
        }
        return static_cast<std::size_t>(value_at + 8 + 4 * w * h);
    }
    if (const std::uint64_t fixed = exr_fixed_size(type)) return static_cast<std::size_t>(value_at + fixed);
    if (size > left) {  // strings, vectors and types OpenEXR does not know: `size` bytes, allocated first
        error = fmt::format("claims {} bytes, more than the {} bytes left in the file", size, left);
        return std::string::npos;
    }
    return static_cast<std::size_t>(value_at + size);
}

// An OpenEXR file's header attributes, checked before OpenEXR reads them: OpenEXR 3.1 allocates
// whatever size an attribute declares (found by fuzz_image: a 1.4 KB file asked for 1.9 GB).
// Each attribute is a name, a type name (both NUL-terminated) and a 4-byte little-endian size,
// then the value. The walk follows OpenEXR's own reading, which does not always skip `size`
// bytes (a channel list ends at its empty name; an int is 4 bytes whatever it declares), so an
// attribute hidden where a lying size would have skipped is seen too (found by fuzz_image's
// hour). A value that asks for more than the file holds is refused at its byte offset. Files that
// are not EXR (by their magic number) are left alone; only the first megabyte is looked at.
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
        const std::string_view type(head.data() + name_end + 1, type_end - name_end - 1);
        std::string error;
        const std::size_t name_at = at;
        at = exr_value_end(head, type, type_end + 5, read_u32(head, type_end + 1), file_size, error);
        if (!error.empty()) {
            std::string name = head.substr(name_at, std::min<std::size_t>(name_end - name_at, 64));
            for (char& ch : name) ch = ch >= ' ' && ch <= '~' ? ch : '?';  // a fuzzed name's bytes, printable
            return fmt::format("byte {}: OpenEXR header attribute '{}' {}", type_end + 1, name, error);
        }
        if (at == std::string::npos) return {};
    }
}

}  // namespace

std::string image_admission_error(const fs::path& path, long long width, long long height, long long max_pixels,
                                  int bytes_per_pixel, double pixels_per_byte) {
    if (width <= 0 || height <= 0 || static_cast<double>(width) * static_cast<double>(height) > static_cast<double>(max_pixels)) {
        const double pixels = std::min(9.0e18, std::max(0.0, static_cast<double>(width) * static_cast<double>(height)));
        return fmt::format("image '{}' is {} x {} pixels: {}", path.string(), width, height,
                           width <= 0 || height <= 0 ? std::string("an empty image")
                                                     : over_limit(Limit::kTexturePixels, static_cast<long long>(pixels), max_pixels));
    }
    std::error_code ec;
    const auto file_size = fs::file_size(path, ec);
    if (pixels_per_byte > 0 && !ec &&
        static_cast<double>(width) * static_cast<double>(height) > pixels_per_byte * static_cast<double>(file_size) + 4096)
        return fmt::format("image '{}': its header claims {} x {} pixels, more than its {} bytes can hold", path.string(),
                           width, height, file_size);
    return charge_memory(width * height * bytes_per_pixel, "image '" + path.string() + "'");
}

void admit_image(const fs::path& path, long long width, long long height, long long max_pixels, int bytes_per_pixel,
                 double pixels_per_byte) {
    if (std::string e = image_admission_error(path, width, height, max_pixels, bytes_per_pixel, pixels_per_byte); !e.empty())
        throw IoError(std::move(e));
}

RawImage read_oiio(const fs::path& path, long long max_pixels) {
    const OiioModule* oiio = nullptr;
    try {
        oiio = reinterpret_cast<const OiioModule* (*)()>(module_entry("oiio"))();
    } catch (const IoError& e) {
        throw IoError(fmt::format("cannot read image '{}': {}", path.string(), e.what()));
    }
    if (oiio->abi != kOiioModuleAbi) throw IoError("glint's module libglint_oiio.so is from another build of glint");
    char error[1024] = "";
    OiioImageSpec spec;
    void* image = oiio->open(path.c_str(), &spec, error, sizeof error);
    if (!image) throw IoError(fmt::format("cannot read image '{}': {}", path.string(), error));
    struct Closer {
        const OiioModule* m;
        void* image;
        ~Closer() { m->close(image); }
    } closer{oiio, image};
    admit_image(path, spec.width, spec.height, max_pixels, 4 * std::max(spec.channels, 3) * 2, kAnyPixelsPerByte);
    if (spec.channels <= 0) throw IoError(fmt::format("cannot read image '{}': it has no channels", path.string()));
    RawImage raw;
    raw.width = spec.width;
    raw.height = spec.height;
    raw.channels = spec.channels;
    raw.is_float = spec.is_float;
    raw.data.resize(static_cast<std::size_t>(spec.width) * static_cast<std::size_t>(spec.height) *
                    static_cast<std::size_t>(spec.channels));
    if (!oiio->read(image, raw.data.data(), error, sizeof error))
        throw IoError(fmt::format("cannot read image '{}': {}", path.string(), error));
    return raw;
}

// The format a file's first bytes show, among those glint reads itself ("" if none).
const char* format_by_content(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    char b[8] = {};
    in.read(b, sizeof b);
    const std::string_view h(b, static_cast<std::size_t>(std::max<std::streamsize>(0, in.gcount())));
    if (h.rfind("\x89PNG\r\n\x1a\n", 0) == 0) return "PNG";
    if (h.rfind("\x76\x2f\x31\x01", 0) == 0) return "OpenEXR";
    if (h.rfind("\xff\xd8\xff", 0) == 0) return "JPEG";
    if (h.rfind("#?", 0) == 0) return "Radiance HDR";
    if (h.rfind("PF", 0) == 0 || h.rfind("Pf", 0) == 0) return "PFM";
    return "";
}

ExrChannels read_exr_channels(const fs::path& path, const std::vector<std::string>& wanted, long long max_pixels) {
    if (std::error_code ec; !fs::is_regular_file(path, ec))
        throw IoError(fmt::format("cannot read image '{}': not found", path.string()));
    if (const std::string why = exr_header_error(path); !why.empty())
        throw IoError(fmt::format("cannot read image '{}': {}", path.string(), why));
    return read_exr_planes(path, wanted, max_pixels);
}

Image read_image(const fs::path& path, ImageEncoding encoding, long long max_pixels) {
    if (max_pixels <= 0) max_pixels = limit(Limit::kTexturePixels);
    if (const std::string why = why_not_readable(path); !why.empty())
        throw IoError(fmt::format("cannot read image '{}': it {}", path.string(), why));
    const std::string ext = lower_extension(path);
    {
        // A file whose contents are another format than its extension names (a PNG saved as
        // .exr) is refused in glint's words, before a library reports it in its own.
        const char* named = ext == ".png" ? "PNG" : ext == ".exr" ? "OpenEXR" : ext == ".pfm" ? "PFM"
                            : ext == ".hdr" || ext == ".rgbe" || ext == ".pic"               ? "Radiance HDR"
                            : ext == ".jpg" || ext == ".jpeg" || ext == ".jpe"               ? "JPEG"
                                                                                             : "";
        const char* actual = format_by_content(path);
        if (*named && *actual && std::string_view(named) != actual)
            throw IoError(fmt::format("cannot read image '{}': it is a {} file, not {} as its extension says", path.string(),
                                      actual, named));
    }
    if (const std::string why = exr_header_error(path); !why.empty())
        throw IoError(fmt::format("cannot read image '{}': {}", path.string(), why));
    RawImage raw;
    if (ext == ".pfm") {
        raw = read_pfm(path, max_pixels);
    } else if (ext == ".png") {
        raw = read_png(path, max_pixels);
    } else if (ext == ".exr") {
        raw = read_exr(path, max_pixels);
    } else if (ext == ".hdr" || ext == ".rgbe" || ext == ".pic") {
        raw = read_hdr(path, max_pixels);
    } else if (ext == ".ppm" || ext == ".pgm" || ext == ".pnm") {
        raw = read_pnm(path, max_pixels);
    } else if (ext == ".jpg" || ext == ".jpeg" || ext == ".jpe") {
        if (!read_jpeg(path, max_pixels, raw)) raw = read_oiio(path, max_pixels);  // CMYK
    } else {
        raw = read_oiio(path, max_pixels);
    }
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

void check_writable(const fs::path& path, int width, int height) {
    if (image_format_for(path) == ImageFormat::kJpeg && std::max(width, height) > 65500)
        throw IoError(fmt::format("{}: JPEG holds at most 65500 x 65500 pixels; the image is {} x {} (write .png or .exr)",
                                  path.string(), width, height));
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

namespace {

std::vector<std::uint8_t> ppm_header(int width, int height) {
    const std::string header = fmt::format("P6\n{} {}\n255\n", width, height);
    return {header.begin(), header.end()};
}

std::vector<std::uint8_t> jpeg_bytes(const fs::path& path, const std::uint8_t* rgb, int w, int h,
                                     const ImageMetadata& metadata) {
    try {
        return encode_jpeg(rgb, w, h, metadata);
    } catch (const IoError& e) {
        throw IoError(fmt::format("{}: cannot write the image: {}", path.string(), e.what()));
    }
}

}  // namespace

void write_image(const fs::path& path, const Film& film, const DisplaySettings& display,
                 const ImageMetadata& metadata) {
    const ImageFormat format = image_format_for(path);
    const int w = film.width(), h = film.height();
    const fs::path tmp = temporary_path(path);
    const auto n = static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
    if (format == ImageFormat::kExr) {
        // R, G, B, then with AOVs: albedo.R/G/B, N.X/Y/Z and Z (depth), OpenEXR's names, the
        // half images even.R/G/B and odd.R/G/B and the albedo's, albedo.even.R/G/B and
        // albedo.odd.R/G/B; the image before denoising noisy.R/G/B; then the sample counts.
        const bool counts = film.has_sample_counts(), noisy = film.has_noisy();
        std::vector<std::string> names = {"R", "G", "B"};
        if (film.has_aovs())
            names.insert(names.end(), {"albedo.R", "albedo.G", "albedo.B", "N.X", "N.Y", "N.Z", "Z", "even.R", "even.G",
                                       "even.B", "odd.R", "odd.G", "odd.B", "albedo.even.R", "albedo.even.G",
                                       "albedo.even.B", "albedo.odd.R", "albedo.odd.G", "albedo.odd.B"});
        if (noisy) names.insert(names.end(), {"noisy.R", "noisy.G", "noisy.B"});
        if (counts) names.emplace_back("spp");
        const std::size_t stride = names.size();
        std::vector<float> floats(n * stride);
        tbb::parallel_for(std::size_t{0}, n, [&](std::size_t i) {
            float* px = &floats[i * stride];
            const Color c = film.pixels()[i];
            px[0] = c.r, px[1] = c.g, px[2] = c.b;
            if (film.has_aovs()) {
                const Color a = film.albedo()[i];
                const Normal3 nn = film.normal()[i];
                px[3] = a.r, px[4] = a.g, px[5] = a.b;
                px[6] = nn.x, px[7] = nn.y, px[8] = nn.z;
                px[9] = film.depth()[i];
                const Color e = film.even()[i], o = film.odd()[i];
                px[10] = e.r, px[11] = e.g, px[12] = e.b;
                px[13] = o.r, px[14] = o.g, px[15] = o.b;
                const Color ae = film.even_albedo()[i], ao = film.odd_albedo()[i];
                px[16] = ae.r, px[17] = ae.g, px[18] = ae.b;
                px[19] = ao.r, px[20] = ao.g, px[21] = ao.b;
            }
            if (noisy) {
                const Color c0 = film.noisy()[i];
                float* q = px + (film.has_aovs() ? 22 : 3);
                q[0] = c0.r, q[1] = c0.g, q[2] = c0.b;
            }
            if (counts) px[stride - 1] = film.sample_counts()[i];
        });
        try {
            write_exr(tmp, w, h, names, floats.data(), metadata);
        } catch (const IoError& e) {
            std::error_code ec;
            fs::remove(tmp, ec);
            throw IoError(fmt::format("{}: cannot write the image: {}", path.string(), e.what()));
        }
        move_into_place(path, "the image");
        return;
    }
    if (format == ImageFormat::kHdr || format == ImageFormat::kPfm) {
        static_assert(sizeof(Color) == 3 * sizeof(float));
        const float* rgb = n == 0 ? nullptr : &film.pixels()[0].r;
        write_temporary(path, format == ImageFormat::kHdr ? encode_hdr(rgb, w, h, metadata) : encode_pfm(rgb, w, h), "the image");
        move_into_place(path, "the image");
        return;
    }
    const auto row_bytes = [&](int y, std::uint8_t* out) {
        const Color* px = &film.pixels()[static_cast<std::size_t>(y) * static_cast<std::size_t>(w)];
        static_assert(sizeof(Color) == 3 * sizeof(float));
        encode_8bit(&px->r, static_cast<std::size_t>(w) * 3, out, display);
    };
    if (format == ImageFormat::kPng) {
        write_temporary(path, encode_png(row_bytes, w, h, display.encoding == Encoding::kSrgb, metadata), "the image");
    } else if (format == ImageFormat::kJpeg) {
        std::vector<std::uint8_t> rgb(n * 3);
        tbb::parallel_for(0, h, [&](int y) { row_bytes(y, &rgb[static_cast<std::size_t>(y) * static_cast<std::size_t>(w) * 3]); });
        write_temporary(path, jpeg_bytes(path, rgb.data(), w, h, metadata), "the image");
    } else {  // binary PPM: no place for metadata
        std::vector<std::uint8_t> bytes = ppm_header(w, h);
        const std::size_t header = bytes.size();
        bytes.resize(header + n * 3);
        tbb::parallel_for(0, h, [&](int y) { row_bytes(y, &bytes[header + static_cast<std::size_t>(y) * static_cast<std::size_t>(w) * 3]); });
        write_temporary(path, bytes, "the image");
    }
    move_into_place(path, "the image");
}

struct Image8Writer::Impl {
    fs::path path;
    int width, height;
    bool srgb;
    ImageFormat format;
    BigBuffer<std::uint8_t> rgb;
    std::optional<PngStrips> png;
    Impl(fs::path p, int w, int h, bool s, ImageFormat f)
        : path(std::move(p)), width(w), height(h), srgb(s), format(f),
          rgb(static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 3) {}
};

Image8Writer::Image8Writer(fs::path path, int width, int height, bool srgb) {
    const ImageFormat format = image_format_for(path);
    if (is_linear_format(format))
        throw IoError(fmt::format("{}: a linear image (EXR, HDR, PFM) is written from the film, not from 8-bit codes",
                                  path.string()));
    impl_ = std::make_unique<Impl>(std::move(path), width, height, srgb, format);
    if (format == ImageFormat::kPng) {
        const std::uint8_t* rgb = impl_->rgb.data();
        const std::size_t row = static_cast<std::size_t>(width) * 3;
        impl_->png.emplace([rgb, row](int y, std::uint8_t* out) { std::memcpy(out, rgb + static_cast<std::size_t>(y) * row, row); },
                           width, height);
    }
}

Image8Writer::~Image8Writer() = default;

std::uint8_t* Image8Writer::rgb() { return impl_->rgb.data(); }

void Image8Writer::rows_ready(int y0, int y1) {
    if (impl_->png) impl_->png->rows_ready(y0, y1);
}

void Image8Writer::finish(const ImageMetadata& metadata) {
    const Impl& m = *impl_;
    if (impl_->png) {
        write_temporary(m.path, impl_->png->finish(m.srgb, metadata), "the image");
    } else if (m.format == ImageFormat::kJpeg) {
        write_temporary(m.path, jpeg_bytes(m.path, m.rgb.data(), m.width, m.height, metadata), "the image");
    } else {  // binary PPM: no place for metadata
        std::vector<std::uint8_t> bytes = ppm_header(m.width, m.height);
        bytes.insert(bytes.end(), m.rgb.data(), m.rgb.data() + m.rgb.size());
        write_temporary(m.path, bytes, "the image");
    }
    move_into_place(m.path, "the image");
}

}  // namespace glint
