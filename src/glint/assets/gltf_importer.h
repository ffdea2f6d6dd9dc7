#pragma once
// The glTF importer's inside, shared by its files (not part of the library's interface): gltf.cpp
// (accessors, meshes, compression, the node tree, the entry point), gltf_materials.cpp (images,
// textures, materials and their extensions), gltf_animation.cpp (animation channels sampled at a
// time). mesh_import.h is the interface; the file's conventions are at the top of gltf.cpp.
#include <tiny_gltf.h>

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "glint/assets/draco_decode.h"
#include "glint/assets/mesh_import.h"
#include "glint/base/json_locate.h"

namespace glint::gltf_detail {

// 2^28 values (2 GB as doubles) per accessor: 89M vertices.
inline constexpr std::size_t kMaxAccessorValues = std::size_t{1} << 28;
// An accessor without a bufferView is zeros (the spec), but for its sparse values: 1M zero
// elements beyond those, far more than any exporter writes, and 24 MB as doubles.
inline constexpr std::size_t kMaxZeroElements = std::size_t{1} << 20;
// TEXCOORD_0 to TEXCOORD_7: more than any exporter writes.
inline constexpr int kMaxUvSets = 8;


struct Importer {
    const tinygltf::Model& model;
    std::string file;
    bool binary = false;  // .glb: errors name the JSON value in words only
    ImportedFile out;
    std::map<std::pair<int, bool>, std::shared_ptr<const Image>> images;  // (image, srgb)
    std::map<int, std::uint32_t> mesh_first;   // glTF mesh -> first of our meshes
    std::map<int, std::uint32_t> mesh_count;

    [[noreturn]] void fail(const std::string& what) const { throw IoError(fmt::format("{}: {}", file, what)); }
    /// An error about the JSON value at `pointer` ("/nodes/3/mesh"): in a .gltf it is reported at
    /// that value's line and column, or its nearest enclosing value's if the file leaves it out
    /// (the text is read again, only now).
    [[noreturn]] void fail_at(std::string pointer, const std::string& what) const {
        if (!binary) {
            std::ifstream in(file, std::ios::binary);
            std::ostringstream text;
            text << in.rdbuf();
            for (;;) {
                if (const auto p = json_locate(text.str(), pointer))
                    throw IoError(fmt::format("{}:{}:{}: {}", file, p->line, p->column, what));
                if (pointer.empty()) break;
                pointer.erase(pointer.rfind('/'));
            }
        }
        fail(what);
    }

    // --- accessors ---
    int components(int type) const {
        switch (type) {
            case TINYGLTF_TYPE_SCALAR: return 1;
            case TINYGLTF_TYPE_VEC2: return 2;
            case TINYGLTF_TYPE_VEC3: return 3;
            case TINYGLTF_TYPE_VEC4: return 4;
            default: return 0;
        }
    }
    static int component_size(int ct) {
        switch (ct) {
            case TINYGLTF_COMPONENT_TYPE_BYTE: case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
            case TINYGLTF_COMPONENT_TYPE_SHORT: case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
            case TINYGLTF_COMPONENT_TYPE_INT: case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
            case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
            case TINYGLTF_COMPONENT_TYPE_DOUBLE: return 8;
            default: return 0;
        }
    }

    /// `count` elements of `n` components of type `ct` from buffer view `view`, starting `offset`
    /// bytes into it, into `dst`; `strided`: the view's byteStride applies (vertex attributes),
    /// else the elements are packed (sparse indices and values). Every range is checked, in 128-bit
    /// arithmetic so that no offset or stride read from the file can wrap around. `at` is the
    /// JSON pointer of the object naming the view, for errors.
    void fetch(int view, std::size_t offset, std::size_t count, int n, int ct, bool normalized, bool strided,
               double* dst, const std::string& what, const std::string& at) const;

    /// Buffer view `view` compressed by EXT_meshopt_compression (`ext`), decoded once: vertex
    /// streams (mode ATTRIBUTES, with the OCTAHEDRAL, QUATERNION or EXPONENTIAL filter undone),
    /// index buffers (TRIANGLES) and index sequences (INDICES), by meshoptimizer's decoders.
    const std::vector<unsigned char>& meshopt_view(int view, const tinygltf::Value& ext, const std::string& what) const;
    mutable std::map<int, std::vector<unsigned char>> meshopt_views;

    /// Accessor `index` as doubles, `n` components per element (normalised integers mapped to
    /// [0, 1] or [-1, 1] when the accessor says so), sparse substitutions applied. `ref` is the
    /// JSON pointer of the reference to the accessor, for errors.
    std::vector<double> read(int index, int n, const std::string& what, const std::string& ref) const;

