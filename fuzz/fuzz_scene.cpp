// The YAML scene reader, from text through to the built scene (meshes, textures and media it
// names are looked for in the scratch folder only). The film is overridden small: the size
// limits themselves are the subject of tests, and the fuzzer looks for what the text can do.
#include "fuzz_common.h"
#include "glint/io/build.h"
#include "glint/io/scene_yaml.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace glint;
    const std::string path = (fuzz::scratch() / "scene.yaml").string();
    fuzz::expect_located_errors([&] {
        auto sources = std::make_shared<SourceFiles>();
        const SceneDescription d = parse_scene(std::string(fuzz::as_text(data, size)), path, sources);
        Overrides o;
        o.width = 8;
        o.height = 8;
        o.threads = 1;
        build(d, o, sources);
    });
    return 0;
}
