#pragma once
// The OpenImageIO module's interface (libglint_oiio.so, loaded by module.h only when a texture
// is in a format glint does not read itself: TGA, TIFF, BMP, GIF, WebP, ...). Plain C types, so
// that nothing of OpenImageIO (or its ~260 libraries) reaches a process that does not need it.
#include <cstddef>

namespace glint {

inline constexpr int kOiioModuleAbi = 1;

struct OiioImageSpec {
    int width = 0, height = 0, channels = 0;
    bool is_float = false;
};

struct OiioModule {
    int abi;
    /// Opens `path` and fills `spec` from its header; nullptr and a message in `error` otherwise.
    void* (*open)(const char* path, OiioImageSpec* spec, char* error, std::size_t error_size);
    /// Reads every pixel as floats, spec.channels per pixel, top row first; false and a message
    /// in `error` otherwise.
    bool (*read)(void* image, float* pixels, char* error, std::size_t error_size);
    void (*close)(void* image);
};

}  // namespace glint

/// The module's one export.
extern "C" const glint::OiioModule* glint_oiio_module();
