// BSDF tests: each sampling routine against its own density (chi-square), densities that
// integrate to what is sampled, reciprocity, energy conservation, and closed forms.
#include "glint/materials/bsdf.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "glint/materials/fresnel.h"
#include "glint/materials/metals.h"
#include "glint/samplers/hash.h"
#include "sphere_chi2.h"
#include "testing.h"

namespace glint {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;

float rnd(std::uint32_t seed, std::uint32_t i) { return to_unit_float(hash_combine(seed, i)); }
Sample2 rnd2(std::uint32_t seed, std::uint32_t i) {
    return {rnd(seed, 2 * i), rnd(seed, 2 * i + 1)};
}
Vector3 direction(float theta_deg, float phi_deg = 30) {
    const float t = theta_deg * kPi / 180, p = phi_deg * kPi / 180;
    return {std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t)};
}

Bsdf layered(Bsdf b, float coat, float coat_roughness, Color sheen, float sheen_roughness) {
    if (coat > 0) b.set_clearcoat(coat, coat_roughness);
    if (sheen.max_component() > 0) b.set_sheen(sheen, sheen_roughness);
    return b;
}

struct Case {
    std::string name;
    Bsdf bsdf;
};

// Every lobe kind, smooth and rough, alone and mixed, in the local frame (n = +z).
std::vector<Case> cases() {
    const Normal3 n{0, 0, 1};
    const ConductorLobe gold = make_conductor(ConductorLobe::FresnelKind::kComplex,
                                              kMetals[3].eta, kMetals[3].k, 0.09f);
    const ConductorLobe white_rough =
        make_conductor(ConductorLobe::FresnelKind::kConstant, Color{1}, Color{0}, 0.5f);
    ConductorLobe gold_single = gold;  // pbrt-v4's conductor (a coated conductor's metal)
    gold_single.single_scattering = true;
    ConductorLobe mirror;  // smooth, constant reflectance 1
    DielectricLobe glass_rough;
    glass_rough.eta = 1.5f;
    glass_rough.ggx = Ggx{0.3f};
    DielectricLobe glass_smooth;
    DielectricLobe sheet;
    sheet.thin = true;
    const PlasticLobe plastic_rough = make_plastic(Color{0.8f, 0.3f, 0.2f}, 1.5f, 0.2f);
    const PlasticLobe plastic_smooth = make_plastic(Color{0.5f}, 1.5f, 0);
    const ConductorLobe pbr_metal = make_conductor(ConductorLobe::FresnelKind::kSchlick,
                                                   Color{0.9f, 0.6f, 0.3f}, Color{0}, 0.16f);
    PlasticLobe specular_plastic = make_plastic(Color{0.3f, 0.6f, 0.2f}, 1.5f, 0.3f);
    specular_plastic.specular_weight = 0.6f;
    specular_plastic.specular_color = Color{1, 0.5f, 30};  // 30 f0 > 1: clamped to 1
    return {
        {"diffuse", Bsdf(n, {{DiffuseLobe{Color{0.7f}}, 1.0f}})},
        {"gold rough", Bsdf(n, {{gold, 1.0f}})},
        {"gold rough, single scattering", Bsdf(n, {{gold_single, 1.0f}})},
        {"white conductor alpha 0.5", Bsdf(n, {{white_rough, 1.0f}})},
        {"mirror", Bsdf(n, {{mirror, 1.0f}})},
        {"rough glass", Bsdf(n, {{glass_rough, 1.0f}})},
        {"smooth glass", Bsdf(n, {{glass_smooth, 1.0f}})},
        {"thin sheet", Bsdf(n, {{sheet, 1.0f}})},
        {"rough plastic", Bsdf(n, {{plastic_rough, 1.0f}})},
        {"smooth plastic", Bsdf(n, {{plastic_smooth, 1.0f}})},
        {"article mix", Bsdf(n, {{DiffuseLobe{Color{0.5f}}, 0.6f}, {mirror, 0.4f}})},
        {"pbr mix", Bsdf(n, {{pbr_metal, 0.3f}, {plastic_rough, 0.5f}, {glass_rough, 0.2f}})},
        // make_bsdf's diffusetransmission: R = (0.2, 0.4, 0.1), T = (0.5, 0.3, 0.3), each lobe
        // normalised by its largest channel, which becomes its weight.
        {"diffuse transmission", Bsdf(n, {{DiffuseLobe{Color{0.5f, 1, 0.25f}}, 0.4f},
                                          {DiffuseTransmissionLobe{Color{1, 0.6f, 0.6f}}, 0.5f}})},
        // glTF's layers (KHR_materials_clearcoat, _sheen) and KHR_materials_specular.
        {"rough clear coat over diffuse", layered(Bsdf(n, {{DiffuseLobe{Color{0.9f}}, 1.0f}}), 1, 0.3f, Color{0}, 0)},
        {"smooth clear coat over plastic", layered(Bsdf(n, {{plastic_rough, 1.0f}}), 0.7f, 0, Color{0}, 0)},
        {"sheen over diffuse", layered(Bsdf(n, {{DiffuseLobe{Color{0.8f}}, 1.0f}}), 0, 0, Color{1, 0.8f, 0.6f}, 0.4f)},
        {"coat and sheen over pbr mix",
         layered(Bsdf(n, {{pbr_metal, 0.3f}, {plastic_rough, 0.5f}, {glass_rough, 0.2f}}), 0.5f, 0.2f, Color{0.5f}, 0.8f)},
        {"tinted specular plastic", Bsdf(n, {{specular_plastic, 1.0f}})},
    };
}

