#pragma once
// Integrators answer "what colour arrives along this camera ray". A virtual interface is right
// here: the choice is made once per render, not per ray.
#include <cstdint>
#include <limits>
#include <memory>

#include "glint/math/color.h"
#include "glint/ray.h"
#include "glint/samplers/sampler.h"
#include "glint/scene.h"
#include "glint/spectra/spectrum.h"

namespace glint {

/// Per-thread counters an integrator updates; summed per tile, never shared per ray.
struct RayCounter {
    std::uint64_t rays = 0;
};

/// What the camera ray saw first, for the AOVs denoisers consume. On a miss: albedo is the
/// background colour, normal (0,0,0), hit false.
struct FirstHit {
    Color albedo;
    Normal3 normal;  ///< the unit normal used for shading, world space
    Float depth = 0; ///< distance along the camera ray
    bool hit = false;
};

class Integrator {
public:
    virtual ~Integrator() = default;
    /// Radiance along the camera ray; fills `first` (when not null) with the first hit's AOVs.
    virtual Color li(const Scene& scene, const Ray& camera_ray, SampleStream& samples, RayCounter& counter,
                     FirstHit* first = nullptr) const = 0;
    /// Whether li_packet is offered: for integrators that draw no random numbers.
    virtual bool traces_packets() const { return false; }
    /// out[k] = li(rays[k]) to the bit, for n <= Scene::kPacketSize camera rays traced together
    /// (the scene answers each bounce's rays as one packet).
    virtual void li_packet(const Scene& scene, const Ray* rays, int n, Color* out, RayCounter& counter) const;
};

/// Figure 7: the object's colour where the ray hits, the background elsewhere.
class FlatIntegrator final : public Integrator {
public:
    Color li(const Scene& scene, const Ray& ray, SampleStream& samples, RayCounter& counter,
             FirstHit* first = nullptr) const override;
};

/// Figure 9: (N + 1)/2 of the outward geometric normal, the background elsewhere.
class NormalsIntegrator final : public Integrator {
public:
    Color li(const Scene& scene, const Ray& ray, SampleStream& samples, RayCounter& counter,
             FirstHit* first = nullptr) const override;
};

struct WhittedSettings {
    float ambient = 0.1f;  ///< the article's a
    bool shadows = true;
    int max_depth = 5;     ///< the camera ray is depth 0
};

/// The article's shading, section 4:
///   d = K a + sum over unshadowed lights of K * I * max(0, -L.N)
///   colour = (1 - s) d + s (d * r),  r = colour seen along R = D - 2(N.D)N,
/// traced recursively while depth < max_depth; at the limit r is the background along R.
class WhittedIntegrator final : public Integrator {
public:
    explicit WhittedIntegrator(WhittedSettings settings) : settings_(settings) {}
    Color li(const Scene& scene, const Ray& ray, SampleStream& samples, RayCounter& counter,
             FirstHit* first = nullptr) const override;
    bool traces_packets() const override { return true; }
    void li_packet(const Scene& scene, const Ray* rays, int n, Color* out, RayCounter& counter) const override;
    /// d at a surface point: ambient plus unshadowed direct light (exposed for tests).
    /// `time`: the shadow rays' (moving shapes block where they are then).
    Color direct(const Scene& scene, Point3 p, Normal3 n, Normal3 ng, Color k, RayCounter& counter,
                 Float time = 0) const;
    /// With the shading normal equal to the true one.
    Color direct(const Scene& scene, Point3 p, Normal3 n, Color k, RayCounter& counter) const {
        return direct(scene, p, n, n, k, counter);
    }

private:
    WhittedSettings settings_;
};

enum class LightStrategy { kMis, kLight, kBsdf };

struct PathSettings {
    int max_depth = 16;  ///< scattering events; 1 = direct lighting only
    /// Russian roulette from this depth on (0-based): a path continues with probability
    /// min(1, sqrt(max throughput)).
    int rr_depth = 5;
    /// Clamp each sample's radiance to this luminance-independent maximum per channel (biased;
    /// off when infinite).
    float clamp = std::numeric_limits<float>::infinity();
    /// kMis: light sampling and BSDF sampling combined by the power heuristic; kLight / kBsdf:
    /// one strategy only (for comparisons; kBsdf never sees point, spot or sharp sun lights).
    LightStrategy strategy = LightStrategy::kMis;
    /// How the light to sample is chosen (lights/light_sampler.h); build copies it to the scene.
    LightSamplerKind light_sampler = LightSamplerKind::kBvh;
    /// How image textures are read over a pixel's footprint (kBilinear: no filtering at all,
    /// checkers included).
    TextureFilter texture_filter = TextureFilter::kEwa;
    /// Spectral rendering (spectra/spectrum.h): three wavelengths per path instead of RGB.
    bool spectral = false;
    /// White balance for a light of this colour temperature (kelvin; 0: none), as pbrt-v4's film
    /// "whitebalance" (spectra/spectrum.h, white_balance).
    float white_balance = 0;
};

/// Unidirectional path tracing with next-event estimation and multiple importance sampling
/// (Veach's power heuristic, beta = 2) for every light, Russian roulette and max_depth; through
/// participating media too (delta tracking, ratio-tracked shadow rays, spectral MIS) when the
/// scene has any (path.cpp).
class PathIntegrator final : public Integrator {
public:
    explicit PathIntegrator(PathSettings settings)
        : settings_(settings), balance_(settings.white_balance > 0 ? white_balance(settings.white_balance) : ColorMatrix{}) {}
    Color li(const Scene& scene, const Ray& ray, SampleStream& samples, RayCounter& counter,
             FirstHit* first = nullptr) const override;

private:
    bool roulette(Color& beta, float eta_scale, Color r_u, int depth, float u) const;
    PathSettings settings_;
    ColorMatrix balance_;
};

}  // namespace glint
