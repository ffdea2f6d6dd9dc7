#include "glint/builder/build.h"

#include <fmt/core.h>

#include <filesystem>
#include <algorithm>
#include <array>
#include <functional>
#include <limits>
#include <map>
#include <cmath>
#include <cstdlib>
#include <type_traits>
#include <utility>

#include "glint/image/image_io.h"
#include "glint/base/limits.h"
#include "glint/assets/mesh_import.h"
#include "glint/assets/vdb.h"

namespace glint {

std::vector<std::filesystem::path> model_folders(const std::filesystem::path& scene_dir) {
    std::vector<std::filesystem::path> dirs{scene_dir.empty() ? "." : scene_dir};
    if (const char* env = std::getenv("GLINT_MODEL_PATH")) {
        for (auto& d : split_search_path(env)) dirs.push_back(std::move(d));
    }
    if (std::string(GLINT_DEFAULT_MODEL_DIR).size() > 0) dirs.emplace_back(GLINT_DEFAULT_MODEL_DIR);
    return dirs;
}

namespace {

const SourceLoc kCommandLine{"<command line>", 0, 0};

// The scene's array for each shape type; a shape without one is a compile error.
std::vector<Sphere>& shapes_of(Scene& s, const Sphere&) { return s.spheres; }
std::vector<Plane>& shapes_of(Scene& s, const Plane&) { return s.planes; }
std::vector<Quad>& shapes_of(Scene& s, const Quad&) { return s.quads; }
std::vector<Disk>& shapes_of(Scene& s, const Disk&) { return s.disks; }
std::vector<Triangle>& shapes_of(Scene& s, const Triangle&) { return s.triangles; }
ShapeKind kind_of(const Sphere&) { return ShapeKind::kSphere; }
ShapeKind kind_of(const Quad&) { return ShapeKind::kQuad; }
ShapeKind kind_of(const Disk&) { return ShapeKind::kDisk; }
ShapeKind kind_of(const Triangle&) { return ShapeKind::kTriangle; }

// A mesh file named in a scene: an absolute path as is; a relative one in the scene file's
// folder, then in each folder of $GLINT_MODEL_PATH (colon-separated), then in the models folder
// found at configure time (GLINT_DEFAULT_MODEL_DIR: ../shared/models beside the checkout).
struct FoundModel {
    std::optional<std::filesystem::path> path;
    std::string looked;
};
FoundModel find_model(const std::string& name, const std::filesystem::path& scene_dir) {
    const std::filesystem::path p = name;
    std::error_code ec;  // a name the system cannot check (too long) is not found
    if (p.is_absolute()) return {std::filesystem::exists(p, ec) ? std::optional(p) : std::nullopt, p.string()};
    const std::vector<std::filesystem::path> dirs = model_folders(scene_dir);
    FoundModel f;
    for (const auto& d : dirs) {
        f.looked += (f.looked.empty() ? "" : ", ") + d.string();
        if (std::filesystem::exists(d / p, ec)) {
            f.path = d / p;
            return f;
        }
    }
    return f;
}

// Whether the 3x3 part is a rotation times a uniform scale (what spheres and disks can take);
// the scale factor then.
std::optional<Float> similarity_scale(const Transform& t) {
    const auto& m = t.to_world.m;
    Vector3 c[3];
    for (int j = 0; j < 3; ++j) c[j] = {m[0][j], m[1][j], m[2][j]};
    const Float k2 = dot(c[0], c[0]);
    const Float tol = 1e-4f * k2;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            if (std::abs(dot(c[i], c[j]) - (i == j ? k2 : 0)) > tol) return std::nullopt;
    return std::sqrt(k2);
}

// An analytic shape under a transform; an error message when the shape cannot take it. Mirrors
// keep the front side (the normal is carried by the inverse transpose), so winding-defined
// shapes swap two edges.
std::optional<std::string> transform_shape(Sphere& s, const Transform& t) {
    const auto k = similarity_scale(t);
    if (!k) return "a sphere's transform must scale uniformly (rotate, translate, uniform scale)";
    s.center = t.point(s.center);
    s.radius *= *k;
    return std::nullopt;
}
std::optional<std::string> transform_shape(Plane& p, const Transform& t) {
    p.point = t.point(p.point);
    p.normal = normalize(t.normal(p.normal));
    return std::nullopt;
}
std::optional<std::string> transform_shape(Quad& q, const Transform& t) {
    Vector3 e1 = t.vector(q.edge1), e2 = t.vector(q.edge2);
    if (t.flips()) std::swap(e1, e2);
    const Point3 corner = t.point(q.corner);
    q = Quad::make(corner, e1, e2, q.material);
    return std::nullopt;
}
std::optional<std::string> transform_shape(Disk& d, const Transform& t) {
    const auto k = similarity_scale(t);
    if (!k) return "a disk's transform must scale uniformly (rotate, translate, uniform scale)";
    d.center = t.point(d.center);
    d.normal = normalize(t.normal(d.normal));
    d.radius *= *k;
    return std::nullopt;
}
std::optional<std::string> transform_shape(Triangle& tr, const Transform& t) {
    tr.p0 = t.point(tr.p0);
    tr.p1 = t.point(tr.p1);
    tr.p2 = t.point(tr.p2);
    if (t.flips()) std::swap(tr.p1, tr.p2);
    return std::nullopt;
}

// Adds textures and materials to the scene, loading each image file once.
class MaterialBuilder {
public:
    MaterialBuilder(Scene& scene, Diagnostics& diagnostics, std::filesystem::path scene_dir)
        : scene_(scene), diagnostics_(diagnostics), dir_(std::move(scene_dir)) {}

