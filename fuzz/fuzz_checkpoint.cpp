// The checkpoint reader (glint's own binary format: header, planes, checksum). The harness signs
// every input as the writer does (the last 8 bytes: the checksum of the rest), so that mutations
// reach the planes and what is read from them; unsigned, nearly every mutation stopped at the
// checksum (the idle hour of 2026-11-27: 609 edges, 19 inputs in the corpus, flat after a minute).
// A damaged checksum is the unit tests' case (session/checkpoint_test.cpp).
#include <cstring>
#include <string>

#include "fuzz_common.h"
#include "glint/session/checkpoint.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace glint;
    std::string bytes(fuzz::as_text(data, size));
    if (bytes.size() >= 8) {
        const std::uint64_t sum = hash_bytes(bytes.data(), bytes.size() - 8);
        std::memcpy(bytes.data() + bytes.size() - 8, &sum, 8);
    }
    const auto path = fuzz::put("fuzz.ckpt", bytes);
    fuzz::expect_located_errors([&] { read_checkpoint(path); });
    return 0;
}
