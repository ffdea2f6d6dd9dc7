// glTF: a binary .glb when the input starts with its magic "glTF", a .gltf (JSON) otherwise.
// External buffers and images resolve in the scratch folder only.
#include "fuzz_common.h"
#include "glint/assets/mesh_import.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace glint;
    const std::string_view bytes = fuzz::as_text(data, size);
    const bool glb = bytes.substr(0, 4) == "glTF";
    const auto path = fuzz::put(glb ? "fuzz.glb" : "fuzz.gltf", bytes);
    fuzz::expect_located_errors([&] { import_gltf(path); });
    return 0;
}
