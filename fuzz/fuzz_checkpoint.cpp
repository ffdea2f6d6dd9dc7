// The checkpoint reader (glint's own binary format: header, planes, checksum).
#include "fuzz_common.h"
#include "glint/session/checkpoint.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace glint;
    const auto path = fuzz::put("fuzz.ckpt", fuzz::as_text(data, size));
    fuzz::expect_located_errors([&] { read_checkpoint(path); });
    return 0;
}
