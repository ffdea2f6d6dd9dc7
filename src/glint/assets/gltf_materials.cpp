#include <tiny_gltf.h>

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>

#include "glint/assets/gltf_importer.h"
#include "glint/base/diagnostics.h"
#include "glint/base/limits.h"

namespace glint::gltf_detail {

// --- textures ---
std::shared_ptr<const Image> Importer::image(int index, bool srgb, const std::string& ref) {
    const auto key = std::make_pair(index, srgb);
    if (auto it = images.find(key); it != images.end()) return it->second;
    if (index < 0 || index >= static_cast<int>(model.images.size())) fail_at(ref, fmt::format("image {} does not exist", index));
    const tinygltf::Image& im = model.images[index];
    const std::string at = fmt::format("/images/{}", index);
    if (im.width <= 0 || im.height <= 0 || im.image.empty()) {
        // A file that is not there is "not found", not "could not be decoded".
        if (!im.uri.empty() && im.uri.rfind("data:", 0) != 0) {
            std::string name;  // the uri, percent-decoded as tinygltf does
            for (std::size_t i = 0; i < im.uri.size(); ++i) {
                if (im.uri[i] == '%' && i + 2 < im.uri.size() && std::isxdigit(static_cast<unsigned char>(im.uri[i + 1])) &&
                    std::isxdigit(static_cast<unsigned char>(im.uri[i + 2]))) {
                    name += static_cast<char>(std::stoi(im.uri.substr(i + 1, 2), nullptr, 16));
                    i += 2;
                } else {
                    name += im.uri[i];
                }
            }
            const std::filesystem::path path = std::filesystem::path(file).parent_path() / name;
            std::error_code ec;
            if (!std::filesystem::exists(path, ec))
                fail_at(at + "/uri", fmt::format("image {}: '{}' not found (looked for {})", index, im.uri, path.string()));
            if (const std::string why = why_not_readable(path); !why.empty())
                fail_at(at + "/uri", fmt::format("image {}: cannot read '{}': it {}", index, path.string(), why));
        }
        fail_at(at, fmt::format("image {} ('{}') could not be decoded", index, im.uri.empty() ? im.name : im.uri));
    }
    if (static_cast<long long>(im.width) * im.height > limit(Limit::kTexturePixels))
        fail_at(at, fmt::format("image {} is {} x {} pixels: {}", index, im.width, im.height,
                                over_limit(Limit::kTexturePixels, static_cast<long long>(im.width) * im.height)));
    if (const std::string e = charge_memory(static_cast<long long>(im.width) * im.height * 16, fmt::format("image {}", index)); !e.empty())
        fail_at(at, e);
    const int comps = im.component, bytes = im.bits == 16 ? 2 : 1;
    if (comps < 1 || comps > 4 || im.image.size() < static_cast<std::size_t>(im.width) * im.height * comps * bytes)
        fail_at(at, fmt::format("image {} has an unexpected pixel layout", index));
    auto img = std::make_shared<Image>();
    img->width = im.width;
    img->height = im.height;
    img->texels.resize(static_cast<std::size_t>(im.width) * im.height);
    const auto decode = [srgb](float x) { return srgb ? srgb_decode(x) : x; };
    // Alpha (grey + alpha, or RGBA) is linear in every colour space; kept only when some
    // texel is not opaque.
    const bool has_alpha = comps == 2 || comps == 4;
    if (has_alpha) img->alpha.resize(img->texels.size());
    bool translucent = false;
    for (std::size_t i = 0; i < img->texels.size(); ++i) {
        float c[4] = {0, 0, 0, 1};
        for (int k = 0; k < comps; ++k) {
            const std::size_t o = (i * comps + k) * bytes;
            c[k] = bytes == 2 ? (im.image[o] | im.image[o + 1] << 8) / 65535.0f : im.image[o] / 255.0f;
        }
        if (comps == 2) c[3] = c[1];
        if (comps < 3) c[1] = c[2] = c[0];
        img->texels[i] = Color{decode(c[0]), decode(c[1]), decode(c[2])};
        if (has_alpha) {
            img->alpha[i] = c[3];
            translucent |= c[3] < 1;
        }
    }
    if (!translucent) img->alpha.clear();
    images.emplace(key, img);
    return img;
}

/// A texture reference as an image TextureDesc (its sampler's wraps, KHR_texture_transform).
/// `ref`: the JSON pointer of the texture reference (".../baseColorTexture"), for errors.
TextureDesc Importer::texture(int index, int tex_coord, const tinygltf::ExtensionMap& ext, bool srgb, const char* what,
                    const std::string& ref) {
    if (index < 0 || index >= static_cast<int>(model.textures.size()))
        fail_at(ref + "/index", fmt::format("{}: texture {} does not exist", what, index));
    const tinygltf::Texture& t = model.textures[index];
    TextureDesc d;
    d.kind = TextureDesc::Kind::kImage;
    d.pixels = image(t.source, srgb, fmt::format("/textures/{}/source", index));
    d.filename.value = fmt::format("{}#image{}", file, t.source);
    if (t.sampler >= 0 && t.sampler < static_cast<int>(model.samplers.size())) {
        d.wrap = wrap(model.samplers[t.sampler].wrapS);
        d.wrap_v = wrap(model.samplers[t.sampler].wrapT);
    } else {
        d.wrap_v = WrapMode::kRepeat;
    }
    if (const auto it = ext.find("KHR_texture_transform"); it != ext.end()) {
        // glTF uv' = T(offset) R(rotation) S(scale) uv, in glTF's (v down) space; in ours,
        // F T F with F(u, v) = (u, 1 - v).
        const tinygltf::Value& v = it->second;
        double off[2] = {0, 0}, sc[2] = {1, 1};
        if (v.Has("offset") && v.Get("offset").ArrayLen() == 2)
            for (int k = 0; k < 2; ++k) off[k] = v.Get("offset").Get(k).GetNumberAsDouble();
        if (v.Has("scale") && v.Get("scale").ArrayLen() == 2)
            for (int k = 0; k < 2; ++k) sc[k] = v.Get("scale").Get(k).GetNumberAsDouble();
        const double r = number(v, "rotation", 0), c = std::cos(r), s = std::sin(r);
        // T = [a b e; c d f] in glTF space.
        const double a = c * sc[0], b = s * sc[1], e = off[0];
        const double cc = -s * sc[0], dd = c * sc[1], f = off[1];
        // F T F: u' = a u + b (1 - v) + e ; v' = 1 - (cc u + dd (1 - v) + f).
        d.uv_transform = {Float(a), Float(-b), Float(b + e), Float(-cc), Float(dd), Float(1 - dd - f)};
        if (v.Has("texCoord")) tex_coord = whole(v.Get("texCoord"));  // overrides; -1 if not a set number
    }
    if (tex_coord < 0 || tex_coord >= kMaxUvSets)
        fail_at(ref + "/texCoord", fmt::format("{}: texCoord {} (glint reads TEXCOORD_0 to TEXCOORD_{})", what,
                                               tex_coord, kMaxUvSets - 1));
    d.uv_set = static_cast<std::uint8_t>(tex_coord);
    return d;
}

MaterialDesc Importer::material(int index) {
    const tinygltf::Material& m = model.materials[index];
    const std::string at = fmt::format("/materials/{}", index);
    MaterialDesc d;
    d.kind = MaterialDesc::Kind::kPbr;
    const auto& pbr = m.pbrMetallicRoughness;
    if (pbr.baseColorFactor.size() != 4)
        fail_at(at + "/pbrMetallicRoughness/baseColorFactor", "baseColorFactor must be 4 numbers");
    const Color base{float(pbr.baseColorFactor[0]), float(pbr.baseColorFactor[1]), float(pbr.baseColorFactor[2])};
    d.color = pbr.baseColorTexture.index >= 0
                  ? scaled(texture(pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord,
                                   pbr.baseColorTexture.extensions, true, "baseColorTexture",
                                   at + "/pbrMetallicRoughness/baseColorTexture"),
                           base)
                  : constant(base);
    if (vertex_colored[static_cast<std::size_t>(index)]) d.color = product(std::move(d.color), vertex_color(false));
    d.metallic = float(pbr.metallicFactor);
    d.roughness = float(pbr.roughnessFactor);
    if (pbr.metallicRoughnessTexture.index >= 0)
        d.metallic_roughness = texture(pbr.metallicRoughnessTexture.index, pbr.metallicRoughnessTexture.texCoord,
                                       pbr.metallicRoughnessTexture.extensions, false, "metallicRoughnessTexture",
                                       at + "/pbrMetallicRoughness/metallicRoughnessTexture");
    if (m.normalTexture.index >= 0) {
        d.normal_map = texture(m.normalTexture.index, m.normalTexture.texCoord, m.normalTexture.extensions,
                               false, "normalTexture", at + "/normalTexture");
        d.normal_scale = float(m.normalTexture.scale);
    }
    if (m.occlusionTexture.index >= 0)
        (void)texture(m.occlusionTexture.index, m.occlusionTexture.texCoord, m.occlusionTexture.extensions,
                      false, "occlusionTexture", at + "/occlusionTexture");  // checked, not applied (see the top)
    if (m.emissiveFactor.size() != 3) fail_at(at + "/emissiveFactor", "emissiveFactor must be 3 numbers");
    Color emissive{float(m.emissiveFactor[0]), float(m.emissiveFactor[1]), float(m.emissiveFactor[2])};
    const auto& ext = m.extensions;
    if (const auto it = ext.find("KHR_materials_emissive_strength"); it != ext.end())
        emissive = emissive * float(number(it->second, "emissiveStrength", 1));
    if (const auto it = ext.find("KHR_materials_transmission"); it != ext.end())
        d.transmission = float(number(it->second, "transmissionFactor", 0));
    if (const auto it = ext.find("KHR_materials_ior"); it != ext.end()) d.ior = float(number(it->second, "ior", 1.5));
    if (const auto it = ext.find("KHR_materials_dispersion"); it != ext.end()) {
        // dispersion = 20 / V_d (the Abbe number), about the index at 587.56 nm; spectral mode only.
        const double dispersion = number(it->second, "dispersion", 0);
        if (!(dispersion >= 0)) fail_at(at + "/extensions/KHR_materials_dispersion/dispersion", "KHR_materials_dispersion: dispersion must be >= 0");
        if (dispersion > 0) d.ior_spectrum = std::make_shared<const Spectrum>(Spectrum::from_abbe(d.ior, float(20 / dispersion)));
    }
    if (const auto it = ext.find("KHR_materials_volume"); it != ext.end()) volume(it->second, at, d);
    if (const auto it = ext.find("KHR_materials_clearcoat"); it != ext.end()) clearcoat(it->second, at, d);
    if (const auto it = ext.find("KHR_materials_sheen"); it != ext.end()) sheen(it->second, at, d);
    if (const auto it = ext.find("KHR_materials_specular"); it != ext.end()) specular(it->second, at, d);
    if (emissive.max_component() > 0) {
        d.emission = Emission{emissive, m.doubleSided, std::nullopt, nullptr};
        if (m.emissiveTexture.index >= 0)
            d.emission_map = texture(m.emissiveTexture.index, m.emissiveTexture.texCoord,
                                     m.emissiveTexture.extensions, true, "emissiveTexture", at + "/emissiveTexture");
    }
    return d;
}

/// alphaMode MASK (cut at alphaCutoff) or BLEND (stochastic): the base colour's alpha, factor
/// x texture x vertex colour, as a cut-out; none when OPAQUE or nothing is ever translucent.
std::optional<AlphaDesc> Importer::alpha(int index) {
    const tinygltf::Material& m = model.materials[index];
    const std::string at = fmt::format("/materials/{}", index);
    if (m.alphaMode.empty() || m.alphaMode == "OPAQUE") return std::nullopt;
    if (m.alphaMode != "MASK" && m.alphaMode != "BLEND")
        fail_at(at + "/alphaMode", fmt::format("alphaMode '{}': must be OPAQUE, MASK or BLEND", m.alphaMode));
    AlphaDesc a;
    a.stochastic = m.alphaMode == "BLEND";
    a.cutoff = float(m.alphaCutoff);
    if (!a.stochastic && !(a.cutoff >= 0 && std::isfinite(a.cutoff)))
        fail_at(at + "/alphaCutoff", fmt::format("alphaCutoff {}: must be a number >= 0", m.alphaCutoff));
    const auto& pbr = m.pbrMetallicRoughness;
    const float factor = float(pbr.baseColorFactor[3]);
    std::optional<TextureDesc> t;
    if (pbr.baseColorTexture.index >= 0) {
        TextureDesc tex = texture(pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord,
                                  pbr.baseColorTexture.extensions, true, "baseColorTexture",
                                  at + "/pbrMetallicRoughness/baseColorTexture");
        if (!tex.pixels->alpha.empty()) {  // an opaque image leaves the factor alone
            tex.alpha_channel = true;
            t = std::move(tex);
        }
    }
    if (vertex_colored[static_cast<std::size_t>(index)])
        t = t ? product(std::move(*t), vertex_color(true)) : vertex_color(true);
    if (!t) {  // a constant alpha: decided once, here
        const bool opaque = a.stochastic ? factor >= 1 : factor >= a.cutoff;
        if (opaque) return std::nullopt;
        if (!a.stochastic) {
            out.notes.push_back(fmt::format("{}: material '{}' is cut away whole (alpha {} < alphaCutoff {})",
                                            file, m.name, factor, a.cutoff));
        }
        a.texture = constant(Color{factor});
    } else {
        a.texture = factor == 1 ? std::move(*t) : scaled(std::move(*t), Color{factor});
    }
    return a;
}

Color Importer::color_factor(const tinygltf::Value& v, const char* key, Color fallback, const std::string& at,
                   bool unbounded) const {
    if (!v.Has(key)) return fallback;
    const tinygltf::Value& x = v.Get(key);
    if (!x.IsArray() || x.ArrayLen() != 3) fail_at(at + "/" + key, fmt::format("{} must be 3 numbers", key));
    float c[3];
    for (int k = 0; k < 3; ++k) {
        const double f = x.Get(k).IsNumber() ? x.Get(k).GetNumberAsDouble() : -1;
        if (!(f >= 0 && (unbounded ? std::isfinite(f) : f <= 1)))
            fail_at(at + "/" + key, fmt::format("{} must be numbers in [0, {}", key, unbounded ? "inf)" : "1]"));
        c[k] = float(f);
    }
    return Color{c[0], c[1], c[2]};
}

/// The texture `key` of extension object `v` (a textureInfo), times `factor`; the factor
/// alone without one. `alpha`: the texture's alpha channel is read (as grey).
TextureDesc Importer::factor_texture(const tinygltf::Value& v, const char* key, Color factor, bool srgb, bool alpha,
                           const std::string& at) {
    if (!v.Has(key)) return constant(factor);
    const tinygltf::Value& info = v.Get(key);
    const std::string where = at + "/" + key;
    if (!info.IsObject() || !info.Has("index") || !info.Get("index").IsNumber())
        fail_at(where, fmt::format("{} must be an object with an index", key));
    tinygltf::ExtensionMap ext;
    if (info.Has("extensions") && info.Get("extensions").Has("KHR_texture_transform"))
        ext["KHR_texture_transform"] = info.Get("extensions").Get("KHR_texture_transform");
    const int tex_coord = info.Has("texCoord") ? whole(info.Get("texCoord")) : 0;
    TextureDesc t = texture(whole(info.Get("index")), tex_coord, ext, srgb, key, where);
    t.alpha_channel = alpha;
    return scaled(std::move(t), factor);
}

// Clear coat: weight = clearcoatFactor x clearcoatTexture.r, roughness =
// clearcoatRoughnessFactor x clearcoatRoughnessTexture.g. The coat's own normal map is not
// applied (it shares the base's shading normal): noted.
void Importer::clearcoat(const tinygltf::Value& v, const std::string& at, MaterialDesc& d) {
    const std::string e = at + "/extensions/KHR_materials_clearcoat";
    const float w = factor(v, "clearcoatFactor", 0, e);
    if (w == 0) return;
    d.clearcoat = factor_texture(v, "clearcoatTexture", Color{w}, false, false, e);
    d.clearcoat_roughness =
        factor_texture(v, "clearcoatRoughnessTexture", Color{factor(v, "clearcoatRoughnessFactor", 0, e)}, false, false, e);
    if (v.Has("clearcoatNormalTexture"))
        out.notes.push_back(fmt::format("{}: {}: clearcoatNormalTexture is not applied (the coat uses the base's normal)",
                                        file, e));
}

// KHR_materials_volume: a thick (thicknessFactor > 0) transmissive material whose inside
// absorbs, attenuationColor being what is left after attenuationDistance (world units):
// sigma_a = -ln(colour) / distance, an interior medium of every surface of the material.
// A thickness of 0 is thin-walled (no medium); thicknessTexture only shapes the thin-walled
// approximation of rasterisers, so a path tracer, which has the real geometry, skips it.
void Importer::volume(const tinygltf::Value& v, const std::string& at, MaterialDesc& d) {
    const std::string ext = at + "/extensions/KHR_materials_volume";
    const double thickness = number(v, "thicknessFactor", 0);
    if (!(thickness >= 0)) fail_at(ext + "/thicknessFactor", "KHR_materials_volume: thicknessFactor must be >= 0");
    const double distance = v.Has("attenuationDistance") ? number(v, "attenuationDistance", 0)
                                                          : std::numeric_limits<double>::infinity();
    if (!(distance > 0))
        fail_at(ext + "/attenuationDistance", "KHR_materials_volume: attenuationDistance must be positive");
    double c[3] = {1, 1, 1};
    if (v.Has("attenuationColor")) {
        const tinygltf::Value& a = v.Get("attenuationColor");
        if (!a.IsArray() || a.ArrayLen() != 3)
            fail_at(ext + "/attenuationColor", "KHR_materials_volume: attenuationColor must be 3 numbers");
        for (int k = 0; k < 3; ++k) {
            c[k] = a.Get(k).GetNumberAsDouble();
            if (!(c[k] >= 0 && c[k] <= 1))
                fail_at(ext + "/attenuationColor", "KHR_materials_volume: attenuationColor must lie in [0, 1]");
        }
    }
    if (thickness == 0 || std::isinf(distance) || (c[0] == 1 && c[1] == 1 && c[2] == 1)) return;
    MediumDesc m;
    const auto sigma = [&](double x) { return float(-std::log(std::max(x, 1e-6)) / distance); };
    m.sigma_a = Color{sigma(c[0]), sigma(c[1]), sigma(c[2])};
    d.interior = m;
}

}  // namespace glint::gltf_detail