    // --- textures ---
    std::shared_ptr<const Image> image(int index, bool srgb, const std::string& ref);

    static WrapMode wrap(int mode) {
        if (mode == TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE) return WrapMode::kClamp;
        if (mode == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT) return WrapMode::kMirror;
        return WrapMode::kRepeat;
    }

    /// A JSON number that is a whole number in int's range; -1 otherwise (an index nothing has).
    static int whole(const tinygltf::Value& v) {
        if (!v.IsNumber()) return -1;
        const double x = v.GetNumberAsDouble();
        return x >= -2147483648.0 && x < 2147483648.0 && x == std::floor(x) ? static_cast<int>(x) : -1;
    }

    static double number(const tinygltf::Value& v, const char* key, double fallback) {
        if (!v.Has(key)) return fallback;
        const tinygltf::Value& x = v.Get(key);
        return x.IsNumber() ? x.GetNumberAsDouble() : fallback;
    }

    /// A texture reference as an image TextureDesc (its sampler's wraps, KHR_texture_transform).
    /// `ref`: the JSON pointer of the texture reference (".../baseColorTexture"), for errors.
    TextureDesc texture(int index, int tex_coord, const tinygltf::ExtensionMap& ext, bool srgb, const char* what,
                        const std::string& ref);

    static TextureDesc constant(Color c) {
        TextureDesc d;
        d.value = c;
        return d;
    }
    static TextureDesc scaled(TextureDesc t, Color factor) {
        if (factor.r == 1 && factor.g == 1 && factor.b == 1) return t;
        TextureDesc d;
        d.kind = TextureDesc::Kind::kScale;
        d.children = {std::move(t), constant(factor)};
        return d;
    }

    static TextureDesc product(TextureDesc a, TextureDesc b) {
        TextureDesc d;
        d.kind = TextureDesc::Kind::kScale;
        d.children = {std::move(a), std::move(b)};
        return d;
    }
    static TextureDesc vertex_color(bool alpha) {
        TextureDesc d;
        d.kind = TextureDesc::Kind::kVertexColor;
        d.alpha_channel = alpha;
        return d;
    }

    MaterialDesc material(int index);

    /// alphaMode MASK (cut at alphaCutoff) or BLEND (stochastic): the base colour's alpha, factor
    /// x texture x vertex colour, as a cut-out; none when OPAQUE or nothing is ever translucent.
    std::optional<AlphaDesc> alpha(int index);

    // --- KHR_materials_clearcoat, _sheen, _specular ---

    /// A factor in [0, 1] named `key` of extension object `v`.
    float factor(const tinygltf::Value& v, const char* key, float fallback, const std::string& at) const {
        if (!v.Has(key)) return fallback;
        const tinygltf::Value& x = v.Get(key);
        const double f = x.IsNumber() ? x.GetNumberAsDouble() : std::numeric_limits<double>::quiet_NaN();
        if (!(f >= 0 && f <= 1)) fail_at(at + "/" + key, fmt::format("{} must be a number in [0, 1]", key));
        return float(f);
    }
    Color color_factor(const tinygltf::Value& v, const char* key, Color fallback, const std::string& at,
                       bool unbounded) const;
    /// The texture `key` of extension object `v` (a textureInfo), times `factor`; the factor
    /// alone without one. `alpha`: the texture's alpha channel is read (as grey).
    TextureDesc factor_texture(const tinygltf::Value& v, const char* key, Color factor, bool srgb, bool alpha,
                               const std::string& at);

    // Clear coat: weight = clearcoatFactor x clearcoatTexture.r, roughness =
    // clearcoatRoughnessFactor x clearcoatRoughnessTexture.g. The coat's own normal map is not
    // applied (it shares the base's shading normal): noted.
    void clearcoat(const tinygltf::Value& v, const std::string& at, MaterialDesc& d);

    // Sheen: colour = sheenColorFactor x sheenColorTexture (sRGB), roughness =
    // sheenRoughnessFactor x sheenRoughnessTexture.a.
    void sheen(const tinygltf::Value& v, const std::string& at, MaterialDesc& d) {
        const std::string e = at + "/extensions/KHR_materials_sheen";
        const Color c = color_factor(v, "sheenColorFactor", Color{0}, e, false);
        if (c.max_component() == 0) return;
        d.sheen = factor_texture(v, "sheenColorTexture", c, true, false, e);
        d.sheen_roughness =
            factor_texture(v, "sheenRoughnessTexture", Color{factor(v, "sheenRoughnessFactor", 0, e)}, false, true, e);
    }

