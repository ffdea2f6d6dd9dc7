#pragma once
// Writing images through OpenImageIO, atomically: the image goes to a temporary file in the
// destination folder, which is renamed over the destination only once it is complete. A failed
// or killed run never leaves a truncated image and never clobbers an existing one.
#include <filesystem>
#include <stdexcept>
#include <string>

#include "glint/film/film.h"
#include "glint/film/tonemap.h"

namespace glint {

class IoError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

enum class ImageFormat { kPng, kExr, kPpm };

/// The format for a path's extension (.png, .exr, .ppm, case-insensitive); throws IoError
/// naming the supported ones otherwise.
ImageFormat image_format_for(const std::filesystem::path& path);

/// Checks, before any rendering, that `path` can be written: a known extension and an existing,
/// writable folder. Throws IoError with the reason.
void check_writable(const std::filesystem::path& path);

/// PNG/PPM: 8-bit RGB through `display` (exposure, curve, encoding); EXR: the linear values as
/// 32-bit float RGB, unclamped (no exposure, no curve).
void write_image(const std::filesystem::path& path, const Film& film,
                 const DisplaySettings& display);

}  // namespace glint
