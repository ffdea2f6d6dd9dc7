#pragma once
// Every file format glint reads as a scene, in one table: the scene files (glint's YAML and
// JSON, pbrt-v4) and the mesh files rendered directly (PLY, OBJ, glTF). `glint render`, `info`,
// `convert`, `--list-formats`, the Python-facing session and the fuzzers all pick a reader here,
// by the file's extension, and by its first bytes when the extension is not one of the table's.
// Adding a format: docs/architecture.md, "Adding a scene or mesh file format".
#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "glint/base/diagnostics.h"
#include "glint/description/scene_description.h"

namespace glint {

struct ReadOptions {
    bool strict = false;  ///< pbrt: what glint cannot render is an error, not a warning
    double frame = 0;     ///< the animation frame whose keyframed values are read
    std::string camera;   ///< glTF rendered directly: the camera by name ("": the first)
};

struct SceneFileFormat {
    std::string_view name;                     ///< "yaml", "pbrt", "gltf", ...
    std::vector<std::string_view> extensions;  ///< lower case, with the dot; ".ply.gz" is one
    std::string_view description;
    bool mesh = false;       ///< a mesh file: rendered under a sky, framed by its bounds (or its camera)
    bool convert = false;    ///< `glint convert` reads it
    bool animated = false;   ///< keyframes or an animation are read at ReadOptions::frame
    /// Text to description (scene files; null for meshes, which the builder imports).
    SceneDescription (*parse)(const std::string& text, const std::string& path, std::shared_ptr<SourceFiles> sources,
                              const ReadOptions& options) = nullptr;
};

/// Every format, in the order `glint render --list-formats` prints them.
std::span<const SceneFileFormat> scene_file_formats();

/// The format of `path`: by extension (any case); otherwise by content (a binary glTF's or a
/// PLY's signature); otherwise glint's YAML reader, which says what is wrong with the text.
const SceneFileFormat& scene_file_format(const std::filesystem::path& path);

/// Reads a scene file or a mesh file as a description (a mesh becomes the scene that renders
/// it: the mesh under a sky, path traced; its camera is placed after building, by
/// place_mesh_camera). `sources` receives every file's text, for diagnostics.
SceneDescription read_scene_file(const std::string& path, std::shared_ptr<SourceFiles> sources,
                                 const ReadOptions& options = {});

}  // namespace glint
