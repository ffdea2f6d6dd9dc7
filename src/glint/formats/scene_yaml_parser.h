#pragma once
// The YAML/JSON scene reader's inside, shared by its files (not part of the library's interface):
// scene_yaml.cpp (the root, animation, camera, film, sampler, integrator, background, lights),
// scene_yaml_materials.cpp (textures, materials, media), scene_yaml_objects.cpp (objects and
// transforms). scene_yaml.h is the interface.
#include <fmt/core.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <array>
#include <initializer_list>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "glint/description/scene_description.h"
#include "glint/formats/scene_yaml.h"
#include "glint/formats/yaml_reader.h"

namespace glint::yaml_detail {

inline constexpr double kInf = std::numeric_limits<double>::infinity();

inline std::string join(const std::vector<std::string>& names) {
    std::string out;
    for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
    return out;
}

// N from "<array N>" (an array handed over beside the text); -1 if the text is not of that form.
long long array_number(const std::string& s);

template <typename T, typename Read>
void assign(const std::optional<YAML::Node>& node, T& field, Read read) {
    if (!node) return;
    if (auto v = read(*node)) field = static_cast<T>(*v);
}

class SceneParser {
public:
    SceneParser(Diagnostics& diagnostics, const std::string& path, const InlineArrays* arrays = nullptr)
        : r_(diagnostics, path), arrays_(arrays) {}

    void parse_root(const YAML::Node& root, SceneDescription& scene);
    void ior(const YAML::Node& n, MaterialDesc& d);

private:
    // Replaces, in place, every `{keyframes: [[frame, value], ...], interpolation: ...}` under
    // `node` with its value at scene.frame (docs/scene-format.md, "Animation").
    void animate(YAML::Node& node, SceneDescription& scene);

    // A keyframed value at `frame`: a number, or a list of numbers, as a node made here (errors
    // about it are located at the keyframes map).
    std::optional<YAML::Node> keyframed(const YAML::Node& node, double frame);

    // The value at `f` of keys (t[i], v[i]), t increasing: held before the first and after the
    // last; between keys linear (0), the earlier key's (1), or smooth (2): a cubic Hermite
    // through the keys whose slopes are the central differences (Catmull-Rom, non-uniform), one-sided at the ends.
    static std::vector<double> interpolate(const std::vector<double>& t, const std::vector<std::vector<double>>& v,
                                           double f, int curve);

    // The value of a polymorphic map's `type` key, checked against `types`.
    std::optional<std::string> type_of(const YAML::Node& node, const std::string& context,
                                       const std::vector<std::string>& types,
                                       std::optional<std::string> fallback = std::nullopt);

    // A name from a fixed list, mapped to its value; otherwise "unknown WHAT 'x' (known: ...)".
    template <typename T>
    std::optional<T> choice(const YAML::Node& node, const char* what,
                            std::initializer_list<std::pair<const char*, T>> options) {
        const auto name = r_.string(node);
        if (!name) return std::nullopt;
        std::string known;
        for (const auto& [key, value] : options) {
            if (*name == key) return value;
            known += (known.empty() ? "" : ", ") + std::string(key);
        }
        r_.error(node, fmt::format("unknown {} '{}' (known: {})", what, *name, known));
        return std::nullopt;
    }

    auto positive(const char* what) {
        return [this, what](const YAML::Node& n) { return r_.number_in(n, what, 0, kInf, true); };
    }
    auto point() {
        return [this](const YAML::Node& n) { return r_.point(n); };
    }
    auto direction(const char* what) {
        return [this, what](const YAML::Node& n) { return r_.direction(n, what); };
    }
    auto color() {
        return [this](const YAML::Node& n) { return r_.color(n); };
    }

    CameraDesc camera(const YAML::Node& node);

    void handedness(MapReader& m, bool& right) {
        if (auto n = m.get("handedness")) {
            if (auto h = choice<bool>(*n, "handedness", {{"left", false}, {"right", true}}))
                right = *h;
        }
    }

    // `shutter: [open, close]`, frames from the scene's frame (open <= close; equal: an instant).
    void shutter(MapReader& m) {
        const auto n = m.get("shutter");
        if (!n) return;
        const auto bad = [&] { r_.error(*n, "camera: 'shutter' must be [open, close], two frame offsets with open <= close"); };
        if (!n->IsSequence() || n->size() != 2) return bad();
        const auto open = r_.number_in((*n)[0], "shutter open", -1e6, 1e6), close = r_.number_in((*n)[1], "shutter close", -1e6, 1e6);
        if (!open || !close) return;
        if (!(*open <= *close)) return bad();
        shutter_ = {*open, *close};
        shutter_loc_ = r_.loc(*n);
    }
    std::array<double, 2> shutter_{0, 0};
    SourceLoc shutter_loc_;

    void lens(MapReader& m, Float& aperture, std::optional<Float>& focus) {
        assign(m.get("aperture_radius"), aperture, [this](const YAML::Node& n) {
            return r_.number_in(n, "aperture_radius", 0, kInf);
        });
        if (auto n = m.get("focus_distance")) {
            if (auto v = positive("focus_distance")(*n)) focus = static_cast<Float>(*v);
        }
    }

    void film(const YAML::Node& node, FilmDesc& f);

    FilterDesc filter(const YAML::Node& node);

    void sampler(const YAML::Node& node, SamplerDesc& s);

    void integrator(const YAML::Node& node, IntegratorDesc& d);

