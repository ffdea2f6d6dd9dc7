// The pbrt-v4 reader, from text through to the built scene (Include and mesh files are looked for
// in the scratch folder only).
#include "fuzz_common.h"
#include "glint/io/build.h"
#include "glint/io/pbrt.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace glint;
    const std::string path = (fuzz::scratch() / "scene.pbrt").string();
    fuzz::expect_located_errors([&] {
        auto sources = std::make_shared<SourceFiles>();
        const SceneDescription d = parse_pbrt(std::string(fuzz::as_text(data, size)), path, sources);
        Overrides o;
        o.width = 8;
        o.height = 8;
        o.threads = 1;
        build(d, o, sources);
    });
    return 0;
}