TEST(Bsdf, LambertEvalIsAlbedoOverPi) {
    const Bsdf b(Normal3{0, 0, 1}, {{DiffuseLobe{Color{0.6f, 0.3f, 0.1f}}, 1.0f}});
    const Color f = b.eval(direction(20), direction(70, 200));
    EXPECT_NEAR(f.r, 0.6f / kPi, 1e-7f);
    EXPECT_NEAR(f.b, 0.1f / kPi, 1e-7f);
    EXPECT_EQ(b.eval(direction(20), direction(120)), Color{0});  // below: nothing
}

TEST(Fresnel, DielectricMatchesClosedForms) {
    // Normal incidence: ((eta - 1) / (eta + 1))^2 = 0.04 for glass.
    EXPECT_NEAR(fresnel_dielectric(1, 1.5f), 0.04f, 1e-6f);
    // From inside, beyond the critical angle asin(1/1.5) = 41.8 degrees: total reflection.
    EXPECT_EQ(fresnel_dielectric(-std::cos(45 * kPi / 180), 1.5f), 1.0f);
    // Brewster's angle atan(1.5): the parallel component vanishes; R = r_perp^2 / 2.
    const float tb = std::atan(1.5f), ct = std::cos(std::asin(std::sin(tb) / 1.5f));
    const float rs = (std::cos(tb) - 1.5f * ct) / (std::cos(tb) + 1.5f * ct);
    EXPECT_NEAR(fresnel_dielectric(std::cos(tb), 1.5f), 0.5f * rs * rs, 1e-6f);
    // A conductor with k = 0 is a dielectric.
    EXPECT_NEAR(fresnel_complex(0.6f, {1.5f, 0}), fresnel_dielectric(0.6f, 1.5f), 1e-6f);
}

TEST(Metals, NormalIncidenceReflectanceMatchesTheFormula) {
    for (const MetalPreset& m : kMetals) {
        for (int c = 0; c < 3; ++c) {
            const float e = m.eta[c], k = m.k[c];
            const float expected = ((e - 1) * (e - 1) + k * k) / ((e + 1) * (e + 1) + k * k);
            EXPECT_NEAR(fresnel_conductor(1, m.eta, m.k)[c], expected, 1e-5f) << m.name;
        }
    }
    // Gold: warm, much less blue.
    const Color gold = fresnel_conductor(1, kMetals[3].eta, kMetals[3].k);
    EXPECT_NEAR(gold.r, 0.94f, 0.02f);
    EXPECT_NEAR(gold.b, 0.37f, 0.02f);
}

