#pragma once
// Participating media: a closed set (std::variant) of plain structs, as materials are.
// Coefficients are RGB per unit of scene length: absorption sigma_a, scattering sigma_s,
// extinction sigma_t = sigma_a + sigma_s, and emitted radiance Le (a medium emits sigma_a Le per
// unit length, pbrt's convention, so that an optically thick emitter looks like a surface of
// radiance Le).
//
// Free-flight sampling is delta tracking in the null-scattering formulation (Miller, Georgiev and
// Jarosz 2019; pbrt-v4's SampleT_maj): along a ray the medium offers segments of constant
// majorant sigma_maj >= sigma_t; tentative collisions are drawn at exponential distances with
// sigma_maj of one "hero" channel, and at each the caller decides absorption, scattering or a
// null collision. sample_t_maj below walks the segments and calls back at each tentative
// collision; the caller's weights make RGB media unbiased for any hero (spectral MIS).
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <variant>

#include "glint/math/color.h"
#include "glint/math/transform.h"
#include "glint/media/grid.h"
#include "glint/media/phase.h"
#include "glint/ray.h"
#include "glint/samplers/hash.h"

namespace glint {

using MediumId = std::uint32_t;
inline constexpr MediumId kNoMedium = 0xffffffffU;

/// The media on the two sides of a surface: `interior` behind the geometric normal, `exterior`
/// on the side it points to. A surface without an interface leaves a ray's medium unchanged.
struct MediumInterface {
    MediumId interior = kNoMedium;
    MediumId exterior = kNoMedium;
    /// The medium a ray leaving the surface along a direction with this dot product with the
    /// geometric normal is in.
    MediumId side(Float cos_n) const { return cos_n > 0 ? exterior : interior; }
};

/// A medium's coefficients at one point.
struct MediumPoint {
    Color sigma_a, sigma_s, Le;
};

/// A medium's coefficients at a path's wavelengths (spectral mode, issue 36): sigma_a and
/// sigma_s (per unit density in a grid) upsampled as unbounded spectra and the emission colour
/// as an illuminant; `wl` for a grid's black-body emission. Where a function takes one, null
/// means RGB mode (the medium's own colours).
struct Wavelengths;
struct SpectralMedium {
    Color sigma_a, sigma_s, Le;
    const Wavelengths* wl = nullptr;
};

/// Constant coefficients everywhere.
struct HomogeneousMedium {
    Color sigma_a{0}, sigma_s{0}, Le{0};
    HgPhase phase;
};

/// Coefficients scaled by a density grid (media/grid.h) placed in the world by `transform`
/// (grid index space to world: the file's voxel-to-world transform, then the object's). The
/// majorant grid bounds the density per cell of about a brick.
struct GridMedium {
    Transform transform;
    Color sigma_a{0}, sigma_s{0};  ///< per unit density (the scene's density scale applied)
    VoxelGrid density;
    MajorantGrid majorant;
    HgPhase phase;
    /// Emission: none, Le = emission_color x (grid value) x emission_scale, or Le = the colour of
    /// a blackbody at temperature (grid value x temperature_scale) kelvin (normalised to a peak
    /// of 1, pbrt-v4's convention) x emission_scale.
    enum class EmissionKind : std::uint8_t { kNone, kGrid, kTemperature };
    EmissionKind emission_kind = EmissionKind::kNone;
    VoxelGrid emission;  ///< in the same index space as density
    Color emission_color{1};
    float emission_scale = 1;
    float temperature_scale = 1;

    MediumPoint at(Point3 p_index, const SpectralMedium* sm = nullptr) const;
};

using Medium = std::variant<HomogeneousMedium, GridMedium>;

/// The phase function of a medium.
inline const HgPhase& phase_of(const Medium& m) {
    return std::visit([](const auto& x) -> const HgPhase& { return x.phase; }, m);
}

/// exp(-sigma d) per channel, with exp(-0 d) = 1 exactly even for an infinite d.
inline Color transmittance(Color sigma, float d) {
    const auto one = [d](float s) { return s == 0 ? 1.0f : std::exp(-s * d); };
    return {one(sigma.r), one(sigma.g), one(sigma.b)};
}

/// Equiangular sampling of a distance along a ray towards a point (Kulla and Fajardo 2012): the
/// density over t in [0, t_max) is proportional to 1/|x(t) - c|^2, the falloff of a point
/// light's irradiance, so points near the light are drawn as often as they matter. Valid only
/// when the point lies off the ray's line (D > 0) and the angle subtended is not zero.
struct Equiangular {
    float delta = 0;   ///< t of the point on the ray closest to c
    float D = 0;       ///< distance from c to the ray's line
    float theta_a = 0, theta_b = 0;

