#pragma once
// Scene files in YAML (yaml-cpp). JSON is accepted too: it is YAML 1.2. The format is documented
// in docs/scene-format.md.
#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "glint/base/diagnostics.h"
#include "glint/description/scene_description.h"

namespace glint {

/// Numbers given beside a scene's text instead of in it (the Python module's numpy arrays,
/// docs/python.md): an inline mesh's `positions`, `indices`, `normals`, `uvs` or `colors`, an
/// image texture's `pixels` or a grid medium's `voxels` whose value is the string "<array N>"
/// reads arrays[N]. The memory stays the caller's; the parser copies it once, into the mesh,
/// image or grid.
struct ArrayView {
    const float* floats = nullptr;         ///< rows x columns floats, row-major; or
    const std::uint32_t* ints = nullptr;   ///< rows x columns indices
    std::size_t rows = 0, columns = 0;
    /// The array's own shape, row-major (rows = shape[0], columns = the product of the rest);
    /// dims 1 to 3. Pixels are (height, width[, channels]), voxels (nz, ny, nx).
    std::array<std::size_t, 3> shape{0, 0, 0};
    int dims = 0;
};
using InlineArrays = std::vector<ArrayView>;

/// Reads and parses a scene file. All errors (syntax, unknown keys, wrong types, out-of-range
/// values) are collected and thrown together as one SceneError; a missing file is a SceneError
/// too. `sources` receives the file text for later diagnostics (build's name resolution).
/// `frame`: the animation frame whose keyframed values are read (docs/scene-format.md, "Animation").
SceneDescription load_scene_file(const std::string& path, std::shared_ptr<SourceFiles> sources, double frame = 0);

/// Parses scene text; `path` names it in messages and resolves nothing else.
SceneDescription parse_scene(const std::string& text, const std::string& path,
                             std::shared_ptr<SourceFiles> sources, double frame = 0,
                             const InlineArrays* arrays = nullptr);

/// parse_scene, with what moves over the camera's shutter (`shutter: [open, close]`, in frames
/// from `frame`) given its motion keys (scene_yaml_motion.cpp; docs/motion.md).
SceneDescription parse_scene_over_shutter(const std::string& text, const std::string& path,
                                          std::shared_ptr<SourceFiles> sources, double frame = 0,
                                          const InlineArrays* arrays = nullptr);

}  // namespace glint
