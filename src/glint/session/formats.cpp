#include "glint/session/formats.h"

#include <algorithm>
#include <array>
#include <cctype>

#include "glint/assets/mesh_import.h"
#include "glint/formats/pbrt.h"
#include "glint/formats/scene_yaml.h"

namespace glint {

namespace {

SceneDescription parse_yaml(const std::string& text, const std::string& path, std::shared_ptr<SourceFiles> sources,
                            const ReadOptions& options) {
    return parse_scene_over_shutter(text, path, std::move(sources), options.frame);
}

SceneDescription parse_pbrt_file(const std::string& text, const std::string& path,
                                 std::shared_ptr<SourceFiles> sources, const ReadOptions& options) {
    SceneDescription d = parse_pbrt(text, path, std::move(sources), {options.strict});
    d.frame = options.frame;
    return d;
}

const std::array kFormats{
    SceneFileFormat{"yaml", {".yaml", ".yml"}, "glint's scene format (docs/scene-format.md)", false, true, true, parse_yaml},
    SceneFileFormat{"json", {".json"}, "glint's scene format written as JSON", false, true, true, parse_yaml},
    SceneFileFormat{"pbrt", {".pbrt"}, "pbrt-v4 scene (docs/pbrt.md)", false, true, false, parse_pbrt_file},
    SceneFileFormat{"gltf", {".gltf"}, "glTF 2.0, JSON with its buffers and images beside it", true, false, true, nullptr},
    SceneFileFormat{"glb", {".glb"}, "glTF 2.0, binary", true, false, true, nullptr},
    SceneFileFormat{"obj", {".obj"}, "Wavefront OBJ with its MTL materials", true, false, false, nullptr},
    SceneFileFormat{"ply", {".ply", ".ply.gz"}, "Stanford PLY, ASCII or binary, or gzip-compressed", true, false, false,
                    nullptr},
};

std::string lower(std::string s) {
    for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

const SceneFileFormat& named(std::string_view name) {
    return *std::find_if(kFormats.begin(), kFormats.end(), [&](const SceneFileFormat& f) { return f.name == name; });
}

// A mesh file rendered directly: the mesh under a sky, path traced; the camera is placed after
// building (place_mesh_camera).
SceneDescription mesh_file_scene(const std::string& path, const std::string& camera) {
    SceneDescription d;
    d.path = path;
    d.integrator.kind = IntegratorKind::kPath;
    d.background = SkyBackground{};  // a default environment: the sky lights the model
    d.film.width.value = 800;
    d.film.height.value = 600;
    d.sampler.spp.value = 64;
    ObjectDesc o;
    MeshFileDesc f;
    f.file.value = std::filesystem::path(path).filename().string();
    f.file.loc = {"<command line>", 0, 0};
    f.camera = camera;
    o.shape = f;
    o.material_given = false;
    d.objects.push_back(o);
    return d;
}

}  // namespace

std::span<const SceneFileFormat> scene_file_formats() { return kFormats; }

const SceneFileFormat& scene_file_format(const std::filesystem::path& path) {
    const std::string name = lower(path.filename().string());
    for (const SceneFileFormat& f : kFormats)
        for (std::string_view ext : f.extensions)
            if (name.size() > ext.size() && name.compare(name.size() - ext.size(), ext.size(), ext) == 0) return f;
    if (const auto m = mesh_format(path)) return named(*m == MeshFormat::kGlb ? "glb" : "ply");  // by content
    return named("yaml");
}

SceneDescription read_scene_file(const std::string& path, std::shared_ptr<SourceFiles> sources,
                                 const ReadOptions& options) {
    const SceneFileFormat& format = scene_file_format(path);
    if (format.mesh) return mesh_file_scene(path, options.camera);
    const std::string text = read_scene_text(path, sources);
    return format.parse(text, path, std::move(sources), options);
}

}  // namespace glint
