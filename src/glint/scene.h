#pragma once
// The render-time scene: flat arrays indexed by ids, no names, no maps, no owning pointers.
// Shapes live in one array per kind; meshes are stored once and placed by instances.
//
// Acceleration (two levels, as Embree and pbrt): a 4-wide BVH over every bounded shape and every
// instance (accel/bvh.h), and per mesh a BVH over its triangles in object space
// (accel/mesh_bvh.h), shared by its instances. Planes are unbounded and tested first, in a loop.
// With `accel = AccelKind::kEmbree` (built with GLINT_EMBREE) Embree 3 replaces both levels.
//
// After filling or changing the arrays, call commit() before tracing (as with Embree's
// rtcCommitScene): it builds the acceleration structures and the light sampler.
#include <array>
#include <memory>
#include <optional>
#include <vector>

#include "glint/accel/bvh.h"
#include "glint/accel/mesh_bvh.h"
#include "glint/accel/sphere_set.h"

#include "glint/background.h"
#include "glint/cameras/camera.h"
#include "glint/math/bounds.h"
#include "glint/math/motion.h"
#include "glint/interaction.h"
#include "glint/lights/light.h"
#include "glint/lights/light_sampler.h"
#include "glint/materials/material.h"
#include "glint/media/medium.h"
#include "glint/shapes/disk.h"
#include "glint/shapes/mesh.h"
#include "glint/shapes/plane.h"
#include "glint/shapes/quad.h"
#include "glint/shapes/sphere.h"
#include "glint/shapes/triangle.h"
#include "glint/spectra/rgb_spectrum.h"
#include "glint/textures/mipmap.h"
#include "glint/textures/texture.h"

namespace glint {

struct WatertightRaySse;  // shapes/triangle_sse.h

/// glint's BVH, the same with spatial splits in the mesh BVHs, or Embree 3 (when built in).
enum class AccelKind { kBvh, kSbvh, kEmbree };
const char* accel_name(AccelKind kind);  ///< "bvh", "sbvh", "embree"

class EmbreeAccel;

/// A cut-out on a mesh instance (pbrt's "alpha", glTF's alphaMode): a = the texture's channel
/// mean at the hit. A mask keeps the surface where a >= cutoff; a stochastic one keeps it for
/// a fraction a of the rays (a hash of the ray and the triangle decides), so on average the
/// surface lets 1 - a through. Every ray (camera, bounce, shadow) sees the same surface, in
/// both BVH backends (an any-hit filter).
struct AlphaMask {
    TextureId texture = 0;
    float cutoff = 0.5f;
    bool stochastic = false;
};

struct Scene {
    std::vector<Sphere> spheres;
    std::vector<Plane> planes;
    std::vector<Quad> quads;
    std::vector<Disk> disks;
    std::vector<Triangle> triangles;
    std::vector<TriangleMesh> meshes;
    std::vector<Instance> instances;
    /// Motion over the shutter (math/motion.h), referenced by moving instances and shapes.
    std::vector<Motion> motions;
    /// An analytic shape (sphere, quad, disk or triangle; not a plane) that moves: stored in its
    /// array in object space, placed in the world by motions[motion] (object-to-world keys), whose
    /// keys must be similarities (rotation, translation, uniform scale: what keeps the shape a
    /// sphere or a disk, and its light samples' solid-angle densities what they are). Instances
    /// move by Instance::motion.
    struct MovingShape {
        ShapeKind kind;
        std::uint32_t index;
        std::uint32_t motion;
    };
    std::vector<MovingShape> moving_shapes;
    /// Per light of `lights` (may be shorter): an index into motions that carries a point or spot
    /// light's position over the shutter, or -1.
    std::vector<std::int32_t> light_motion;
    std::vector<AlphaMask> alpha_masks;
    std::vector<Material> materials;
    std::vector<Emission> emission;  ///< per material; missing entries emit nothing
    std::vector<std::optional<NormalMap>> normal_maps;  ///< per material; missing: none
    std::vector<Texture> textures;
    std::vector<Image> images;
    std::vector<Light> lights;
    /// Spectral mode: per light of `lights` (may be shorter), its spectrum (Y = 1) or null.
    std::vector<std::shared_ptr<const Spectrum>> light_spectra;
    const Spectrum* light_spectrum(std::uint32_t light) const {
        return light < light_spectra.size() ? light_spectra[light].get() : nullptr;
    }
    /// Spectral mode: a constant background's spectrum, or null (its colour is upsampled).
    const Spectrum* background_spectrum() const {
        const auto* c = std::get_if<ConstantBackground>(&background);
        return c ? c->spectrum.get() : nullptr;
    }
    /// A constant texture's colour ready to be read as a reflectance spectrum (set by commit());
    /// null for the other textures. Spectral mode reads it instead of upsampling the colour at
    /// every hit: the same values, bit for bit, without the table lookup.
    const RgbReflectance* texture_reflectance(TextureId id) const {
        return id < constant_reflectance_.size() && constant_reflectance_[id] ? &*constant_reflectance_[id] : nullptr;
    }
    /// Participating media, and the one the camera (and so everything no boundary encloses) is in.
    std::vector<Medium> media;
    MediumId camera_medium = kNoMedium;
    /// Per material slot: the media on its two sides; missing or empty entries change nothing
    /// (build gives every object that bounds a medium a slot of its own).
    std::vector<std::optional<MediumInterface>> medium_interfaces;
    Background background = SkyBackground{};
    AccelKind accel = AccelKind::kBvh;  ///< read by commit()
    LightSamplerKind light_sampling = LightSamplerKind::kBvh;  ///< read by commit()
    /// The camera's pixel footprint: set (by build, for the path tracer), textures are filtered
    /// over it (MIP maps for image textures, a box for checkers); unset, each reads one point.
    std::optional<PixelFootprint> footprint;
    /// The mesh BVHs' traversal kernel, read by commit(); empty: default_simd_isa().
    std::optional<SimdIsa> mesh_isa;