    MaterialId add_material(const MaterialDesc& d) {
        using K = MaterialDesc::Kind;
        const float alpha = d.roughness * d.roughness;
        switch (d.kind) {
            case K::kArticle:
                scene_.materials.push_back(ArticleMaterial{add_texture(d.color), d.shininess});
                break;
            case K::kDiffuse: scene_.materials.push_back(DiffuseMaterial{add_texture(d.color)}); break;
            case K::kConductor: {
                ConductorMaterial c{make_conductor(ConductorLobe::FresnelKind::kComplex, d.eta, d.k, alpha),
                                    std::nullopt, d.eta_spectrum, d.k_spectrum, nullptr};
                if (d.eta_spectrum && d.k_spectrum && !c.lobe.ggx.smooth()) {
                    // Spectral mode's multiple-scattering term: F_avg every 5 nm, read per hit.
                    std::vector<float> lambda, value;
                    for (float l = kLambdaMin; l <= kLambdaMax; l += 5) {
                        lambda.push_back(l);
                        value.push_back(make_conductor(ConductorLobe::FresnelKind::kComplex, Color{(*d.eta_spectrum)(l)},
                                                       Color{(*d.k_spectrum)(l)}, alpha).f_avg.r);
                    }
                    c.f_avg_spectrum = std::make_shared<const PiecewiseLinearSpectrum>(std::move(lambda), std::move(value));
                }
                if (d.reflectance) c.reflectance = add_texture(*d.reflectance);
                scene_.materials.push_back(c);
                break;
            }
            case K::kDielectric: {
                DielectricLobe lobe;
                lobe.eta = d.ior;
                lobe.ggx = Ggx{alpha};
                lobe.thin = d.thin;
                lobe.tint = d.tint;
                scene_.materials.push_back(DielectricMaterial{lobe, d.ior_spectrum});
                break;
            }
            case K::kPlastic:
                scene_.materials.push_back(
                    PlasticMaterial{add_texture(d.color), make_plastic(Color{0}, d.ior, alpha)});
                break;
            case K::kInterface: scene_.materials.push_back(InterfaceMaterial{}); break;
            case K::kCoated: {
                CoatedMaterial c;
                c.layer.eta = d.ior;
                c.layer.coat = Ggx{d.coat_roughness * d.coat_roughness};
                c.layer.conductor_base = d.coated_conductor;
                if (d.coated_conductor) {
                    // The metal's index relative to the coat it lies under, as pbrt-v4 takes it.
                    c.layer.metal = Ggx{alpha};
                    c.eta = d.eta / d.ior;
                    c.k = d.k / d.ior;
                    c.eta_spectrum = d.eta_spectrum;
                    c.k_spectrum = d.k_spectrum;
                    if (d.reflectance) c.reflectance = add_texture(*d.reflectance);
                } else {
                    c.base = add_texture(d.color);
                }
                c.layer.thickness = std::max(d.thickness, std::numeric_limits<float>::min());
                c.layer.albedo = d.layer_albedo;
                c.layer.g = d.g;
                c.layer.max_depth = d.layer_depth;
                c.layer.samples = d.layer_samples;
                scene_.materials.push_back(c);
                break;
            }
            case K::kDiffuseTransmission: {
                TextureDesc t;
                t.value = Color{0.25f};
                scene_.materials.push_back(DiffuseTransmissionMaterial{
                    add_texture(d.color), add_texture(d.transmittance.value_or(t))});
                break;
            }
            case K::kMix: {
                TextureDesc half;
                half.value = Color{0.5f};
                scene_.materials.push_back(MixMaterial{{0, 0}, add_texture(d.amount.value_or(half))});
                pending_mixes_.push_back({static_cast<MaterialId>(scene_.materials.size() - 1), d.mix, false});
                break;
            }
            case K::kPbr: {
                PbrMaterial p{add_texture(d.color), d.metallic, d.roughness, d.transmission, d.ior,
                              diffuse_fresnel_inside(d.ior), std::nullopt, {}, {}, {}, {}, {}, {}, d.ior_spectrum};
                if (d.metallic_roughness) p.metallic_roughness = add_texture(*d.metallic_roughness);
                const auto optional = [&](const std::optional<TextureDesc>& t) {
                    return t ? std::optional<TextureId>(add_texture(*t)) : std::nullopt;
                };
                p.clearcoat = optional(d.clearcoat);
                p.clearcoat_roughness = optional(d.clearcoat_roughness);
                p.sheen = optional(d.sheen);
                p.sheen_roughness = optional(d.sheen_roughness);
                p.specular = optional(d.specular);
                p.specular_color = optional(d.specular_color);
                scene_.materials.push_back(p);
                break;
            }
        }
        scene_.emission.resize(scene_.materials.size());
        scene_.emission.back() = d.emission;
        if (d.emission_map) scene_.emission.back().texture = add_texture(*d.emission_map);
        if (d.normal_map) {
            scene_.normal_maps.resize(scene_.materials.size());
            scene_.normal_maps.back() = NormalMap{add_texture(*d.normal_map), d.normal_scale};
        }
        if (d.interior) {  // an importer's medium inside every surface of this material
            scene_.media.push_back(HomogeneousMedium{d.interior->sigma_a, d.interior->sigma_s,
                                                     d.interior->emission, HgPhase{d.interior->g}});
            scene_.medium_interfaces.resize(scene_.materials.size());
            scene_.medium_interfaces.back() =
                MediumInterface{static_cast<MediumId>(scene_.media.size() - 1), scene_.camera_medium};
        }
        return static_cast<MaterialId>(scene_.materials.size() - 1);
    }