// Chi-square of every case's sampling against its density, from several viewing angles on both
// sides, with the probability of delta or failed samples as one extra cell.
TEST(Bsdf, SamplingMatchesPdfChiSquare) {
    int case_index = 0;
    for (const Case& c : cases()) {
        int angle_index = 0;
        for (const float theta : {10.0f, 55.0f, 85.0f, 140.0f}) {
            if (!testing::variation_runs(angle_index++, case_index, 4)) continue;
            const Vector3 wo = direction(theta, 40);
            const std::uint32_t seed = hash_combine(static_cast<std::uint32_t>(case_index), static_cast<std::uint32_t>(theta));
            const auto fit = testing::fit_sphere(
                [&](int i) -> std::optional<Vector3> {
                    const auto s = c.bsdf.sample(wo, rnd(seed ^ 0x9e3779b9U, static_cast<std::uint32_t>(i)),
                                                 rnd2(seed, static_cast<std::uint32_t>(i)));
                    if (!s || s->specular) return std::nullopt;
                    return s->wi;
                },
                [&](Vector3 wi) { return c.bsdf.pdf(wo, wi); }, 400000, 20, 40, 40);
            EXPECT_TRUE(fit.ok()) << c.name << " at theta_o " << theta << ": " << fit.report();
        }
        ++case_index;
    }
}

// The density integrates to the probability that sampling returns a non-delta direction: 1 for
// Lambert, less where microfacet reflections can leave below the horizon (those samples fail).
TEST(Bsdf, PdfsIntegrateToTheSampledFraction) {
    int case_index = 0;
    for (const Case& c : cases()) {
        ++case_index;
        int angle_index = 0;
        for (const float theta : {5.0f, 45.0f, 80.0f, 130.0f}) {
            if (!testing::variation_runs(angle_index++, case_index, 4)) continue;
            const Vector3 wo = direction(theta);
            const auto fit = testing::fit_sphere(
                [&](int i) -> std::optional<Vector3> {
                    const auto s = c.bsdf.sample(wo, rnd(21, static_cast<std::uint32_t>(i)),
                                                 rnd2(22, static_cast<std::uint32_t>(i)));
                    if (!s || s->specular) return std::nullopt;
                    return s->wi;
                },
                [&](Vector3 wi) { return c.bsdf.pdf(wo, wi); }, 200000, 40, 80, 16);
            EXPECT_NEAR(fit.pdf_integral, 1 - fit.other_fraction, 0.01) << c.name << " at " << theta;
            if (c.name == "diffuse") EXPECT_NEAR(fit.pdf_integral, 1.0, 0.002);
        }
    }
}

// f(wo, wi) = f(wi, wo) for reflection; for refraction the radiance form obeys
// f(a, b) eta_b^2 = f(b, a) eta_a^2 (eta of the side each direction is on).
TEST(Bsdf, Reciprocity) {
    for (const Case& c : cases()) {
        for (std::uint32_t i = 0; i < 2000; ++i) {
            const Vector3 a = sample_uniform_sphere(rnd2(1, i));
            const Vector3 b = sample_uniform_sphere(rnd2(2, i));
            const float inside = c.name == "diffuse transmission" ? 1.0f : 1.5f;  // no index there
            const float eta_a = a.z < 0 ? inside : 1, eta_b = b.z < 0 ? inside : 1;
            const Color ab = c.bsdf.eval(a, b) * (eta_b * eta_b);
            const Color ba = c.bsdf.eval(b, a) * (eta_a * eta_a);
            for (int k = 0; k < 3; ++k) {
                ASSERT_NEAR(ab[k], ba[k], 2e-3f * std::max(1.0f, std::abs(ab[k])))
                    << c.name << " a " << a.x << "," << a.y << "," << a.z << " b " << b.x << ","
                    << b.y << "," << b.z;
            }
        }
    }
}

