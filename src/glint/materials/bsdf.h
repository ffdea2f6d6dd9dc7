#pragma once
// BSDFs, evaluated in the local shading frame where +z is the surface normal (outward, as the
// shape defines it). Conventions (pbrt's): wo points towards the viewer, wi towards the light,
// both unit vectors leaving the surface; eval returns f(wo, wi) without the cosine; transmission
// carries radiance (the 1 / eta^2 factor is included). A lobe may contain delta parts (mirror
// reflection, smooth refraction): eval and pdf never see them, sample returns them with
// `specular` set and f / pdf equal to the delta's weight.
//
// Lobes are plain structs in a closed set; a Bsdf is a weighted sum of up to three of them (under
// glTF's clear-coat and sheen layers, when a material has them),
// built per hit from a material (materials/material.h).
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <type_traits>
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
    /// The sample came from a random walk (LayeredLobe): f / pdf is its unbiased weight, but pdf
    /// is the walk's own density, not the lobe's; MIS must ask the Bsdf's pdf (pbrt-v4's
    /// pdfIsProportional).
    bool pdf_is_proportional = false;
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
    /// Without Kulla and Conty's term: pbrt-v4's conductor, as its coatedconductor holds it.
    bool single_scattering = false;
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
    /// glTF's KHR_materials_specular: the coat's Fresnel F(cos) (of eta, normal value f0) becomes
    /// weight (f0' + (1 - f0') (F - f0) / (1 - f0)) with f0' = min(f0 specular_color, 1): the
    /// colour tints normal incidence, the weight scales all of it (grazing reflection = weight).
    /// The base sees 1 - max channel of that. Defaults change nothing.
    float specular_weight = 1;
    Color specular_color{1};
    Color eval(Vector3 wo, Vector3 wi) const;
    float pdf(Vector3 wo, Vector3 wi) const;
    std::optional<BsdfSample> sample(Vector3 wo, float uc, Sample2 u) const;

    /// The coat's reflectance at cos (per channel, KHR_materials_specular applied).
    Color coat_fresnel(float cos) const;

private:
    float coat_probability(float cos_o) const;
};

/// glTF's sheen (KHR_materials_sheen): fibres on the surface, Estevez and Kulla's "Charlie"
/// distribution D(m) = (2 + 1/a) sin(theta_m)^(1/a) / (2 pi), a = roughness^2 (roughness at least
/// 0.07), with Neubelt and Pettineo's visibility 1 / (4 (cos_i + cos_o - cos_i cos_o)):
/// f = color D V, reflection only, two-sided, sampled by the cosine.
struct SheenLobe {
    Color color{0};
    float roughness = 0.5f;
    Color eval(Vector3 wo, Vector3 wi) const;
    float pdf(Vector3 wo, Vector3 wi) const;
    std::optional<BsdfSample> sample(Vector3 wo, float uc, Sample2 u) const;
};

/// Directional albedos (the fraction reflected towards a viewer at cos = mu), tabulated once by
/// quadrature at first use: of a white sheen lobe, and of glTF's clear coat (a GGX dielectric
/// of index 1.5, single scattering) of the given roughness.
float sheen_albedo(float mu, float roughness);
float clearcoat_albedo(float mu, float roughness);
/// glTF's clear coat: a GGX dielectric of index 1.5 (the complex Fresnel with k = 0) and the
/// given roughness, single scattering only.
ConductorLobe clearcoat_lobe(float roughness);

/// The constant part of a layered BSDF (below), held by its material: a dielectric coat of
/// index eta (GGX width `coat`, smooth below Ggx::kSmooth) over a diffuse base or, with
/// `conductor_base`, a metal (GGX width `metal`, single scattering as pbrt-v4's); a slab of
/// `thickness` between them, filled with a medium of `albedo` and Henyey-Greenstein `g`
/// (sigma_t = 1); `samples` random walks of at most `max_depth` bounces per estimate.
struct LayeredParams {
    float eta = 1.5f;
    Ggx coat{0};
    bool conductor_base = false;
    Ggx metal{0};
    float thickness = 0.01f;
    Color albedo{0};
    float g = 0;
    int max_depth = 10;
    int samples = 1;
};

/// pbrt-v4's layered BSDF (coateddiffuse, coatedconductor; Guo et al. 2018's position-free
/// Monte Carlo as pbrt-v4 implements it), two-sided. f and pdf are stochastic estimates from
/// random walks seeded by a hash of the directions, so every call with the same arguments
/// returns the same value; sample() follows one walk and marks its pdf as proportional. A Bsdf
/// holding a LayeredLobe must hold it alone (a mixture would weigh a walk's sample by the noisy
/// pdf estimate). Per hit it carries only the colours (the lobe stays as small as the
/// others); the rest is the material's, which outlives every Bsdf made from it.
struct LayeredLobe {
    const LayeredParams* layer = nullptr;
    Color base{0.5f};  ///< the diffuse base's albedo, or the metal's eta relative to the coat
    Color k{0};        ///< the metal's k relative to the coat
    Color albedo{0};   ///< the slab medium's albedo (the layer's, at the path's wavelengths)
    Color eval(Vector3 wo, Vector3 wi) const;
    float pdf(Vector3 wo, Vector3 wi) const;
    std::optional<BsdfSample> sample(Vector3 wo, float uc, Sample2 u) const;
};

