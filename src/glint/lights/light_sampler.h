#pragma once
// Light sampling for the path tracer: every light of a committed scene (the file's lights, one
// area light per emitting shape, and the environment) in one index space, chosen for a shaded
// point by a light BVH (lights/light_bvh.h; the default) or in proportion to power, and sampled
// by solid angle from the point.
#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "glint/interaction.h"
#include "glint/lights/light.h"
#include "glint/lights/light_bvh.h"
#include "glint/samplers/distribution.h"

namespace glint {

struct Scene;
class Spectrum;

/// Radiance L arriving at the shaded point from direction wi, with the density of wi by solid
/// angle (for a delta light: 1, and delta set).
struct LightLiSample {
    Color L;
    Vector3 wi;
    float pdf = 0;
    float distance = 0;  ///< how far a shadow ray must stay clear (infinite for distant lights)
    bool delta = false;
    /// For area lights: the sampled point and the light's normal there, where the shadow ray
    /// must end (spawn_ray_to).
    bool on_surface = false;
    Point3 p_light{0, 0, 0};
    Normal3 n_light{0, 1, 0};
    /// Spectral mode: the light's own spectrum (Y = 1; L is its colour), or null (L upsampled).
    const Spectrum* spectrum = nullptr;
};

inline constexpr std::uint32_t kNoLight = 0xffffffffU;
static_assert(kNoLight == kNoBvhLight);

/// How the path tracer chooses the light to sample at a point. kBvh: distant lights (suns, the
/// environment) share n / (n + 1) of the choices in proportion to their power, the rest go
/// down the light BVH by importance at the point. kPower: every light in proportion to its power,
/// wherever the point is (what glint did before the BVH; kept for comparison).
enum class LightSamplerKind { kBvh, kPower };

class LightSampler {
public:
    /// Called by Scene::commit: gathers the lights and their powers; `radius` bounds the scene
    /// (distant lights' power is what crosses a disk of that radius).
    void build(const Scene& scene, float radius, LightSamplerKind kind = LightSamplerKind::kBvh);

    std::uint32_t count() const { return static_cast<std::uint32_t>(lights_.size()) + (env_ ? 1 : 0); }
    LightSamplerKind kind() const { return kind_; }
    /// A light chosen with probability proportional to its power, wherever the point is (for
    /// points in media, whose light is chosen before the point is known).
    std::uint32_t pick(float u, float* pmf) const;
    float pmf(std::uint32_t light) const { return distribution_.pmf(light); }
    /// A light chosen for point p on a surface with geometric normal n (zero in a medium) by
    /// the scene's light sampler; kNoLight with pmf 0 when no light can reach p.
    std::uint32_t pick(Point3 p, Normal3 n, float u, float* pmf) const;
    /// The probability with which pick(p, n, ...) chooses `light`.
    float pmf(Point3 p, Normal3 n, std::uint32_t light) const;
    const LightBvh& bvh() const { return bvh_; }
    /// The share of choices the distant lights take (kBvh).
    float distant_share() const { return p_distant_; }

    /// `time`: the path's (a moving light is sampled where it is then).
    std::optional<LightLiSample> sample_li(const Scene& scene, std::uint32_t light, Point3 p,
                                           Sample2 u, Float time = 0) const;
    /// The solid-angle density with which sample_li(light, p) produces the direction wi that
    /// reaches the light at the point `on_light` (for area lights; ignored otherwise).
    float pdf_li(const Scene& scene, std::uint32_t light, Point3 p, Vector3 wi,
                 Point3 on_light, Float time = 0) const;

    /// sample_li and pdf_li with a moving analytic shape where it is stored (p, wi and on_light
    /// carried there; meshes are placed at `time` by the scene).
    std::optional<LightLiSample> sample_li_stored(const Scene& scene, std::uint32_t light, Point3 p, Sample2 u,
                                                  Float time) const;
    float pdf_li_stored(const Scene& scene, std::uint32_t light, Point3 p, Vector3 wi, Point3 on_light,
                        Float time) const;

    /// The area light of an emitting shape, or kNoLight.
    std::uint32_t light_of(ShapeKind kind, std::uint32_t index, std::uint32_t prim = 0) const {
        if (kind == ShapeKind::kMesh) {
            if (index >= instance_first_.size() || instance_first_[index] == kNoLight) return kNoLight;
            return mesh_light_[instance_first_[index] + prim];
        }
        const auto& v = shape_light_[static_cast<std::size_t>(kind)];
        return index < v.size() ? v[index] : kNoLight;
    }
    /// Lights a ray that leaves the scene can meet: soft suns, then the environment.
    const std::vector<std::uint32_t>& distant() const { return distant_; }
    std::uint32_t environment() const { return env_ ? static_cast<std::uint32_t>(lights_.size()) : kNoLight; }
    /// Radiance a ray leaving the scene along unit `d` receives from distant light `light`.
    Color distant_radiance(const Scene& scene, std::uint32_t light, Vector3 d, Float time = 0) const;
    const Light& light(std::uint32_t i) const { return lights_[i]; }
    /// Where a point or spot light sits (media sample distances towards it); nullopt for every
    /// other light.
    std::optional<Point3> position(std::uint32_t light) const {
        if (light >= lights_.size()) return std::nullopt;
        if (const auto* p = std::get_if<PointLight>(&lights_[light])) return p->position;
        if (const auto* s = std::get_if<SpotLight>(&lights_[light])) return s->position;
        return std::nullopt;
    }

private:
    /// sample_li_stored's work, written into `s` (default-constructed) field by field; false when
    /// the light gives no sample from p.
    bool sample_li_into(const Scene& scene, std::uint32_t light, Point3 p, Sample2 u, Float time,
                        LightLiSample& s) const;
    std::vector<Light> lights_;  ///< the file's lights, then the area lights; the environment is last
    bool env_ = false;
    LightSamplerKind kind_ = LightSamplerKind::kBvh;
    Distribution1D distribution_;
    /// kBvh: the distant lights (their share p_distant_, among them by power) and the BVH over
    /// the others; distant_slot_[light]: the light's index in distant_distribution_, or kNoLight.
    LightBvh bvh_;
    float p_distant_ = 0;
    std::vector<std::uint32_t> distant_lights_, distant_slot_;
    Distribution1D distant_distribution_;
    std::array<std::vector<std::uint32_t>, 5> shape_light_;
    /// Mesh instances: where each emitting instance's per-triangle light ids start in
    /// mesh_light_ (kNoLight for instances that emit nothing).
    std::vector<std::uint32_t> instance_first_, mesh_light_;
    std::vector<std::uint32_t> distant_;
};

}  // namespace glint