// The directional albedo, integral of f cos over the sphere (deltas included), estimated by
// importance sampling: never above 1 beyond noise. A white rough metal reflects all of it
// (Kulla-Conty), a white diffuse all of it.
TEST(Bsdf, EnergyIsConserved) {
    int case_index = 0;
    for (const Case& c : cases()) {
        ++case_index;
        int angle_index = 0;
        for (const float theta : {0.5f, 30.0f, 60.0f, 85.0f, 120.0f}) {
            if (!testing::variation_runs(angle_index++, case_index, 5)) continue;
            const Vector3 wo = direction(theta);
            constexpr int kN = 200000;
            double sum[3] = {0, 0, 0}, sum2[3] = {0, 0, 0};
            for (int i = 0; i < kN; ++i) {
                const auto s = c.bsdf.sample(wo, rnd(7, static_cast<std::uint32_t>(i)),
                                             rnd2(8, static_cast<std::uint32_t>(i)));
                if (!s) continue;
                const Color w = s->f * (std::abs(s->wi.z) / s->pdf);
                for (int k = 0; k < 3; ++k) sum[k] += w[k], sum2[k] += w[k] * w[k];
            }
            for (int k = 0; k < 3; ++k) {
                const double mean = sum[k] / kN;
                const double se = std::sqrt(std::max(0.0, sum2[k] / kN - mean * mean) / kN);
                EXPECT_LE(mean, 1 + 4 * se + 1e-4) << c.name << " theta " << theta;
                if (c.name == "white conductor alpha 0.5" && theta < 90) {
                    EXPECT_NEAR(mean, 1, 0.01) << "white rough metal at " << theta;
                }
                if (c.name == "diffuse transmission") {  // all of R + T, from either side
                    const double expected[3] = {0.2 + 0.5, 0.4 + 0.3, 0.1 + 0.3};
                    EXPECT_NEAR(mean, expected[k], 4 * se + 1e-4) << "channel " << k << " theta " << theta;
                }
            }
        }
    }
}

// E(mu, alpha) of the table agrees with a brute-force Monte Carlo integral of the single-
// scattering GGX lobe sampled uniformly over the hemisphere (an independent path).
TEST(Ggx, AlbedoTableMatchesBruteForce) {
    for (const float alpha : {0.2f, 0.6f, 1.0f}) {
        for (const float mu : {0.15f, 0.5f, 0.95f}) {
            const Ggx ggx{alpha};
            const Vector3 wo{std::sqrt(1 - mu * mu), 0, mu};
            double sum = 0;
            constexpr int kN = 1 << 20;
            for (int i = 0; i < kN; ++i) {
                Vector3 wi = sample_uniform_sphere(rnd2(11, static_cast<std::uint32_t>(i)));
                if (wi.z <= 0) continue;
                const Vector3 wm = normalize(wo + wi);
                sum += ggx.d(wm) * ggx.g(wo, wi) / (4 * wo.z * wi.z) * wi.z / kUniformSpherePdf;
            }
            EXPECT_NEAR(ggx_albedo(mu, alpha), sum / kN, 0.01) << alpha << " " << mu;
        }
    }
}

// The layer tables agree with brute-force Monte Carlo integrals of the lobes sampled uniformly
// over the hemisphere; a smooth coat reflects exactly Fresnel's F(mu) of index 1.5.
TEST(Layers, AlbedoTablesMatchBruteForce) {
    // Roughness from 0.3: below, 2^20 uniform directions put too few in the coat's narrow peak.
    for (const float r : {0.3f, 0.55f, 1.0f}) {
        for (const float mu : {0.1f, 0.5f, 0.95f}) {
            const Vector3 wo{std::sqrt(1 - mu * mu), 0, mu};
            const SheenLobe sheen{Color{1}, r};
            const ConductorLobe coat = clearcoat_lobe(r);
            double e_sheen = 0, e_coat = 0;
            constexpr int kN = 1 << 20;
            for (int i = 0; i < kN; ++i) {
                const Vector3 wi = sample_uniform_sphere(rnd2(13, static_cast<std::uint32_t>(i)));
                if (wi.z <= 0) continue;
                e_sheen += sheen.eval(wo, wi).r * wi.z / kUniformSpherePdf;
                e_coat += coat.eval(wo, wi).r * wi.z / kUniformSpherePdf;
            }
            EXPECT_NEAR(sheen_albedo(mu, r), e_sheen / kN, 0.01 + 0.02 * e_sheen / kN) << r << " " << mu;
            EXPECT_NEAR(clearcoat_albedo(mu, r), e_coat / kN, 0.01) << r << " " << mu;
        }
    }
    for (const float mu : {0.05f, 0.3f, 1.0f}) EXPECT_NEAR(clearcoat_albedo(mu, 0), fresnel_dielectric(mu, 1.5f), 0.01f) << mu;
    // The sheen's peak is broad in phi: uniform directions resolve it at low roughness too.
    for (const float mu : {0.1f, 0.5f, 0.95f}) {
        const Vector3 wo{std::sqrt(1 - mu * mu), 0, mu};
        const SheenLobe sheen{Color{1}, 0.1f};
        double e = 0;
        constexpr int kN = 1 << 20;
        for (int i = 0; i < kN; ++i) {
            const Vector3 wi = sample_uniform_sphere(rnd2(17, static_cast<std::uint32_t>(i)));
            if (wi.z > 0) e += sheen.eval(wo, wi).r * wi.z / kUniformSpherePdf;
        }
        EXPECT_NEAR(sheen_albedo(mu, 0.1f), e / kN, 0.01 + 0.02 * e / kN) << mu;
    }
}