    /// nullopt when c is on (or numerically at) the ray's line, or the interval is empty.
    static std::optional<Equiangular> make(const Ray& ray, float t_max, Point3 c) {
        const Vector3 oc = c - ray.origin;
        const float delta = dot(oc, ray.direction);
        const float D = length(oc - ray.direction * delta);
        if (!(D > 1e-6f * std::max(1.0f, std::abs(delta)))) return std::nullopt;
        const float a = std::atan2(-delta, D);
        const float b = std::isinf(t_max) ? 1.57079632679f : std::atan2(t_max - delta, D);
        if (!(b > a)) return std::nullopt;
        return Equiangular{delta, D, a, b};
    }
    float sample(float u) const { return delta + D * std::tan(theta_a + u * (theta_b - theta_a)); }
    float pdf(float t) const {
        const float x = t - delta;
        return D / ((theta_b - theta_a) * (D * D + x * x));
    }
};

/// The linear sRGB colour of a blackbody at `kelvin`, normalised so that its spectral radiance
/// peaks at 1 (the spectrum integrated against the CIE 1931 observer, divided by the integral of
/// y-bar, as an emission spectrum in pbrt-v4). 0 at or below 0 K.
Color blackbody_rgb(float kelvin);
/// The coefficients of `m` at the wavelengths `wl` (see SpectralMedium).
SpectralMedium spectral_medium(const Medium& m, const Wavelengths& wl);

/// Walks the majorant segments of `medium` along `ray` (unit direction, world units) over
/// [0, t_max) and draws tentative collisions with the hero channel's majorant. At each one,
/// calls f(p, point, sigma_maj, T_maj) with T_maj the majorant transmittance since the previous
/// collision (or the start); f returns false to stop. Returns the majorant transmittance from
/// the last collision to t_max (Color{1} if f stopped the walk). `u` is the first uniform
/// number, `rng` supplies the rest. The ray is taken by value: f may change the caller's ray.
template <typename F>
Color sample_t_maj(const Medium& medium, const Ray ray, float t_max, float u, HashRng& rng,
                   int hero, F&& f, const SpectralMedium* sm = nullptr) {
    Color T_maj{1};
    // One segment [t0, t1) of constant majorant; false when f stopped.
    const auto segment = [&](float t0, float t1, Color sigma_maj, const auto& point_at) {
        const float s = sigma_maj[hero];
        if (s == 0) {
            T_maj *= transmittance(sigma_maj, t1 - t0);
            return true;
        }
        for (;;) {
            const float t = t0 - std::log1p(-u) / s;
            u = rng.next();
            if (!(t < t1)) {
                T_maj *= transmittance(sigma_maj, t1 - t0);
                return true;
            }
            T_maj *= transmittance(sigma_maj, t - t0);
            if (!f(ray.at(t), point_at(t), sigma_maj, T_maj)) {
                T_maj = Color{1};
                return false;
            }
            T_maj = Color{1};
            t0 = t;
        }
    };
    if (const auto* h = std::get_if<HomogeneousMedium>(&medium)) {
        const MediumPoint mp = sm ? MediumPoint{sm->sigma_a, sm->sigma_s, sm->Le} : MediumPoint{h->sigma_a, h->sigma_s, h->Le};
        segment(0, t_max, h->sigma_a + h->sigma_s, [&mp](float) { return mp; });
        return T_maj;
    }
    const auto& g = std::get<GridMedium>(medium);
    const Ray local = object_ray(g.transform, ray);
    const Color sigma_t = sm ? sm->sigma_a + sm->sigma_s : g.sigma_a + g.sigma_s;
    MajorantWalk walk(g.majorant, local.origin, local.direction, 0, t_max);
    MajorantSegment seg;
    while (walk.next(seg)) {
        const bool go_on = segment(seg.t0, seg.t1, sigma_t * seg.sigma, [&](float t) { return g.at(local.at(t), sm); });
        if (!go_on) return T_maj;
    }
    return T_maj;
}

}  // namespace glint
