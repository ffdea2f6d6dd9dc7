// PLY in its three encodings (ascii, binary little- and big-endian), from memory.
#include "fuzz_common.h"
#include "glint/assets/mesh_import.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace glint;
    const std::string bytes(fuzz::as_text(data, size));
    fuzz::expect_located_errors([&] { parse_ply(bytes, "fuzz.ply"); });
    return 0;
}