// KHR_materials_specular's defaults change nothing; its weight is the grazing reflectance, its
// colour tints normal incidence (f0 = 0.04 x colour, at most 1).
TEST(Layers, SpecularWeightAndColourShapeTheCoatFresnel) {
    PlasticLobe p = make_plastic(Color{0.5f}, 1.5f, 0.2f);
    for (const float c : {0.0f, 0.3f, 1.0f}) EXPECT_EQ(p.coat_fresnel(c), Color{fresnel_dielectric(c, 1.5f)});
    p.specular_weight = 0.5f;
    p.specular_color = Color{1, 10, 50};
    const Color f1 = p.coat_fresnel(1), f0 = p.coat_fresnel(1e-6f);
    EXPECT_NEAR(f1.r, 0.5f * 0.04f, 1e-5f);
    EXPECT_NEAR(f1.g, 0.5f * 0.4f, 1e-5f);
    EXPECT_NEAR(f1.b, 0.5f, 1e-5f);  // 0.04 x 50 clamped to 1
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(f0[k], 0.5f, 1e-3f);
}

// A specular weight of 0 leaves no coat at all: a white base is a white Lambertian, whose albedo
// is 1 from every direction (quadrature over the hemisphere); between 0 and 1 no energy is made.
TEST(Layers, ASpecularWeightOfZeroLeavesThePlainBase) {
    for (const float weight : {0.0f, 0.5f}) {
        PlasticLobe p = make_plastic(Color{1.0f}, 1.5f, 0.3f);
        p.specular_weight = weight;
        for (const float mu : {0.2f, 0.6f, 1.0f}) {
            const Vector3 wo{std::sqrt(1 - mu * mu), 0, mu};
            double albedo = 0;
            constexpr int kN = 400;  // midpoint rule in (cos theta, phi)
            for (int i = 0; i < kN; ++i)
                for (int j = 0; j < kN; ++j) {
                    const float c = (i + 0.5f) / kN, phi = 2 * kPi * (j + 0.5f) / kN, s = std::sqrt(1 - c * c);
                    albedo += p.eval(wo, {s * std::cos(phi), s * std::sin(phi), c}).r * c * (2 * kPi) / (kN * kN);
                }
            if (weight == 0) EXPECT_NEAR(albedo, 1.0, 2e-3) << mu;
            else EXPECT_LE(albedo, 1.0 + 2e-3) << mu;
        }
    }
}

// A sheen or coat adds reflection where the base has little, and takes it from the base: the
// coated diffuse reflects more at grazing angles and less at normal incidence into the diffuse.
TEST(Layers, ACoatTakesFromTheBaseWhatItReflects) {
    const Normal3 n{0, 0, 1};
    const Bsdf base(n, {{DiffuseLobe{Color{0.9f}}, 1.0f}});
    const Bsdf coated = layered(base, 1, 0.3f, Color{0}, 0);
    const Vector3 wo = direction(40), wi = direction(70, 200);
    const float expected = 0.9f / kPi * (1 - clearcoat_albedo(wo.z, 0.3f)) * (1 - clearcoat_albedo(wi.z, 0.3f));
    const ConductorLobe coat = clearcoat_lobe(0.3f);
    EXPECT_NEAR(coated.eval(wo, wi).r, expected + coat.eval(wo, wi).r, 1e-6f);
}

