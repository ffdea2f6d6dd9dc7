// The image readers textures and environment maps go through. The first byte picks the file's
// extension (the readers choose by it), the rest is the file.
#include "fuzz_common.h"

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