    std::optional<Background> background(const YAML::Node& node,
                                         std::optional<EnvironmentDesc>& environment);

    void lights(const YAML::Node& node, std::vector<Light>& out, std::vector<std::shared_ptr<const Spectrum>>& spectra);
    /// A spectrum value: {blackbody: kelvin}, a name pbrt-v4 knows, or [nm, value, ...].
    std::optional<Spectrum> spectrum(const YAML::Node& n);
    /// An emitter's `spectrum` (as spectrum() reads it), normalised to Y = 1. `rgb` (the colour
    /// given beside it) becomes the spectrum's colour at the same luminance.
    std::shared_ptr<const Spectrum> emitter_spectrum(const YAML::Node& n, Color& rgb);

    // A texture: a number (grey), a colour [r, g, b], or a map with a type.
    std::optional<TextureDesc> texture(const YAML::Node& node);

    MaterialDesc material(const YAML::Node& node, const std::string& context);

    void materials(const YAML::Node& node, std::vector<NamedMaterial>& out);

    MaterialRef material_ref(const YAML::Node& node);

    Located<std::string> located_name(const YAML::Node& node) {
        Located<std::string> l{"", r_.loc(node)};
        if (const auto v = r_.string(node)) l.value = *v;
        return l;
    }

    // The coefficients of a medium: sigma_a and sigma_s, or the artist's albedo, density and
    // scale (sigma_s = albedo density scale, sigma_a = (1 - albedo) density scale).
    void coefficients(MapReader& m, const YAML::Node& node, const std::string& context, MediumDesc& d);

    MediumDesc medium(const YAML::Node& node, const std::string& context);

    void media(const YAML::Node& node, std::vector<NamedMedium>& out);

    void objects(const YAML::Node& node, std::vector<ObjectDesc>& out);
    // A mesh given by its arrays (`positions`, `indices`, ...; scene_yaml_mesh.cpp); null after an error.
    std::shared_ptr<const TriangleMesh> inline_mesh(MapReader& m, const YAML::Node& item);
    // An inline mesh's array of `columns` numbers a row, given as "<array N>": arrays_[N], checked
    // (columns, kind, size); null after an error.
    const ArrayView* handed_array(const YAML::Node& node, const char* key, std::size_t columns, bool ints);
    // The same given as a YAML list (flat, or of rows), read into `floats` or (ints) `indices`.
    bool mesh_list(const YAML::Node& node, const char* key, std::size_t columns, bool ints,
                   std::vector<float>& floats, std::vector<std::uint32_t>& indices);
    // A float array either way: a view of the handed-over memory, or of `storage` (a list read
    // into it); nullopt after an error.
    std::optional<std::span<const float>> mesh_floats(const YAML::Node& node, const char* key, std::size_t columns,
                                       std::vector<float>& storage);
    // Whether `rows` vertices (or triangles) fit the limits and the memory budget; errors otherwise.
    bool check_mesh_size(const YAML::Node& node, const char* key, std::size_t rows, bool triangles);

    // Numbers in a block of `min_dims` to `max_dims` dimensions (scene_yaml_pixels.cpp): a YAML
    // list nested that deep, every row of one length, or "<array N>" (float32, its own shape).
    // At most `max_values` numbers; nullopt after an error, located at `node`.
    struct NumberBlock {
        std::vector<float> storage;      ///< the list's numbers, when read from YAML
        std::span<const float> values;   ///< row-major: storage, or the handed-over memory
        std::array<std::size_t, 3> shape{0, 0, 0};
        int dims = 0;
    };
    std::optional<NumberBlock> number_block(const YAML::Node& node, const std::string& what, int min_dims,
                                            int max_dims, long long max_values);
    // Whether every value is finite and >= 0; an error naming the first that is not otherwise.
    bool check_values(const YAML::Node& node, const std::string& what, std::span<const float> values);
    // An image texture's `pixels`: (height, width[, channels]) with 1, 3 or 4 channels, row 0 at the
    // top, linear unless `encoding` is srgb; null after an error.
    std::shared_ptr<const Image> inline_image(const YAML::Node& node, ImageEncoding encoding);
    // A grid medium's `voxels` (nz, ny, nx; x fastest) filling the box `min`..`max` of `m`, before
    // the medium's `transform`; sets d.inline_density and d.transform.
    void inline_voxels(MapReader& m, const YAML::Node& node, MediumDesc& d);

    std::vector<Diagnostic> warnings_;  ///< into SceneDescription::warnings
    /// Inline meshes by the arrays they were read from ("<array 0>|<array 1>|-|..."): shared.
    std::map<std::string, std::shared_ptr<const TriangleMesh>> shared_meshes_;

    // `transform`: one step or a list of steps, applied in the order listed (the first step acts
    // on the object first). Each step is a one-key map: translate, scale (a number or three),
    // rotate {angle (degrees), axis}, matrix (3 or 4 rows of 4; a 4th row must be 0 0 0 1), or
    // look_at {from, to, up}.
    std::optional<Transform> transform(const YAML::Node& node);

    // An object of this shape; material, placement and location are filled in after.
    template <typename Shape>
    static ObjectDesc object_of(const Shape& shape) {
        ObjectDesc o;
        o.shape = shape;
        return o;
    }

    // The six faces of an axis-aligned box as quads whose normals (edge1 x edge2) point outward.
    static std::array<Quad, 6> box_faces(Point3 lo, Point3 hi);

    YamlReader r_;
    const InlineArrays* arrays_ = nullptr;
};

}  // namespace glint::yaml_detail