TEST(Bsdf, SmoothGlassSplitsByFresnelAndBendsBySnell) {
    DielectricLobe glass;  // eta 1.5
    const Bsdf b(Normal3{0, 0, 1}, {{glass, 1.0f}});
    const Vector3 wo = direction(60, 0);
    const float r = fresnel_dielectric(std::cos(60 * kPi / 180), 1.5f);
    const auto reflected = b.sample(wo, r * 0.5f, {0.5f, 0.5f});
    ASSERT_TRUE(reflected && reflected->specular);
    EXPECT_NEAR(reflected->pdf, r, 1e-6f);
    EXPECT_NEAR(reflected->wi.z, wo.z, 1e-6f);
    const auto refracted = b.sample(wo, (1 + r) * 0.5f, {0.5f, 0.5f});
    ASSERT_TRUE(refracted && refracted->specular);
    // sin(theta_t) = sin(60) / 1.5, and the radiance is compressed by 1 / eta^2.
    const float sin_t = std::sqrt(1 - refracted->wi.z * refracted->wi.z);
    EXPECT_NEAR(sin_t, std::sin(60 * kPi / 180) / 1.5f, 1e-5f);
    EXPECT_LT(refracted->wi.z, 0);
    const float throughput = refracted->f.r * std::abs(refracted->wi.z) / refracted->pdf;
    EXPECT_NEAR(throughput, 1 / 2.25f, 1e-5f);
}

// The one-lobe constructor (make_bsdf's) against the list one with that lobe at weight 1: the
// same frame, selection and kind, so the same bits from every query, on a tilted normal.
TEST(Bsdf, OneLobeIsTheListOfThatLobe) {
    const Normal3 n = normalize(Normal3{0.3f, -0.5f, 0.8f});
    DielectricLobe glass_rough;
    glass_rough.ggx = Ggx{0.3f};
    DielectricLobe sheet;
    sheet.thin = true;
    const auto same = [&](const auto& lobe, const std::string& name) {
        SCOPED_TRACE(name);
        const Bsdf list(n, {{lobe, 1.0f}}), one(n, lobe);
        EXPECT_EQ(one.has_smooth_part(), list.has_smooth_part());
        EXPECT_EQ(one.lobe_count(), 1);
        for (std::uint32_t i = 0; i < 64; ++i) {
            const Vector3 wo = to_vector(normalize(Normal3{2 * rnd(1, i) - 1, 2 * rnd(2, i) - 1, 2 * rnd(3, i) - 1}));
            const Vector3 wi = to_vector(normalize(Normal3{2 * rnd(4, i) - 1, 2 * rnd(5, i) - 1, 2 * rnd(6, i) - 1}));
            EXPECT_EQ(one.eval(wo, wi), list.eval(wo, wi));
            EXPECT_EQ(one.pdf(wo, wi), list.pdf(wo, wi));
            const auto a = one.sample(wo, rnd(7, i), rnd2(8, i)), b = list.sample(wo, rnd(7, i), rnd2(8, i));
            ASSERT_EQ(a.has_value(), b.has_value());
            if (a) {
                EXPECT_EQ(a->f, b->f);
                EXPECT_EQ(a->wi, b->wi);
                EXPECT_EQ(a->pdf, b->pdf);
                EXPECT_EQ(a->specular, b->specular);
            }
        }
    };
    same(DiffuseLobe{Color{0.7f, 0.5f, 0.2f}}, "diffuse");
    same(make_conductor(ConductorLobe::FresnelKind::kComplex, kMetals[3].eta, kMetals[3].k, 0.09f), "gold");
    same(ConductorLobe{}, "mirror");
    same(glass_rough, "rough glass");
    same(DielectricLobe{}, "smooth glass");
    same(sheet, "thin sheet");
    same(make_plastic(Color{0.8f, 0.3f, 0.2f}, 1.5f, 0.2f), "rough plastic");
    same(DiffuseTransmissionLobe{Color{1, 0.6f, 0.6f}}, "diffuse transmission");
}

}  // namespace
}  // namespace glint
