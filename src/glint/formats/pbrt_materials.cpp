#include <fmt/core.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <numbers>

#include "glint/base/limits.h"
#include "glint/formats/pbrt_parser.h"
#include "glint/image/image_io.h"
#include "glint/materials/metals.h"
#include "glint/media/medium.h"

namespace glint::pbrt_detail {

// The slab of pbrt-v4's coated materials: thickness (0.01), albedo (0) and g (0) of its medium,
// maxdepth (10) and nsamples (1) of the random walks. Constants only (textures are refused by
// the getters, with the spot).
void Parser::layer(MaterialDesc& m, ParamList& pl) {
    const auto check = [&](const char* name, bool ok, const char* what) {
        if (!ok) diag_.error(pl.find(name)->loc, fmt::format("{}: {}", name, what));
        return ok;
    };
    if (auto v = get_float(pl, "thickness"); v && check("thickness", *v > 0 && std::isfinite(*v), "must be positive"))
        m.thickness = float(*v);
    if (auto v = get_color(pl, "albedo", false)) {
        m.layer_albedo = Color{std::clamp(v->r, 0.0f, 1.0f), std::clamp(v->g, 0.0f, 1.0f), std::clamp(v->b, 0.0f, 1.0f)};
    }
    if (auto v = get_float(pl, "g"); v && check("g", std::isfinite(*v), "must be a number"))
        m.g = float(std::clamp(*v, -0.999, 0.999));
    if (auto v = get_int(pl, "maxdepth"); v && check("maxdepth", *v >= 1 && *v <= 1000, "must be in [1, 1000]"))
        m.layer_depth = *v;
    if (auto v = get_int(pl, "nsamples"); v && check("nsamples", *v >= 1 && *v <= 100, "must be in [1, 100]"))
        m.layer_samples = *v;
}

std::optional<MaterialDesc> Parser::material(const Token& t, const std::string& type, ParamList& pl) {
    using K = MaterialDesc::Kind;
    MaterialDesc m;
    // pbrt's roughness: alpha = sqrt(r) when remapped (the default), r otherwise; glint's
    // roughness is sqrt(alpha).
    const auto roughness = [&](double fallback, const std::string& prefix = "") {
        const bool remap = get_bool(pl, "remaproughness").value_or(true);
        double r = fallback;
        if (auto v = get_float(pl, prefix + "roughness")) r = *v;
        const auto u = get_float(pl, prefix + "uroughness"), v = get_float(pl, prefix + "vroughness");
        if (u || v) {
            if (u && v && *u != *v) warn(pl.find(prefix + "uroughness")->loc, "anisotropic roughness not supported; using the mean");
            r = ((u ? *u : r) + (v ? *v : r)) / 2;
        }
        const double alpha = remap ? std::sqrt(std::max(0.0, r)) : std::max(0.0, r);
        return float(std::sqrt(alpha));
    };
    ignore(pl, {"displacement", "normalmap"}, "ignored (no bump or normal maps from pbrt files yet)");
    if (type == "diffuse") {
        m.kind = K::kDiffuse;
        m.color = get_texture(pl, "reflectance", false, 0.5f).value_or(TextureDesc{});
        if (!pl.find("reflectance")) m.color.value = Color{0.5f};
    } else if (type == "coateddiffuse") {
        m.kind = K::kCoated;  // pbrt-v4's layered BSDF: a diffuse base under a dielectric coat
        m.color = get_texture(pl, "reflectance", false, 0.5f).value_or(TextureDesc{});
        if (!pl.find("reflectance")) m.color.value = Color{0.5f};
        m.coat_roughness = roughness(0);
        if (auto eta = get_float(pl, "eta")) m.ior = float(*eta);
        layer(m, pl);
    } else if (type == "conductor" || type == "coatedconductor") {
        m.kind = K::kConductor;
        const std::string prefix = type == "coatedconductor" ? "conductor." : "";
        if (type == "coatedconductor") {
            m.kind = K::kCoated;  // a conductor base under a dielectric coat
            m.coated_conductor = true;
            m.coat_roughness = roughness(0, "interface.");
            if (auto eta = get_float(pl, "interface.eta")) m.ior = float(*eta);
            layer(m, pl);
        }
        if (pl.find("reflectance")) {
            m.reflectance = get_texture(pl, "reflectance", false, 1);
        } else {
            for (const MetalPreset& p : kMetals)
                if (p.name == "copper") m.eta = p.eta, m.k = p.k;  // pbrt's default conductor is copper
            if (const auto eta = get_color(pl, prefix + "eta", false)) m.eta = *eta;
            if (const auto k = get_color(pl, prefix + "k", false)) m.k = *k;
            // Spectral mode: the measured spectra (pbrt's default conductor: copper's).
            m.eta_spectrum = pl.find(prefix + "eta") ? get_spectrum(pl, prefix + "eta")
                                                      : std::make_shared<const Spectrum>(Spectrum::tabulated(*named_spectrum("metal-Cu-eta")));
            m.k_spectrum = pl.find(prefix + "k") ? get_spectrum(pl, prefix + "k")
                                                  : std::make_shared<const Spectrum>(Spectrum::tabulated(*named_spectrum("metal-Cu-k")));
        }
        m.roughness = roughness(0, prefix);
    } else if (type == "dielectric" || type == "thindielectric") {
        m.kind = K::kDielectric;
        m.thin = type == "thindielectric";
        if (pl.find("eta")) {
            const auto c = get_color(pl, "eta", false);
            m.ior = c ? c->g : 1.5f;
            m.ior_spectrum = get_spectrum(pl, "eta");  // a glass or a table: dispersion in spectral mode
            if (m.ior_spectrum) m.ior = (*m.ior_spectrum)(587.56f);
        }
        m.roughness = roughness(0);
    } else if (type == "interface") {
        m.kind = K::kInterface;
    } else if (type == "diffusetransmission") {
        m.kind = K::kDiffuseTransmission;
        const double scale = get_float(pl, "scale").value_or(1);
        const auto scaled = [&](const char* name) {
            TextureDesc d = get_texture(pl, name, false, 0.25f).value_or(TextureDesc{});
            if (!pl.find(name)) d.value = Color{0.25f};
            if (scale == 1) return d;
            if (d.kind == TextureDesc::Kind::kConstant) {
                d.value = d.value * float(scale);
                return d;
            }
            TextureDesc f, product;
            f.value = Color{float(scale)};
            product.kind = TextureDesc::Kind::kScale;
            product.children = {d, f};
            return product;
        };
        m.color = scaled("reflectance");
        m.transmittance = scaled("transmittance");
    } else if (type == "mix") {
        m.kind = K::kMix;
        Param* mats = pl.find("materials");
        if (!mats || mats->type != "string" || mats->strings.size() != 2) {
            diag_.error(mats ? mats->loc : t.loc(), "mix: needs \"string materials\" [ \"a\" \"b\" ]");
            if (mats) mats->used = true;
            return std::nullopt;
        }
        mats->used = true;
        for (const std::string& name : mats->strings) {
            const auto it = named_materials_.find(name);
            if (it == named_materials_.end()) {
                diag_.error(mats->loc, fmt::format("mix: unknown material \"{}\"", name));
                return std::nullopt;
            }
            m.mix.push_back({it->second, mats->loc});
        }
        if (pl.find("amount")) m.amount = get_texture(pl, "amount", true, 0.5f);
    } else {
        warn(t.loc(), fmt::format("material \"{}\" not supported; using diffuse 0.5", type));
        pl.use_all();
        m.kind = K::kDiffuse;
        m.color.value = Color{0.5f};
    }
    if (Param* p = pl.find("type")) p->used = true;  // MakeNamedMaterial's
    return m;
}

// Spectral mode's emission spectrum of a light parameter given as a black body or a spectrum
// (pbrt-v4 normalises both to a luminance of 1; the colour read by get_color has that luminance).
std::shared_ptr<const Spectrum> Parser::emission_spectrum(ParamList& pl, const std::string& name) {
    const Param* p = pl.find(name);
    if (!p) return nullptr;
    if (p->type == "blackbody" && p->numbers.size() == 1 && p->numbers[0] > 0)
        return std::make_shared<const Spectrum>(Spectrum::blackbody(float(p->numbers[0])).normalised_emission());
    if (p->type != "spectrum" || p->numbers.size() == 1) return nullptr;
    auto values = spectrum_values(*p, name, false);  // get_color reported any error
    if (!values) return nullptr;
    return std::make_shared<const Spectrum>(Spectrum::tabulated(std::move(*values)).normalised_emission());
}

// The spectrum of the light just added, if its colour parameter was one.
void Parser::light_spectrum(ParamList& pl, const std::string& name) {
    if (auto s = emission_spectrum(pl, name)) {
        d_.light_spectra.resize(d_.lights.size());
        d_.light_spectra.back() = std::move(s);
    }
}

void Parser::light(const Token& t, const std::string& type, ParamList pl) {
    float s = float(get_float(pl, "scale").value_or(1));
    // pbrt-v4's "power" (point, spot) and "illuminance" (distant, infinite) scale the given
    // colour so that the light emits that power or gives that illuminance (RGB colours keep
    // their own magnitude: pbrt normalises only the illuminant's spectrum).
    const auto target = [&](const char* name) -> std::optional<double> {
        const auto v = get_float(pl, name);
        if (v && !(*v > 0)) return std::nullopt;  // pbrt: non-positive means "not given"
        return v;
    };    const auto pt = [&](const char* name, D3 fallback) {
        const auto v = get_floats(pl, name, "point3", 3);
        return v && v->size() == 3 ? D3{(*v)[0], (*v)[1], (*v)[2]} : fallback;
    };
    const auto to_point = [](D3 p) { return Point3{Float(p[0]), Float(p[1]), Float(p[2])}; };
    if (type == "point") {
        if (const auto p = target("power")) s *= float(*p / (4 * std::numbers::pi));
        const Color I = get_color(pl, "I", true).value_or(Color{1}) * s;
        const D3 f = pt("from", {0, 0, 0});
        d_.lights.push_back(PointLight{to_point(gs_.ctm.point(f[0], f[1], f[2])), I});
        light_spectrum(pl, "I");
    } else if (type == "spot") {
        const D3 f = pt("from", {0, 0, 0}), to = pt("to", {0, 0, 1});
        const double cone = get_float(pl, "coneangle").value_or(30), delta = get_float(pl, "conedeltaangle").value_or(5);
        if (const auto p = target("power")) {  // the cone's solid angle, the falloff counted half
            const double to_rad = std::numbers::pi / 180, c_end = std::cos(cone * to_rad),
                         c_start = std::cos((cone - delta) * to_rad);
            s *= float(*p / (2 * std::numbers::pi * ((1 - c_start) + (c_start - c_end) / 2)));
        }
        const Color I = get_color(pl, "I", true).value_or(Color{1}) * s;
        const D3 wf = gs_.ctm.point(f[0], f[1], f[2]), wt = gs_.ctm.point(to[0], to[1], to[2]);
        const D3 dir = sub(wt, wf);
        if (!(len3(dir) > 0)) {
            diag_.error(t.loc(), "spot light: from and to are the same point");
            return;
        }
        const D3 u = unit3(dir);
        const double to_rad = std::numbers::pi / 180;
        SpotLight l{to_point(wf), Vector3{Float(u[0]), Float(u[1]), Float(u[2])}, I,
                    Float(std::cos(std::max(0.0, cone - delta) * to_rad)), Float(std::cos(cone * to_rad))};
        d_.lights.push_back(l);
        light_spectrum(pl, "I");
    } else if (type == "distant") {
        if (const auto e = target("illuminance")) s *= float(*e);
        const Color L = get_color(pl, "L", true).value_or(Color{1}) * s;
        const D3 f = pt("from", {0, 0, 0}), to = pt("to", {0, 0, 1});
        const D3 dir = gs_.ctm.vector(to[0] - f[0], to[1] - f[1], to[2] - f[2]);
        if (!(len3(dir) > 0)) {
            diag_.error(t.loc(), "distant light: from and to are the same point");
            return;
        }
        const D3 u = unit3(dir);
        d_.lights.push_back(DirectionalLight{Vector3{Float(u[0]), Float(u[1]), Float(u[2])}, L});
        light_spectrum(pl, "L");
    } else if (type == "infinite") {
        if (auto file = get_string(pl, "filename")) {
            // pbrt-v4's environment maps are square, equal-area octahedral images with +z at
            // their centre, oriented by the light's transform: resampled at load. (A 2:1 map
            // would be a pbrt-v3 lat-long one, which pbrt-v4 refuses; build says so.)
            EnvironmentDesc e;
            e.filename = {*file, pl.find("filename")->loc};  // build resolves it against the scene's folder
            e.scale = s;
            e.equal_area = true;
            const auto inv = gs_.ctm.inverse();
            if (inv) e.world_to_light = inv->to34();
            if (const auto illuminance = target("illuminance")) {  // computed from the map by build
                const D3 up = unit3(gs_.ctm.vector(0, 0, 1));
                e.illuminance = float(*illuminance);
                e.up = Vector3{Float(up[0]), Float(up[1]), Float(up[2])};
            }
            d_.environment = e;
        } else {
            if (const auto e = target("illuminance")) s *= float(*e / std::numbers::pi);  // E = pi L
            const Color L = get_color(pl, "L", true).value_or(Color{1}) * s;
            d_.background = ConstantBackground{L, emission_spectrum(pl, "L")};
        }
        ignore(pl, "portal", "\"portal\" ignored");
    } else {
        warn(t.loc(), fmt::format("light \"{}\" not supported; left out", type));
        pl.use_all();
    }
    check_unused(pl, "LightSource \"" + type + "\"");
}

void Parser::area_light(const Token& t, const std::string& type, ParamList pl) {
    if (type != "diffuse") {
        warn(t.loc(), fmt::format("area light \"{}\" not supported; the shapes do not emit", type));
        pl.use_all();
        return;
    }
    Emission e;
    e.radiance = get_color(pl, "L", true).value_or(Color{1}) * float(get_float(pl, "scale").value_or(1));
    e.two_sided = get_bool(pl, "twosided").value_or(false);
    e.spectrum = emission_spectrum(pl, "L");
    gs_.area_power.reset();
    if (const auto p = get_float(pl, "power"); p && *p > 0) gs_.area_power = Located<double>{*p, pl.find("power")->loc};
    ignore(pl, "filename", "image area lights not supported; using L");
    check_unused(pl, "AreaLightSource");
    gs_.area_light = e;
    gs_.area_light_loc = t.loc();
}

void Parser::texture(const Token& t, const std::string& name, const std::string& kind, const std::string& type,
                     ParamList pl) {
    if (kind != "spectrum" && kind != "float" && kind != "color" && kind != "rgb") {
        diag_.error(t.loc(), fmt::format("Texture \"{}\": the kind is \"spectrum\" or \"float\", not \"{}\"", name, kind));
        return;
    }
    const bool is_float = kind == "float";
    TextureEntry e;
    e.is_float = is_float;
    using K = TextureDesc::Kind;
    // pbrt-v4 reads a 2D mapping's parameters (uscale, vscale, udelta, vdelta, mapping) only
    // for textures looked up by (u, v): an image and a 2D checkerboard; elsewhere they are
    // unknown, as in pbrt-v4.
    double us = 1, vs = 1, ud = 0, vd = 0;
    // `deltas`: whether the texture applies udelta and vdelta (the checkerboard); elsewhere ignored.
    const auto uv_mapping = [&](bool deltas) {
        if (const auto mapping = get_string(pl, "mapping"); mapping && *mapping != "uv")
            warn(pl.find("mapping")->loc, fmt::format("texture \"{}\": mapping \"{}\" not supported; using uv", name, *mapping));
        for (const char* n : {"udelta", "vdelta"})
            if (!deltas) ignore(pl, n, fmt::format("texture \"{}\": \"{}\" ignored", name, n));
        us = get_float(pl, "uscale").value_or(1);
        vs = get_float(pl, "vscale").value_or(1);
        if (deltas) {
            ud = get_float(pl, "udelta").value_or(0);
            vd = get_float(pl, "vdelta").value_or(0);
        }
    };
    if (type == "imagemap") {
        uv_mapping(false);
        for (const char* quiet : {"filter", "maxanisotropy"})  // filtering is glint's own choice
            if (Param* p = pl.find(quiet)) p->used = true;
        ignore(pl, "invert", fmt::format("texture \"{}\": \"invert\" ignored", name));
        e.desc.kind = K::kImage;
        const auto file = get_string(pl, "filename");
        if (!file) {
            diag_.error(t.loc(), fmt::format("Texture \"{}\": imagemap needs \"string filename\"", name));
            return;
        }
        e.desc.filename = {*file, pl.find("filename")->loc};
        if (auto enc = get_string(pl, "encoding")) {
            if (*enc == "sRGB") e.desc.encoding = ImageEncoding::kSrgb;
            else if (*enc == "linear") e.desc.encoding = ImageEncoding::kLinear;
            else warn(pl.find("encoding")->loc, fmt::format("encoding \"{}\" not supported; using the file's", *enc));
        }
        if (auto wrap = get_string(pl, "wrap")) {
            if (*wrap == "clamp") e.desc.wrap = WrapMode::kClamp;
            else if (*wrap != "repeat") warn(pl.find("wrap")->loc, fmt::format("wrap \"{}\": using repeat", *wrap));
        }
        if (get_float(pl, "scale")) warn(pl.find("scale")->loc, "imagemap \"scale\" ignored");
        if (us != 1 || vs != 1) e.desc.uv_transform = {Float(us), 0, 0, 0, Float(vs), 0};
    } else if (type == "constant") {
        e.desc.kind = K::kConstant;
        e.desc = get_texture(pl, "value", is_float, 1).value_or(TextureDesc{});
    } else if (type == "scale") {
        e.desc.kind = K::kScale;
        e.desc.children.push_back(get_texture(pl, "tex", is_float, 1).value_or(TextureDesc{}));
        e.desc.children.push_back(get_texture(pl, "scale", true, 1).value_or(TextureDesc{}));
        if (!pl.find("tex")) e.desc.children[0].value = Color{1};
        if (!pl.find("scale")) e.desc.children[1].value = Color{1};
    } else if (type == "mix") {
        e.desc.kind = K::kMix;
        TextureDesc a = get_texture(pl, "tex1", is_float, 0).value_or(TextureDesc{});
        TextureDesc b = get_texture(pl, "tex2", is_float, 1).value_or(TextureDesc{});
        if (!pl.find("tex1")) a.value = Color{0};
        if (!pl.find("tex2")) b.value = Color{1};
        TextureDesc amount = get_texture(pl, "amount", true, 0.5f).value_or(TextureDesc{});
        if (!pl.find("amount")) amount.value = Color{0.5f};
        e.desc.children = {a, b, amount};
    } else if (type == "checkerboard") {
        e.desc.kind = K::kChecker;
        const auto constant = [&](const char* n, float fallback) {
            const auto tx = get_texture(pl, n, is_float, fallback);
            if (tx && tx->kind != K::kConstant) warn(pl.find(n)->loc, "checkerboard of textures: using constant colours");
            return tx && tx->kind == K::kConstant ? tx->value : Color{fallback};
        };
        const auto dim = get_int(pl, "dimension");
        double size = 1;
        if (dim && *dim == 3) {
            // pbrt-v4's 3D checker has cells of 1 in the texture's space, placed by the
            // transform at the Texture directive: a uniform scale s gives cells of s.
            const auto x = gs_.ctm.vector(1, 0, 0), y = gs_.ctm.vector(0, 1, 0), z = gs_.ctm.vector(0, 0, 1);
            size = len3(x);
            const bool uniform = std::abs(len3(y) - size) <= 1e-6 * size && std::abs(len3(z) - size) <= 1e-6 * size &&
                                 std::abs(x[0] * y[0] + x[1] * y[1] + x[2] * y[2]) <= 1e-6 * size * size;
            const auto o = gs_.ctm.point(0, 0, 0);
            if (!uniform || o[0] != 0 || o[1] != 0 || o[2] != 0 || !(size > 0))
                warn(t.loc(), "3D checkerboard: only a uniform scale of its space is applied");
            if (!(size > 0) || !std::isfinite(size)) size = 1;
        }
        e.desc.checker = CheckerTexture{Float(size), constant("tex1", 1), constant("tex2", 0)};
        if (dim && *dim != 2 && *dim != 3)
            warn(pl.find("dimension")->loc, fmt::format("checkerboard of dimension {}: using 2 (pbrt-v4 has 2 and 3)", *dim));
        if (!dim || *dim != 3) {
            // pbrt-v4's 2D checkerboard: cells of 1 over (s, t) = (uscale u + udelta, vscale v + vdelta).
            uv_mapping(true);
            CheckerTexture& c = e.desc.checker;
            c.on_uv = true;
            c.u_scale = Float(us);
            c.v_scale = Float(vs);
            c.u_offset = Float(ud);
            c.v_offset = Float(vd);
        }
    } else {
        warn(t.loc(), fmt::format("texture \"{}\" not supported; using a constant 0.5", type));
        pl.use_all();
        e.desc.kind = K::kConstant;
        e.desc.value = Color{0.5f};
    }
    check_unused(pl, "Texture \"" + name + "\"");
    textures_[name] = e;
}

void Parser::medium(const Token& t, const std::string& name, ParamList pl) {
    const auto type = get_string(pl, "type");
    if (!type) {
        diag_.error(t.loc(), fmt::format("MakeNamedMedium \"{}\": no \"string type\"", name));
        return;
    }
    media_.insert(name);
    if (*type == "uniformgrid") {
        // pbrt-v4's grid medium: nx x ny x nz density samples (x fastest) over the box [p0, p1]
        // of the medium's space, sample (i, j, k) at p0 + (p1 - p0) (i + 0.5, j + 0.5, k + 0.5) / n,
        // trilinear between samples: glint's voxel grid with that index-to-world transform.
        MediumDesc m;
        m.kind = MediumDesc::Kind::kGrid;
        const float sc = float(get_float(pl, "scale").value_or(1));
        m.sigma_a = get_color(pl, "sigma_a", false).value_or(Color{1}) * sc;
        m.sigma_s = get_color(pl, "sigma_s", false).value_or(Color{1}) * sc;
        m.g = float(get_float(pl, "g").value_or(0));
        if (!(std::abs(m.g) < 1)) diag_.error(pl.find("g")->loc, "g must be in (-1, 1)");
        const long long nx = get_int(pl, "nx").value_or(1), ny = get_int(pl, "ny").value_or(1),
                        nz = get_int(pl, "nz").value_or(1);
        const auto* density = get_floats(pl, "density", "float", 1);
        const auto pt = [&](const char* n, D3 fallback) {
            const auto v = get_floats(pl, n, "point3", 3);
            return v && v->size() == 3 ? D3{(*v)[0], (*v)[1], (*v)[2]} : fallback;
        };
        const D3 p0 = pt("p0", {0, 0, 0}), p1 = pt("p1", {1, 1, 1});
        for (const char* n : {"Le", "Lescale", "temperature", "temperaturecutoff", "temperaturescale"})
            ignore(pl, n, fmt::format("uniformgrid \"{}\": grid emission from pbrt files not supported; ignored", n));
        check_unused(pl, "MakeNamedMedium \"" + name + "\"");
        const SourceLoc at = pl.find("density") ? pl.find("density")->loc : t.loc();
        if (!density) {
            diag_.error(t.loc(), "uniformgrid: needs \"float density\"");
        } else if (nx < 1 || ny < 1 || nz < 1) {
            diag_.error(at, "uniformgrid: nx, ny, nz must be at least 1");
        } else if (double(nx) * double(ny) * double(nz) > double(limit(Limit::kGridVoxels))) {
            diag_.error(at, fmt::format("uniformgrid: {}", over_limit(Limit::kGridVoxels, static_cast<long long>(double(nx) * double(ny) * double(nz)))));
        } else if (static_cast<long long>(density->size()) != nx * ny * nz) {
            diag_.error(at, fmt::format("uniformgrid: {} density values for nx x ny x nz = {}", density->size(), nx * ny * nz));
        } else if (!(p1[0] > p0[0] && p1[1] > p0[1] && p1[2] > p0[2])) {
            diag_.error(pl.find("p1") ? pl.find("p1")->loc : t.loc(), "uniformgrid: p1 must exceed p0 on every axis");
        } else if (std::any_of(density->begin(), density->end(), [](double v) { return !(v >= 0) || !std::isfinite(v); })) {
            diag_.error(at, "uniformgrid: density values must be finite and non-negative");
        } else {
            const int ix = int(nx), iy = int(ny), iz = int(nz);
            m.inline_density = std::make_shared<const VoxelGrid>(VoxelGrid::from_function(
                {0, 0, 0}, {ix, iy, iz}, [&](int i, int j, int k) {
                    return float((*density)[(std::size_t(k) * std::size_t(iy) + std::size_t(j)) * std::size_t(ix) + std::size_t(i)]);
                }));
            // medium space -> world, then the box, then the half-voxel offset.
            M4 box;
            const double n3[3] = {double(nx), double(ny), double(nz)};
            for (int a = 0; a < 3; ++a) {
                const double step = (p1[a] - p0[a]) / n3[a];
                box.m[a][a] = step;
                box.m[a][3] = p0[a] + 0.5 * step;
            }
            const M4 to_world = gs_.ctm * box;
            if (const auto tr = to_world.affine() ? Transform::from(to_world.to34()) : std::nullopt) m.transform = *tr;
            else diag_.error(t.loc(), "uniformgrid: the medium's transform is singular or projective");
        }
        d_.media.push_back({name, m, t.loc()});
        return;
    }
    if (*type != "homogeneous") {
        warn(t.loc(), fmt::format("medium \"{}\" of type \"{}\" not supported; treated as empty", name, *type));
        pl.use_all();
        d_.media.push_back({name, MediumDesc{}, t.loc()});
        return;
    }
    MediumDesc m;
    const float sc = float(get_float(pl, "scale").value_or(1));
    m.sigma_a = get_color(pl, "sigma_a", false).value_or(Color{0.0011f, 0.0024f, 0.014f}) * sc;
    m.sigma_s = get_color(pl, "sigma_s", false).value_or(Color{2.55f, 3.21f, 3.77f}) * sc;
    m.emission = get_color(pl, "Le", true).value_or(Color{0}) * float(get_float(pl, "Lescale").value_or(1));
    m.g = float(get_float(pl, "g").value_or(0));
    if (!(std::abs(m.g) < 1)) diag_.error(pl.find("g")->loc, "g must be in (-1, 1)");
    ignore(pl, "preset", "named scattering presets are not known to glint; using sigma_a and sigma_s");
    check_unused(pl, "MakeNamedMedium \"" + name + "\"");
    d_.media.push_back({name, m, t.loc()});
}

}  // namespace glint::pbrt_detail
