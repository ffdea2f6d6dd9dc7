// pbrt-v4's layered BSDF (coateddiffuse, coatedconductor): stochastic evaluation by random walks
// between a dielectric coat and a base, after Guo, Hasan and Zhao, "Position-Free Monte Carlo
// Simulation for Arbitrary Layered BSDFs" (2018), with the estimators pbrt-v4 (Pharr, Jakob and
// Humphreys, 4th edition, section 14.3) derives: next-event estimation through the exit
// interface weighted by the power heuristic, Russian roulette after 3 bounces, the pdf as a
// mix of its TRT estimate and a uniform sphere. The coat's interface needs what DielectricLobe
// does not offer: sampling restricted to reflection or to transmission, and the adjoint form
// (no 1 / eta^2 on transmission) for the walk started from wi.
#include <bit>
#include <cmath>
#include <numbers>

#include "glint/materials/bsdf.h"
#include "glint/materials/fresnel.h"
#include "glint/media/phase.h"
#include "glint/samplers/hash.h"
#include "glint/samplers/warp.h"

namespace glint {

namespace {

enum class Part : std::uint8_t { kAll, kReflection, kTransmission };
enum class Mode : std::uint8_t { kRadiance, kImportance };

bool same_hemisphere(Vector3 a, Vector3 b) { return a.z * b.z > 0; }

// Probabilities of choosing reflection and transmission, given their Fresnel weights r, t and
// the part asked for; false when nothing may be chosen.
bool choice(float r, float t, Part part, float& pr, float& pt) {
    pr = part == Part::kTransmission ? 0 : r;
    pt = part == Part::kReflection ? 0 : t;
    return pr + pt > 0;
}

// The coat: a dielectric interface (smooth or GGX-rough) of relative index eta.
struct Coat {
    float eta;
    Ggx ggx;
    bool smooth() const { return ggx.smooth() || eta == 1; }

    Color f(Vector3 wo, Vector3 wi, Mode mode) const {
        if (smooth()) return Color{0};
        Vector3 wm;
        float etap;
        if (!generalized_half(wo, wi, eta, wm, etap)) return Color{0};
        const float fr = fresnel_dielectric(dot(wo, wm), eta);
        if (etap == 1) return Color{ggx.d(wm) * ggx.g(wo, wi) * fr / std::abs(4 * wi.z * wo.z)};
        const float denom = sqr(dot(wi, wm) + dot(wo, wm) / etap) * wi.z * wo.z;
        float ft = ggx.d(wm) * (1 - fr) * ggx.g(wo, wi) * std::abs(dot(wi, wm) * dot(wo, wm) / denom);
        if (mode == Mode::kRadiance) ft /= sqr(etap);
        return Color{ft};
    }

    float pdf(Vector3 wo, Vector3 wi, Part part) const {
        if (smooth()) return 0;
        Vector3 wm;
        float etap;
        if (!generalized_half(wo, wi, eta, wm, etap)) return 0;
        const float r = fresnel_dielectric(dot(wo, wm), eta);
        float pr, pt;
        if (!choice(r, 1 - r, part, pr, pt)) return 0;
        if (etap == 1) return ggx.d_visible(wo, wm) / (4 * std::abs(dot(wo, wm))) * pr / (pr + pt);
        const float denom = sqr(dot(wi, wm) + dot(wo, wm) / etap);
        return ggx.d_visible(wo, wm) * std::abs(dot(wi, wm)) / denom * pt / (pr + pt);
    }