    /// Points the mixes added so far at their materials, by name (`names`: the named materials,
    /// whose ids are their indices). Unknown names, interface materials in a mix and mixes that
    /// contain themselves are errors.
    void resolve_mixes(const std::vector<std::string>& names) {
        for (PendingMix& p : pending_mixes_) {
            if (p.names.size() != 2) {
                diagnostics_.error(p.names.empty() ? SourceLoc{} : p.names[0].loc, "a mix material names two materials");
                continue;
            }
            auto& mix = std::get<MixMaterial>(scene_.materials[p.slot]);
            int found = 0;
            for (std::size_t i = 0; i < 2; ++i) {
                const auto it = std::find(names.begin(), names.end(), p.names[i].value);
                if (it == names.end()) {
                    const std::string guess = closest_match(p.names[i].value, names);
                    diagnostics_.error(p.names[i].loc, fmt::format("mix: unknown material '{}'{}", p.names[i].value,
                                                                   guess.empty() ? "" : fmt::format("; did you mean '{}'?", guess)));
                    continue;
                }
                const auto id = static_cast<MaterialId>(it - names.begin());
                if (std::holds_alternative<InterfaceMaterial>(scene_.materials[id]))
                    diagnostics_.error(p.names[i].loc, "mix: an interface material cannot be mixed (it is no surface)");
                mix.materials[i] = id;
                ++found;
            }
            p.resolved = found == 2;
        }
        // Cycles and depth: the longest chain of mixes below each one (Scene::surface_material
        // follows at most 16).
        std::map<MaterialId, int> depth;  // -1: being visited
        std::function<int(MaterialId)> chain = [&](MaterialId m) -> int {
            const auto* mix = std::get_if<MixMaterial>(&scene_.materials[m]);
            if (!mix) return 0;
            if (const auto it = depth.find(m); it != depth.end()) return it->second;
            depth[m] = -1;
            int deepest = 0;
            for (const MaterialId c : mix->materials) {
                const int d = chain(c);
                if (d < 0) return depth[m] = -1;
                deepest = std::max(deepest, d);
            }
            return depth[m] = deepest + 1;
        };
        for (const PendingMix& p : pending_mixes_) {
            if (!p.resolved) continue;
            const int d = chain(p.slot);
            if (d < 0) diagnostics_.error(p.names[0].loc, "mix: the mix contains itself");
            else if (d > 16) diagnostics_.error(p.names[0].loc, "mix: mixes nest more than 16 deep");
        }
        pending_mixes_.clear();
    }

    /// A slot of its own for material `m` with the media `mi` on its sides (the medium interface
    /// is part of the surface record: objects sharing a material may bound different media).
    MaterialId add_slot(MaterialId m, MediumInterface mi) {
        scene_.materials.push_back(scene_.materials[m]);
        const auto slot = static_cast<MaterialId>(scene_.materials.size() - 1);
        scene_.emission.resize(scene_.materials.size());
        scene_.emission[slot] = scene_.emission_of(m);
        if (m < scene_.normal_maps.size() && scene_.normal_maps[m]) {
            scene_.normal_maps.resize(scene_.materials.size());
            scene_.normal_maps[slot] = scene_.normal_maps[m];
        }
        scene_.medium_interfaces.resize(scene_.materials.size());
        scene_.medium_interfaces[slot] = mi;
        return slot;
    }

    /// The environment image: loaded linear (an HDR radiance map), relative to the scene file.
    /// Notes for the user go to `notes`.
    void set_environment(const EnvironmentDesc& e, std::vector<std::string>& notes) {
        const ImageId id = add_image(e.filename, ImageEncoding::kAuto);
        if (e.equal_area) {
            const Image& square = scene_.images[id];
            if (square.width == 2 * square.height) {  // a latitude-longitude map after all
                notes.push_back(fmt::format("{}:{}:{}: warning: {} is 2:1, read as a latitude-longitude map (y up, the "
                                             "light's transform not applied); pbrt-v4 expects square equal-area maps",
                                             e.filename.loc.file, e.filename.loc.line, e.filename.loc.column, e.filename.value));
                scene_.background = EnvironmentMap::make(square, e.scale);
                return;
            }
            if (square.width != square.height) {
                diagnostics_.error(e.filename.loc, fmt::format("{}: an equal-area environment map must be square, not {}x{}",
                                                               e.filename.value, square.width, square.height));
                return;
            }
            Image latlong = equal_area_to_latlong(square, e.world_to_light);
            float scale = e.scale;
            if (e.illuminance) {
                const double from_map = illuminance(latlong, e.up);
                if (from_map > 0) scale *= float(*e.illuminance / from_map);
            }
            scene_.background = EnvironmentMap::make(std::move(latlong), scale);
            return;
        }
        scene_.background = EnvironmentMap::make(scene_.images[id], e.scale);
    }

    /// An alpha mask for instances, its texture added.
    std::int32_t add_alpha(const AlphaDesc& a) {
        scene_.alpha_masks.push_back(AlphaMask{add_texture(a.texture), a.cutoff, a.stochastic});
        return static_cast<std::int32_t>(scene_.alpha_masks.size() - 1);
    }

private:
    // Children first, so a texture's ids always point at earlier entries (a tree, no cycles).
    TextureId add_texture(const TextureDesc& d) {
        Texture t = ConstantTexture{d.value, d.spectrum};
        switch (d.kind) {
            case TextureDesc::Kind::kConstant: break;
            case TextureDesc::Kind::kChecker: t = d.checker; break;
            case TextureDesc::Kind::kVertexColor: t = VertexColorTexture{d.alpha_channel}; break;
            case TextureDesc::Kind::kImage: {
                const ImageId image = d.pixels ? add_pixels(d.pixels) : add_image(d.filename, d.encoding);
                t = ImageTexture{image, d.wrap, d.size, d.wrap_v.value_or(d.wrap), d.uv_transform, d.uv_set, d.alpha_channel};
                break;
            }
            case TextureDesc::Kind::kScale:
                t = ScaleTexture{add_texture(d.children.at(0)), add_texture(d.children.at(1))};
                break;
            case TextureDesc::Kind::kMix:
                t = MixTexture{add_texture(d.children.at(0)), add_texture(d.children.at(1)),
                               add_texture(d.children.at(2))};
                break;
        }
        scene_.textures.push_back(t);
        return static_cast<TextureId>(scene_.textures.size() - 1);
    }

    // Texels an importer decoded already, each image once.
    ImageId add_pixels(const std::shared_ptr<const Image>& pixels) {
        if (const auto it = pixel_cache_.find(pixels.get()); it != pixel_cache_.end()) return it->second;
        scene_.images.push_back(*pixels);
        const auto id = static_cast<ImageId>(scene_.images.size() - 1);
        pixel_cache_.emplace(pixels.get(), id);
        return id;
    }

