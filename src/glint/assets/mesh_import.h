#pragma once
// Mesh files: PLY (a reader of our own), OBJ + MTL (tinyobjloader). Each importer returns meshes
// in their own space with materials numbered locally; build() turns them into scene materials
// and instances. Bad input throws IoError whose message starts with the file name (and, for
// text formats, the line): "bunny.ply:12: ...".
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "glint/image/image_io.h"
#include "glint/description/scene_description.h"
#include "glint/lights/light.h"
#include "glint/math/transform.h"
#include "glint/shapes/mesh.h"

namespace glint {

struct ImportedMaterial {
    std::string name;
    MaterialDesc desc;  ///< texture file names are absolute or relative to the mesh file's folder
    std::optional<AlphaDesc> alpha;  ///< glTF alphaMode MASK or BLEND: a cut-out on its meshes
};

/// One placement of a mesh (glTF nodes; OBJ and PLY have one per mesh, untransformed).
struct ImportedNode {
    std::uint32_t mesh = 0;
    Transform transform;
};

/// A camera found in a file (glTF), in glint's frame.
struct GltfCamera {
    std::string name;
    Point3 position;
    Vector3 direction, up;
    float yfov_degrees = 40;  ///< perspective
    bool orthographic = false;
    float ymag = 1;  ///< orthographic: half the visible height (the width follows the film)
};

struct ImportedFile {
    /// mesh.material / face_materials index `materials`; kNoImportedMaterial: the scene's default.
    std::vector<TriangleMesh> meshes;
    std::vector<ImportedMaterial> materials;
    std::vector<ImportedNode> nodes;
    /// glTF, when motion times are asked: per node, its placement at each of them (the frame's
    /// where it is singular then); empty otherwise.
    std::vector<std::vector<Transform>> node_motion;
    std::size_t dropped_triangles = 0;  ///< degenerate or non-finite, left out
    std::vector<std::string> notes;     ///< things a user should hear about (missing textures, ...)
    std::vector<Light> lights;          ///< glTF KHR_lights_punctual, placed by their nodes
    std::optional<GltfCamera> camera;   ///< glTF: the first camera, or the one named
    std::vector<GltfCamera> cameras;    ///< glTF: every camera of the scene, in node order
};

inline constexpr MaterialId kNoImportedMaterial = 0xffffffffu;

enum class MeshFormat { kPly, kObj, kGltf, kGlb };
/// The format a file's extension names (any case), if it is a mesh format; for a file without
/// one of these extensions, the format its first bytes show (binary glTF, PLY), if any.
std::optional<MeshFormat> mesh_format(const std::filesystem::path& path);

/// By extension: .ply, .obj, .gltf, .glb. `time`: seconds into a glTF file's animation.
ImportedFile import_mesh_file(const std::filesystem::path& path, double time = 0, const std::vector<double>& motion_times = {});
/// `camera`: the name of the camera to use (empty: the first one met in the node hierarchy).
/// `time`: the nodes are placed as the file's first animation has them at this many seconds.
/// `motion_times`: seconds at which nodes' placements are also wanted (motion blur; node_motion).
ImportedFile import_gltf(const std::filesystem::path& path, const std::string& camera = "", double time = 0,
                         const std::vector<double>& motion_times = {});
ImportedFile import_ply(const std::filesystem::path& path);
ImportedFile import_obj(const std::filesystem::path& path);

/// Whether one mesh of `vertices` and `triangles` may be read: the vertices and triangles limits,
/// then its share of the memory budget (vertex attributes, indices, the acceleration structure),
/// charged here. Returns the error text, or empty.
std::string mesh_size_error(long long vertices, long long triangles);

/// The PLY reader on bytes already in memory (`name` is used in messages); for tests and fuzzing.
ImportedFile parse_ply(const std::string& bytes, const std::string& name);
/// The OBJ reader on text already in memory; `mtllib` files and texture maps are looked for in `dir`.
ImportedFile parse_obj(const std::string& text, const std::string& name, const std::filesystem::path& dir);

}  // namespace glint
