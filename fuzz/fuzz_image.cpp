// The image readers textures and environment maps go through. The first byte picks the file's
// extension (the readers choose by it), the rest is the file.
#include "fuzz_common.h"
#include "glint/base/module.h"

// OpenImageIO's module (and its ~260 libraries) loads on the first TGA or TIFF: seconds under
// ASan on a busy machine, counted against that input's 10 s limit; and when the limit fired during
// the load, libFuzzer's alarm handler deadlocked in ASan's allocator (the image target's hour
// stalled on it). Loaded once before fuzzing instead.
extern "C" int LLVMFuzzerInitialize(int*, char***) {
    try {
        glint::module_entry("oiio");
    } catch (...) {  // without the module, TGA and TIFF inputs get their located error
    }
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace glint;
    static constexpr const char* kExtensions[] = {".png", ".exr", ".hdr", ".pfm", ".jpg", ".tga", ".ppm", ".tif"};
    if (size < 1) return 0;
    const char* ext = kExtensions[data[0] % std::size(kExtensions)];
    const auto path = fuzz::put(std::string("fuzz") + ext, fuzz::as_text(data + 1, size - 1));
    // 4M pixels at most (48 MB as float RGB), the limit a scene can set for itself.
    fuzz::expect_located_errors([&] { read_image(path, ImageEncoding::kAuto, 1 << 22); });
    return 0;
}
