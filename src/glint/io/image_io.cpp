#include "glint/io/image_io.h"

#include "glint/io/limits.h"

#include <unistd.h>

#include <OpenImageIO/imageio.h>
#include <fmt/core.h>

#include <algorithm>
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

Image read_image(const fs::path& path, ImageEncoding encoding, long long max_pixels) {
    auto in = OIIO::ImageInput::open(path.string());
    if (!in) {
        std::string why = OIIO::geterror();
        if (why.empty()) why = "cannot open it";
        throw IoError(fmt::format("cannot read image '{}': {}", path.string(), why));
    }
    const OIIO::ImageSpec& spec = in->spec();
    const long long pixels = static_cast<long long>(spec.width) * spec.height;
    if (spec.width <= 0 || spec.height <= 0 || pixels > max_pixels) {
        throw IoError(fmt::format("image '{}' is {} x {} pixels; the limit is {} pixels",
                                  path.string(), spec.width, spec.height, max_pixels));
    }
    const int channels = spec.nchannels;
    std::vector<float> data(static_cast<std::size_t>(pixels) * static_cast<std::size_t>(channels));
    if (!in->read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, data.data())) {
        throw IoError(fmt::format("cannot read image '{}': {}", path.string(), in->geterror()));
    }
    const bool is_float = spec.format.basetype == OIIO::TypeDesc::FLOAT ||
                          spec.format.basetype == OIIO::TypeDesc::HALF ||
                          spec.format.basetype == OIIO::TypeDesc::DOUBLE;
    const bool decode = encoding == ImageEncoding::kSrgb ||
                        (encoding == ImageEncoding::kAuto && !is_float);
    Image image;
    image.width = spec.width;
    image.height = spec.height;
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

void write_image(const fs::path& path, const Film& film, const DisplaySettings& display) {
    const ImageFormat format = image_format_for(path);
    const int w = film.width(), h = film.height();
    const fs::path dir = path.parent_path().empty() ? fs::path(".") : path.parent_path();
    const fs::path tmp =
        dir / fmt::format(".{}.glint-{}.tmp", path.filename().string(), ::getpid());

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
        // R, G, B, then with AOVs: albedo.R/G/B, N.X/Y/Z and Z (depth), OpenEXR's names.
        const int channels = film.has_aovs() ? 10 : 3;
        OIIO::ImageSpec spec(w, h, channels, OIIO::TypeDesc::FLOAT);
        spec.attribute("compression", "zip");
        if (film.has_aovs()) {
            spec.channelnames = {"R",   "G",   "B",   "albedo.R", "albedo.G",
                                 "albedo.B", "N.X", "N.Y", "N.Z", "Z"};
            spec.z_channel = 9;
        }
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
        }
        ok = out->open(tmp.string(), spec) &&
             out->write_image(OIIO::TypeDesc::FLOAT, floats.data());
    } else {
        OIIO::ImageSpec spec(w, h, 3, OIIO::TypeDesc::UINT8);
        spec.attribute("oiio:ColorSpace", display.encoding == Encoding::kSrgb ? "sRGB" : "Linear");
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
