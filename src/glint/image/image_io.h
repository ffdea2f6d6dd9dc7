#pragma once
// Reading and writing image files (the formats and their libraries: image_formats.h). Writes are
// atomic (base/atomic_file.h): a failed or killed run never leaves a truncated image and never
// clobbers an existing one.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>
#include <string_view>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "glint/film/film.h"
#include "glint/film/tonemap.h"
#include "glint/base/atomic_file.h"
#include "glint/base/errors.h"
#include "glint/base/limits.h"
#include "glint/textures/texture.h"

namespace glint {

enum class ImageFormat { kPng, kExr, kPpm, kJpeg, kHdr, kPfm };

/// EXR, HDR and PFM hold the film's linear values (no exposure, no curve); PNG, JPEG and PPM
/// hold 8-bit codes through the display transform.
constexpr bool is_linear_format(ImageFormat f) {
    return f == ImageFormat::kExr || f == ImageFormat::kHdr || f == ImageFormat::kPfm;
}

/// How the values in an image file map to linear RGB: kAuto treats integer formats (8/16-bit
/// PNG, JPEG, ...) as sRGB-encoded and floating-point ones (EXR, HDR) as linear.
enum class ImageEncoding { kAuto, kSrgb, kLinear };

/// The inverse of the sRGB transfer curve.
float srgb_decode(float v);

/// Reads an image file as linear RGB (grey is replicated, alpha dropped): PNG, EXR, JPEG, HDR,
/// PFM and PPM/PGM by glint's own readers, anything else through the OpenImageIO module.
/// Throws IoError, naming the file, if it cannot be opened or read, or if it has more than
/// `max_pixels` pixels (default: the texture-pixels limit; checked from the header, before
/// reading) or more than the memory budget allows.
Image read_image(const std::filesystem::path& path, ImageEncoding encoding, long long max_pixels = 0);

/// An image format glint writes (and reads with its own readers): one table, which
/// image_format_for and `glint render --list-formats` read.
struct ImageFormatInfo {
    ImageFormat format;
    std::vector<std::string_view> extensions;  ///< lower case, with the dot
    std::string_view description;
};
std::span<const ImageFormatInfo> image_formats();

/// The format for a path's extension (.png, .exr, .ppm, .jpg/.jpeg, .hdr, .pfm;
/// case-insensitive); throws IoError naming the supported ones otherwise.
ImageFormat image_format_for(const std::filesystem::path& path);

/// Checks, before any rendering, that `path` can be written: a known extension, an existing,
/// writable folder, and (when given) a size the format can hold (JPEG: at most 65,500 pixels a
/// side). Throws IoError with the reason.
void check_writable(const std::filesystem::path& path, int width = 0, int height = 0);

/// Name and value pairs written into the image's header (EXR attributes, PNG text chunks):
/// glint writes the spp reached, the render time and the scene.
using ImageMetadata = std::vector<std::pair<std::string, std::string>>;

/// PNG/JPEG/PPM: 8-bit RGB through `display` (exposure, curve, encoding); EXR: the linear values
/// as 32-bit float RGB, unclamped (no exposure, no curve), plus the film's AOVs if it has them as
/// channels albedo.R/G/B, N.X/Y/Z and Z, and its per-pixel sample counts as channel `spp`;
/// HDR (RGBE) and PFM: the linear RGB values alone.
void write_image(const std::filesystem::path& path, const Film& film,
                 const DisplaySettings& display, const ImageMetadata& metadata = {});

/// Named channels of an OpenEXR file (its first part), as float planes of width x height.
struct ExrChannels {
    int width = 0, height = 0;
    std::vector<std::string> names;          ///< every channel the file has
    std::vector<std::vector<float>> planes;  ///< one per name asked for; empty where the file lacks it
};
/// Reads the channels `wanted` of an EXR (checked as read_image checks, against `max_pixels` and the
/// memory budget, before anything is allocated). Throws IoError naming the file.
ExrChannels read_exr_channels(const std::filesystem::path& path, const std::vector<std::string>& wanted,
                              long long max_pixels);

/// A PNG, JPEG or PPM written while it is rendered (render_8bit's output): the renderer fills rgb()
/// (width x height x 3 bytes, rows top first, codes already through the display transform) and
/// announces final rows with rows_ready (from any thread), which encodes each PNG strip on that
/// thread as soon as its rows are in; finish() encodes what is left and writes the file
/// atomically, as write_image. The bytes are write_image's for the same codes. A linear format's
/// path (EXR, HDR, PFM) is an error: it takes the linear film. (JPEG is encoded in finish().)
class Image8Writer {
public:
    Image8Writer(std::filesystem::path path, int width, int height, bool srgb);
    ~Image8Writer();
    Image8Writer(const Image8Writer&) = delete;
    Image8Writer& operator=(const Image8Writer&) = delete;
    std::uint8_t* rgb();
    void rows_ready(int y0, int y1);
    void finish(const ImageMetadata& metadata = {});

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace glint