    /// Builds the derived data (acceleration structures, light sampler, which textures read uv)
    /// from the arrays. Throws std::runtime_error when `accel` is kEmbree and glint was built
    /// without Embree.
    void commit();

    /// Nearest hit in [kRayTMin, ray.t_max).
    std::optional<Hit> intersect(const Ray& ray) const;
    /// Whether anything lies in [kRayTMin, ray.t_max); stops at the first blocker.
    bool occluded(const Ray& ray) const;
    /// The same answers by testing every primitive (the reference the accelerators are tested
    /// against; needs commit() too).
    std::optional<Hit> intersect_brute_force(const Ray& ray) const;
    bool occluded_brute_force(const Ray& ray) const;

    /// Triangle `prim` of instance `inst` in world space at `time`, wound so that its normal()
    /// is the geometric normal the interaction reports (area lights on meshes use it).
    Triangle world_triangle(std::uint32_t inst, std::uint32_t prim, Float time = 0) const;
    /// Whether anything moves over the shutter (set by commit()): only then do camera samples
    /// draw a time.
    bool has_motion() const { return has_motion_; }
    /// The motion of a shape (kMesh: of instance `index`), or null when it is still.
    const Motion* motion_of(ShapeKind kind, std::uint32_t index) const;
    /// Moving shape m (an index into moving_shapes) against the ray at its time: lowers ray.t_max
    /// and sets best for a hit nearer than it (scene_motion.cpp; both backends use it).
    void closest_moving(std::uint32_t m, Ray& ray, std::optional<Hit>& best) const;
    bool any_moving(std::uint32_t m, const Ray& ray) const;
    /// Moving shape m's box over the whole shutter: with `padded`, the box the trees use (a
    /// sphere's, quad's or disk's grown for its test's rounding, math/bounds.h); without, the exact
    /// one (the scene's extent).
    Bounds3 moving_bounds(std::uint32_t m, bool padded = true) const;
    /// Light i of `lights` where it is and where it points at `time`: its keys carry a light at
    /// the origin with its stored direction (math/motion.h, light_keys).
    Light light_at(std::size_t i, Float time) const {
        Light l = lights[i];
        if (i < light_motion.size() && light_motion[i] >= 0) {
            const Transform x = motions[static_cast<std::size_t>(light_motion[i])].at(time);
            std::visit(
                [&](auto& v) {
                    if constexpr (requires { v.position; }) v.position = x.point(Point3{0, 0, 0});
                    if constexpr (requires { v.direction; }) v.direction = normalize(x.vector(v.direction));
                },
                l);
        }
        return l;
    }
    /// Instance i's object-to-world transform at `time`.
    Transform placement(std::uint32_t i, Float time) const {
        const Instance& in = instances[i];
        return in.motion < 0 ? in.transform : motions[static_cast<std::size_t>(in.motion)].at(time);
    }
    MaterialId instance_material(std::uint32_t inst, std::uint32_t prim) const {
        const Instance& i = instances[inst];
        return i.material ? *i.material : meshes[i.mesh].material_of(prim);
    }
    const std::vector<MeshBvh>& mesh_bvhs() const { return mesh_bvhs_; }
    /// The SIMD sphere set, if commit() chose it over the BVH (spheres and planes alone).
    const SphereSet& sphere_set() const { return sphere_set_; }
    /// Bytes held by the acceleration structures (either backend).
    std::size_t accel_memory_bytes() const;
    Bounds3 bounds() const { return bounds_; }
    /// The colour of texture `id` at a surface point. The uv and the vertex colour are computed
    /// only for textures that read them (an atan2 and an acos per sphere hit otherwise wasted).
    Color texture(TextureId id, const SurfaceInteraction& si) const {
        // The article's textures inline; the rest go through the general (recursive) evaluate.
        const Texture& t = textures[id];
        if (const auto* c = std::get_if<ConstantTexture>(&t)) return c->value;
        if (const auto* k = std::get_if<CheckerTexture>(&t); k && !footprint && !k->on_uv) return k->eval(si.p);
        return texture_general(id, si);
    }
    /// The reflectance spectrum of texture `id`, if it is a constant given as one (spectral mode
    /// reads it instead of upsampling the colour).
    const Spectrum* texture_spectrum(TextureId id) const {
        const auto* c = std::get_if<ConstantTexture>(&textures[id]);
        return c ? c->spectrum.get() : nullptr;
    }
    const Emission& emission_of(MaterialId m) const { return m < emission.size() ? emission[m] : kNoEmission; }
    /// The background the camera sees along d, directly or through perfect mirrors and glass:
    /// with texture filtering on (a footprint) an environment map is read over the pixel's
    /// angular size (trilinear over its MIP pyramid); every other lookup is evaluate()'s, which
    /// light sampling's densities are made from (docs/textures.md).
    /// `spread`: the pixel's angle there, if known (a path's offset rays through curved mirrors
    /// and lenses); otherwise a pixel's angle at the image's centre.
    Color background_seen(Vector3 d, Float spread = -1) const;
    /// Radiance the surface at si emits towards wo (unit, pointing away from the surface).
    Color emitted(const SurfaceInteraction& si, Vector3 wo) const {
        const Emission& e = emission_of(si.material);
        if (!e.emits()) return Color{0};
        if (!(e.two_sided || dot(si.n, wo) > 0)) return Color{0};
        return e.texture ? e.radiance * texture(*e.texture, si) : e.radiance;
    }
    /// The radiance area light `l` (of `material`) emits at its point q (normal n): the
    /// material's emission, times its emission texture there, if any.
    Color light_radiance(const AreaLight& l, MaterialId material, Point3 q, Normal3 n, Float time = 0) const;
    /// Whether the path tracer must track media: some medium or interface-only surface exists
    /// (set by commit()). Without, it runs the surface-only loop it always ran.
    bool has_media() const { return has_media_; }
    bool is_interface(MaterialId m) const {
        return m < materials.size() && std::holds_alternative<InterfaceMaterial>(materials[m]);
    }
    /// The medium interface of a material slot, if it has one.
    const MediumInterface* medium_interface(MaterialId m) const {
        return m < medium_interfaces.size() && medium_interfaces[m] ? &*medium_interfaces[m] : nullptr;
    }
    /// The material that scatters at si: si.material, or for a mix the material it picks there
    /// (mixes may nest; build refuses cycles).
    MaterialId surface_material(const SurfaceInteraction& si) const;
    /// Whether instance i's surface is there at triangle `prim`, barycentrics (b1, b2), for `ray`
    /// (world space): its alpha mask's verdict (true without one).
    bool alpha_keeps(std::uint32_t instance, std::uint32_t prim, float b1, float b2, const Ray& ray) const;
    /// The share of rays alpha_keeps lets meet that point: 1 or 0 for a cutoff mask, the alpha for
    /// a stochastic one, 1 without a mask (light samples on emitting meshes are weighed by it).
    float alpha_coverage(std::uint32_t instance, std::uint32_t prim, float b1, float b2) const;
    /// The material of a hit without the full interaction.
    MaterialId material_of(const Hit& hit) const;
    /// The nearest hit that is not an interface surface, and whether one lies in the way: for
    /// the integrators that do not track media (Whitted, the debug views), to which interfaces
    /// are invisible.
    std::optional<Hit> intersect_opaque(const Ray& ray) const;
    bool occluded_opaque(const Ray& ray) const;
    /// Packet forms of the two, for up to RayPacket::kSize (16) rays: each answer is the one
    /// intersect_opaque/occluded_opaque gives for that ray, to the bit. Scenes of spheres and
    /// planes test one sphere against all the rays at once; the rest ask ray by ray.
    static constexpr int kPacketSize = RayPacket::kSize;
    void intersect_opaque(const Ray* rays, int n, std::optional<Hit>* hits) const;
    /// Bit k set when ray k is blocked.
    std::uint32_t occluded_opaque(const Ray* rays, int n) const;
    /// Every light, for the path tracer; built by commit().
    const LightSampler& light_sampler() const { return light_sampler_; }

