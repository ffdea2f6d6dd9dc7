#pragma once
// BSDFs, evaluated in the local shading frame where +z is the surface normal (outward, as the
// shape defines it). Conventions (pbrt's): wo points towards the viewer, wi towards the light,
// both unit vectors leaving the surface; eval returns f(wo, wi) without the cosine; transmission
// carries radiance (the 1 / eta^2 factor is included). A lobe may contain delta parts (mirror
// reflection, smooth refraction): eval and pdf never see them, sample returns them with
// `specular` set and f / pdf equal to the delta's weight.
//
// Lobes are plain structs in a closed set; a Bsdf is a weighted sum of up to three of them,
// built per hit from a material (materials/material.h).
#include <array>
#include <cstdint>
#include <optional>
#include <variant>

#include "glint/materials/microfacet.h"
#include "glint/math/color.h"
#include "glint/math/frame.h"
#include "glint/math/vector.h"
#include "glint/samplers/stratified.h"

namespace glint {

struct BsdfSample {
    Color f;            ///< f(wo, wi); for a delta, the weight such that f / pdf is the throughput
    Vector3 wi;         ///< local frame
    float pdf = 0;      ///< solid-angle density (a delta: the discrete probability of choosing it)
    bool specular = false;
    float eta = 1;      ///< the relative index crossed (1 for reflection)
};

/// Lambert: f = albedo / pi on the side of wo (two-sided).
struct DiffuseLobe {
    Color albedo;
    Color eval(Vector3 wo, Vector3 wi) const;
    float pdf(Vector3 wo, Vector3 wi) const;
    std::optional<BsdfSample> sample(Vector3 wo, float uc, Sample2 u) const;
};

/// Lambertian transmission: f = transmittance / pi on the side opposite wo (pbrt's
/// diffusetransmission pairs it with a DiffuseLobe for its reflectance).
struct DiffuseTransmissionLobe {
    Color transmittance;
    Color eval(Vector3 wo, Vector3 wi) const;
    float pdf(Vector3 wo, Vector3 wi) const;
    std::optional<BsdfSample> sample(Vector3 wo, float uc, Sample2 u) const;
};

/// A metal: GGX microfacet reflection (a mirror when smooth), two-sided. Fresnel: the complex
/// index (eta, k), Schlick with f0, or a constant reflectance (the article's mirror). Rough
/// metals add Kulla and Conty's multiple-scattering term so that energy lost between microfacets
/// returns (a white rough metal reflects everything, as a white furnace test demands).
struct ConductorLobe {
    enum class FresnelKind : std::uint8_t { kComplex, kSchlick, kConstant };
    FresnelKind kind = FresnelKind::kConstant;
    Color eta{1}, k{0};  ///< kComplex; kSchlick and kConstant use eta as f0 / reflectance
    Ggx ggx{0};
    Color fresnel(float cos_i) const;
    Color eval(Vector3 wo, Vector3 wi) const;
    float pdf(Vector3 wo, Vector3 wi) const;
    std::optional<BsdfSample> sample(Vector3 wo, float uc, Sample2 u) const;
    /// Hemispherical average of the Fresnel term, 2 int F(mu) mu dmu (for the multiple
    /// scattering colour); computed by make_conductor.
    Color f_avg{1};
};

/// Glass: reflection and refraction at an interface of relative index eta (inside / outside),
/// smooth (delta) or rough (GGX, Walter et al. 2007). `thin`: a sheet with no thickness, whose
/// transmission leaves undeflected and whose reflectance sums the inter-reflections. `tint`
/// multiplies transmission (glTF's base colour on transmissive materials).
struct DielectricLobe {
    float eta = 1.5f;
    Ggx ggx{0};
    bool thin = false;
    Color tint{1};
    Color eval(Vector3 wo, Vector3 wi) const;
    float pdf(Vector3 wo, Vector3 wi) const;
    std::optional<BsdfSample> sample(Vector3 wo, float uc, Sample2 u) const;
};

/// Plastic: a diffuse base under a dielectric coat of index eta (smooth or GGX-rough), two-sided.
/// Base term (Weidlich-Wilkie style, as Mitsuba's plastic):
///   f_base = albedo (1 - F(cos_i)) (1 - F(cos_o)) / (pi eta^2 (1 - albedo Fdr)),
/// with Fdr the coat's internal diffuse reflectance; it is energy-conserving by construction.
struct PlasticLobe {
    Color albedo;
    float eta = 1.5f;
    Ggx ggx{0};
    float fdr_inside = 0;  ///< computed by make_plastic
    Color eval(Vector3 wo, Vector3 wi) const;
    float pdf(Vector3 wo, Vector3 wi) const;
    std::optional<BsdfSample> sample(Vector3 wo, float uc, Sample2 u) const;

private:
    float coat_probability(float cos_o) const;
};

using Lobe = std::variant<DiffuseLobe, ConductorLobe, DielectricLobe, PlasticLobe, DiffuseTransmissionLobe>;

ConductorLobe make_conductor(ConductorLobe::FresnelKind kind, Color eta, Color k, float alpha);
PlasticLobe make_plastic(Color albedo, float eta, float alpha);
/// Internal diffuse reflectance of an interface seen from the denser side: 2 int F(mu, 1/eta)
/// mu dmu.
float diffuse_fresnel_inside(float eta);
/// E(mu, alpha): the fraction of light a white GGX conductor reflects in one scattering, for a
/// viewer at cos = mu (a table computed once by quadrature); E_avg(alpha) its cosine average.
float ggx_albedo(float mu, float alpha);
float ggx_albedo_average(float alpha);

/// A weighted sum of lobes in a shading frame. Lobe i is chosen for sampling with probability
/// proportional to weight_i (the sum of the weights may be below 1: energy absorbed).
class Bsdf {
public:
    Bsdf() = default;
    Bsdf(Normal3 n, std::initializer_list<std::pair<Lobe, float>> lobes);

    Vector3 to_local(Vector3 v) const { return {dot(v, t_), dot(v, b_), dot(v, n_)}; }
    Vector3 to_world(Vector3 v) const { return t_ * v.x + b_ * v.y + n_ * v.z; }

    /// World-space directions.
    Color eval(Vector3 wo, Vector3 wi) const;
    float pdf(Vector3 wo, Vector3 wi) const;
    /// uc chooses the lobe (and within it); u the direction. Returns a world-space wi.
    std::optional<BsdfSample> sample(Vector3 wo, float uc, Sample2 u) const;
    /// Whether any lobe has a non-delta part (light sampling is worth doing).
    bool has_smooth_part() const { return has_non_delta_; }
    int lobe_count() const { return count_; }

private:
    Vector3 t_{1, 0, 0}, b_{0, 1, 0}, n_{0, 0, 1};
    std::array<Lobe, 3> lobes_{};
    std::array<float, 3> weight_{};
    std::array<float, 3> select_{};
    int count_ = 0;
    bool has_non_delta_ = false;
};

}  // namespace glint
