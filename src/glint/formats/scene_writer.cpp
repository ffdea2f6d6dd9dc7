#include "glint/formats/scene_writer.h"
#include "glint/description/vocabulary.h"

#include "glint/assets/vdb.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <numbers>

#include "glint/image/image_io.h"

namespace glint {

namespace {

// Floats as their shortest round-trip decimal form: the YAML file reads back the same bits.
std::string num(float v) { return fmt::format("{}", v); }
std::string vec(float x, float y, float z) { return fmt::format("[{}, {}, {}]", num(x), num(y), num(z)); }
std::string vec(Point3 p) { return vec(p.x, p.y, p.z); }
std::string vec(Vector3 v) { return vec(v.x, v.y, v.z); }
std::string vec(Normal3 n) { return vec(n.x, n.y, n.z); }
std::string vec(Color c) { return vec(c.r, c.g, c.b); }

// A dielectric's index as the reader takes it: a number, a named glass, Sellmeier's
// coefficients, or a number with its Abbe number (after it, as `abbe`).
std::string dispersive_ior(const MaterialDesc& m) {
    const Spectrum* s = m.ior_spectrum.get();
    if (!s) return num(m.ior);
    const float* p = s->parameters();
    switch (s->kind()) {
        case Spectrum::Kind::kSellmeier:
            return fmt::format("{{sellmeier: [{}, {}, {}, {}, {}, {}]}}", num(p[0]), num(p[1]), num(p[2]), num(p[3]),
                               num(p[4]), num(p[5]));
        case Spectrum::Kind::kCauchy: {
            constexpr double l_f = 486.13, l_c = 656.27;
            const double v_d = (m.ior - 1) / (p[1] * (1 / (l_f * l_f) - 1 / (l_c * l_c)));
            return fmt::format("{}, abbe: {}", num(m.ior), num(float(v_d)));
        }
        default: return s->name().empty() ? num(m.ior) : s->name();
    }
}

// An emitter's spectrum as the reader takes it (the reader normalises it again).
std::string spectrum_yaml(const Spectrum& s) {
    if (s.kind() == Spectrum::Kind::kBlackbody) return fmt::format("{{blackbody: {}}}", num(s.kelvin()));
    if (!s.name().empty() && named_spectrum(s.name())) return s.name();  // not a file's name
    std::string out = "[";
    const auto& l = s.table().lambda();
    const auto& v = s.table().value();
    for (std::size_t i = 0; i < l.size(); ++i) out += fmt::format("{}{}, {}", i ? ", " : "", num(l[i]), num(v[i]));
    return out + "]";
}

// A metal's eta or k: its spectrum (measured, named) where it has one, else the colour.
std::string eta_k(Color rgb, const std::shared_ptr<const Spectrum>& s) { return s ? spectrum_yaml(*s) : vec(rgb); }

// YAML double-quoted string.
std::string yaml_quoted(const std::string& s) {
    std::string out = "\"";
    for (const char c : s) {
        if (c == '"' || c == '\\') out += '\\';
        out += c;
    }
    return out + "\"";
}

class Writer {
public:
    Writer(const SceneDescription& d, const std::filesystem::path& out) : d_(d), out_(out) {
        source_dir_ = std::filesystem::path(d.path).parent_path();
        out_dir_ = out.parent_path();
    }
    WrittenScene run();

private:
    // A file the source names relative to its own folder, named so that it resolves from the
    // YAML file's folder. Names that do not exist there (models found on the search path) stay.
    std::string file(const std::string& name) const {
        const std::filesystem::path p(name);
        if (p.is_absolute()) return name;
        const std::filesystem::path at = source_dir_ / p;
        std::error_code ec;
        if (!std::filesystem::exists(at, ec)) return name;
        const auto base = std::filesystem::absolute(out_dir_.empty() ? "." : out_dir_, ec);
        const auto rel = std::filesystem::relative(std::filesystem::absolute(at, ec), base, ec);
        return ec || rel.empty() ? std::filesystem::absolute(at).string() : rel.string();
    }
    std::string texture(const TextureDesc& t) const;
    std::string material(const MaterialDesc& m) const;
    std::string medium(const MediumDesc& m);
    std::string object(const ObjectDesc& o);

