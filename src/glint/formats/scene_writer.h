#pragma once
// A SceneDescription written back as a glint YAML scene (docs/scene-format.md): what
// `glint convert scene.pbrt -o scene.yaml` does, so that users can move a pbrt scene over.
// Meshes are referenced, not inlined: meshes given in the source file itself (pbrt's
// trianglemesh, loopsubdiv, ...) are written as binary PLY files beside the YAML file; mesh and
// image files the source names are referenced by paths that resolve from the YAML file's folder.
#include <filesystem>
#include <string>
#include <vector>

#include "glint/description/scene_description.h"

namespace glint {

struct WrittenScene {
    std::string yaml;
    std::vector<std::filesystem::path> meshes;  ///< the files written beside it: PLY meshes, VDB grids
};

/// Writes the YAML text for `d` (to be saved as `out`) and the PLY files of its inline meshes,
/// named `<out's stem>-mesh-<n>.ply` in out's folder. Throws IoError when a file cannot be
/// written, or for what glint's YAML cannot express (a grid medium's file is kept as given).
WrittenScene write_scene_yaml(const SceneDescription& d, const std::filesystem::path& out);

/// A triangle mesh as binary little-endian PLY (positions, normals and uvs when present).
void write_ply(const std::filesystem::path& path, const TriangleMesh& mesh);

}  // namespace glint