    // Specular: weight = specularFactor x specularTexture.a, colour = specularColorFactor x
    // specularColorTexture (sRGB); both shape the dielectric's reflection (PlasticLobe).
    void specular(const tinygltf::Value& v, const std::string& at, MaterialDesc& d) {
        const std::string e = at + "/extensions/KHR_materials_specular";
        d.specular = factor_texture(v, "specularTexture", Color{factor(v, "specularFactor", 1, e)}, false, true, e);
        d.specular_color =
            factor_texture(v, "specularColorTexture", color_factor(v, "specularColorFactor", Color{1}, e, true), true, false, e);
    }

    // KHR_materials_volume: a thick (thicknessFactor > 0) transmissive material whose inside
    // absorbs, attenuationColor being what is left after attenuationDistance (world units):
    // sigma_a = -ln(colour) / distance, an interior medium of every surface of the material.
    // A thickness of 0 is thin-walled (no medium); thicknessTexture only shapes the thin-walled
    // approximation of rasterisers, so a path tracer, which has the real geometry, skips it.
    void volume(const tinygltf::Value& v, const std::string& at, MaterialDesc& d);

    // --- meshes ---

    /// A primitive compressed by KHR_draco_mesh_compression, decoded: its attributes by name
    /// (the extension's map from glTF names to Draco's attribute ids) and its triangles.
    struct DracoPrimitive {
        DracoMesh mesh;
        std::map<std::string, int> ids;
    };
    DracoPrimitive decode_draco(const tinygltf::Value& ext, const std::string& at, const std::string& what) const;
    /// Attribute `name` of a Draco primitive as doubles, `n` components per point; nothing if the
    /// primitive's extension does not list it.
    std::optional<std::vector<double>> draco_attribute(const DracoPrimitive& d, const std::string& name, int n,
                                                       const std::string& at, const std::string& what) const;

    void mesh(int index);

    // --- animation ---
    /// A node's translation, rotation (quaternion x, y, z, w) and scale set by an animation.
    struct Pose {
        std::optional<std::array<double, 3>> t, s;
        std::optional<std::array<double, 4>> r;
    };
    std::map<int, Pose> posed;  // node -> what the animation sets at the time rendered

    /// The file's first animation at `time` seconds (held before its first key and after its
    /// last): the translation, rotation and scale channels, sampled LINEAR (rotations by slerp),
    /// STEP or CUBICSPLINE as the spec defines. Morph target weights are left out with a note.
    void animate(double time);

    /// One channel's value at `time`: keys `t`, values `v` of `n` numbers (for CUBICSPLINE,
    /// in-tangent, value, out-tangent per key); curve 0 LINEAR, 1 STEP, 2 CUBICSPLINE. Rotations
    /// (`quaternion`) interpolate by slerp along the shorter arc, and come out unit length.
    static std::vector<double> sample(const std::vector<double>& t, const std::vector<double>& v, int n, double time,
                                      int curve, bool quaternion);

    Matrix34 node_matrix(int index) const;
    /// Every node's world matrix in glint's frame under the pose `posed` holds, from `index` down.
    void world_matrices(int index, const Matrix34& parent, int depth, std::map<int, Matrix34>& out) const;
    /// out.node_motion at `times` (seconds).
    void sample_motion(const std::vector<double>& times, const std::vector<int>& scene_roots);

    std::optional<GltfCamera> camera;
    std::string camera_name;
    /// Per material: whether some primitive drawn with it has COLOR_0 (which multiplies its
    /// base colour, and its alpha the base alpha).
    std::vector<bool> vertex_colored;
    /// The glTF node of each entry of out.nodes (for node_motion).
    std::vector<int> node_of;

    /// A file that requires an extension glint lacks cannot be shown as its author meant: an
    /// error. One that only uses such an extension renders without it, with a note naming it.
    void check_extensions();

    /// The nodes must form trees (the spec): a node listed as the child of two parents, or twice,
    /// would be visited once per path, exponentially many times in a chain of such nodes.
    void check_trees() const;
    /// The nodes no node lists as a child.
    std::vector<int> roots() const;

    // Indices are valid and the nodes form trees (check_trees()), so a cycle of children cannot be
    // reached: each of its nodes has its parent in the cycle, so none is a root. The depth limit
    // only keeps the recursion's stack small.
    void visit(int index, const Matrix34& parent, int depth);
};

}  // namespace glint::gltf_detail