    const SceneDescription& d_;
    std::filesystem::path out_, source_dir_, out_dir_;
    WrittenScene result_;
    std::map<const TriangleMesh*, std::string> mesh_files_;
    int vdb_count_ = 0;
};

std::string Writer::texture(const TextureDesc& t) const {
    using K = TextureDesc::Kind;
    switch (t.kind) {
        case K::kConstant:
            return t.spectrum ? fmt::format("{{type: constant, spectrum: {}}}", spectrum_yaml(*t.spectrum)) : vec(t.value);
        case K::kChecker: {
            const CheckerTexture& c = t.checker;
            std::string s = fmt::format("{{type: checker, size: {}, even: {}, odd: {}", num(c.size), vec(c.even), vec(c.odd));
            if (c.on_uv) {
                s += ", space: uv";
                if (c.u_scale != 1 || c.v_scale != 1) s += fmt::format(", uv_scale: [{}, {}]", num(c.u_scale), num(c.v_scale));
                if (c.u_offset != 0 || c.v_offset != 0) s += fmt::format(", uv_offset: [{}, {}]", num(c.u_offset), num(c.v_offset));
            }
            return s + "}";
        }
        case K::kImage: {
            if (t.pixels) throw IoError("convert: image textures given as pixels are not written yet");
            std::string s = fmt::format("{{type: image, filename: {}", yaml_quoted(file(t.filename.value)));
            if (t.encoding == ImageEncoding::kSrgb) s += ", encoding: srgb";
            if (t.encoding == ImageEncoding::kLinear) s += ", encoding: linear";
            if (t.wrap == WrapMode::kClamp) s += ", wrap: clamp";
            if (t.uv_transform[0] != 1 && t.uv_transform[0] == t.uv_transform[4] && t.uv_transform[0] > 0)
                s += ", size: " + num(1 / t.uv_transform[0]);
            return s + "}";
        }
        case K::kScale:
            return fmt::format("{{type: scale, texture: {}, factor: {}}}", texture(t.children.at(0)), texture(t.children.at(1)));
        case K::kMix:
            return fmt::format("{{type: mix, a: {}, b: {}, amount: {}}}", texture(t.children.at(0)),
                               texture(t.children.at(1)), texture(t.children.at(2)));
        case K::kVertexColor: return "{type: vertex_color}";
    }
    return vec(t.value);
}

std::string Writer::material(const MaterialDesc& m) const {
    using K = MaterialDesc::Kind;
    std::string s;
    switch (m.kind) {
        case K::kArticle: s = fmt::format("type: article, color: {}, shininess: {}", texture(m.color), num(m.shininess)); break;
        case K::kDiffuse: s = fmt::format("type: diffuse, albedo: {}", texture(m.color)); break;
        case K::kConductor:
            s = m.reflectance ? fmt::format("type: conductor, reflectance: {}", texture(*m.reflectance))
                              : fmt::format("type: conductor, eta: {}, k: {}", eta_k(m.eta, m.eta_spectrum), eta_k(m.k, m.k_spectrum));
            s += ", roughness: " + num(m.roughness);
            break;
        case K::kDielectric:
            s = fmt::format("type: dielectric, ior: {}, roughness: {}", dispersive_ior(m), num(m.roughness));
            if (m.thin) s += ", thin: true";
            if (m.tint != Color{1}) s += ", tint: " + vec(m.tint);
            break;
        case K::kPlastic:
            s = fmt::format("type: plastic, albedo: {}, ior: {}, roughness: {}", texture(m.color), num(m.ior), num(m.roughness));
            break;
        case K::kPbr:
            s = fmt::format("type: pbr, base_color: {}, metallic: {}, roughness: {}, transmission: {}, ior: {}",
                            texture(m.color), num(m.metallic), num(m.roughness), num(m.transmission), dispersive_ior(m));
            for (const auto& [key, layer] : {std::pair{"clearcoat", &m.clearcoat}, {"clearcoat_roughness", &m.clearcoat_roughness},
                                             {"sheen", &m.sheen}, {"sheen_roughness", &m.sheen_roughness},
                                             {"specular", &m.specular}, {"specular_color", &m.specular_color}})
                if (*layer) s += fmt::format(", {}: {}", key, texture(**layer));
            break;
        case K::kInterface: s = "type: interface"; break;
        case K::kCoated:
            if (m.coated_conductor) {
                s = m.reflectance ? fmt::format("type: coated_conductor, reflectance: {}", texture(*m.reflectance))
                                  : fmt::format("type: coated_conductor, eta: {}, k: {}", eta_k(m.eta, m.eta_spectrum),
                                                eta_k(m.k, m.k_spectrum));
                s += fmt::format(", roughness: {}, coat_roughness: {}", num(m.roughness), num(m.coat_roughness));
            } else {
                s = fmt::format("type: coated_diffuse, albedo: {}, roughness: {}", texture(m.color), num(m.coat_roughness));
            }
            s += fmt::format(", ior: {}, thickness: {}, layer_albedo: {}, g: {}, max_depth: {}, samples: {}", num(m.ior),
                             num(m.thickness), vec(m.layer_albedo), num(m.g), m.layer_depth, m.layer_samples);
            break;
        case K::kDiffuseTransmission:
            s = fmt::format("type: diffuse_transmission, reflectance: {}, transmittance: {}", texture(m.color),
                            texture(m.transmittance.value_or(TextureDesc{})));
            break;
        case K::kMix:
            s = fmt::format("type: mix, materials: [{}, {}]", yaml_quoted(m.mix.at(0).value), yaml_quoted(m.mix.at(1).value));
            if (m.amount) s += ", amount: " + texture(*m.amount);
            break;
    }
    if (m.emission.emits()) {
        s += ", emission: " + vec(m.emission.radiance);
        if (m.emission.spectrum) s += ", emission_spectrum: " + spectrum_yaml(*m.emission.spectrum);
        if (m.emission.two_sided) s += ", two_sided: true";
    }
    if (m.normal_map) {
        s += ", normal_map: " + texture(*m.normal_map);
        if (m.normal_scale != 1) s += ", normal_scale: " + num(m.normal_scale);
    }
    return "{" + s + "}";
}

std::string transform_yaml(const Transform& t);

std::string Writer::medium(const MediumDesc& m) {
    std::string s = fmt::format("type: {}, sigma_a: {}, sigma_s: {}, g: {}",
                                m.kind == MediumDesc::Kind::kHomogeneous ? "homogeneous" : "grid", vec(m.sigma_a),
                                vec(m.sigma_s), num(m.g));
    if (m.kind == MediumDesc::Kind::kHomogeneous) {
        if (m.emission.max_component() > 0) s += ", emission: " + vec(m.emission);
        return "{" + s + "}";
    }
    if (m.emission_kind != MediumDesc::Emission::kNone)
        throw IoError("convert: grid media with emission are not written yet");
    if (m.inline_density) {  // a pbrt uniformgrid: its voxels into a .vdb beside the YAML file
        const std::string name = fmt::format("{}-medium-{}.vdb", out_.stem().string(), ++vdb_count_);
        write_vdb(out_dir_ / name, {{"density", m.inline_density.get()}}, 1.0f);  // index space = the file's space
        result_.meshes.push_back(out_dir_ / name);
        s += ", file: " + yaml_quoted(name);
    } else {
        s += fmt::format(", file: {}, grid: {}", yaml_quoted(file(m.file.value)), yaml_quoted(m.density_grid.value));
    }
    if (m.transform) s += ", transform: " + transform_yaml(*m.transform);
    return "{" + s + "}";
}

std::string transform_yaml(const Transform& t) {
    const auto& m = t.to_world.m;
    return fmt::format("{{matrix: [[{}, {}, {}, {}], [{}, {}, {}, {}], [{}, {}, {}, {}]]}}", num(m[0][0]), num(m[0][1]),
                       num(m[0][2]), num(m[0][3]), num(m[1][0]), num(m[1][1]), num(m[1][2]), num(m[1][3]), num(m[2][0]),
                       num(m[2][1]), num(m[2][2]), num(m[2][3]));
}

std::string Writer::object(const ObjectDesc& o) {
    std::string s = std::visit(
        [&](const auto& shape) -> std::string {
            using S = std::decay_t<decltype(shape)>;
            if constexpr (std::is_same_v<S, Sphere>) {
                return fmt::format("type: sphere, center: {}, radius: {}", vec(shape.center), num(shape.radius));
            } else if constexpr (std::is_same_v<S, Plane>) {
                return fmt::format("type: plane, point: {}, normal: {}", vec(shape.point), vec(shape.normal));
            } else if constexpr (std::is_same_v<S, Quad>) {
                return fmt::format("type: quad, corner: {}, edge1: {}, edge2: {}", vec(shape.corner), vec(shape.edge1),
                                   vec(shape.edge2));
            } else if constexpr (std::is_same_v<S, Disk>) {
                return fmt::format("type: disk, center: {}, normal: {}, radius: {}", vec(shape.center), vec(shape.normal),
                                   num(shape.radius));
            } else if constexpr (std::is_same_v<S, Triangle>) {
                return fmt::format("type: triangle, vertices: [{}, {}, {}]", vec(shape.p0), vec(shape.p1), vec(shape.p2));
            } else if constexpr (std::is_same_v<S, MeshFileDesc>) {
                return fmt::format("type: mesh, file: {}", yaml_quoted(file(shape.file.value)));
            } else {  // InlineMeshDesc: a PLY file beside the YAML file, once per mesh
                auto it = mesh_files_.find(shape.mesh.get());
                if (it == mesh_files_.end()) {
                    const std::string name =
                        fmt::format("{}-mesh-{}.ply", out_.stem().string(), mesh_files_.size() + 1);
                    write_ply(out_dir_ / name, *shape.mesh);
                    result_.meshes.push_back(out_dir_ / name);
                    it = mesh_files_.emplace(shape.mesh.get(), name).first;
                }
                return fmt::format("type: mesh, file: {}", yaml_quoted(it->second));
            }
        },
        o.shape);
    if (!std::holds_alternative<MeshFileDesc>(o.shape) || o.material_given) {
        if (const auto* name = std::get_if<std::string>(&o.material.value))
            s += ", material: " + yaml_quoted(*name);
        else
            s += ", material: " + material(std::get<MaterialDesc>(o.material.value));
    }
    if (o.alpha) {
        s += fmt::format(", alpha: {}, alpha_mode: {}", texture(o.alpha->texture), o.alpha->stochastic ? "blend" : "mask");
        if (!o.alpha->stochastic) s += ", alpha_cutoff: " + num(o.alpha->cutoff);
    }
    if (o.transform) s += ", transform: " + transform_yaml(*o.transform);
    if (o.interior) s += ", interior: " + yaml_quoted(o.interior->value);
    if (o.exterior) s += ", exterior: " + yaml_quoted(o.exterior->value);
    return "  - {" + s + "}\n";
}

WrittenScene Writer::run() {
    std::string y = fmt::format("# Converted by glint {} from {}\n", GLINT_VERSION, d_.path);
    if (const auto* c = std::get_if<LookAtCameraDesc>(&d_.camera)) {
        y += fmt::format("camera: {{type: look_at, from: {}, to: {}, up: {}, fov: {}", vec(c->from), vec(c->to), vec(c->up),
                         num(c->fov));
        if (c->aperture_radius > 0) y += ", aperture_radius: " + num(c->aperture_radius);
        if (c->focus_distance) y += ", focus_distance: " + num(*c->focus_distance);
        if (c->right_handed) y += ", handedness: right";
        if (c->orthographic) y += ", projection: orthographic, height: " + num(c->height);
        if (c->window)
            y += fmt::format(", window: [{}, {}, {}, {}]", num((*c->window)[0]), num((*c->window)[1]),
                             num((*c->window)[2]), num((*c->window)[3]));
        y += "}\n";
    } else {
        const auto& a = std::get<ArticleCameraDesc>(d_.camera);
        y += fmt::format("camera: {{type: article, position: {}, direction: {}, up: {}, viewport_height: {}, near: {}",
                         vec(a.position), vec(a.direction), vec(a.up), num(a.viewport_height), num(a.near));
        if (a.viewport_width) y += ", viewport_width: " + num(*a.viewport_width);
        if (a.aperture_radius > 0) y += ", aperture_radius: " + num(a.aperture_radius);
        if (a.focus_distance) y += ", focus_distance: " + num(*a.focus_distance);
        if (a.right_handed) y += ", handedness: right";
        y += "}\n";
    }
    const FilterDesc& f = d_.film.filter;
    std::string filter = fmt::format("{{type: {}, radius: {}", vocabulary_name(f.type), num(f.radius));
    if (f.type == FilterType::kGaussian) filter += ", sigma: " + num(f.sigma);
    y += fmt::format("film: {{width: {}, height: {}, filter: {}}}", d_.film.width.value, d_.film.height.value, filter + "}");
    if (!d_.film.filename.value.empty()) y.insert(y.size() - 1, ", filename: " + yaml_quoted(d_.film.filename.value));
    if (const auto& c = d_.film.crop_window)
        y.insert(y.size() - 1, fmt::format(", crop: [{}, {}, {}, {}]", num(c->value[0]), num(c->value[1]),
                                           num(c->value[2]), num(c->value[3])));
    if (const auto& p = d_.film.pixel_bounds)
        y.insert(y.size() - 1, fmt::format(", crop_pixels: [{}, {}, {}, {}]", p->value[0], p->value[1],
                                           p->value[2], p->value[3]));
    if (d_.film.scale != 1) y.insert(y.size() - 1, ", scale: " + num(d_.film.scale));
    const DisplaySettings& display = d_.film.display;
    if (display.encoding != Encoding::kSrgb) y.insert(y.size() - 1, fmt::format(", encoding: {}", vocabulary_name(display.encoding)));
    if (display.curve != ToneCurve::kClamp) y.insert(y.size() - 1, fmt::format(", tonemap: {}", vocabulary_name(display.curve)));
    if (display.exposure != 0) y.insert(y.size() - 1, ", exposure: " + num(display.exposure));
    if (d_.film.aovs) y.insert(y.size() - 1, ", aovs: true");
    if (d_.film.denoise) y.insert(y.size() - 1, ", denoise: true");
    y += "\n";
    y += fmt::format("sampler: {{type: {}, spp: {}, seed: {}", vocabulary_name(d_.sampler.type),
                     d_.sampler.spp.value, d_.sampler.seed);
    if (d_.sampler.noise_threshold > 0)
        y += fmt::format(", noise_threshold: {}, min_spp: {}", d_.sampler.noise_threshold, d_.sampler.min_spp);
    y += "}\n";
    if (d_.integrator.kind == IntegratorKind::kPath) {
        const PathSettings& p = d_.integrator.path;
        y += fmt::format("integrator: {{type: path, max_depth: {}", d_.integrator.max_depth.value);
        if (p.rr_depth != PathSettings{}.rr_depth) y += fmt::format(", rr_depth: {}", p.rr_depth);
        if (std::isfinite(p.clamp)) y += ", clamp: " + num(p.clamp);
        if (p.strategy != LightStrategy::kMis) y += fmt::format(", strategy: {}", vocabulary_name(p.strategy));
        if (p.light_sampler != LightSamplerKind::kBvh)
            y += fmt::format(", light_sampler: {}", vocabulary_name(p.light_sampler));
        if (p.texture_filter != TextureFilter::kEwa)
            y += fmt::format(", texture_filter: {}", vocabulary_name(p.texture_filter));
        if (p.spectral) y += ", spectral: true";
        if (p.white_balance > 0) y += ", white_balance: " + num(p.white_balance);
        y += "}\n";
    } else if (d_.integrator.kind == IntegratorKind::kFlat || d_.integrator.kind == IntegratorKind::kNormals) {
        y += fmt::format("integrator: {{type: {}}}\n", d_.integrator.kind == IntegratorKind::kFlat ? "flat" : "normals");
    } else
        y += fmt::format("integrator: {{type: whitted, ambient: {}, shadows: {}, max_depth: {}}}\n", num(d_.integrator.ambient),
                         d_.integrator.shadows, d_.integrator.max_depth.value);
    if (d_.environment && d_.environment->equal_area)
        throw IoError("convert: pbrt-v4's equal-area environment maps are not written yet (glint's YAML reads "
                      "latitude-longitude maps)");
    if (d_.environment) {
        y += fmt::format("background: {{type: environment, filename: {}, scale: {}}}\n", yaml_quoted(file(d_.environment->filename.value)),
                         num(d_.environment->scale));
    } else if (const auto* c = std::get_if<ConstantBackground>(&d_.background)) {
        y += fmt::format("background: {{type: constant, color: {}{}}}\n", vec(c->color),
                         c->spectrum ? ", spectrum: " + spectrum_yaml(*c->spectrum) : "");
    } else if (const auto* sky = std::get_if<SkyBackground>(&d_.background)) {
        y += fmt::format("background: {{type: sky, horizon: {}, zenith: {}}}\n", vec(sky->horizon), vec(sky->zenith));
    }
    if (!d_.lights.empty()) {
        y += "lights:\n";
        const auto deg = [](float c) { return num(float(std::acos(std::clamp(c, -1.0f, 1.0f)) * 180 / std::numbers::pi)); };
        for (std::size_t i = 0; i < d_.lights.size(); ++i) {
            const Light& l = d_.lights[i];
            const std::string spectrum =
                i < d_.light_spectra.size() && d_.light_spectra[i] ? ", spectrum: " + spectrum_yaml(*d_.light_spectra[i]) : "";
            if (const auto* p = std::get_if<PointLight>(&l)) {
                y += fmt::format("  - {{type: point, position: {}, intensity: {}{}}}\n", vec(p->position), vec(p->intensity), spectrum);
            } else if (const auto* s = std::get_if<SpotLight>(&l)) {
                y += fmt::format("  - {{type: spot, position: {}, direction: {}, intensity: {}, cone_angle: {}, falloff_start: {}{}}}\n",
                                 vec(s->position), vec(s->direction), vec(s->intensity), deg(s->cos_outer), deg(s->cos_inner),
                                 spectrum);
            } else if (const auto* dl = std::get_if<DirectionalLight>(&l)) {
                y += fmt::format("  - {{type: directional, direction: {}, intensity: {}", vec(dl->direction), vec(dl->intensity));
                if (dl->soft())
                    y += ", angular_diameter: " +
                         num(float(4 * std::asin(std::sqrt(dl->one_minus_cos / 2)) * 180 / std::numbers::pi));
                y += spectrum + "}\n";
            }
        }
    }
    if (!d_.media.empty()) {
        y += "media:\n";
        for (const NamedMedium& m : d_.media) y += fmt::format("  {}: {}\n", yaml_quoted(m.name), medium(m.medium));
    }
    if (d_.medium) y += "medium: " + yaml_quoted(d_.medium->value) + "\n";
    if (!d_.materials.empty()) {
        y += "materials:\n";
        for (const NamedMaterial& m : d_.materials) y += fmt::format("  {}: {}\n", yaml_quoted(m.name), material(m.material));
    }
    if (!d_.objects.empty()) {
        y += "objects:\n";
        for (const ObjectDesc& o : d_.objects) y += object(o);
    }
    result_.yaml = std::move(y);
    return std::move(result_);
}

}  // namespace

void write_ply(const std::filesystem::path& path, const TriangleMesh& mesh) {
    std::string header = "ply\nformat binary_little_endian 1.0\ncomment written by glint\n";
    header += fmt::format("element vertex {}\nproperty float x\nproperty float y\nproperty float z\n", mesh.positions.size());
    const bool normals = mesh.normals.size() == mesh.positions.size();
    const bool uvs = mesh.uvs.size() == mesh.positions.size();
    if (normals) header += "property float nx\nproperty float ny\nproperty float nz\n";
    if (uvs) header += "property float u\nproperty float v\n";
    header += fmt::format("element face {}\nproperty list uchar int vertex_indices\nend_header\n", mesh.triangle_count());
    std::string body;
    body.reserve(mesh.positions.size() * 32 + mesh.indices.size() * 5);
    const auto put = [&](const auto& v) {
        char b[sizeof v];
        std::memcpy(b, &v, sizeof v);
        body.append(b, sizeof v);
    };
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
        put(float(mesh.positions[i].x)), put(float(mesh.positions[i].y)), put(float(mesh.positions[i].z));
        if (normals) put(float(mesh.normals[i].x)), put(float(mesh.normals[i].y)), put(float(mesh.normals[i].z));
        if (uvs) put(float(mesh.uvs[i].x)), put(float(mesh.uvs[i].y));
    }
    for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
        put(std::uint8_t(3));
        for (int k = 0; k < 3; ++k) put(std::int32_t(mesh.indices[t + static_cast<std::size_t>(k)]));
    }
    std::ofstream out(path, std::ios::binary);
    out << header << body;
    out.close();
    if (!out) throw IoError(fmt::format("{}: cannot write: {}", path.string(), std::strerror(errno)));
}

WrittenScene write_scene_yaml(const SceneDescription& d, const std::filesystem::path& out) {
    return Writer(d, out).run();
}

}  // namespace glint