    // Relative paths are relative to the scene file's folder.
    ImageId add_image(const Located<std::string>& filename, ImageEncoding encoding) {
        std::filesystem::path path = filename.value;
        if (path.is_relative()) path = dir_ / path;
        const auto key = std::make_pair(path.lexically_normal().string(), encoding);
        if (const auto it = cache_.find(key); it != cache_.end()) return it->second;
        Image image;
        try {
            image = read_image(path, encoding);
        } catch (const IoError& e) {
            diagnostics_.error(filename.loc, e.what());
            image = Image{1, 1, {Color{0}}, {}};  // keeps ids valid; the build fails anyway
        }
        scene_.images.push_back(std::move(image));
        const auto id = static_cast<ImageId>(scene_.images.size() - 1);
        cache_.emplace(key, id);
        return id;
    }

    struct PendingMix {
        MaterialId slot;
        std::vector<Located<std::string>> names;
        bool resolved = false;
    };
    std::vector<PendingMix> pending_mixes_;
    Scene& scene_;
    Diagnostics& diagnostics_;
    std::filesystem::path dir_;
    std::map<std::pair<std::string, ImageEncoding>, ImageId> cache_;
    std::map<const Image*, ImageId> pixel_cache_;
};

// A command-line value wins over the file's; range errors point at whichever was used.
int pick(const Located<int>& from_file, const std::optional<long long>& flag, const char* what,
         long long lo, long long hi, Diagnostics& diagnostics) {
    if (!flag) return from_file.value;
    if (*flag < lo || *flag > hi) {
        diagnostics.error(kCommandLine,
                          fmt::format("--{} must be in [{}, {}], got {}", what, lo, hi, *flag));
        return from_file.value;
    }
    return static_cast<int>(*flag);
}

// A medium from its description; grid files are read here. Errors go to `diagnostics` (the
// medium is then left empty, keeping ids valid; the build fails anyway).
Medium make_medium(const MediumDesc& d, Diagnostics& diagnostics, const std::filesystem::path& scene_dir) {
    if (d.kind == MediumDesc::Kind::kHomogeneous)
        return HomogeneousMedium{d.sigma_a, d.sigma_s, d.emission, HgPhase{d.g}};
    GridMedium g;
    g.sigma_a = d.sigma_a;
    g.sigma_s = d.sigma_s;
    g.phase = HgPhase{d.g};
    if (d.inline_density) {  // pbrt's uniformgrid: the voxels came with the scene
        g.transform = d.transform.value_or(Transform{});
        g.density = *d.inline_density;
        g.majorant = MajorantGrid(g.density);
        return g;
    }
    std::filesystem::path path = d.file.value;
    if (path.is_relative()) path = scene_dir / path;
    // A grid of the file, its name and type checked first so that those errors point at the key
    // that names the grid.
    const auto read = [&](const Located<std::string>& name) -> std::optional<VdbGrid> {
        try {
            const auto grids = vdb_grids(path);
            const auto it = std::find_if(grids.begin(), grids.end(), [&](const auto& x) { return x.first == name.value; });
            const SourceLoc at = name.loc.line > 0 ? name.loc : d.file.loc;
            if (it == grids.end()) {
                std::vector<std::string> names;
                std::string known;
                for (const auto& x : grids) {
                    names.push_back(x.first);
                    known += fmt::format("{}{} ({})", known.empty() ? "" : ", ", x.first, x.second);
                }
                const std::string guess = closest_match(name.value, names);
                diagnostics.error(at, fmt::format("{}: no grid named '{}'{} (grids in the file: {})", d.file.value,
                                                  name.value, guess.empty() ? "" : fmt::format("; did you mean '{}'?", guess),
                                                  known.empty() ? "none" : known));
                return std::nullopt;
            }
            if (it->second != "float") {
                diagnostics.error(at, fmt::format("{}: grid '{}' holds {} values; glint reads float grids",
                                                  d.file.value, name.value, it->second));
                return std::nullopt;
            }
            return read_vdb_grid(path, name.value);
        } catch (const IoError& e) {
            diagnostics.error(d.file.loc, e.what());
            return std::nullopt;
        }
    };
    auto density = read(d.density_grid);
    if (!density) return g;
    g.transform = d.transform.value_or(Transform{}) * density->index_to_world;
    g.density = std::move(density->grid);
    g.majorant = MajorantGrid(g.density);
    if (d.emission_kind != MediumDesc::Emission::kNone) {
        auto e = read(d.emission_grid);
        if (!e) return g;
        if (!(e->index_to_world.to_world == density->index_to_world.to_world)) {
            diagnostics.error(d.emission_grid.loc,
                              fmt::format("{}: grid '{}' is placed by another voxel transform than density grid "
                                          "'{}'; glint needs them to share one", d.file.value,
                                          d.emission_grid.value, d.density_grid.value));
            return g;
        }
        g.emission = std::move(e->grid);
        g.emission_kind = d.emission_kind == MediumDesc::Emission::kGrid ? GridMedium::EmissionKind::kGrid
                                                                         : GridMedium::EmissionKind::kTemperature;
        g.emission_color = d.emission;
        g.emission_scale = d.emission_scale;
        g.temperature_scale = d.temperature_scale;
    }
    return g;
}

// The film's size and crop, the sampler, threads and display: limits first, since the render
// allocates per pixel.
void build_film(const SceneDescription& d, const Overrides& overrides, RenderJob& job, Diagnostics& diagnostics) {
    job.width = pick(d.film.width, overrides.width, "width", 1, kMaxFilmSide, diagnostics);
    job.height = pick(d.film.height, overrides.height, "height", 1, kMaxFilmSide, diagnostics);
    const long long pixels = static_cast<long long>(job.width) * job.height;
    const SourceLoc film_loc = overrides.width || overrides.height ? kCommandLine : d.film.width.loc;
    if (pixels > limit(Limit::kFilmPixels)) {
        diagnostics.error(film_loc, fmt::format("a film of {} x {}: {}", job.width, job.height,
                                                over_limit(Limit::kFilmPixels, pixels)));
    } else if (const std::string e = charge_memory(pixels * 64, "the film"); !e.empty()) {
        // 64 bytes a pixel: the progressive sums and sample counts, the film, the output image.
        diagnostics.error(film_loc, e);
    }
    job.film_width = job.width;
    job.film_height = job.height;
    if (d.film.crop_window || d.film.pixel_bounds) {
        std::array<long long, 4> b{};  // x0, x1, y0, y1
        SourceLoc loc;
        if (d.film.crop_window) {
            const auto& c = d.film.crop_window->value;
            loc = d.film.crop_window->loc;
            const auto edge = [](float f, int n) {
                return static_cast<long long>(std::ceil(static_cast<double>(std::clamp(f, 0.0f, 1.0f)) * n));
            };
            b = {edge(std::min(c[0], c[1]), job.width), edge(std::max(c[0], c[1]), job.width),
                 edge(std::min(c[2], c[3]), job.height), edge(std::max(c[2], c[3]), job.height)};
        } else {
            const auto& p = d.film.pixel_bounds->value;
            loc = d.film.pixel_bounds->loc;
            b = {std::clamp<long long>(p[0], 0, job.width), std::clamp<long long>(p[1], 0, job.width),
                 std::clamp<long long>(p[2], 0, job.height), std::clamp<long long>(p[3], 0, job.height)};
        }
        if (b[1] <= b[0] || b[3] <= b[2]) {
            diagnostics.error(loc, fmt::format("the crop holds no pixel of the {} x {} frame (pixels "
                                               "[{}, {}) x [{}, {}))",
                                               job.width, job.height, b[0], b[1], b[2], b[3]));
        } else {
            job.options.offset_x = static_cast<int>(b[0]);
            job.options.offset_y = static_cast<int>(b[2]);
            job.film_width = static_cast<int>(b[1] - b[0]);
            job.film_height = static_cast<int>(b[3] - b[2]);
        }
    }
    job.options.scale = d.film.scale;
    job.options.spp = pick(d.sampler.spp, overrides.spp, "spp", 1, kMaxSpp, diagnostics);
    job.options.seed = overrides.seed.value_or(d.sampler.seed);
    job.options.sampler = d.sampler.type;
    job.options.noise_threshold = static_cast<float>(d.sampler.noise_threshold);
    job.options.min_spp = std::min(d.sampler.min_spp, job.options.spp);
    if (overrides.threads) {
        if (*overrides.threads < 0 || *overrides.threads > kMaxThreads) {
            diagnostics.error(kCommandLine, fmt::format("--threads must be in [0, {}], got {}",
                                                        kMaxThreads, *overrides.threads));
        } else {
            job.options.threads = static_cast<int>(*overrides.threads);
        }
    }
    job.display = d.film.display;
    job.options.filter = d.film.filter;
    job.aovs = d.film.aovs || overrides.aovs;
    job.denoise = d.film.denoise || overrides.denoise;
    job.filename = d.film.filename.value;

}

Camera make_camera(const CameraDesc& desc, int width, int height) {
    Camera camera;
    if (const auto* a = std::get_if<ArticleCameraDesc>(&desc)) {
        const Float vw = a->viewport_width.value_or(a->viewport_height * static_cast<Float>(width) /
                                                    static_cast<Float>(height));
        camera = Camera(a->position, a->direction, a->up, vw, a->viewport_height, a->near, width, height);
        camera.set_lens(a->aperture_radius, a->focus_distance.value_or(a->near));
        if (a->right_handed) camera.make_right_handed(width);
    } else {
        const auto& l = std::get<LookAtCameraDesc>(desc);
        if (l.orthographic) {
            camera = Camera::orthographic(l.from, l.to - l.from, l.up, l.height, width, height);
        } else {
            camera = Camera::look_at(l.from, l.to, l.up, l.fov, width, height);
        }
        if (l.window) {
            const auto& w = *l.window;
            camera.set_window(w[0], w[1], w[2], w[3], width);
        }
        camera.set_lens(l.aperture_radius, l.focus_distance.value_or(length(l.to - l.from)));
        if (l.right_handed) camera.make_right_handed(width);
    }
    return camera;
}

void build_camera(const SceneDescription& d, RenderJob& job, Diagnostics& diagnostics) {
    job.camera = make_camera(d.camera, job.width, job.height);
    if (d.camera_motion.size() < 2) return;
    // A moving camera: its frame (right, up, view, position) at each key; what else changes
    // (the field of view, the lens) is the first key's.
    std::vector<Transform> frames;
    for (const CameraDesc& c : d.camera_motion) {
        const auto frame = make_camera(c, job.width, job.height).frame();
        if (!frame) {
            diagnostics.error(d.shutter_loc, "the camera's frame is degenerate at some time of the shutter");
            return;
        }
        frames.push_back(*frame);
    }
    job.camera.set_motion(Motion(std::move(frames)));
}

void build_integrator(const SceneDescription& d, const Overrides& overrides, RenderJob& job,
                      Diagnostics& diagnostics) {
    job.scene.light_sampling = LightSamplerKind::kPower;  // the other integrators sample no light
    if (overrides.spectral.value_or(false) && d.integrator.kind != IntegratorKind::kPath)
        diagnostics.error(kCommandLine, "--spectral: only the path tracer renders spectrally (this scene's integrator is not `path`)");
    switch (d.integrator.kind) {
        case IntegratorKind::kFlat: job.integrator = std::make_unique<FlatIntegrator>(); break;
        case IntegratorKind::kNormals: job.integrator = std::make_unique<NormalsIntegrator>(); break;
        case IntegratorKind::kWhitted: {
            WhittedSettings s;
            s.ambient = d.integrator.ambient;
            s.shadows = d.integrator.shadows;
            s.max_depth =
                pick(d.integrator.max_depth, overrides.max_depth, "max-depth", 0, kMaxDepth,
                     diagnostics);
            job.integrator = std::make_unique<WhittedIntegrator>(s);
            break;
        }
        case IntegratorKind::kPath: {
            PathSettings s = d.integrator.path;
            s.max_depth = pick(d.integrator.max_depth, overrides.max_depth, "max-depth", 0,
                               kMaxDepth, diagnostics);
            if (overrides.light_sampler) s.light_sampler = *overrides.light_sampler;
            job.scene.light_sampling = s.light_sampler;
            if (overrides.texture_filter) s.texture_filter = *overrides.texture_filter;
            job.texture_filter = s.texture_filter;
            if (overrides.spectral) s.spectral = *overrides.spectral;
            job.spectral = s.spectral;
            job.white_balance = s.white_balance;
            job.integrator = std::make_unique<PathIntegrator>(s);
            break;
        }
    }

}

// The scene's contents: media, then named materials (ids in file order), then objects; each mesh
// file imported once however many objects include it (their instances then share its meshes and
// its BVH).
class ContentsBuilder {
public:
    ContentsBuilder(const SceneDescription& d, RenderJob& job, Diagnostics& diagnostics)
        : d_(d), job_(job), scene_(job.scene), diagnostics_(diagnostics),
          scene_dir_(std::filesystem::path(d.path).parent_path()), materials_(job.scene, diagnostics, scene_dir_),
          time_(d.frame / d.fps) {
        // glTF animations are also read across the shutter (in seconds), at the keys the YAML
        // reader reads the scene's keyframes at.
        if (d.shutter[1] > d.shutter[0]) {
            const int segments = shutter_segments(d.shutter[1] - d.shutter[0]);
            for (int k = 0; k <= segments; ++k)
                motion_times_.push_back((d.frame + d.shutter[0] + (d.shutter[1] - d.shutter[0]) * k / segments) / d.fps);
        }
    }