using Lobe = std::variant<DiffuseLobe, ConductorLobe, DielectricLobe, PlasticLobe,
                          DiffuseTransmissionLobe, LayeredLobe>;

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
    Bsdf() {}  // user-provided: the lobes' storage (below) is left as it is
    Bsdf(Normal3 n, std::initializer_list<std::pair<Lobe, float>> lobes);
    /// One lobe of weight 1: what Bsdf(n, {{lobe, 1}}) makes, the lobe built in place (the list's
    /// pair and its copy were 1.4 % of the pbrt-v4 Cornell box's instructions; performance.md,
    /// step 20). L is one of Lobe's alternatives.
    template <typename L>
    Bsdf(Normal3 n, const L& lobe) {
        set_frame(n);
        std::construct_at(&lobes_[0], std::in_place_type<L>, lobe);
        weight_[0] = select_[0] = 1;
        count_ = 1;
        has_non_delta_ = non_delta(lobe);
    }

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

    /// glTF's layers over the lobes, outermost first: a clear coat (KHR_materials_clearcoat:
    /// `weight` of a GGX dielectric of index 1.5) and a sheen (KHR_materials_sheen). Each layer L
    /// of directional albedo E_L adds its own reflection and scales what lies under it by
    /// (1 - E_L(mu_o)) (1 - E_L(mu_i)): energy is conserved (what the layer reflects towards the
    /// viewer is what it keeps from the layers below) and f stays reciprocal. The glTF
    /// specification's real-time form scales by the viewer's side only; glint keeps reciprocity.
    void set_clearcoat(float weight, float roughness);
    void set_sheen(Color color, float roughness);

private:
    struct LayerWeights {
        float p_coat = 0, p_sheen = 0;  ///< sampling probabilities of the coat and the sheen
    };
    LayerWeights layer_weights(Vector3 wo) const;
    Color eval_lobes(Vector3 wo, Vector3 wi) const;  ///< local frame, layers left out
    float pdf_lobes(Vector3 wo, Vector3 wi) const;
    std::optional<BsdfSample> sample_lobes(Vector3 wo, float uc, Sample2 u) const;  ///< local frame
    /// The layered parts, out of line so that a Bsdf without layers runs the lobes' code alone.
    [[gnu::noinline]] std::optional<BsdfSample> sample_layered(Vector3 wo, float uc, Sample2 u) const;
    [[gnu::noinline]] Color eval_local(Vector3 wo, Vector3 wi) const;  ///< everything, local frame
    [[gnu::noinline]] float pdf_local(Vector3 wo, Vector3 wi, const LayerWeights& w) const;
    float coat_keep(Vector3 wo, Vector3 wi) const;   ///< (1 - E_coat(mu_o)) (1 - E_coat(mu_i))
    float sheen_keep(Vector3 wo, Vector3 wi) const;
    bool layered() const { return coat_weight_ > 0 || sheen_.color.max_component() > 0; }

    float coat_weight_ = 0;
    float coat_roughness_ = 0;  ///< the coat's lobe is clearcoat_lobe(coat_roughness_), made when used
    SheenLobe sheen_;

    void set_frame(Normal3 n);
    /// Whether a lobe has a part that is not a delta (light sampling can reach it).
    template <typename L>
    static bool non_delta(const L& l) {
        if constexpr (std::is_same_v<L, ConductorLobe>) return !l.ggx.smooth();
        if constexpr (std::is_same_v<L, DielectricLobe>) return !(l.thin || l.ggx.smooth() || l.eta == 1);
        return true;
    }

    Vector3 t_{1, 0, 0}, b_{0, 1, 0}, n_{0, 0, 1};
    // lobes_[0, count_) are the lobes; the rest is storage never read. A union, so that nothing
    // initialises it: a value-initialised std::array was zeroed whole (168 bytes with the
    // weights, GCC's `rep stos`), 40 % of the constructor's time in perf on the Cornell box. Lobe
    // is trivially copyable, so a Bsdf still copies as plain bytes.
    static_assert(std::is_trivially_copyable_v<Lobe> && std::is_trivially_destructible_v<Lobe>);
    union {
        std::array<Lobe, 3> lobes_;
    };
    std::array<float, 3> weight_{};
    std::array<float, 3> select_{};
    int count_ = 0;
    bool has_non_delta_ = false;
};

}  // namespace glint
