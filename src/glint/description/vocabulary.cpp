#include "glint/description/vocabulary.h"

#include <stdexcept>

namespace glint {

namespace {

// Keys every object takes, whatever its shape (after `type` and the shape's own).
#define GLINT_OBJECT_KEYS "material", "transform", "interior", "exterior"
// Keys every material takes.
#define GLINT_MATERIAL_KEYS "type", "emission", "emission_spectrum", "two_sided", "normal_map", "normal_scale"
// Keys of the coated materials' slab (pbrt-v4's LayeredBxDF).
#define GLINT_LAYER_KEYS "ior", "thickness", "layer_albedo", "g", "max_depth", "samples"
// Keys of both media.
#define GLINT_MEDIUM_KEYS "type", "sigma_a", "sigma_s", "albedo", "density", "scale", "g"

const std::vector<VocabularyEntry>& table() {
    static const std::vector<VocabularyEntry> t{
        {"scene", "", {"camera", "film", "sampler", "integrator", "background", "lights", "materials", "media",
                       "medium", "objects", "animation"}},
        {"animation", "", {"fps"}},
        {"keyframes", "", {"keyframes", "interpolation"}},
        {"interpolation", "linear", {}},
        {"interpolation", "step", {}},
        {"interpolation", "smooth", {}},
        {"camera", "article", {"type", "position", "direction", "up", "viewport_width", "viewport_height", "near",
                               "aperture_radius", "focus_distance", "handedness", "shutter"}},
        {"camera", "look_at", {"type", "from", "to", "up", "fov", "aperture_radius", "focus_distance", "handedness",
                               "projection", "height", "window", "shutter"}},
        {"film", "", {"width", "height", "encoding", "tonemap", "exposure", "filter", "aovs", "denoise", "filename", "crop",
                      "crop_pixels", "scale"}},
        {"encoding", "srgb", {}},
        {"encoding", "raw", {}},
        {"tone_curve", "clamp", {}},
        {"tone_curve", "reinhard", {}},
        {"tone_curve", "aces", {}},
        {"filter", "box", {"type", "radius"}},
        {"filter", "tent", {"type", "radius"}},
        {"filter", "gaussian", {"type", "radius", "sigma"}},
        {"filter", "blackman_harris", {"type", "radius"}},
        {"sampler", "", {"type", "spp", "seed", "noise_threshold", "min_spp"}},
        {"sampler_type", "sobol", {}},
        {"sampler_type", "stratified", {}},
        {"sampler_type", "independent", {}},
        {"integrator", "flat", {"type"}},
        {"integrator", "normals", {"type"}},
        {"integrator", "whitted", {"type", "max_depth", "ambient", "shadows"}},
        {"integrator", "path", {"type", "max_depth", "rr_depth", "clamp", "strategy", "light_sampler", "texture_filter", "spectral", "white_balance"}},
        {"strategy", "mis", {}},
        {"strategy", "light", {}},
        {"strategy", "bsdf", {}},
        {"light_sampler", "bvh", {}},
        {"light_sampler", "power", {}},
        {"texture_filter", "ewa", {}},
        {"texture_filter", "trilinear", {}},
        {"texture_filter", "none", {}},
        {"background", "sky", {"type", "horizon", "zenith"}},
        {"background", "constant", {"type", "color", "spectrum"}},
        {"background", "environment", {"type", "filename", "scale"}},
        {"light", "directional", {"type", "direction", "intensity", "spectrum", "angular_diameter"}},
        {"light", "point", {"type", "position", "intensity", "spectrum"}},
        {"light", "spot", {"type", "position", "direction", "intensity", "spectrum", "cone_angle", "falloff_start"}},
        {"material", "article", {GLINT_MATERIAL_KEYS, "color", "shininess"}},
        {"material", "diffuse", {GLINT_MATERIAL_KEYS, "albedo"}},
        {"material", "conductor", {GLINT_MATERIAL_KEYS, "metal", "eta", "k", "reflectance", "roughness"}},
        {"material", "dielectric", {GLINT_MATERIAL_KEYS, "ior", "abbe", "roughness", "thin", "tint"}},
        {"material", "plastic", {GLINT_MATERIAL_KEYS, "albedo", "ior", "roughness"}},
        {"material", "pbr", {GLINT_MATERIAL_KEYS, "base_color", "metallic", "roughness", "transmission", "ior", "abbe",
                             "clearcoat", "clearcoat_roughness", "sheen", "sheen_roughness", "specular",
                             "specular_color"}},
        {"material", "interface", {"type"}},
        {"material", "diffuse_transmission", {GLINT_MATERIAL_KEYS, "reflectance", "transmittance"}},
        {"material", "mix", {GLINT_MATERIAL_KEYS, "materials", "amount"}},
        {"material", "coated_diffuse", {GLINT_MATERIAL_KEYS, GLINT_LAYER_KEYS, "albedo", "roughness"}},
        {"material", "coated_conductor", {GLINT_MATERIAL_KEYS, GLINT_LAYER_KEYS, "metal", "eta", "k", "reflectance",
                                          "roughness", "coat_roughness"}},
        {"metal", "aluminium", {}},
        {"metal", "chromium", {}},
        {"metal", "copper", {}},
        {"metal", "gold", {}},
        {"metal", "iron", {}},
        {"metal", "platinum", {}},
        {"metal", "silver", {}},
        {"texture", "constant", {"type", "color", "spectrum"}},
        {"texture", "checker", {"type", "size", "even", "odd", "space", "uv_scale", "uv_offset"}},
        {"texture", "image", {"type", "filename", "pixels", "encoding", "wrap", "size"}},
        {"texture", "scale", {"type", "texture", "factor"}},
        {"texture", "mix", {"type", "a", "b", "amount"}},
        {"texture", "vertex_color", {"type"}},
        {"texture_encoding", "auto", {}},
        {"texture_encoding", "srgb", {}},
        {"texture_encoding", "linear", {}},
        {"wrap", "repeat", {}},
        {"wrap", "clamp", {}},
        {"wrap", "mirror", {}},
        {"medium", "homogeneous", {GLINT_MEDIUM_KEYS, "emission"}},
        {"medium", "grid", {GLINT_MEDIUM_KEYS, "file", "grid", "voxels", "min", "max", "emission_grid", "emission", "temperature_grid",
                            "temperature_scale", "emission_scale", "transform"}},
        {"object", "sphere", {"type", "center", "radius", GLINT_OBJECT_KEYS}},
        {"object", "plane", {"type", "point", "normal", GLINT_OBJECT_KEYS}},
        {"object", "quad", {"type", "corner", "edge1", "edge2", GLINT_OBJECT_KEYS}},
        {"object", "disk", {"type", "center", "normal", "radius", GLINT_OBJECT_KEYS}},
        {"object", "triangle", {"type", "vertices", GLINT_OBJECT_KEYS}},
        {"object", "polygon", {"type", "vertices", GLINT_OBJECT_KEYS}},
        {"object", "box", {"type", "min", "max", GLINT_OBJECT_KEYS}},
        {"object", "mesh", {"type", "file", "positions", "indices", "normals", "uvs", "colors", GLINT_OBJECT_KEYS, "alpha", "alpha_mode", "alpha_cutoff"}},
        {"alpha_mode", "mask", {}},
        {"alpha_mode", "blend", {}},
        {"transform", "translate", {}},
        {"transform", "scale", {}},
        {"transform", "rotate", {"angle", "axis"}},
        {"transform", "matrix", {}},
        {"transform", "look_at", {"from", "to", "up"}},
    };
    return t;
}

#undef GLINT_OBJECT_KEYS
#undef GLINT_MATERIAL_KEYS
#undef GLINT_LAYER_KEYS
#undef GLINT_MEDIUM_KEYS

}  // namespace

std::span<const VocabularyEntry> vocabulary() { return table(); }

std::vector<std::string> vocabulary_types(std::string_view kind) {
    std::vector<std::string> out;
    for (const VocabularyEntry& e : table())
        if (e.kind == kind) out.emplace_back(e.type);
    if (out.empty()) throw std::logic_error("vocabulary: no kind " + std::string(kind));
    return out;
}

std::vector<std::string> vocabulary_keys(std::string_view kind, std::string_view type) {
    for (const VocabularyEntry& e : table())
        if (e.kind == kind && e.type == type) return {e.keys.begin(), e.keys.end()};
    throw std::logic_error("vocabulary: no " + std::string(kind) + " '" + std::string(type) + "'");
}

namespace {
std::string_view nth(std::string_view kind, int i) {
    int k = 0;
    for (const VocabularyEntry& e : table())
        if (e.kind == kind && k++ == i) return e.type;
    throw std::logic_error("vocabulary: no value " + std::to_string(i) + " of " + std::string(kind));
}
}  // namespace

// The table lists each of these sets in its enumeration's order (the tests check each name).
std::string_view vocabulary_name(SamplerType t) { return nth("sampler_type", static_cast<int>(t)); }
std::string_view vocabulary_name(FilterType t) { return nth("filter", static_cast<int>(t)); }
std::string_view vocabulary_name(ToneCurve t) { return nth("tone_curve", static_cast<int>(t)); }
std::string_view vocabulary_name(Encoding e) { return nth("encoding", static_cast<int>(e)); }
std::string_view vocabulary_name(LightStrategy s) { return nth("strategy", static_cast<int>(s)); }
std::string_view vocabulary_name(LightSamplerKind k) { return nth("light_sampler", static_cast<int>(k)); }
std::string_view vocabulary_name(TextureFilter f) { return nth("texture_filter", static_cast<int>(f)); }

}  // namespace glint