    void add_media_and_materials() {
        scene_.background = d_.background;
        scene_.lights = d_.lights;
        scene_.light_spectra = d_.light_spectra;
        // Moving and turning lights: stored as they are at the opening, placed by keys that carry
        // a light at the origin (math/motion.h, light_keys; Scene::light_at).
        for (std::size_t i = 0; i < d_.light_paths.size() && i < scene_.lights.size(); ++i) {
            const auto& path = d_.light_paths[i];
            const auto& turns = i < d_.light_turns.size() ? d_.light_turns[i] : std::vector<Vector3>{};
            if (path.size() < 2 && turns.size() < 2) continue;
            Point3 at{0, 0, 0};  // where a light that only turns stays
            std::visit(
                [&](auto& l) {
                    if constexpr (requires { l.position; }) {
                        if (!path.empty()) l.position = path.front();
                        at = l.position;
                    }
                    if constexpr (requires { l.direction; }) {
                        if (!turns.empty()) l.direction = normalize(turns.front());
                    }
                },
                scene_.lights[i]);
            scene_.motions.emplace_back(light_keys(path, turns, at));
            scene_.light_motion.resize(scene_.lights.size(), -1);
            scene_.light_motion[i] = static_cast<std::int32_t>(scene_.motions.size() - 1);
        }
        // Media first: materials (glTF volumes) and objects refer to them.
        for (const NamedMedium& m : d_.media) {
            medium_names_.push_back(m.name);
            scene_.media.push_back(make_medium(m.medium, diagnostics_, scene_dir_));
        }
        if (d_.medium) scene_.camera_medium = medium_id(*d_.medium).value_or(kNoMedium);
        if (d_.environment) materials_.set_environment(*d_.environment, job_.notes);
        for (const NamedMaterial& m : d_.materials) {
            names_.push_back(m.name);
            materials_.add_material(m.material);
        }
        materials_.resolve_mixes(names_);
    }