    std::optional<BsdfSample> sample(Vector3 wo, float uc, Sample2 u, Mode mode, Part part) const {
        if (wo.z == 0) return std::nullopt;
        if (smooth()) {
            const float r = fresnel_dielectric(wo.z, eta);
            float pr, pt;
            if (!choice(r, 1 - r, part, pr, pt)) return std::nullopt;
            if (uc < pr / (pr + pt)) {
                const Vector3 wi{-wo.x, -wo.y, wo.z};
                return BsdfSample{Color{r / std::abs(wi.z)}, wi, pr / (pr + pt), true};
            }
            Vector3 wi;
            float etap;
            if (!refract(wo, {0, 0, 1}, eta, wi, etap) || wi.z == 0) return std::nullopt;
            float ft = (1 - r) / std::abs(wi.z);
            if (mode == Mode::kRadiance) ft /= sqr(etap);
            return BsdfSample{Color{ft}, wi, pt / (pr + pt), true, etap};
        }
        const Vector3 wm = ggx.sample_visible(wo, u);
        const float r = fresnel_dielectric(dot(wo, wm), eta);
        float pr, pt;
        if (!choice(r, 1 - r, part, pr, pt)) return std::nullopt;
        Vector3 wi;
        float etap = 1;
        if (uc < pr / (pr + pt)) {
            wi = reflect_about(wo, wm);
            if (!same_hemisphere(wo, wi)) return std::nullopt;
        } else {
            if (!refract(wo, wm, eta, wi, etap) || same_hemisphere(wo, wi) || wi.z == 0) return std::nullopt;
        }
        const float p = pdf(wo, wi, part);
        if (!(p > 0)) return std::nullopt;
        return BsdfSample{f(wo, wi, mode), wi, p, false, etap};
    }
};

// The base: reflection only (a diffuse or a conductor lobe), so it has no transmission part.
struct Base {
    bool conductor;
    DiffuseLobe diffuse;
    ConductorLobe metal;
    explicit Base(const LayeredLobe& l) : conductor(l.layer->conductor_base), diffuse{l.base} {
        if (conductor) {
            metal.kind = ConductorLobe::FresnelKind::kComplex;
            metal.eta = l.base;
            metal.k = l.k;
            metal.ggx = l.layer->metal;
            metal.single_scattering = true;  // pbrt-v4's ConductorBxDF
        }
    }
    bool specular() const { return conductor && metal.ggx.smooth(); }
    Color f(Vector3 wo, Vector3 wi) const { return conductor ? metal.eval(wo, wi) : diffuse.eval(wo, wi); }
    float pdf(Vector3 wo, Vector3 wi) const { return conductor ? metal.pdf(wo, wi) : diffuse.pdf(wo, wi); }
    std::optional<BsdfSample> sample(Vector3 wo, float uc, Sample2 u) const {
        return conductor ? metal.sample(wo, uc, u) : diffuse.sample(wo, uc, u);
    }
};

// Transmittance of the slab's medium (sigma_t = 1) along w over a height difference dz.
float slab_tr(float dz, Vector3 w) {
    if (std::abs(dz) <= std::numeric_limits<float>::min()) return 1;
    return std::exp(-std::abs(dz / w.z));
}

std::uint32_t hash_vector(std::uint32_t seed, Vector3 v) {
    seed = hash_combine(seed, std::bit_cast<std::uint32_t>(v.x));
    seed = hash_combine(seed, std::bit_cast<std::uint32_t>(v.y));
    return hash_combine(seed, std::bit_cast<std::uint32_t>(v.z));
}

// A deterministic stream from a pair of hashes (the walk's randomness is a function of its
// arguments, as in pbrt-v4, so repeated evaluations agree and images do not depend on threads).
struct WalkRng {
    HashRng rng;
    WalkRng(std::uint32_t a, std::uint32_t b) : rng{hash_combine(a, b)} {}
    float operator()() { return rng.next(); }
    Sample2 two() {
        const float x = rng.next();
        return {x, rng.next()};
    }
};

}  // namespace

Color LayeredLobe::eval(Vector3 wo, Vector3 wi) const {
    if (wo.z < 0) wo = -wo, wi = -wi;  // two-sided: always entered through the coat
    // The base transmits nothing, so light leaves through the coat: f is 0 across the surface.
    if (!same_hemisphere(wo, wi)) return Color{0};
    const LayeredParams& p = *layer;
    const Coat top{p.eta, p.coat};
    const Base bottom(*this);
    const int n = std::max(1, p.samples);
    Color f = top.f(wo, wi, Mode::kRadiance) * float(n);
    WalkRng r(hash_vector(0x6c61796bU, wo), hash_vector(0x65726564U, wi));
    const HgPhase phase{p.g};
    const bool scatters = albedo.max_component() > 0;
    for (int s = 0; s < n; ++s) {
        // Into the slab through the coat, from wo; and the virtual light's way in from wi.
        const auto wos = top.sample(wo, r(), r.two(), Mode::kRadiance, Part::kTransmission);
        if (!wos || wos->f.max_component() <= 0 || !(wos->pdf > 0) || wos->wi.z == 0) continue;
        const auto wis = top.sample(wi, r(), r.two(), Mode::kImportance, Part::kTransmission);
        if (!wis || wis->f.max_component() <= 0 || !(wis->pdf > 0) || wis->wi.z == 0) continue;
        Color beta = wos->f * std::abs(wos->wi.z) / wos->pdf;
        float z = p.thickness;
        Vector3 w = wos->wi;
        for (int depth = 0; depth < p.max_depth; ++depth) {
            if (depth > 3 && beta.max_component() < 0.25f) {
                const float q = std::max(0.0f, 1 - beta.max_component());
                if (r() < q) break;
                beta = beta / (1 - q);
            }
            if (!scatters) {
                z = z == p.thickness ? 0 : p.thickness;
                beta = beta * slab_tr(p.thickness, w);
            } else {
                const float dz = -std::log(1 - r()) * std::abs(w.z);  // sigma_t = 1
                const float zp = w.z > 0 ? z + dz : z - dz;
                if (zp == z) continue;
                if (0 < zp && zp < p.thickness) {
                    // Scattering in the slab: next-event estimation out through the coat along wis.
                    float wt = 1;
                    if (!top.smooth()) wt = power_heuristic(wis->pdf, phase.pdf(-w, -wis->wi));
                    f += beta * albedo * phase.p(-w, -wis->wi) * wt * slab_tr(zp - p.thickness, wis->wi) *
                         wis->f / wis->pdf;
                    const PhaseSample ps = phase.sample(-w, r.two());
                    if (!(ps.pdf > 0) || ps.wi.z == 0) continue;
                    beta *= albedo * ps.p / ps.pdf;
                    w = ps.wi;
                    z = zp;
                    // The phase sample itself may leave through the coat towards wi.
                    if (z < p.thickness && w.z > 0 && !top.smooth()) {
                        const Color f_exit = top.f(-w, wi, Mode::kRadiance);
                        if (f_exit.max_component() > 0) {
                            const float exit_pdf = top.pdf(wi, -w, Part::kTransmission);
                            f += beta * slab_tr(zp - p.thickness, ps.wi) * f_exit * power_heuristic(ps.pdf, exit_pdf);
                        }
                    }
                    continue;
                }
                z = std::clamp(zp, 0.0f, p.thickness);
            }
            if (z == p.thickness) {
                // Back at the coat from below: reflect into the slab again.
                const auto bs = top.sample(-w, r(), r.two(), Mode::kRadiance, Part::kReflection);
                if (!bs || bs->f.max_component() <= 0 || !(bs->pdf > 0) || bs->wi.z == 0) break;
                beta *= bs->f * std::abs(bs->wi.z) / bs->pdf;
                w = bs->wi;
            } else {
                // At the base: next-event estimation along wis, then a sampled bounce.
                if (!bottom.specular()) {
                    float wt = 1;
                    if (!top.smooth()) wt = power_heuristic(wis->pdf, bottom.pdf(-w, -wis->wi));
                    f += beta * bottom.f(-w, -wis->wi) * std::abs(wis->wi.z) * wt *
                         slab_tr(p.thickness, wis->wi) * wis->f / wis->pdf;
                }
                const auto bs = bottom.sample(-w, r(), r.two());
                if (!bs || bs->f.max_component() <= 0 || !(bs->pdf > 0) || bs->wi.z == 0) break;
                beta *= bs->f * std::abs(bs->wi.z) / bs->pdf;
                w = bs->wi;
                if (!top.smooth()) {
                    const Color f_exit = top.f(-w, wi, Mode::kRadiance);
                    if (f_exit.max_component() > 0) {
                        float wt = 1;
                        if (!bottom.specular()) wt = power_heuristic(bs->pdf, top.pdf(wi, -w, Part::kTransmission));
                        f += beta * slab_tr(p.thickness, bs->wi) * f_exit * wt;
                    }
                }
            }
        }
    }
    return f / float(n);
}

float LayeredLobe::pdf(Vector3 wo, Vector3 wi) const {
    if (wo.z < 0) wo = -wo, wi = -wi;
    const LayeredParams& p = *layer;
    const Coat top{p.eta, p.coat};
    const Base bottom(*this);
    const int n = std::max(1, p.samples);
    WalkRng r(hash_vector(0x70646677U, wi), hash_vector(0x70646f77U, wo));
    float sum = 0;
    if (same_hemisphere(wo, wi)) {
        sum += float(n) * top.pdf(wo, wi, Part::kReflection);
        for (int s = 0; s < n; ++s) {
            // The TRT term: in through the coat, off the base, out through the coat.
            const auto wos = top.sample(wo, r(), r.two(), Mode::kRadiance, Part::kTransmission);
            const auto wis = top.sample(wi, r(), r.two(), Mode::kImportance, Part::kTransmission);
            if (!wos || !(wos->pdf > 0) || wos->f.max_component() <= 0 || !wis || !(wis->pdf > 0) ||
                wis->f.max_component() <= 0)
                continue;
            if (top.smooth()) {
                sum += bottom.pdf(-wos->wi, -wis->wi);
                continue;
            }
            const auto rs = bottom.sample(-wos->wi, r(), r.two());
            if (!rs || !(rs->pdf > 0) || rs->f.max_component() <= 0) continue;
            if (bottom.specular()) {
                sum += top.pdf(-rs->wi, wi, Part::kAll);
            } else {
                const float r_pdf = bottom.pdf(-wos->wi, -wis->wi);
                sum += power_heuristic(wis->pdf, r_pdf) * r_pdf;
                const float t_pdf = top.pdf(-rs->wi, wi, Part::kAll);
                sum += power_heuristic(rs->pdf, t_pdf) * t_pdf;
            }
        }
    }
    // (Nothing is transmitted: the base reflects only.) A tenth of the density is uniform over
    // the sphere, so the estimate is never 0 where f is not.
    return 0.1f / (4 * std::numbers::pi_v<float>) + 0.9f * sum / float(n);
}

std::optional<BsdfSample> LayeredLobe::sample(Vector3 wo, float uc, Sample2 u) const {
    const bool flip = wo.z < 0;
    if (flip) wo = -wo;
    const LayeredParams& p = *layer;
    const Coat top{p.eta, p.coat};
    const Base bottom(*this);
    auto bs = top.sample(wo, uc, u, Mode::kRadiance, Part::kAll);
    if (!bs || bs->f.max_component() <= 0 || !(bs->pdf > 0) || bs->wi.z == 0) return std::nullopt;
    if (bs->wi.z > 0) {  // reflected by the coat
        if (flip) bs->wi = -bs->wi;
        bs->pdf_is_proportional = true;
        return bs;
    }
    Vector3 w = bs->wi;
    bool specular_path = bs->specular;
    WalkRng r(hash_vector(0x73616d70U, wo), hash_combine(std::bit_cast<std::uint32_t>(uc),
                                                         hash_combine(std::bit_cast<std::uint32_t>(u.x),
                                                                      std::bit_cast<std::uint32_t>(u.y))));
    Color f = bs->f * std::abs(bs->wi.z);
    float pdf = bs->pdf;
    float z = p.thickness;
    const HgPhase phase{p.g};
    const bool scatters = albedo.max_component() > 0;
    for (int depth = 0; depth < p.max_depth; ++depth) {
        const float rr_beta = f.max_component() / pdf;
        if (depth > 3 && rr_beta < 0.25f) {
            const float q = std::max(0.0f, 1 - rr_beta);
            if (r() < q) return std::nullopt;
            pdf *= 1 - q;
        }
        if (w.z == 0) return std::nullopt;
        if (scatters) {
            const float dz = -std::log(1 - r()) * std::abs(w.z);
            const float zp = w.z > 0 ? z + dz : z - dz;
            if (zp == z) return std::nullopt;
            if (0 < zp && zp < p.thickness) {
                const PhaseSample ps = phase.sample(-w, r.two());
                if (!(ps.pdf > 0) || ps.wi.z == 0) return std::nullopt;
                f *= albedo * ps.p;
                pdf *= ps.pdf;
                specular_path = false;
                w = ps.wi;
                z = zp;
                continue;
            }
            z = std::clamp(zp, 0.0f, p.thickness);
        } else {
            z = z == p.thickness ? 0 : p.thickness;
            f = f * slab_tr(p.thickness, w);
        }
        std::optional<BsdfSample> is;
        if (z == 0) {
            is = bottom.sample(-w, r(), r.two());
        } else {
            is = top.sample(-w, r(), r.two(), Mode::kRadiance, Part::kAll);
        }
        if (!is || is->f.max_component() <= 0 || !(is->pdf > 0) || is->wi.z == 0) return std::nullopt;
        f *= is->f;
        pdf *= is->pdf;
        specular_path = specular_path && is->specular;
        w = is->wi;
        if (z == p.thickness && w.z > 0) {  // out through the coat
            BsdfSample out{f, flip ? -w : w, pdf, specular_path};
            out.pdf_is_proportional = true;
            return out;
        }
        f = f * std::abs(is->wi.z);
    }
    return std::nullopt;
}

}  // namespace glint