    /// The interpolated vertex colour of a mesh that has them; 1 elsewhere.
    Color vertex_color(const SurfaceInteraction& si) const;
    /// The mesh's interpolated per-vertex alpha; 1 where it has none.
    Float vertex_alpha(const SurfaceInteraction& si) const;
    /// Texture coordinate set `set` (0: uv(si)); set 0's where the mesh has no such set.
    Point2 uv(const SurfaceInteraction& si, int set) const;
    /// Texture coordinates of a surface point, by the hit shape's convention (shapes/*.h).
    Point2 uv(const SurfaceInteraction& si) const;

    /// Phase two: the full interaction for the winning hit.
    /// `differential`: the path's offset rays, if it carries them (kept in si.differential for
    /// the texture lookups, a normal map's among them).
    SurfaceInteraction interaction(const Ray& ray, const Hit& hit,
                                   const RayDifferential* differential = nullptr) const;
    /// The surface's own shading normal at q, a point of si's tangent plane near si.p (unit; on
    /// meshes interpolated, before any normal map): a sphere's normal there, a mesh's interpolated
    /// normal at q's barycentrics, si.n on flat shapes and meshes without normals.
    Normal3 smooth_normal_at(const SurfaceInteraction& si, Point3 q) const;

private:
    friend class EmbreeAccel;
    std::size_t bounded_count() const {
        return spheres.size() + quads.size() + disks.size() + triangles.size() + instances.size();
    }
    /// Tests top-level primitive `ref` (kind in the top bits, index below) against the ray.
    void closest_top(std::uint32_t ref, Ray& ray, const WatertightRaySse& wr, std::optional<Hit>& best) const;
    bool any_top(std::uint32_t ref, const Ray& ray, const WatertightRaySse& wr) const;
    /// The interaction of a hit on a moving analytic shape: found where the shape is stored, moved.
    SurfaceInteraction moving_interaction(const Motion& motion, const Ray& ray, const Hit& hit) const;
    /// Fills shape_motion_ and tells which shapes move (for commit()).
    void index_motion();
    std::optional<MeshHit> closest_instance(std::uint32_t inst, const Ray& ray) const;
    bool any_instance(std::uint32_t inst, const Ray& ray) const;
    /// A still shape's interaction, shading normal included (a mesh's interpolated one, else n).
    SurfaceInteraction base_interaction(const Ray& ray, const Hit& hit) const;
    /// Bends si.ns by the material's normal map (meshes with texture coordinates).
    void apply_normal_map(SurfaceInteraction& si, const Ray& ray) const;
    /// Whether a mesh triangle's geometric normal is flipped to agree with its vertex normals.
    /// `ng`: the triangle's object-space (p1 - p0) x (p2 - p0).
    bool flip_mesh_normal(const TriangleMesh& m, std::uint32_t prim, Vector3 ng) const;

