#pragma once
// build: SceneDescription (+ command-line overrides) -> everything a render needs. Resolves
// material names to ids, applies defaults, and checks limits (film size, spp, depth) before
// anything large is allocated. All errors are collected and thrown as one SceneError.
#include <memory>
#include <optional>
#include <string>

#include "glint/cameras/camera.h"
#include "glint/film/tonemap.h"
#include "glint/integrators/integrator.h"
#include "glint/base/diagnostics.h"
#include "glint/assets/mesh_import.h"
#include "glint/description/scene_description.h"
#include "glint/render/render.h"
#include "glint/scene.h"

namespace glint {

/// Values from the command line that override the scene file.
struct Overrides {
    std::optional<long long> width, height, spp, max_depth, threads;
    std::optional<std::uint64_t> seed;
    bool aovs = false;  ///< --aovs: write the AOVs even if the scene does not ask
    bool denoise = false;  ///< --denoise: denoise even if the scene does not ask
    std::optional<AccelKind> accel;  ///< --accel
    std::optional<LightSamplerKind> light_sampler;  ///< --light-sampler
    std::optional<TextureFilter> texture_filter;     ///< --texture-filter
    std::optional<bool> spectral;                    ///< --spectral / --rgb
};

struct RenderJob {
    Scene scene;
    Camera camera;
    std::unique_ptr<Integrator> integrator;
    RenderOptions options;
    int width = 0, height = 0;  ///< the camera's whole frame
    /// The film written: the whole frame, or the crop (options.offset_x/y place it).
    int film_width = 0, film_height = 0;
    DisplaySettings display;
    bool aovs = false;
    bool denoise = false;  ///< the written image is denoised (the features are rendered for it)
    /// How the path tracer's textures are read over the pixel footprint (set_texture_footprint);
    /// kBilinear (the other integrators, or `none`): one point per sample.
    TextureFilter texture_filter = TextureFilter::kBilinear;
    bool filter_textures() const { return texture_filter != TextureFilter::kBilinear; }
    bool spectral = false;  ///< the path tracer traces wavelengths (PathSettings::spectral)
    float white_balance = 0;  ///< PathSettings::white_balance
    /// Whether the render keeps the AOVs and the half images: to write them, or to denoise.
    bool features() const { return aovs || denoise; }
    std::string filename;  ///< the scene's film.filename, or empty
    std::vector<std::string> notes;  ///< for the user: dropped triangles, importer warnings
    /// The first camera found in an included glTF file (used when rendering that file directly).
    std::optional<GltfCamera> file_camera;
    /// Every camera of the included glTF files, placed (listed by `glint info`).
    std::vector<GltfCamera> file_cameras;
    /// The text of every scene file read (for messages, and a checkpoint's fingerprint).
    std::shared_ptr<SourceFiles> sources;
};

/// Where mesh files named by a scene are looked for, in order: the scene's folder, each folder of
/// $GLINT_MODEL_PATH (colon-separated), then the models folder found at configure time.
std::vector<std::filesystem::path> model_folders(const std::filesystem::path& scene_dir);

RenderJob build(const SceneDescription& description, const Overrides& overrides,
                std::shared_ptr<SourceFiles> sources);

/// Gives the path tracer's scene the camera's pixel footprint (scaled by max(1/8, 1/sqrt(spp))),
/// over which its textures are filtered; build calls it, and whoever replaces the camera after.
void set_texture_footprint(RenderJob& job);

}  // namespace glint
