// A scene reader from text through to the built scene: the YAML reader (fuzz_scene), or the
// pbrt-v4 reader when built with GLINT_FUZZ_PBRT (fuzz_pbrt). Meshes, textures, media and
// included files it names are looked for in the scratch folder only. The film is overridden
// small: the size limits themselves are the subject of tests, and the fuzzer looks for what the
// text can do.
#include "fuzz_common.h"
#include "glint/builder/build.h"
#include "glint/session/formats.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace glint;
#ifdef GLINT_FUZZ_PBRT
    const std::string path = (fuzz::scratch() / "scene.pbrt").string();
    const ReadOptions options;
#else
    const std::string path = (fuzz::scratch() / "scene.yaml").string();
    // A frame between whole numbers, so keyframed values are interpolated, not just looked up.
    const ReadOptions options{false, 1.5, ""};
#endif
    // The reader the format table picks for the file's name, as glint render would.
    const auto parse = [&](const std::string& text, const std::string& p, std::shared_ptr<SourceFiles> s) {
        return scene_file_format(p).parse(text, p, std::move(s), options);
    };
    fuzz::expect_located_errors([&] {
        auto sources = std::make_shared<SourceFiles>();
        const SceneDescription d = parse(std::string(fuzz::as_text(data, size)), path, sources);
        Overrides o;
        o.width = 8;
        o.height = 8;
        o.threads = 1;
        build(d, o, sources);
    });
    return 0;
}