    Bounds3 bounds_;  ///< around every bounded shape and instance
    Bvh4 top_;
    std::vector<std::uint32_t> top_refs_;  ///< leaf order
    std::vector<MeshBvh> mesh_bvhs_;
    SphereSet sphere_set_;  ///< replaces top_ for scenes of spheres (and planes) alone
    std::vector<std::optional<RgbReflectance>> constant_reflectance_;  ///< per texture (commit())
    /// Per lone triangle, its normal() (commit()): a hit's interaction reads it instead of a
    /// cross product, a square root and a division per hit.
    std::vector<Normal3> triangle_normals_;
    std::shared_ptr<const EmbreeAccel> embree_;  ///< immutable once built; copies share it
    /// texture() for the textures that are neither constants nor checkers (out of line, so that
    /// the two common cases stay small enough to inline).
    Color texture_general(TextureId id, const SurfaceInteraction& si) const;
    static constexpr std::uint8_t kReadsUv = 1, kReadsVertexColor = 2, kReadsMoreUvs = 4, kReadsFootprint = 8;
    struct UvSetArg {
        const Scene* scene;
        const SurfaceInteraction* si;
    };
    static Point2 uv_set_of(const void* arg, int set) {
        const auto* a = static_cast<const UvSetArg*>(arg);
        return a->scene->uv(*a->si, set);
    }
    std::vector<std::uint8_t> texture_reads_;  ///< per texture, set by commit()
    std::size_t committed_count_ = 0;
    bool has_media_ = false;
    bool has_interfaces_ = false;
    /// Per image: its MIP pyramid, for the images filtered textures read (built by commit()).
    std::vector<MipPyramid> pyramids_;
    MipPyramid env_pyramid_;  ///< the environment map's, when textures are filtered (commit())
    /// uv (set 0) at point q of si's surface (q near si.p, on its tangent plane).
    Point2 uv_near(const SurfaceInteraction& si, Point3 q) const;
    /// uv(si) for a shape where it is stored.
    Point2 uv_static(const SurfaceInteraction& si) const;
    /// Barycentrics (b1, b2) of point q in the plane of instance inst's triangle prim.
    Point2 mesh_barycentrics(std::uint32_t inst, std::uint32_t prim, Point3 q, Float time) const;
    /// Per shape kind (not kMesh): each shape's index into motions, or -1; empty when none moves.
    std::array<std::vector<std::int32_t>, 5> shape_motion_;
    bool has_motion_ = false;
    /// An instance's alpha mask (which it must have) at barycentrics (b1, b2) of triangle prim.
    float mask_alpha(std::uint32_t instance, std::uint32_t prim, float b1, float b2) const;
    LightSampler light_sampler_;
};

}  // namespace glint
