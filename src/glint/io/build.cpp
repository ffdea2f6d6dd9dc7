#include "glint/io/build.h"

#include <fmt/core.h>

#include <filesystem>
#include <map>
#include <utility>

#include "glint/io/image_io.h"
#include "glint/io/limits.h"

namespace glint {

namespace {

const SourceLoc kCommandLine{"<command line>", 0, 0};

// The scene's array for each shape type; a shape without one is a compile error.
std::vector<Sphere>& shapes_of(Scene& s, const Sphere&) { return s.spheres; }
std::vector<Plane>& shapes_of(Scene& s, const Plane&) { return s.planes; }
std::vector<Quad>& shapes_of(Scene& s, const Quad&) { return s.quads; }
std::vector<Disk>& shapes_of(Scene& s, const Disk&) { return s.disks; }
std::vector<Triangle>& shapes_of(Scene& s, const Triangle&) { return s.triangles; }

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
                                    std::nullopt};
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
                scene_.materials.push_back(DielectricMaterial{lobe});
                break;
            }
            case K::kPlastic:
                scene_.materials.push_back(
                    PlasticMaterial{add_texture(d.color), make_plastic(Color{0}, d.ior, alpha)});
                break;
            case K::kPbr:
                scene_.materials.push_back(PbrMaterial{add_texture(d.color), d.metallic, d.roughness,
                                                       d.transmission, d.ior,
                                                       diffuse_fresnel_inside(d.ior)});
                break;
        }
        scene_.emission.resize(scene_.materials.size());
        scene_.emission.back() = d.emission;
        return static_cast<MaterialId>(scene_.materials.size() - 1);
    }

    /// The environment image: loaded linear (an HDR radiance map), relative to the scene file.
    void set_environment(const EnvironmentDesc& e) {
        const ImageId id = add_image(e.filename, ImageEncoding::kAuto);
        scene_.background = EnvironmentMap::make(scene_.images[id], e.scale);
    }

private:
    // Children first, so a texture's ids always point at earlier entries (a tree, no cycles).
    TextureId add_texture(const TextureDesc& d) {
        Texture t = ConstantTexture{d.value};
        switch (d.kind) {
            case TextureDesc::Kind::kConstant: break;
            case TextureDesc::Kind::kChecker: t = d.checker; break;
            case TextureDesc::Kind::kImage:
                t = ImageTexture{add_image(d.filename, d.encoding), d.wrap, d.size};
                break;
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
            image = Image{1, 1, {Color{0}}};  // keeps ids valid; the build fails anyway
        }
        scene_.images.push_back(std::move(image));
        const auto id = static_cast<ImageId>(scene_.images.size() - 1);
        cache_.emplace(key, id);
        return id;
    }

    Scene& scene_;
    Diagnostics& diagnostics_;
    std::filesystem::path dir_;
    std::map<std::pair<std::string, ImageEncoding>, ImageId> cache_;
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

}  // namespace

RenderJob build(const SceneDescription& d, const Overrides& overrides,
                std::shared_ptr<SourceFiles> sources) {
    Diagnostics diagnostics(std::move(sources));
    RenderJob job;

    // Film and sampling limits come first: nothing below allocates per pixel, but the render does.
    job.width = pick(d.film.width, overrides.width, "width", 1, kMaxFilmSide, diagnostics);
    job.height = pick(d.film.height, overrides.height, "height", 1, kMaxFilmSide, diagnostics);
    const long long pixels = static_cast<long long>(job.width) * job.height;
    if (pixels > kMaxFilmPixels) {
        const SourceLoc loc = overrides.width || overrides.height ? kCommandLine : d.film.width.loc;
        diagnostics.error(loc, fmt::format("a film of {} x {} = {} pixels is larger than the limit "
                                           "of {} pixels",
                                           job.width, job.height, pixels, kMaxFilmPixels));
    }
    job.options.spp = pick(d.sampler.spp, overrides.spp, "spp", 1, kMaxSpp, diagnostics);
    job.options.seed = overrides.seed.value_or(d.sampler.seed);
    job.options.sampler = d.sampler.type;
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
    job.filename = d.film.filename.value;

    // Camera.
    if (const auto* a = std::get_if<ArticleCameraDesc>(&d.camera)) {
        const Float vw = a->viewport_width.value_or(a->viewport_height *
                                                    static_cast<Float>(job.width) /
                                                    static_cast<Float>(job.height));
        job.camera = Camera(a->position, a->direction, a->up, vw, a->viewport_height, a->near,
                            job.width, job.height);
        job.camera.set_lens(a->aperture_radius, a->focus_distance.value_or(a->near));
        if (a->right_handed) job.camera.make_right_handed(job.width);
    } else {
        const auto& l = std::get<LookAtCameraDesc>(d.camera);
        job.camera = Camera::look_at(l.from, l.to, l.up, l.fov, job.width, job.height);
        job.camera.set_lens(l.aperture_radius, l.focus_distance.value_or(length(l.to - l.from)));
        if (l.right_handed) job.camera.make_right_handed(job.width);
    }

    // Integrator.
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
            job.integrator = std::make_unique<PathIntegrator>(s);
            break;
        }
    }

    // Scene contents: named materials first (ids in file order), then objects.
    Scene& scene = job.scene;
    scene.background = d.background;
    scene.lights = d.lights;
    MaterialBuilder materials(scene, diagnostics, std::filesystem::path(d.path).parent_path());
    if (d.environment) materials.set_environment(*d.environment);
    std::vector<std::string> names;
    for (const NamedMaterial& m : d.materials) {
        names.push_back(m.name);
        materials.add_material(m.material);
    }
    for (const ObjectDesc& o : d.objects) {
        MaterialId id = 0;
        if (const auto* name = std::get_if<std::string>(&o.material.value)) {
            const auto it = std::find(names.begin(), names.end(), *name);
            if (it == names.end()) {
                std::string known;
                for (const auto& n : names) known += (known.empty() ? "" : ", ") + n;
                const std::string guess = closest_match(*name, names);
                diagnostics.error(
                    o.material.loc,
                    fmt::format("unknown material '{}'{} ({})", *name,
                                guess.empty() ? "" : fmt::format("; did you mean '{}'?", guess),
                                known.empty() ? "no materials are defined"
                                              : fmt::format("known: {}", known)));
                continue;
            }
            id = static_cast<MaterialId>(it - names.begin());
        } else {
            id = materials.add_material(std::get<MaterialDesc>(o.material.value));
        }
        std::visit(
            [&](auto shape) {
                shape.material = id;
                shapes_of(scene, shape).push_back(shape);
            },
            o.shape);
    }

    diagnostics.throw_if_errors();
    scene.commit();
    return job;
}

}  // namespace glint
