// OBJ + MTL: the input is an OBJ text, optionally followed by "\n#MTL\n" and the text of the
// material library it may name as `mtllib m.mtl`.
#include "fuzz_common.h"
#include "glint/assets/mesh_import.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace glint;
    const std::string_view all = fuzz::as_text(data, size);
    const std::size_t split = all.find("\n#MTL\n");
    fuzz::put("m.mtl", split == std::string_view::npos ? std::string_view{} : all.substr(split + 6));
    const std::string obj(all.substr(0, split));
    fuzz::expect_located_errors([&] { parse_obj(obj, "fuzz.obj", fuzz::scratch()); });
    return 0;
}