    void add_object(const ObjectDesc& o);
    void add_mesh_file(const ObjectDesc& o, const MeshFileDesc& file, MaterialId id);
    std::optional<std::int32_t> add_motion(std::vector<Transform> keys, const ObjectDesc& o);
    /// Makes `inst` move by `keys` (its transform the first); false after an error.
    bool place_moving(Instance& inst, std::vector<Transform> keys, const ObjectDesc& o);
    /// A moving analytic shape: kept in object space, placed by the object's motion.
    template <typename S>
    void add_moving_shape(const S& shape, const ObjectDesc& o) {
        if constexpr (std::is_same_v<S, Plane>) {
            diagnostics_.error(o.transform_loc, "a plane cannot move (it has no bounds to sweep); use a quad");
        } else {
            for (const Transform& k : o.motion)
                if (!similarity_scale(k)) {
                    diagnostics_.error(o.transform_loc, "a moving sphere, quad, disk or triangle may only rotate, "
                                                        "translate and scale uniformly at every time of the shutter");
                    return;
                }
            const auto m = add_motion(o.motion, o);
            if (!m) return;
            if (*m < 0) {  // keys alike: still after all
                S placed = shape;
                transform_shape(placed, o.motion.front());
                shapes_of(scene_, placed).push_back(placed);
                return;
            }
            auto& array = shapes_of(scene_, shape);
            array.push_back(shape);
            scene_.moving_shapes.push_back({kind_of(shape), static_cast<std::uint32_t>(array.size() - 1),
                                            static_cast<std::uint32_t>(*m)});
        }
    }

private:
    std::optional<MediumId> medium_id(const Located<std::string>& name) {
        if (name.value == "none") return kNoMedium;
        const auto it = std::find(medium_names_.begin(), medium_names_.end(), name.value);
        if (it != medium_names_.end()) return static_cast<MediumId>(it - medium_names_.begin());
        std::string known;
        for (const auto& n : medium_names_) known += (known.empty() ? "" : ", ") + n;
        const std::string guess = closest_match(name.value, medium_names_);
        diagnostics_.error(name.loc, fmt::format("unknown medium '{}'{} ({})", name.value,
                                                 guess.empty() ? "" : fmt::format("; did you mean '{}'?", guess),
                                                 known.empty() ? "no media are defined; 'none' is vacuum"
                                                               : fmt::format("known: {}, or none", known)));
        return std::nullopt;
    }

