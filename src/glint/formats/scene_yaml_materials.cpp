#include <fmt/core.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "glint/base/limits.h"
#include "glint/description/vocabulary.h"
#include "glint/formats/scene_yaml_parser.h"
#include "glint/materials/metals.h"

namespace glint::yaml_detail {

// A texture: a number (grey), a colour [r, g, b], or a map with a type.
std::optional<TextureDesc> SceneParser::texture(const YAML::Node& node) {
    TextureDesc t;
    if (node.IsScalar()) {
        const auto v = r_.number(node);
        if (!v) return std::nullopt;
        if (*v < 0) {
            r_.error(node, "colour components must be >= 0");
            return std::nullopt;
        }
        t.value = Color{static_cast<float>(*v)};
        return t;
    }
    if (node.IsSequence()) {
        const auto c = r_.color(node);
        if (!c) return std::nullopt;
        t.value = *c;
        return t;
    }
    const auto type =
        type_of(node, "texture", vocabulary_types("texture"));
    if (!type) return std::nullopt;
    if (*type == "vertex_color") {
        MapReader m(r_, node, "vertex_color texture", vocabulary_keys("texture", "vertex_color"));
        t.kind = TextureDesc::Kind::kVertexColor;
    } else if (*type == "constant") {
        MapReader m(r_, node, "constant texture", vocabulary_keys("texture", "constant"));
        const auto s = m.get("spectrum");
        if (!s) {
            assign(m.require("color"), t.value, color());
        } else if (m.has("color")) {
            r_.error(*s, "constant texture: give 'color' or 'spectrum', not both");
        } else if (const auto r = spectrum(*s)) {
            // A reflectance: at most 1 at every wavelength. RGB mode uses its colour under D65.
            int peak = 360;
            for (int l = 361; l <= 830; ++l)
                if ((*r)(float(l)) > (*r)(float(peak))) peak = l;
            if ((*r)(float(peak)) > 1 + 1e-6f) {
                r_.error(*s, fmt::format("constant texture: a reflectance spectrum is at most 1; it is {} at {} nm",
                                         (*r)(float(peak)), peak));
            } else {
                t.value = reflectance_rgb(*r);
                t.spectrum = std::make_shared<const Spectrum>(*r);
            }
        }
    } else if (*type == "checker") {
        t.kind = TextureDesc::Kind::kChecker;
        MapReader m(r_, node, "checker texture", vocabulary_keys("texture", "checker"));
        assign(m.get("size"), t.checker.size, positive("size"));
        assign(m.require("even"), t.checker.even, color());
        assign(m.require("odd"), t.checker.odd, color());
        if (const auto n = m.get("space")) {
            if (const auto uv = choice<bool>(*n, "space", {{"world", false}, {"uv", true}})) t.checker.on_uv = *uv;
        }
        // On uv: (s, t) = (u_scale u + u_offset, v_scale v + v_offset), pbrt-v4's uscale, udelta, ...
        const auto uv_pair = [&](const char* key, Float& a, Float& b) {
            const auto n = m.get(key);
            if (!n) return;
            if (!t.checker.on_uv) {
                r_.error(*n, fmt::format("checker texture: '{}' needs 'space: uv'", key));
            } else if (const auto p = r_.pair(*n, key)) {
                a = static_cast<Float>((*p)[0]);
                b = static_cast<Float>((*p)[1]);
            }
        };
        uv_pair("uv_scale", t.checker.u_scale, t.checker.v_scale);
        uv_pair("uv_offset", t.checker.u_offset, t.checker.v_offset);
    } else if (*type == "image") {
        t.kind = TextureDesc::Kind::kImage;
        MapReader m(r_, node, "image texture", vocabulary_keys("texture", "image"));
        if (const auto n = m.get("encoding")) {
            if (auto e = choice<ImageEncoding>(*n, "encoding",
                                               {{"auto", ImageEncoding::kAuto},
                                                {"srgb", ImageEncoding::kSrgb},
                                                {"linear", ImageEncoding::kLinear}}))
                t.encoding = *e;
        }
        // An image file, or its pixels in the scene itself (scene_yaml_pixels.cpp).
        if (const auto n = m.get("pixels")) {
            if (m.has("filename")) r_.error(*m.get("filename"), "image texture: give 'filename' or 'pixels', not both");
            else t.pixels = inline_image(*n, t.encoding);
        } else if (const auto f = m.require("filename")) {
            t.filename.loc = r_.loc(*f);
            assign(f, t.filename.value, [this](const YAML::Node& v) { return r_.string(v); });
        }
        if (const auto n = m.get("wrap")) {
            if (auto w = choice<WrapMode>(
                    *n, "wrap", {{"repeat", WrapMode::kRepeat}, {"clamp", WrapMode::kClamp}, {"mirror", WrapMode::kMirror}}))
                t.wrap = *w;
        }
        assign(m.get("size"), t.size, positive("size"));
    } else {
        const bool scale = *type == "scale";
        t.kind = scale ? TextureDesc::Kind::kScale : TextureDesc::Kind::kMix;
        const std::vector<std::string> parts =
            scale ? std::vector<std::string>{"texture", "factor"}
                  : std::vector<std::string>{"a", "b", "amount"};
        MapReader m(r_, node, fmt::format("{} texture", *type), vocabulary_keys("texture", *type));
        for (const std::string& part : parts) {
            const auto child_node = m.require(part);
            const auto child = child_node ? texture(*child_node) : std::nullopt;
            t.children.push_back(child.value_or(TextureDesc{}));
        }
    }
    return t;
}

MaterialDesc SceneParser::material(const YAML::Node& node, const std::string& context) {
    MaterialDesc d;
    if (!node.IsMap()) {
        r_.error(node, fmt::format("{}: expected a map of keys, got {}", context, describe(node)));
        return d;
    }
    const auto type = type_of(node, "material", vocabulary_types("material"), "article");
    if (!type) return d;
    if (*type == "interface") {
        d.kind = MaterialDesc::Kind::kInterface;
        MapReader m(r_, node, context, vocabulary_keys("material", "interface"));
        return d;
    }
    using K = MaterialDesc::Kind;
    if (*type == "article") d.kind = K::kArticle;
    if (*type == "diffuse") d.kind = K::kDiffuse;
    if (*type == "conductor") d.kind = K::kConductor;
    if (*type == "dielectric") d.kind = K::kDielectric;
    if (*type == "plastic") d.kind = K::kPlastic;
    if (*type == "diffuse_transmission") d.kind = K::kDiffuseTransmission;
    if (*type == "mix") d.kind = K::kMix;
    if (*type == "coated_diffuse" || *type == "coated_conductor") {
        d.kind = K::kCoated;
        d.coated_conductor = *type == "coated_conductor";
        d.color.value = Color{0.5f};  // pbrt-v4's coateddiffuse reflectance
    }
    if (*type == "pbr") {
        d.kind = K::kPbr;
        d.roughness = 0.5f;
    }
    MapReader m(r_, node, context, vocabulary_keys("material", *type));
    const auto tex = [&](const char* key) {
        if (auto n = m.get(key)) {
            if (auto t = texture(*n)) d.color = *t;
        }
    };
    const auto unit = [this](const char* what) {
        return [this, what](const YAML::Node& v) { return r_.number_in(v, what, 0, 1); };
    };
    tex("color");
    tex("albedo");
    tex("base_color");
    if (d.kind == K::kDiffuseTransmission) {
        d.color.value = Color{0.25f};
        d.transmittance = TextureDesc{};
        d.transmittance->value = Color{0.25f};
        if (auto n = m.get("reflectance"))
            if (auto t = texture(*n)) d.color = *t;
        if (auto n = m.get("transmittance"))
            if (auto t = texture(*n)) d.transmittance = *t;
    }
    if (d.kind == K::kMix) {
        if (auto n = m.require("materials")) {
            if (!n->IsSequence() || n->size() != 2) {
                r_.error(*n, fmt::format("{}: 'materials' is a list of two material names", context));
            } else {
                for (std::size_t i = 0; i < 2; ++i)
                    if (auto name = r_.string((*n)[i])) d.mix.push_back({*name, r_.loc((*n)[i])});
            }
        }
        if (auto n = m.get("amount"))
            if (auto t = texture(*n)) d.amount = *t;
    }
    if (d.kind == K::kPbr) {  // glTF's clear coat, sheen and specular: numbers, colours or textures
        for (auto [key, slot] : {std::pair{"clearcoat", &d.clearcoat}, {"clearcoat_roughness", &d.clearcoat_roughness},
                                 {"sheen", &d.sheen}, {"sheen_roughness", &d.sheen_roughness},
                                 {"specular", &d.specular}, {"specular_color", &d.specular_color}})
            if (auto n = m.get(key))
                if (auto t = texture(*n)) *slot = *t;
    }
    assign(m.get("shininess"), d.shininess, unit("shininess"));
    assign(m.get("roughness"), d.roughness, unit("roughness"));
    if (d.kind == K::kCoated) {
        // A coated diffuse's roughness is its coat's; a coated conductor's is the metal's.
        if (!d.coated_conductor) std::swap(d.roughness, d.coat_roughness);
        assign(m.get("coat_roughness"), d.coat_roughness, unit("coat_roughness"));
        assign(m.get("thickness"), d.thickness, [this](const YAML::Node& v) {
            return r_.number_in(v, "thickness", 0, 1e30, true);
        });
        assign(m.get("layer_albedo"), d.layer_albedo, color());
        assign(m.get("g"), d.g, [this](const YAML::Node& v) { return r_.number_in(v, "g", -0.999, 0.999); });
        assign(m.get("max_depth"), d.layer_depth, [this](const YAML::Node& v) { return r_.integer_in(v, "max_depth", 1, 1000); });
        assign(m.get("samples"), d.layer_samples, [this](const YAML::Node& v) { return r_.integer_in(v, "samples", 1, 100); });
    }
    assign(m.get("metallic"), d.metallic, unit("metallic"));
    assign(m.get("transmission"), d.transmission, unit("transmission"));
    if (const auto n = m.get("ior")) {
        ior(*n, d);
        if (d.ior_spectrum && d.kind != K::kDielectric && d.kind != K::kPbr)
            r_.error(*n, fmt::format("{}: a dispersive 'ior' (a glass or Sellmeier's coefficients) is for a dielectric or pbr", context));
    }
    if (const auto n = m.get("abbe")) {
        // Cauchy's dispersion through the index at 587.56 nm and the Abbe number.
        if (!m.has("ior") || d.ior_spectrum) {
            r_.error(*n, fmt::format("{}: 'abbe' goes with a number 'ior' (the index at 587.56 nm)", context));
        } else if (const auto v = r_.number_in(*n, "abbe", 1, 1000)) {
            d.ior_spectrum = std::make_shared<const Spectrum>(Spectrum::from_abbe(d.ior, float(*v)));
        }
    }
    assign(m.get("thin"), d.thin, [this](const YAML::Node& v) { return r_.boolean(v); });
    assign(m.get("tint"), d.tint, color());
    assign(m.get("emission"), d.emission.radiance, color());
    if (const auto n = m.get("emission_spectrum")) {
        if (!m.has("emission")) r_.error(*n, fmt::format("{}: 'emission_spectrum' goes with an 'emission' (its strength)", context));
        else d.emission.spectrum = emitter_spectrum(*n, d.emission.radiance);
    }
    assign(m.get("two_sided"), d.emission.two_sided,
           [this](const YAML::Node& v) { return r_.boolean(v); });
    if (const auto n = m.get("normal_map")) {
        if (auto t = texture(*n)) {
            // A normal map holds directions, not colours: an image is read as stored unless told.
            if (t->kind == TextureDesc::Kind::kImage && t->encoding == ImageEncoding::kAuto)
                t->encoding = ImageEncoding::kLinear;
            d.normal_map = std::move(*t);
        }
    }
    assign(m.get("normal_scale"), d.normal_scale, [this](const YAML::Node& v) {
        return r_.number_in(v, "normal_scale", 0, 100);
    });
    if (m.has("normal_scale") && !m.has("normal_map"))
        r_.error(node, fmt::format("{}: 'normal_scale' goes with a 'normal_map'", context));
    if (d.kind == K::kConductor || (d.kind == K::kCoated && d.coated_conductor)) {
        const auto metal = m.get("metal");
        const auto eta = m.get("eta"), k = m.get("k"), reflectance = m.get("reflectance");
        const int forms = (metal ? 1 : 0) + (eta || k ? 1 : 0) + (reflectance ? 1 : 0);
        if (forms > 1) {
            r_.error(node, fmt::format("{}: give one of 'metal', 'eta' and 'k', or "
                                       "'reflectance'", context));
        }
        if (metal) {
            if (const auto name = r_.string(*metal)) {
                const auto it = std::find_if(kMetals.begin(), kMetals.end(),
                                             [&](const MetalPreset& p) { return p.name == *name; });
                if (it == kMetals.end()) {
                    std::vector<std::string> names;
                    for (const auto& p : kMetals) names.emplace_back(p.name);
                    const std::string guess = closest_match(*name, names);
                    r_.error(*metal, fmt::format("unknown metal '{}'{} (known: {})", *name,
                                                 guess.empty() ? "" : fmt::format("; did you mean '{}'?", guess),
                                                 join(names)));
                } else {
                    d.eta = it->eta;
                    d.k = it->k;
                    // Spectral mode: the measured index where glint has its table.
                    static constexpr std::pair<std::string_view, std::string_view> kMeasured[] = {
                        {"silver", "Ag"}, {"aluminium", "Al"}, {"gold", "Au"}, {"copper", "Cu"}};
                    for (const auto& [glint_name, element] : kMeasured) {
                        if (*name != glint_name) continue;
                        const auto named = [](std::string n) {
                            Spectrum s = Spectrum::tabulated(*named_spectrum(n));
                            s.set_name(std::move(n));
                            return std::make_shared<const Spectrum>(std::move(s));
                        };
                        d.eta_spectrum = named(fmt::format("metal-{}-eta", element));
                        d.k_spectrum = named(fmt::format("metal-{}-k", element));
                    }
                }
            }
        } else if (eta || k) {
            if (!(eta && k)) r_.error(node, fmt::format("{}: 'eta' and 'k' go together", context));
            // Each a colour [r, g, b], or a spectrum (a name such as metal-Au-eta, [nm, value, ...])
            // read as it is in spectral mode; RGB mode's stand-in is a named metal's preset or the
            // values at 650, 550 and 450 nm.
            const auto part = [&](const std::optional<YAML::Node>& n, Color& rgb, std::shared_ptr<const Spectrum>& out) {
                if (!n) return;
                if (n->IsSequence() && n->size() == 3) return assign(n, rgb, color());
                if (auto s = spectrum(*n)) {
                    const Color* named = named_metal_rgb(s->name());
                    rgb = named ? *named : Color{(*s)(650), (*s)(550), (*s)(450)};
                    out = std::make_shared<const Spectrum>(std::move(*s));
                }
            };
            part(eta, d.eta, d.eta_spectrum);
            part(k, d.k, d.k_spectrum);
        } else if (reflectance) {
            if (auto t = texture(*reflectance)) d.reflectance = *t;
        } else {
            TextureDesc white;  // no form given: a perfect mirror-white metal
            white.value = Color{1};
            d.reflectance = white;
        }
    }
    return d;
}

// A dielectric's index: a number, a glass pbrt-v4 names ("glass-BK7", ...: a measured table), or
// {sellmeier: [B1, B2, B3, C1, C2, C3]} (C in square micrometres). The number RGB mode uses is
// the index at 587.56 nm (the helium d line glass catalogues quote).
void SceneParser::ior(const YAML::Node& n, MaterialDesc& d) {
    constexpr float kLambdaD = 587.56f;
    const auto set = [&](Spectrum s) {
        // In (0, 10] over the whole visible range (a Sellmeier resonance inside it is refused).
        for (float l = kLambdaMin; l <= kLambdaMax; l += 1) {
            const float v = l == kLambdaMin ? s(kLambdaD) : s(l);
            const float at = l == kLambdaMin ? kLambdaD : l;
            if (!(v > 0 && v <= 10)) {
                r_.error(n, fmt::format("ior: the index at {} nm is {}; it must be in (0, 10] from 360 to 830 nm", at, v));
                return;
            }
        }
        const float nd = s(kLambdaD);
        d.ior = nd;
        d.ior_spectrum = std::make_shared<const Spectrum>(std::move(s));
    };
    if (n.IsMap()) {
        MapReader m(r_, n, "ior", {"sellmeier"});
        if (!m.valid()) return;
        const auto c = m.require("sellmeier");
        if (!c) return;
        if (!c->IsSequence() || c->size() != 6) {
            r_.error(*c, "sellmeier: expected 6 numbers [B1, B2, B3, C1, C2, C3]");
            return;
        }
        float b[3], cc[3];
        for (std::size_t i = 0; i < 6; ++i) {
            const auto v = r_.number_in((*c)[i], "sellmeier coefficient", 0, 1e6);
            if (!v) return;
            (i < 3 ? b[i] : cc[i - 3]) = float(*v);
        }
        set(Spectrum::sellmeier(b, cc));
        return;
    }
    if (n.IsScalar() && !n.Scalar().empty() && std::isalpha(static_cast<unsigned char>(n.Scalar()[0]))) {
        const std::string name = n.Scalar();
        if (name.rfind("glass-", 0) == 0) {
            if (const PiecewiseLinearSpectrum* s = named_spectrum(name)) {
                Spectrum t = Spectrum::tabulated(*s);
                t.set_name(name);
                set(std::move(t));
                return;
            }
        }
        std::vector<std::string> glasses;
        for (const std::string_view g : named_spectrum_names())
            if (g.rfind("glass-", 0) == 0) glasses.emplace_back(g);
        const std::string guess = closest_match(name, glasses);
        r_.error(n, fmt::format("ior: unknown glass '{}'{} (known: {})", name,
                                guess.empty() ? "" : fmt::format("; did you mean '{}'?", guess), join(glasses)));
        return;
    }
    if (const auto v = r_.number_in(n, "ior", 0, 10, true)) d.ior = float(*v);
}

void SceneParser::materials(const YAML::Node& node, std::vector<NamedMaterial>& out) {
    if (!node.IsMap()) {
        r_.error(node, fmt::format("materials: expected a map from names to materials, got {}",
                                   describe(node)));
        return;
    }
    for (auto it = node.begin(); it != node.end(); ++it) {
        const auto name = r_.string(it->first);
        if (!name) continue;
        const bool duplicate = std::any_of(out.begin(), out.end(), [&](const NamedMaterial& m) {
            return m.name == *name;
        });
        if (duplicate) {
            r_.error(it->first, fmt::format("materials: duplicate material name '{}'", *name));
            continue;
        }
        if (*name == "interface") {
            r_.error(it->first, "materials: 'interface' is the built-in material of surfaces that "
                                "only bound a medium; choose another name");
            continue;
        }
        out.push_back({*name, material(it->second, fmt::format("material '{}'", *name)),
                       r_.loc(it->first)});
    }
}

MaterialRef SceneParser::material_ref(const YAML::Node& node) {
    if (node.IsScalar() && node.Scalar() == "interface") {
        MaterialDesc d;
        d.kind = MaterialDesc::Kind::kInterface;
        return {d, r_.loc(node)};
    }
    if (node.IsScalar()) return {node.Scalar(), r_.loc(node)};
    return {material(node, "material"), r_.loc(node)};
}

// The coefficients of a medium: sigma_a and sigma_s, or the artist's albedo, density and
// scale (sigma_s = albedo density scale, sigma_a = (1 - albedo) density scale).
void SceneParser::coefficients(MapReader& m, const YAML::Node& node, const std::string& context, MediumDesc& d) {
    const auto sa = m.get("sigma_a"), ss = m.get("sigma_s");
    const auto albedo = m.get("albedo"), density = m.get("density"), scale = m.get("scale");
    const bool physical = sa || ss, artist = albedo || density || scale;
    if (physical && artist) {
        r_.error(node, fmt::format("{}: give 'sigma_a' and 'sigma_s', or 'albedo', 'density' and "
                                   "'scale', not both", context));
        return;
    }
    if (physical) {
        assign(sa, d.sigma_a, color());
        assign(ss, d.sigma_s, color());
        return;
    }
    Color a{1};
    double k = 1, f = 1;
    if (albedo) {
        std::optional<Color> c;
        if (!albedo->IsScalar()) c = r_.color(*albedo);
        else if (const auto v = r_.number(*albedo)) c = Color{static_cast<float>(*v)};
        if (c) {
            if (!(c->max_component() <= 1 && c->r >= 0 && c->g >= 0 && c->b >= 0))
                r_.error(*albedo, fmt::format("{}: albedo must be in [0, 1]", context));
            else a = *c;
        }
    }
    assign(density, k, [this](const YAML::Node& v) { return r_.number_in(v, "density", 0, kInf); });
    assign(scale, f, [this](const YAML::Node& v) { return r_.number_in(v, "scale", 0, kInf); });
    const float sigma_t = static_cast<float>(k * f);
    d.sigma_s = a * sigma_t;
    d.sigma_a = (Color{1} - a) * sigma_t;
}

MediumDesc SceneParser::medium(const YAML::Node& node, const std::string& context) {
    MediumDesc d;
    const auto type = type_of(node, "medium", vocabulary_types("medium"));
    if (!type) return d;
    if (*type == "grid") d.kind = MediumDesc::Kind::kGrid;
    MapReader m(r_, node, context, vocabulary_keys("medium", *type));
    coefficients(m, node, context, d);
    if (const auto g = m.get("g")) {
        if (const auto v = r_.number(*g)) {
            if (!(std::abs(*v) < 1)) r_.error(*g, fmt::format("{}: g must lie in (-1, 1), got {}", context, *v));
            else d.g = static_cast<float>(*v);
        }
    }
    assign(m.get("emission"), d.emission, color());
    if (d.kind == MediumDesc::Kind::kGrid) {
        const auto voxels = m.get("voxels");
        if (voxels) {  // the density in the scene itself, not a file
            for (const char* k : {"file", "grid", "emission_grid", "temperature_grid"})
                if (m.has(k)) r_.error(*m.get(k), fmt::format("{}: '{}' names a grid in a file; with 'voxels' give none", context, k));
        } else {
            for (const char* k : {"min", "max"})
                if (m.has(k)) r_.error(*m.get(k), fmt::format("{}: '{}' places 'voxels', which are not given", context, k));
            if (const auto f = m.require("file")) d.file = located_name(*f);
        }
        if (const auto g = m.get("grid")) d.density_grid = located_name(*g);
        const auto eg = m.get("emission_grid"), tg = m.get("temperature_grid");
        if (eg && tg) {
            r_.error(*tg, fmt::format("{}: give 'emission_grid' or 'temperature_grid', not both", context));
        } else if (eg) {
            d.emission_kind = MediumDesc::Emission::kGrid;
            d.emission_grid = located_name(*eg);
            if (!m.has("emission")) d.emission = Color{1};
        } else if (tg) {
            d.emission_kind = MediumDesc::Emission::kTemperature;
            d.emission_grid = located_name(*tg);
        }
        if (m.has("emission") && !eg) {
            r_.error(*m.get("emission"), fmt::format("{}: 'emission' is the colour of an 'emission_grid', "
                                                     "which is not given", context));
        }
        assign(m.get("emission_scale"), d.emission_scale, [this](const YAML::Node& v) {
            return r_.number_in(v, "emission_scale", 0, kInf);
        });
        assign(m.get("temperature_scale"), d.temperature_scale, [this](const YAML::Node& v) {
            return r_.number_in(v, "temperature_scale", 0, kInf);
        });
        if (const auto t = m.get("transform")) d.transform = transform(*t);
        if (voxels) inline_voxels(m, *voxels, d);
    }
    return d;
}

void SceneParser::media(const YAML::Node& node, std::vector<NamedMedium>& out) {
    if (!node.IsMap()) {
        r_.error(node, fmt::format("media: expected a map from names to media, got {}", describe(node)));
        return;
    }
    for (auto it = node.begin(); it != node.end(); ++it) {
        const auto name = r_.string(it->first);
        if (!name) continue;
        if (*name == "none") {
            r_.error(it->first, "media: 'none' means vacuum; choose another name");
            continue;
        }
        if (std::any_of(out.begin(), out.end(), [&](const NamedMedium& m) { return m.name == *name; })) {
            r_.error(it->first, fmt::format("media: duplicate medium name '{}'", *name));
            continue;
        }
        out.push_back({*name, medium(it->second, fmt::format("medium '{}'", *name)), r_.loc(it->first)});
    }
}

}  // namespace glint::yaml_detail
