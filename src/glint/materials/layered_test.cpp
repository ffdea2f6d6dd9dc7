// The layered BSDF (pbrt-v4's coateddiffuse / coatedconductor) against things computed apart
// from it: a white furnace (a lossless coat over a white base reflects everything), energy
// conservation, reciprocity of the estimate, its sampling against its own evaluation (the
// weighted histogram of sampled directions against the integral of f cos over each cell), and
// the value against an analog simulation of photons in the slab written here from the physics
// alone (Fresnel's equations and Snell's law at the coat, free flights and Henyey-Greenstein
// scattering in the slab, a Lambertian base).
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "glint/materials/bsdf.h"
#include "glint/materials/fresnel.h"
#include "glint/materials/metals.h"
#include "glint/media/phase.h"
#include "glint/samplers/hash.h"
#include "glint/samplers/warp.h"
#include "stats.h"

namespace glint {
namespace {

constexpr double kPi = std::numbers::pi;

float rnd(std::uint32_t seed, std::uint32_t i) { return to_unit_float(hash_combine(seed, i)); }
Sample2 rnd2(std::uint32_t seed, std::uint32_t i) { return {rnd(seed, 2 * i), rnd(seed, 2 * i + 1)}; }
Vector3 direction(double theta_deg, double phi_deg = 30) {
    const double t = theta_deg * kPi / 180, p = phi_deg * kPi / 180;
    return {float(std::sin(t) * std::cos(p)), float(std::sin(t) * std::sin(p)), float(std::cos(t))};
}

Vector3 sample_uniform_hemisphere(Sample2 u) {
    const Vector3 w = sample_uniform_sphere(u);
    return {w.x, w.y, std::abs(w.z)};
}

// A layered lobe with its own parameters (a material holds them in a render).
struct Coated {
    std::shared_ptr<LayeredParams> p = std::make_shared<LayeredParams>();
    Color base{0.5f}, k{0};
    LayeredLobe lobe() const { return {p.get(), base, k, p->albedo}; }
    Color eval(Vector3 wo, Vector3 wi) const { return lobe().eval(wo, wi); }
    float pdf(Vector3 wo, Vector3 wi) const { return lobe().pdf(wo, wi); }
    std::optional<BsdfSample> sample(Vector3 wo, float uc, Sample2 u) const { return lobe().sample(wo, uc, u); }
};

Coated coated_diffuse(Color base, float eta, float alpha, float thickness, Color albedo, float g) {
    Coated l;
    l.base = base;
    l.p->eta = eta;
    l.p->coat = Ggx{alpha};
    l.p->thickness = thickness;
    l.p->albedo = albedo;
    l.p->g = g;
    return l;
}

struct Mean {
    double sum = 0, sum2 = 0;
    long n = 0;
    void add(double v) { sum += v, sum2 += v * v, ++n; }
    double mean() const { return sum / double(n); }
    double stderr_() const { return std::sqrt(std::max(0.0, sum2 / double(n) - mean() * mean()) / double(n)); }
};

// The directional albedo from wo by sampling: the mean of f |cos| / pdf (what a path carries).
Mean albedo_by_sampling(const Coated& l, Vector3 wo, int n, int channel = 0) {
    Mean m;
    for (int i = 0; i < n; ++i) {
        const auto s = l.sample(wo, rnd(7, std::uint32_t(i)), rnd2(8, std::uint32_t(i)));
        m.add(s && s->pdf > 0 ? double(s->f[channel]) * std::abs(s->wi.z) / s->pdf : 0.0);
    }
    return m;
}

// The same by evaluation: f cos over the hemisphere, cosine-weighted directions (each f itself
// a random-walk estimate from its own seed), plus the smooth coat's mirror reflection, which
// eval leaves out as a delta.
Mean albedo_by_evaluation(const Coated& l, Vector3 wo, int n, int channel = 0) {
    Mean m;
    const double mirror = l.p->coat.smooth() ? fresnel_dielectric(wo.z, l.p->eta) : 0.0;
    for (int i = 0; i < n; ++i) {
        const Vector3 wi = sample_cosine_hemisphere(rnd2(9, std::uint32_t(i)));
        if (!(wi.z > 0)) {
            m.add(mirror);
            continue;
        }
        m.add(mirror + double(l.eval(wo, wi)[channel]) * kPi);  // f cos / (cos / pi)
    }
    return m;
}

TEST(Layered, WhiteFurnaceLosslessCoatOverWhiteBaseReflectsEverything) {
    // A smooth coat, a slab too thin to absorb, a white base and no depth limit worth the name:
    // every photon leaves again, so the directional albedo is 1 from every direction. (A rough
    // coat loses what its single-scattering microfacet model loses at each of the many passes
    // light makes; the analog simulation below checks that case.)
    for (const float alpha : {0.0f}) {
        Coated l = coated_diffuse(Color{1}, 1.5f, alpha, 1e-7f, Color{0}, 0);
        l.p->max_depth = 10000;
        for (const double theta : {0.0, 45.0, 80.0}) {
            const Vector3 wo = direction(theta);
            const Mean s = albedo_by_sampling(l, wo, 40000);
            EXPECT_NEAR(s.mean(), 1, 4 * s.stderr_() + 2e-3) << "sampling, alpha " << alpha << " theta " << theta;
            const Mean e = albedo_by_evaluation(l, wo, 20000);
            EXPECT_NEAR(e.mean(), 1, 4 * e.stderr_() + 2e-3) << "evaluation, alpha " << alpha << " theta " << theta;
        }
    }
}

TEST(Layered, EnergyIsConservedAndSamplingAgreesWithEvaluation) {
    Coated copper;  // relative to the coat, as build() makes it
    copper.p->conductor_base = true;
    copper.base = kMetals[2].eta / 1.5f;
    copper.k = kMetals[2].k / 1.5f;
    copper.p->metal = Ggx{0.1f};
    copper.p->coat = Ggx{0.05f};
    const std::vector<std::pair<std::string, Coated>> lobes{
        {"smooth coat, absorbing slab", coated_diffuse(Color{0.8f, 0.4f, 0.2f}, 1.5f, 0, 0.3f, Color{0}, 0)},
        {"rough coat, scattering slab", coated_diffuse(Color{0.6f}, 1.33f, 0.3f, 0.5f, Color{0.9f, 0.5f, 0.2f}, 0.4f)},
        {"coated copper", copper},
    };
    for (const auto& [name, l] : lobes) {
        for (const double theta : {10.0, 60.0}) {
            const Vector3 wo = direction(theta);
            for (int c = 0; c < 3; ++c) {
                const Mean s = albedo_by_sampling(l, wo, 30000, c);
                const Mean e = albedo_by_evaluation(l, wo, 30000, c);
                EXPECT_LE(s.mean(), 1 + 4 * s.stderr_()) << name;
                EXPECT_LE(e.mean(), 1 + 4 * e.stderr_()) << name;
                EXPECT_NEAR(s.mean(), e.mean(), 4 * std::hypot(s.stderr_(), e.stderr_()) + 2e-3)
                    << name << ", theta " << theta << ", channel " << c;
            }
        }
    }
}

TEST(Layered, EstimateIsReciprocal) {
    Coated l = coated_diffuse(Color{0.7f, 0.5f, 0.3f}, 1.5f, 0.2f, 0.2f, Color{0.8f}, 0.3f);
    l.p->samples = 20000;  // the estimate's noise well below the tolerance
    for (const auto& [a, b] : {std::pair{direction(20, 10), direction(70, 200)}, {direction(5, 0), direction(50, 90)}}) {
        const Color ab = l.eval(a, b), ba = l.eval(b, a);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(ab[c], ba[c], 0.03 * ab[c]) << "channel " << c;
    }
}

TEST(Layered, SampledDirectionsCarryTheWeightEvaluationGivesEachCell) {
    // Cells of equal theta extent over the upper hemisphere: the walk's samples put the weight
    // f cos / pdf into the cells they land in; integrated f cos over each cell must agree, cell
    // by cell (a chi-square over the cells with both estimates' variances).
    const Coated l = coated_diffuse(Color{0.9f}, 1.5f, 0.15f, 0.1f, Color{0.7f}, -0.3f);
    const Vector3 wo = direction(35);
    constexpr int kCells = 9;
    std::vector<Mean> by_sample(kCells), by_eval(kCells);
    const int n = 200000;
    const auto cell = [](Vector3 w) { return std::min(kCells - 1, int(std::acos(std::clamp(w.z, 0.0f, 1.0f)) / (kPi / 2) * kCells)); };
    for (int i = 0; i < n; ++i) {
        const auto s = l.sample(wo, rnd(1, std::uint32_t(i)), rnd2(2, std::uint32_t(i)));
        const double w = s && s->pdf > 0 && s->wi.z > 0 ? double(s->f.r) * s->wi.z / s->pdf : 0.0;
        for (int k = 0; k < kCells; ++k) by_sample[std::size_t(k)].add(s && s->wi.z > 0 && cell(s->wi) == k ? w : 0.0);
        // Uniform directions over the hemisphere (pdf 1 / 2 pi) for the evaluation side.
        const Vector3 wi = sample_uniform_hemisphere(rnd2(3, std::uint32_t(i)));
        const double v = double(l.eval(wo, wi).r) * wi.z * 2 * kPi;
        for (int k = 0; k < kCells; ++k) by_eval[std::size_t(k)].add(wi.z > 0 && cell(wi) == k ? v : 0.0);
    }
    double chi2 = 0;
    for (int k = 0; k < kCells; ++k) {
        const double d = by_sample[std::size_t(k)].mean() - by_eval[std::size_t(k)].mean();
        const double var = std::pow(by_sample[std::size_t(k)].stderr_(), 2) + std::pow(by_eval[std::size_t(k)].stderr_(), 2);
        chi2 += d * d / var;
    }
    EXPECT_LT(chi2, testing::chi_square_critical_1e4(kCells)) << "chi2 " << chi2;
}

// Photons from direction wi_in (arriving at the coat), followed one by one through the slab as
// physics has it; the fraction of their energy leaving into each theta cell. A smooth coat
// reflects or refracts by Fresnel's equations and Snell's law (its first mirror reflection is
// left out: eval leaves out deltas); a rough coat scatters by the GGX dielectric lobe's own
// sampling (DielectricLobe, tested on its own in bsdf_test.cpp), each event weighing the photon
// by f |cos| / pdf with the radiance factor 1 / eta^2 taken back out (photons carry energy).
std::vector<double> analog_photons(float base, float eta, float alpha, float thickness, float albedo, float g,
                                   Vector3 wi_in, int n, int cells) {
    std::vector<double> out(std::size_t(cells), 0);
    const HgPhase phase{g};
    DielectricLobe coat;
    coat.eta = eta;
    coat.ggx = Ggx{alpha};
    const auto cell = [cells](Vector3 w) {
        return std::min(cells - 1, int(std::acos(std::clamp(w.z, 0.0f, 1.0f)) / (kPi / 2) * cells));
    };
    for (int i = 0; i < n; ++i) {
        HashRng r{hash_combine(1234, std::uint32_t(i))};
        double weight = 1;
        // At the coat, from direction `from` (leaving the coat on the side light came from):
        // the new direction of travel, or nothing if the photon is lost.
        const auto cross_coat = [&](Vector3 from) -> std::optional<Vector3> {
            if (alpha == 0) {
                if (r.next() < fresnel_dielectric(from.z, eta)) return Vector3{-from.x, -from.y, from.z};
                Vector3 t;
                float etap;
                if (!refract(from, {0, 0, 1}, eta, t, etap)) return std::nullopt;
                return t;
            }
            const float uc = r.next();
            const auto s = coat.sample(from, uc, {r.next(), r.next()});
            if (!s || !(s->pdf > 0)) return std::nullopt;
            weight *= double(s->f.r) * std::abs(s->wi.z) / s->pdf * (s->eta * s->eta);
            return s->wi;
        };
        auto first = cross_coat(wi_in);
        if (!first) continue;
        Vector3 w = *first;
        if (w.z > 0) {  // reflected by the coat
            if (alpha > 0) out[std::size_t(cell(w))] += weight / n;
            continue;
        }
        float z = thickness;
        for (int bounce = 0; bounce < 100000; ++bounce) {
            // A free flight (sigma_t = 1) to the next event or a boundary.
            const float s = -std::log(1 - r.next());
            const float zp = z + s * w.z;
            if (zp > 0 && zp < thickness) {
                if (r.next() >= albedo) break;  // absorbed
                z = zp;
                w = phase.sample(-w, {r.next(), r.next()}).wi;
                continue;
            }
            if (zp <= 0) {  // the Lambertian base
                if (r.next() >= base) break;
                z = 0;
                w = sample_cosine_hemisphere({r.next(), r.next()});
                continue;
            }
            // At the coat from below: back into the slab, or out.
            z = thickness;
            const auto next = cross_coat(-w);
            if (!next) break;
            w = *next;
            if (w.z > 0) {
                out[std::size_t(cell(w))] += weight / n;
                break;
            }
        }
    }
    return out;
}

TEST(Layered, ValueMatchesAnAnalogSimulationOfTheSlab) {
    struct Setup {
        float base, alpha, thickness, albedo, g;
    };
    for (const Setup& c : {Setup{0.8f, 0, 0.05f, 0, 0}, Setup{0.5f, 0, 0.7f, 0.9f, 0.5f}, Setup{0, 0, 2, 0.95f, -0.4f},
                           Setup{1, 0.2f, 1e-6f, 0, 0}, Setup{0.7f, 0.35f, 0.4f, 0.8f, 0.3f}}) {
        const Vector3 wi_in = direction(40, 0);
        constexpr int kCells = 6;
        const int n = 400000;
        const std::vector<double> photons = analog_photons(c.base, 1.5f, c.alpha, c.thickness, c.albedo, c.g, wi_in, n, kCells);
        Coated l = coated_diffuse(Color{c.base}, 1.5f, c.alpha, c.thickness, Color{c.albedo}, c.g);
        l.p->max_depth = 1000;
        // The fraction into each cell: the integral of f(wo, wi_in) cos(wo) over the cell, by
        // a midpoint rule in (theta, phi), each f a walk estimate of 16 samples.
        l.p->samples = 16;
        for (int k = 0; k < kCells; ++k) {
            const int nt = 16, np = 48;
            double sum = 0;
            for (int a = 0; a < nt; ++a) {
                const double theta = (k + (a + 0.5) / nt) * (kPi / 2) / kCells;
                for (int b = 0; b < np; ++b) {
                    const double phi = (b + 0.5) / np * 2 * kPi;
                    const Vector3 wo = direction(theta * 180 / kPi, phi * 180 / kPi);
                    sum += double(l.eval(wo, wi_in).r) * std::cos(theta) * std::sin(theta);
                }
            }
            const double integral = sum * ((kPi / 2) / kCells / nt) * (2 * kPi / np);
            const double sigma = std::sqrt(photons[std::size_t(k)] * (1 - std::min(1.0, photons[std::size_t(k)])) / n);
            EXPECT_NEAR(integral, photons[std::size_t(k)], 5 * sigma + 0.03 * photons[std::size_t(k)] + 2e-4)
                << "base " << c.base << ", alpha " << c.alpha << ", thickness " << c.thickness << ", albedo " << c.albedo
                << ", cell " << k;
        }
    }
}

TEST(Layered, DensityIsPositiveWhereTheValueIs) {
    const Coated l = coated_diffuse(Color{0.5f}, 1.5f, 0.2f, 0.01f, Color{0}, 0);
    for (int i = 0; i < 200; ++i) {
        const Vector3 wo = sample_uniform_hemisphere(rnd2(4, std::uint32_t(i)));
        const Vector3 wi = sample_uniform_hemisphere(rnd2(5, std::uint32_t(i)));
        if (l.eval(wo, wi).max_component() > 0) {
            EXPECT_GT(l.pdf(wo, wi), 0);
        }
        EXPECT_TRUE(std::isfinite(l.pdf(wo, wi)));
        EXPECT_EQ(l.eval(wo, -wi).max_component(), 0) << "nothing crosses a coated surface";
    }
}

}  // namespace
}  // namespace glint