    struct LoadedFile {
        std::uint32_t first_mesh = 0;
        std::vector<ImportedNode> nodes;
        std::vector<Light> lights;
        std::optional<GltfCamera> camera;
        std::vector<GltfCamera> cameras;
        std::vector<std::int32_t> mesh_alpha;  ///< per mesh: its material's cut-out, or -1
        std::vector<std::vector<Transform>> node_motion;  ///< per node: at motion_times_ (animated glTF)
    };

    const SceneDescription& d_;
    RenderJob& job_;
    Scene& scene_;
    Diagnostics& diagnostics_;
    std::filesystem::path scene_dir_;
    MaterialBuilder materials_;
    double time_;  ///< seconds into glTF animations
    std::vector<double> motion_times_;  ///< seconds: the shutter's keys (empty: an instant)
    std::vector<std::string> medium_names_, names_;
    std::map<std::string, LoadedFile> loaded_;
    std::map<const TriangleMesh*, std::uint32_t> inline_meshes_;
};

// A motion's index in the scene, or -1 for keys that do not move (an error, located at the
// object's transform, for a key that cannot be inverted).
std::optional<std::int32_t> ContentsBuilder::add_motion(std::vector<Transform> keys, const ObjectDesc& o) {
    try {
        Motion m(std::move(keys));
        if (!m.moves()) return -1;
        scene_.motions.push_back(std::move(m));
        return static_cast<std::int32_t>(scene_.motions.size() - 1);
    } catch (const std::invalid_argument&) {
        diagnostics_.error(o.transform_loc, "the object's transform is singular at some time of the shutter");
        return std::nullopt;
    }
}

bool ContentsBuilder::place_moving(Instance& inst, std::vector<Transform> keys, const ObjectDesc& o) {
    const Transform first = keys.front();
    const auto m = add_motion(std::move(keys), o);
    if (!m) return false;
    inst.transform = first;
    inst.motion = *m;
    return true;
}

// A mesh file's instances (its meshes and materials added on first use), its lights and cameras,
// placed by the object's transform.
void ContentsBuilder::add_mesh_file(const ObjectDesc& o, const MeshFileDesc& file, MaterialId id) {
    const MeshFileDesc* mesh_file = &file;
    const auto found = find_model(mesh_file->file.value, scene_dir_);
    if (!found.path) {
        diagnostics_.error(mesh_file->file.loc, fmt::format("mesh file '{}' not found (looked in: {})",
                                                           mesh_file->file.value, found.looked));
        return;
    }
    const std::filesystem::path path = *found.path;
    const std::string key = path.lexically_normal().string();
    auto it = loaded_.find(key);
    if (it == loaded_.end()) {
        ImportedFile f;
        try {
            f = mesh_file->camera.empty() ? import_mesh_file(path, time_, motion_times_)
                                          : import_gltf(path, mesh_file->camera, time_, motion_times_);
        } catch (const IoError& e) {
            diagnostics_.error(mesh_file->file.loc, e.what());
            return;
        }
        // The file's materials become scene materials; faces without one get the
        // object's default material.
        std::vector<MaterialId> ids;
        std::vector<std::int32_t> alphas;  // per file material: its cut-out (glTF alphaMode)
        for (const ImportedMaterial& m : f.materials) {
            ids.push_back(materials_.add_material(m.desc));
            alphas.push_back(m.alpha ? materials_.add_alpha(*m.alpha) : -1);
        }
        std::optional<MaterialId> fallback;  // added only if some face needs it
        const auto map_id = [&](MaterialId local) {
            if (local != kNoImportedMaterial) return ids.at(local);
            if (!fallback) fallback = materials_.add_material(MaterialDesc{});
            return *fallback;
        };
        LoadedFile lf{static_cast<std::uint32_t>(scene_.meshes.size()), f.nodes, f.lights, f.camera, f.cameras, {},
                      f.node_motion};
        for (TriangleMesh& m : f.meshes) {
            lf.mesh_alpha.push_back(m.material != kNoImportedMaterial ? alphas.at(m.material) : -1);
            m.material = map_id(m.material);
            for (MaterialId& fm : m.face_materials) fm = map_id(fm);
            scene_.meshes.push_back(std::move(m));
        }
        if (f.dropped_triangles > 0)
            job_.notes.push_back(fmt::format("{}: dropped {} degenerate triangle{}", mesh_file->file.value,
                                            f.dropped_triangles, f.dropped_triangles == 1 ? "" : "s"));
        for (std::string& n : f.notes) job_.notes.push_back(std::move(n));
        it = loaded_.emplace(key, std::move(lf)).first;
    }
    const Transform place = o.transform.value_or(Transform{});
    for (Light l : it->second.lights) {
        std::visit(
            [&](auto& x) {
                using L = std::decay_t<decltype(x)>;
                if constexpr (std::is_same_v<L, PointLight> || std::is_same_v<L, SpotLight>) x.position = place.point(x.position);
                if constexpr (std::is_same_v<L, SpotLight> || std::is_same_v<L, DirectionalLight>) x.direction = normalize(place.vector(x.direction));
            },
            l);
        scene_.lights.push_back(l);
    }
    const auto placed = [&](GltfCamera c) {
        c.position = place.point(c.position);
        c.direction = normalize(place.vector(c.direction));
        c.up = normalize(place.vector(c.up));
        return c;
    };
    if (it->second.camera && !job_.file_camera) job_.file_camera = placed(*it->second.camera);
    for (const GltfCamera& c : it->second.cameras) job_.file_cameras.push_back(placed(c));
    // The object's cut-out, else (unless the object replaces the file's materials, and
    // with them their alpha) the file material's.
    const std::int32_t alpha = o.alpha ? materials_.add_alpha(*o.alpha) : -1;
    const auto& node_motion = it->second.node_motion;
    for (std::size_t i = 0; i < it->second.nodes.size(); ++i) {
        const ImportedNode& n = it->second.nodes[i];
        const std::int32_t a = o.alpha || id != kNoImportedMaterial ? alpha : it->second.mesh_alpha.at(n.mesh);
        Instance inst{it->second.first_mesh + n.mesh, place * n.transform, std::nullopt, a};
        if (id != kNoImportedMaterial) inst.material = id;
        // Moving by the object's keys, the file's animation, or both (the same key times).
        const std::vector<Transform>* node_keys =
            i < node_motion.size() && node_motion[i].size() == motion_times_.size() ? &node_motion[i] : nullptr;
        if (!o.motion.empty() || node_keys) {
            std::vector<Transform> keys;
            for (std::size_t k = 0; k < motion_times_.size() || k < o.motion.size(); ++k) {
                const Transform outer = o.motion.empty() ? place : o.motion[std::min(k, o.motion.size() - 1)];
                keys.push_back(outer * (node_keys ? (*node_keys)[std::min(k, node_keys->size() - 1)] : n.transform));
            }
            if (!place_moving(inst, std::move(keys), o)) return;
        }
        scene_.instances.push_back(inst);
    }
}

void ContentsBuilder::add_object(const ObjectDesc& o) {
    MaterialId id = 0;
    const auto* mesh_file = std::get_if<MeshFileDesc>(&o.shape);
    if (mesh_file && !o.material_given) {
        id = kNoImportedMaterial;
    } else if (const auto* name = std::get_if<std::string>(&o.material.value)) {
        const auto it = std::find(names_.begin(), names_.end(), *name);
        if (it == names_.end()) {
            std::string known;
            for (const auto& n : names_) known += (known.empty() ? "" : ", ") + n;
            const std::string guess = closest_match(*name, names_);
            diagnostics_.error(
                o.material.loc,
                fmt::format("unknown material '{}'{} ({})", *name,
                            guess.empty() ? "" : fmt::format("; did you mean '{}'?", guess),
                            known.empty() ? "no materials are defined"
                                          : fmt::format("known: {}", known)));
            return;
        }
        id = static_cast<MaterialId>(it - names_.begin());
    } else {
        id = materials_.add_material(std::get<MaterialDesc>(o.material.value));
        materials_.resolve_mixes(names_);
    }
    if (o.interior || o.exterior) {
        const auto in = o.interior ? medium_id(*o.interior) : std::optional<MediumId>(kNoMedium);
        const auto out = o.exterior ? medium_id(*o.exterior) : std::optional<MediumId>(scene_.camera_medium);
        if (!in || !out) return;
        if (id == kNoImportedMaterial) {
            diagnostics_.error((o.interior ? *o.interior : *o.exterior).loc,
                              "a mesh that bounds a medium needs a 'material' of its own (the file's "
                              "materials are shared by every object that loads it)");
            return;
        }
        id = materials_.add_slot(id, MediumInterface{*in, *out});
    }
    if (mesh_file) {
        add_mesh_file(o, *mesh_file, id);
        return;
    }
    if (const auto* inline_mesh = std::get_if<InlineMeshDesc>(&o.shape)) {
        // Each mesh once, however many objects place it (pbrt's object instances).
        auto it = inline_meshes_.find(inline_mesh->mesh.get());
        if (it == inline_meshes_.end()) {
            TriangleMesh m = *inline_mesh->mesh;
            m.material = id;
            it = inline_meshes_.emplace(inline_mesh->mesh.get(), static_cast<std::uint32_t>(scene_.meshes.size())).first;
            scene_.meshes.push_back(std::move(m));
        }
        Instance inst{it->second, o.transform.value_or(Transform{}), id, o.alpha ? materials_.add_alpha(*o.alpha) : -1};
        if (!o.motion.empty() && !place_moving(inst, o.motion, o)) return;
        scene_.instances.push_back(inst);
        return;
    }
    if (o.alpha) diagnostics_.error(o.alpha->loc, "alpha (a cut-out) applies to meshes only");
    std::visit(
        [&](auto shape) {
            using S = decltype(shape);
            if constexpr (!std::is_same_v<S, MeshFileDesc> && !std::is_same_v<S, InlineMeshDesc>) {
                shape.material = id;
                if (!o.motion.empty()) {
                    add_moving_shape(shape, o);
                    return;
                }
                if (o.transform) {
                    if (const auto why = transform_shape(shape, *o.transform)) {
                        diagnostics_.error(o.transform_loc, *why);
                        return;
                    }
                }
                shapes_of(scene_, shape).push_back(shape);
            }
        },
        o.shape);
}

}  // namespace

RenderJob build(const SceneDescription& d, const Overrides& overrides,
                std::shared_ptr<SourceFiles> sources) {
    RenderJob job;
    job.sources = sources;
    Diagnostics diagnostics(std::move(sources));
    for (const Diagnostic& w : d.warnings) {
        std::string text = format_warning(w, diagnostics.sources());
        while (!text.empty() && text.back() == '\n') text.pop_back();
        job.notes.push_back(std::move(text));
    }
    build_film(d, overrides, job, diagnostics);
    build_camera(d, job, diagnostics);
    build_integrator(d, overrides, job, diagnostics);
    ContentsBuilder contents(d, job, diagnostics);
    contents.add_media_and_materials();
    for (const ObjectDesc& o : d.objects) contents.add_object(o);
    if (overrides.accel) job.scene.accel = *overrides.accel;

    diagnostics.throw_if_errors();
    // Unfiltered (the Whitted integrator, or `none`), no image needs a pyramid.
    for (Texture& t : job.scene.textures)
        if (auto* image = std::get_if<ImageTexture>(&t))
            image->filter = job.texture_filter;
    set_texture_footprint(job);  // before commit: it builds the environment's pyramid for it
    job.scene.commit();
    return job;
}

void set_texture_footprint(RenderJob& job) {
    // The Whitted integrator reproduces the article's figures, which read one point per sample.
    if (!job.filter_textures()) {
        job.scene.footprint.reset();
        return;
    }
    const double spp = std::max(1, job.options.spp);
    job.scene.footprint = job.camera.footprint(static_cast<Float>(std::max(0.125, 1 / std::sqrt(spp))));
}

}  // namespace glint
