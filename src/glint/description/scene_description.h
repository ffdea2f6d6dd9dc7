#pragma once
// SceneDescription: what a scene file says, as plain data, every value that can be wrong later
// carrying the SourceLoc it came from. The parser fills it; builder/build.h turns it into a render-time
// Scene. Defaults here are the documented defaults of docs/scene-format.md.
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "glint/background.h"
#include "glint/film/filter.h"
#include "glint/film/tonemap.h"
#include "glint/base/diagnostics.h"
#include "glint/image/image_io.h"
#include "glint/integrators/integrator.h"
#include "glint/lights/light.h"
#include "glint/math/transform.h"
#include "glint/media/grid.h"
#include "glint/materials/material.h"
#include "glint/samplers/sampler.h"
#include "glint/shapes/disk.h"
#include "glint/shapes/plane.h"
#include "glint/shapes/mesh.h"
#include "glint/shapes/quad.h"
#include "glint/shapes/sphere.h"
#include "glint/shapes/triangle.h"
#include "glint/textures/texture.h"

namespace glint {

template <typename T>
struct Located {
    T value{};
    SourceLoc loc;
};

struct ArticleCameraDesc {
    Point3 position{0, 0, -1};
    Vector3 direction{0, 0, 1};
    Vector3 up{0, 1, 0};
    std::optional<Float> viewport_width;  ///< default: viewport_height x film aspect
    Float viewport_height = 2;
    Float near = 1;  ///< the article's z
    Float aperture_radius = 0;
    std::optional<Float> focus_distance;  ///< default: near
    bool right_handed = false;
};

struct LookAtCameraDesc {
    Point3 from{0, 0, -1};
    Point3 to{0, 0, 0};
    Vector3 up{0, 1, 0};
    Float fov = 45;  ///< vertical, degrees
    Float aperture_radius = 0;
    std::optional<Float> focus_distance;  ///< default: |to - from|
    bool right_handed = false;
    /// Orthographic: rays parallel to to - from; `height` is the visible height in world units
    /// (fov unused).
    bool orthographic = false;
    Float height = 2;
    /// The part of the view shown: [x0, x1, y0, y1] in units of half the view's height, (0, 0)
    /// at its centre, y up (pbrt's screenwindow, rescaled to the vertical axis).
    std::optional<std::array<Float, 4>> window;
};

struct EnvironmentDesc {
    Located<std::string> filename;
    float scale = 1;
    /// pbrt-v4's equal-area octahedral layout (a square image), seen through the light's
    /// transform: resampled to latitude-longitude when loaded.
    bool equal_area = false;
    Matrix34 world_to_light;
    /// pbrt's "illuminance": scale the map so that a surface facing `up` receives this much
    /// from the hemisphere above it (computed from the image by build).
    std::optional<float> illuminance;
    Vector3 up{0, 0, 1};
};

using CameraDesc = std::variant<ArticleCameraDesc, LookAtCameraDesc>;

struct FilmDesc {
    Located<int> width{640, {}};
    Located<int> height{360, {}};
    DisplaySettings display;
    FilterDesc filter;
    bool aovs = false;  ///< write albedo, normal and depth channels (EXR only)
    bool denoise = false;  ///< write the image denoised (denoise/denoise.h)
    Located<std::string> filename;  ///< empty: the CLI chooses
    /// Render only part of the frame: [x0, x1, y0, y1] as fractions of the width and height
    /// (y down), pixel bounds rounded up as pbrt's cropwindow; or pixel bounds directly
    /// [x0, x1, y0, y1), clamped to the frame. The image written is the crop.
    std::optional<Located<std::array<float, 4>>> crop_window;
    std::optional<Located<std::array<int, 4>>> pixel_bounds;
    /// Multiplies the radiance of every pixel (pbrt's imaging ratio).
    float scale = 1;
};

enum class IntegratorKind { kFlat, kNormals, kWhitted, kPath };

struct IntegratorDesc {
    IntegratorKind kind = IntegratorKind::kWhitted;
    float ambient = 0.1f;
    bool shadows = true;
    Located<int> max_depth{5, {}};  ///< whitted's default; path's is 16 (set by the parser)
    PathSettings path;              ///< path: everything but max_depth
};

struct SamplerDesc {
    SamplerType type = SamplerType::kSobol;
    Located<int> spp{1, {}};
    std::uint64_t seed = 0;
    double noise_threshold = 0;  ///< adaptive sampling (0: off)
    int min_spp = 0;             ///< adaptive: 0 for Cycles' default
};

/// A texture as the file describes it: a tree (scale and mix have children), turned into
/// Texture ids by build, which also loads the images.
struct TextureDesc {
    enum class Kind { kConstant, kChecker, kImage, kScale, kMix, kVertexColor };
    Kind kind = Kind::kConstant;
    Color value{0.8f};                             ///< constant
    std::shared_ptr<const Spectrum> spectrum;      ///< constant: a reflectance spectrum (value: its colour)
    CheckerTexture checker{1, Color{1}, Color{0}};  ///< checker
    Located<std::string> filename;                 ///< image, as written in the file
    ImageEncoding encoding = ImageEncoding::kAuto;
    WrapMode wrap = WrapMode::kRepeat;
    Float size = 1;
    std::vector<TextureDesc> children;  ///< scale: texture, factor; mix: a, b, amount
    // Set by importers (glTF): a separate v wrap, a uv transform, texels decoded already.
    std::optional<WrapMode> wrap_v;
    std::array<Float, 6> uv_transform{1, 0, 0, 0, 1, 0};
    std::shared_ptr<const Image> pixels;  ///< used instead of `filename` when set
    std::uint8_t uv_set = 0;     ///< image: the texture coordinate set (glTF texCoord)
    bool alpha_channel = false;  ///< image, vertex colour: the alpha channel (as grey)
};

/// A participating medium (media/medium.h) as the file gives it: coefficients already in
/// sigma_a / sigma_s form (the parser turns the albedo + density form into them).
struct MediumDesc {
    enum class Kind { kHomogeneous, kGrid };
    Kind kind = Kind::kHomogeneous;
    Color sigma_a{0}, sigma_s{0};  ///< grid: at density 1
    Color emission{0};             ///< homogeneous: Le; grid: the colour of an emission grid
    float g = 0;
    // grid
    Located<std::string> file;
    Located<std::string> density_grid{"density", {}};
    enum class Emission { kNone, kGrid, kTemperature };
    Emission emission_kind = Emission::kNone;
    Located<std::string> emission_grid;
    float emission_scale = 1;
    float temperature_scale = 1;
    std::optional<Transform> transform;  ///< after the file's own voxel-to-world transform
    /// A density grid given in the scene file itself (pbrt's uniformgrid) instead of `file`; its
    /// index-to-world transform is `transform`.
    std::shared_ptr<const VoxelGrid> inline_density;
};

struct MaterialDesc {
    enum class Kind { kArticle, kDiffuse, kConductor, kDielectric, kPlastic, kPbr, kInterface,
                      kDiffuseTransmission, kMix, kCoated };
    Kind kind = Kind::kArticle;
    TextureDesc color;  ///< article colour, diffuse/plastic albedo, pbr base colour
    float shininess = 0;
    float roughness = 0;  ///< alpha = roughness^2
    // conductor: a complex index (a named metal or eta + k), or a Schlick reflectance texture
    Color eta{0.2f, 0.92f, 1.1f}, k{3.9f, 2.45f, 2.14f};
    std::optional<TextureDesc> reflectance;
    /// Spectral mode: a measured metal's eta and k (eta and k above: their values at 650, 550 and
    /// 450 nm), and a dispersive glass's index (ior: its value at 587.56 nm).
    std::shared_ptr<const Spectrum> eta_spectrum, k_spectrum, ior_spectrum;
    // dielectric, plastic, pbr
    float ior = 1.5f;
    bool thin = false;
    Color tint{1};
    // pbr
    float metallic = 0;
    float transmission = 0;
    Emission emission;
    // Textures from importers (glTF): metallic in blue, roughness in green (multiplying the
    // factors); a tangent-space normal map (+y up) with its scale; emission multiplied by a map.
    std::optional<TextureDesc> metallic_roughness;
    std::optional<TextureDesc> normal_map;
    float normal_scale = 1;
    std::optional<TextureDesc> emission_map;
    /// diffuse_transmission: `color` is the reflectance, this the transmittance.
    std::optional<TextureDesc> transmittance;
    /// mix: the two named materials and the probability of the second (a texture's channel mean).
    std::vector<Located<std::string>> mix;
    std::optional<TextureDesc> amount;
    /// pbr: glTF's layers and specular, each a texture with its factor folded in. clear coat:
    /// weight in red, roughness in green; sheen: colour, roughness (grey); specular: weight (grey),
    /// colour (KHR_materials_clearcoat, _sheen, _specular).
    std::optional<TextureDesc> clearcoat, clearcoat_roughness, sheen, sheen_roughness, specular, specular_color;
    /// coated (pbrt-v4's coateddiffuse / coatedconductor): the base is diffuse (albedo `color`)
    /// or, with coated_conductor, a conductor (eta, k or reflectance; `roughness`); the coat has
    /// index `ior` and its own roughness; between them a slab of `thickness` filled with a
    /// medium of `layer_albedo` and HG `g`; `layer_depth` bounces and `layer_samples` walks.
    bool coated_conductor = false;
    float coat_roughness = 0;
    float thickness = 0.01f;
    Color layer_albedo{0};
    float g = 0;
    int layer_depth = 10;
    int layer_samples = 1;
    /// Set by importers (glTF's KHR_materials_volume): an absorbing interior medium for every
    /// surface of this material.
    std::optional<MediumDesc> interior;
};

struct NamedMedium {
    std::string name;
    MediumDesc medium;
    SourceLoc loc;
};

/// An object's material: a name to resolve, or an inline description.
struct MaterialRef {
    std::variant<std::string, MaterialDesc> value;
    SourceLoc loc;
};

/// A mesh file (OBJ, PLY, glTF) to load at build time; relative to the scene file.
struct MeshFileDesc {
    Located<std::string> file;
    std::string camera;  ///< glTF: the camera to report (`glint render model.glb --camera NAME`)
};

/// A triangle mesh given in the scene file itself (pbrt's trianglemesh), in object space. Objects
/// that share the pointer share the mesh and its BVH (instances).
struct InlineMeshDesc {
    std::shared_ptr<const TriangleMesh> mesh;
};

/// A cut-out on a mesh (scene.h's AlphaMask before its texture is added).
struct AlphaDesc {
    TextureDesc texture;
    float cutoff = 0.5f;
    bool stochastic = false;  ///< pbrt's alpha, glTF's BLEND; else a mask at `cutoff`
    SourceLoc loc;
};

struct ObjectDesc {
    /// Material ids are set by build. A `box` in the file arrives here as six quads.
    std::variant<Sphere, Plane, Quad, Disk, Triangle, MeshFileDesc, InlineMeshDesc> shape = Sphere{{0, 0, 0}, 1};
    /// For a mesh: whether `material` was given (it then replaces the file's materials).
    bool material_given = true;
    MaterialRef material;
    SourceLoc loc;
    std::optional<Transform> transform;  ///< object to world
    SourceLoc transform_loc;
    /// Moving over the shutter: object-to-world transforms at evenly spaced times from its opening
    /// to its close (math/motion.h; `transform`, if set, is the first); empty: still.
    std::vector<Transform> motion;
    /// Names of the media inside and outside the object's surface (empty: not given; "none":
    /// vacuum). With either given the surface bounds a medium; an unset exterior is the scene's
    /// medium.
    std::optional<Located<std::string>> interior, exterior;
    std::optional<AlphaDesc> alpha;  ///< meshes only
};

struct NamedMaterial {
    std::string name;
    MaterialDesc material;
    SourceLoc loc;
};

struct SceneDescription {
    std::string path;
    CameraDesc camera = ArticleCameraDesc{};
    FilmDesc film;
    IntegratorDesc integrator;
    SamplerDesc sampler;
    Background background = SkyBackground{};
    std::optional<EnvironmentDesc> environment;  ///< a background loaded from an image by build
    std::vector<Light> lights;
    /// Per light of `lights` (may be shorter): its spectrum for spectral mode (Y = 1), or null.
    std::vector<std::shared_ptr<const Spectrum>> light_spectra;
    std::vector<NamedMaterial> materials;
    std::vector<NamedMedium> media;
    std::optional<Located<std::string>> medium;  ///< the camera's (the scene's) medium
    std::vector<ObjectDesc> objects;
    /// What the reader approximated or left out (pbrt files), printed as located warnings.
    std::vector<Diagnostic> warnings;
    /// The shutter: [open, close], in frames from `frame` (glint's YAML) or in the file's time
    /// units (pbrt); open == close: an instant. Where something moves over it, camera rays carry a
    /// time in it and the image is motion blurred (docs/motion.md).
    std::array<double, 2> shutter{0, 0};
    SourceLoc shutter_loc;
    /// The camera at evenly spaced times over the shutter (the first = `camera`); empty: still.
    std::vector<CameraDesc> camera_motion;
    /// Per light of `lights` (may be shorter): a point or spot light's position at those times
    /// (empty: it stays), and a spot or directional light's direction (empty: it keeps its own).
    std::vector<std::vector<Point3>> light_paths;
    std::vector<std::vector<Vector3>> light_turns;
    /// Animation: the frame this description is of (keyframed values were read at it), frames
    /// per second (glTF animations are timed in seconds), and whether anything is keyframed.
    double frame = 0;
    double fps = 24;
    bool animated = false;
};

}  // namespace glint
