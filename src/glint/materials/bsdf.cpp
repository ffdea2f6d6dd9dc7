#include "glint/materials/bsdf.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>

#include "glint/materials/fresnel.h"
#include "glint/samplers/warp.h"

namespace glint {

namespace {

constexpr float kInvPi = std::numbers::inv_pi_v<float>;

bool same_side(Vector3 a, Vector3 b) { return a.z * b.z > 0; }
Vector3 mirror_z(Vector3 v) { return {-v.x, -v.y, v.z}; }
Vector3 flip_z(Vector3 v) { return {v.x, v.y, -v.z}; }

// Reflection-only lobes are two-sided: seen from below, mirror both directions to the upper side.
template <typename F>
auto upper(Vector3 wo, Vector3 wi, F f) {
    return wo.z < 0 ? f(flip_z(wo), flip_z(wi)) : f(wo, wi);
}

}  // namespace

// ---------------------------------------------------------------------------------- diffuse

Color DiffuseLobe::eval(Vector3 wo, Vector3 wi) const {
    return same_side(wo, wi) ? albedo * kInvPi : Color{0};
}

float DiffuseLobe::pdf(Vector3 wo, Vector3 wi) const {
    return same_side(wo, wi) ? std::abs(wi.z) * kInvPi : 0;
}

std::optional<BsdfSample> DiffuseLobe::sample(Vector3 wo, float, Sample2 u) const {
    Vector3 wi = sample_cosine_hemisphere(u);
    if (wo.z < 0) wi = flip_z(wi);
    const float pdf = std::abs(wi.z) * kInvPi;
    if (pdf <= 0) return std::nullopt;
    return BsdfSample{albedo * kInvPi, wi, pdf};
}

Color DiffuseTransmissionLobe::eval(Vector3 wo, Vector3 wi) const {
    return same_side(wo, wi) || wo.z == 0 || wi.z == 0 ? Color{0} : transmittance * kInvPi;
}

float DiffuseTransmissionLobe::pdf(Vector3 wo, Vector3 wi) const {
    return same_side(wo, wi) || wo.z == 0 ? 0 : std::abs(wi.z) * kInvPi;
}

std::optional<BsdfSample> DiffuseTransmissionLobe::sample(Vector3 wo, float, Sample2 u) const {
    if (wo.z == 0) return std::nullopt;
    Vector3 wi = sample_cosine_hemisphere(u);
    if (wo.z > 0) wi = flip_z(wi);
    const float pdf = std::abs(wi.z) * kInvPi;
    if (pdf <= 0) return std::nullopt;
    return BsdfSample{transmittance * kInvPi, wi, pdf};
}

// -------------------------------------------------------------------------------- conductor

namespace {

// E(mu, alpha) at the centres of a kN x kN grid, computed by tools/ggx_albedo_table.cpp (an
// accurate quadrature takes seconds, too long for every run). E_avg(alpha) = 2 int E mu dmu is
// integrated here from the same interpolated E that eval uses, so that the multiple-scattering
// term returns exactly the energy the single-scattering term loses.
constexpr int kN = 32;
constexpr float kAlbedo[kN][kN] = {
#include "glint/materials/ggx_albedo_table.inc"
};

float interpolate_mu(int a, float mu);

struct AlbedoAverage {
    float avg[kN];
    AlbedoAverage() {
        constexpr int kSteps = 2048;
        for (int a = 0; a < kN; ++a) {
            double sum = 0;
            for (int i = 0; i < kSteps; ++i) {
                const float mu = (static_cast<float>(i) + 0.5f) / kSteps;
                sum += 2.0 * interpolate_mu(a, mu) * mu / kSteps;
            }
            avg[a] = static_cast<float>(sum);
        }
    }
};

const AlbedoAverage& albedo_average() {
    static const AlbedoAverage table;
    return table;
}

// Linear interpolation between cell centres, clamped at the ends.
void cell(float x, int& i0, int& i1, float& t) {
    const float f = std::clamp(x * kN - 0.5f, 0.0f, static_cast<float>(kN - 1));
    i0 = static_cast<int>(f);
    i1 = std::min(i0 + 1, kN - 1);
    t = f - static_cast<float>(i0);
}

float interpolate_mu(int a, float mu) {
    int m0, m1;
    float tm;
    cell(mu, m0, m1, tm);
    return kAlbedo[a][m0] * (1 - tm) + kAlbedo[a][m1] * tm;
}

}  // namespace

float ggx_albedo(float mu, float alpha) {
    int a0, a1;
    float ta;
    cell(alpha, a0, a1, ta);
    return interpolate_mu(a0, mu) * (1 - ta) + interpolate_mu(a1, mu) * ta;
}

float ggx_albedo_average(float alpha) {
    const AlbedoAverage& table = albedo_average();
    int a0, a1;
    float ta;
    cell(alpha, a0, a1, ta);
    return table.avg[a0] * (1 - ta) + table.avg[a1] * ta;
}

ConductorLobe make_conductor(ConductorLobe::FresnelKind kind, Color eta, Color k, float alpha) {
    ConductorLobe c;
    c.kind = kind;
    c.eta = eta;
    c.k = k;
    c.ggx = Ggx{alpha};
    // F_avg = 2 int F(mu) mu dmu, midpoint rule.
    constexpr int kSteps = 256;
    Color sum{0};
    for (int i = 0; i < kSteps; ++i) {
        const float mu = (static_cast<float>(i) + 0.5f) / kSteps;
        sum += c.fresnel(mu) * (2 * mu / kSteps);
    }
    c.f_avg = sum;
    if (!c.ggx.smooth()) (void)albedo_average();  // build it now, not inside a render
    return c;
}

Color ConductorLobe::fresnel(float cos_i) const {
    switch (kind) {
        case FresnelKind::kComplex: return fresnel_conductor(cos_i, eta, k);
        case FresnelKind::kSchlick: return fresnel_schlick(cos_i, eta);
        case FresnelKind::kConstant: return eta;
    }
    return eta;
}

Color ConductorLobe::eval(Vector3 wo_in, Vector3 wi_in) const {
    if (ggx.smooth()) return Color{0};
    return upper(wo_in, wi_in, [this](Vector3 wo, Vector3 wi) {
        if (wo.z <= 0 || wi.z <= 0) return Color{0};
        const Vector3 wm = normalize(wo + wi);
        const Color single =
            fresnel(dot(wo, wm)) * (ggx.d(wm) * ggx.g(wo, wi) / (4 * wo.z * wi.z));
        // Kulla-Conty: f_ms = (1 - E(mu_o)) (1 - E(mu_i)) / (pi (1 - E_avg)), coloured by
        // F_avg^2 E_avg / (1 - F_avg (1 - E_avg)).
        const float e_avg = ggx_albedo_average(ggx.alpha);
        if (e_avg >= 1 || single_scattering) return single;
        const float ms = (1 - ggx_albedo(wo.z, ggx.alpha)) * (1 - ggx_albedo(wi.z, ggx.alpha)) /
                         (std::numbers::pi_v<float> * (1 - e_avg));
        const Color f_ms{sqr(f_avg.r) * e_avg / (1 - f_avg.r * (1 - e_avg)),
                         sqr(f_avg.g) * e_avg / (1 - f_avg.g * (1 - e_avg)),
                         sqr(f_avg.b) * e_avg / (1 - f_avg.b * (1 - e_avg))};
        return single + f_ms * ms;
    });
}

float ConductorLobe::pdf(Vector3 wo_in, Vector3 wi_in) const {
    if (ggx.smooth()) return 0;
    return upper(wo_in, wi_in, [this](Vector3 wo, Vector3 wi) {
        if (wo.z <= 0 || wi.z <= 0) return 0.0f;
        const float p_ms = single_scattering ? 0 : 1 - ggx_albedo(wo.z, ggx.alpha);
        const Vector3 wm = normalize(wo + wi);
        const float spec = ggx.d_visible(wo, wm) / (4 * dot(wo, wm));
        return (1 - p_ms) * spec + p_ms * wi.z * kInvPi;
    });
}

std::optional<BsdfSample> ConductorLobe::sample(Vector3 wo_in, float uc, Sample2 u) const {
    const bool below = wo_in.z < 0;
    const Vector3 wo = below ? flip_z(wo_in) : wo_in;
    if (wo.z == 0) return std::nullopt;
    Vector3 wi;
    if (ggx.smooth()) {
        wi = mirror_z(wo);
        BsdfSample s{fresnel(wo.z) / wi.z, below ? flip_z(wi) : wi, 1, true};
        return s;
    }
    const float p_ms = single_scattering ? 0 : 1 - ggx_albedo(wo.z, ggx.alpha);
    if (uc < p_ms) {
        wi = sample_cosine_hemisphere(u);
    } else {
        wi = reflect_about(wo, ggx.sample_visible(wo, u));
    }
    if (wi.z <= 0) return std::nullopt;
    const float pdf_value = pdf(wo, wi);
    if (pdf_value <= 0) return std::nullopt;
    return BsdfSample{eval(wo, wi), below ? flip_z(wi) : wi, pdf_value};
}

// ------------------------------------------------------------------------------- dielectric

Color DielectricLobe::eval(Vector3 wo, Vector3 wi) const {
    if (thin || ggx.smooth() || eta == 1) return Color{0};
    Vector3 wm;
    float etap;
    if (!generalized_half(wo, wi, eta, wm, etap)) return Color{0};
    const float f = fresnel_dielectric(dot(wo, wm), eta);
    if (etap == 1) {
        return Color{ggx.d(wm) * ggx.g(wo, wi) * f / std::abs(4 * wi.z * wo.z)};
    }
    const float denom = sqr(dot(wi, wm) + dot(wo, wm) / etap) * wi.z * wo.z;
    const float ft = ggx.d(wm) * (1 - f) * ggx.g(wo, wi) *
                     std::abs(dot(wi, wm) * dot(wo, wm) / denom) / sqr(etap);
    return tint * ft;
}

float DielectricLobe::pdf(Vector3 wo, Vector3 wi) const {
    if (thin || ggx.smooth() || eta == 1) return 0;
    Vector3 wm;
    float etap;
    if (!generalized_half(wo, wi, eta, wm, etap)) return 0;
    const float r = fresnel_dielectric(dot(wo, wm), eta);
    if (etap == 1) return r * ggx.d_visible(wo, wm) / (4 * std::abs(dot(wo, wm)));
    const float denom = sqr(dot(wi, wm) + dot(wo, wm) / etap);
    return (1 - r) * ggx.d_visible(wo, wm) * std::abs(dot(wi, wm)) / denom;
}

std::optional<BsdfSample> DielectricLobe::sample(Vector3 wo, float uc, Sample2 u) const {
    if (wo.z == 0) return std::nullopt;
    if (thin || ggx.smooth() || eta == 1) {
        float r = fresnel_dielectric(wo.z, eta);
        if (thin && r < 1) r += sqr(1 - r) * r / (1 - r * r);  // the sheet's inter-reflections
        const float t = 1 - r;
        if (uc < r) {
            const Vector3 wi = mirror_z(wo);
            return BsdfSample{Color{r / std::abs(wi.z)}, wi, r, true};
        }
        if (thin || eta == 1) {
            const Vector3 wi = -wo;
            return BsdfSample{tint * (t / std::abs(wi.z)), wi, t, true};
        }
        Vector3 wi;
        float etap;
        if (!refract(wo, {0, 0, 1}, eta, wi, etap)) return std::nullopt;
        return BsdfSample{tint * (t / std::abs(wi.z) / sqr(etap)), wi, t, true, etap};
    }
    const Vector3 wm = ggx.sample_visible(wo, u);
    const float r = fresnel_dielectric(dot(wo, wm), eta);
    Vector3 wi;
    float etap = 1;
    if (uc < r) {
        wi = reflect_about(wo, wm);
        if (!same_side(wo, wi)) return std::nullopt;
    } else {
        if (!refract(wo, wm, eta, wi, etap) || same_side(wo, wi) || wi.z == 0) return std::nullopt;
    }
    const float p = pdf(wo, wi);
    if (p <= 0) return std::nullopt;
    return BsdfSample{eval(wo, wi), wi, p, false, etap};
}

// ---------------------------------------------------------------------------------- plastic

float diffuse_fresnel_inside(float eta) {
    constexpr int kSteps = 1024;
    double sum = 0;
    for (int i = 0; i < kSteps; ++i) {
        const float mu = (static_cast<float>(i) + 0.5f) / kSteps;
        sum += 2.0 * fresnel_dielectric(mu, 1 / eta) * mu / kSteps;
    }
    return static_cast<float>(sum);
}

PlasticLobe make_plastic(Color albedo, float eta, float alpha) {
    PlasticLobe p;
    p.albedo = albedo;
    p.eta = eta;
    p.ggx = Ggx{alpha};
    p.fdr_inside = diffuse_fresnel_inside(eta);
    return p;
}

Color PlasticLobe::coat_fresnel(float cos) const {
    const float f = fresnel_dielectric(cos, eta);
    if (specular_weight == 1 && specular_color == Color{1}) return Color{f};
    const float f0 = fresnel_dielectric(1, eta);
    const float t = f0 < 1 ? std::clamp((f - f0) / (1 - f0), 0.0f, 1.0f) : 1;
    const auto channel = [&](float c) {
        const float f0c = std::min(f0 * c, 1.0f);
        return specular_weight * (f0c + (1 - f0c) * t);
    };
    return {channel(specular_color.r), channel(specular_color.g), channel(specular_color.b)};
}

float PlasticLobe::coat_probability(float cos_o) const {
    const float f = coat_fresnel(cos_o).max_component();
    const float base = (1 - f) * (albedo.r + albedo.g + albedo.b) / 3;
    return f + base > 0 ? std::clamp(f / (f + base), 0.05f, 1.0f) : 1.0f;
}

Color PlasticLobe::eval(Vector3 wo_in, Vector3 wi_in) const {
    return upper(wo_in, wi_in, [this](Vector3 wo, Vector3 wi) {
        if (wo.z <= 0 || wi.z <= 0) return Color{0};
        const float fo = coat_fresnel(wo.z).max_component(), fi = coat_fresnel(wi.z).max_component();
        Color base;
        if (specular_weight == 1) {  // the coat whole: refraction's 1/eta^2 and internal reflection
            const float scale = (1 - fo) * (1 - fi) * kInvPi / (eta * eta);
            base = {albedo.r * scale / (1 - albedo.r * fdr_inside), albedo.g * scale / (1 - albedo.g * fdr_inside),
                    albedo.b * scale / (1 - albedo.b * fdr_inside)};
        } else {
            // A weaker coat is that much less of an interface: the interior's terms fade with the
            // weight, so that at 0 the base is the plain Lambertian it then is (white: albedo 1).
            const float w = specular_weight, scale = (1 - fo) * (1 - fi) * kInvPi;
            const auto channel = [&](float a) { return a * scale * (w / (eta * eta * (1 - a * fdr_inside)) + (1 - w)); };
            base = {channel(albedo.r), channel(albedo.g), channel(albedo.b)};
        }
        if (ggx.smooth()) return base;
        const Vector3 wm = normalize(wo + wi);
        // Multiplied in the order of the plain coat's d g F / (4 cos cos), so that its images
        // stay bit for bit what they were.
        const Color f = coat_fresnel(dot(wo, wm));
        const float dg = ggx.d(wm) * ggx.g(wo, wi), den = 4 * wo.z * wi.z;
        return base + Color{dg * f.r / den, dg * f.g / den, dg * f.b / den};
    });
}

float PlasticLobe::pdf(Vector3 wo_in, Vector3 wi_in) const {
    return upper(wo_in, wi_in, [this](Vector3 wo, Vector3 wi) {
        if (wo.z <= 0 || wi.z <= 0) return 0.0f;
        const float pc = coat_probability(wo.z);
        float coat = 0;
        if (!ggx.smooth()) {
            const Vector3 wm = normalize(wo + wi);
            coat = ggx.d_visible(wo, wm) / (4 * dot(wo, wm));
        }
        return pc * coat + (1 - pc) * wi.z * kInvPi;
    });
}

std::optional<BsdfSample> PlasticLobe::sample(Vector3 wo_in, float uc, Sample2 u) const {
    const bool below = wo_in.z < 0;
    const Vector3 wo = below ? flip_z(wo_in) : wo_in;
    if (wo.z == 0) return std::nullopt;
    const float pc = coat_probability(wo.z);
    Vector3 wi;
    if (uc < pc) {
        if (ggx.smooth()) {
            wi = mirror_z(wo);
            return BsdfSample{coat_fresnel(wo.z) / wi.z, below ? flip_z(wi) : wi, pc, true};
        }
        wi = reflect_about(wo, ggx.sample_visible(wo, u));
    } else {
        wi = sample_cosine_hemisphere(u);
    }
    if (wi.z <= 0) return std::nullopt;
    const float p = pdf(wo, wi);
    if (p <= 0) return std::nullopt;
    return BsdfSample{eval(wo, wi), below ? flip_z(wi) : wi, p};
}

// ------------------------------------------------------------------------------------ sheen

namespace {
constexpr float kMinSheenRoughness = 0.07f;
}  // namespace

Color SheenLobe::eval(Vector3 wo_in, Vector3 wi_in) const {
    return upper(wo_in, wi_in, [this](Vector3 wo, Vector3 wi) {
        if (wo.z <= 0 || wi.z <= 0) return Color{0};
        const Vector3 wm = normalize(wo + wi);
        const float a = sqr(std::max(roughness, kMinSheenRoughness));
        const float sin2 = std::max(0.0f, 1 - wm.z * wm.z);
        const float d = (2 + 1 / a) * std::pow(sin2, 0.5f / a) * (0.5f * kInvPi);
        const float v = 1 / (4 * (wi.z + wo.z - wi.z * wo.z));
        return color * (d * v);
    });
}

float SheenLobe::pdf(Vector3 wo, Vector3 wi) const {
    return same_side(wo, wi) ? std::abs(wi.z) * kInvPi : 0;
}

std::optional<BsdfSample> SheenLobe::sample(Vector3 wo, float, Sample2 u) const {
    if (wo.z == 0) return std::nullopt;
    Vector3 wi = sample_cosine_hemisphere(u);
    if (wi.z <= 0) return std::nullopt;
    if (wo.z < 0) wi = flip_z(wi);
    return BsdfSample{eval(wo, wi), wi, std::abs(wi.z) * kInvPi};
}

// ------------------------------------------------------------------------ layer albedo tables

namespace {

// E(mu, roughness) on a 32 x 32 grid (mu and roughness from 0 to 1), each entry given by
// `albedo(mu, roughness)`; read bilinearly.
class AlbedoGrid {
public:
    static constexpr int kN = 32;
    template <typename Albedo>
    explicit AlbedoGrid(Albedo albedo) {
        for (int j = 0; j < kN; ++j)
            for (int i = 0; i < kN; ++i)
                e_[static_cast<std::size_t>(j * kN + i)] =
                    albedo(std::max(static_cast<float>(i) / (kN - 1), 1e-3f), static_cast<float>(j) / (kN - 1));
    }
    float at(float mu, float roughness) const {
        const auto cell = [](float x, int& k0, float& t) {
            const float f = std::clamp(x, 0.0f, 1.0f) * (kN - 1);
            k0 = std::min(static_cast<int>(f), kN - 2);
            t = f - static_cast<float>(k0);
        };
        int i, j;
        float ti, tj;
        cell(mu, i, ti);
        cell(roughness, j, tj);
        const auto e = [&](int jj, int ii) { return e_[static_cast<std::size_t>(jj * kN + ii)]; };
        return (e(j, i) * (1 - ti) + e(j, i + 1) * ti) * (1 - tj) + (e(j + 1, i) * (1 - ti) + e(j + 1, i + 1) * ti) * tj;
    }

private:
    std::array<float, kN * kN> e_{};
};

}  // namespace

ConductorLobe clearcoat_lobe(float roughness) {
    ConductorLobe c;
    c.kind = ConductorLobe::FresnelKind::kComplex;
    c.eta = Color{1.5f};
    c.k = Color{0};
    c.ggx = Ggx{roughness * roughness};
    c.f_avg = Color{0};
    return c;
}

float sheen_albedo(float mu, float roughness) {
    // Midpoint quadrature of f cos over the hemisphere (the lobe is mirror-symmetric in phi):
    // cosine sampling would miss the grazing peak of a low roughness.
    static const AlbedoGrid grid([](float m, float r) {
        const SheenLobe lobe{Color{1}, r};
        const Vector3 wo{std::sqrt(1 - m * m), 0, m};
        constexpr int kTheta = 96, kPhi = 48;
        const float dt = 0.5f * std::numbers::pi_v<float> / kTheta, dp = std::numbers::pi_v<float> / kPhi;
        double sum = 0;
        for (int t = 0; t < kTheta; ++t) {
            const float theta = (t + 0.5f) * dt, st = std::sin(theta), ct = std::cos(theta);
            for (int p = 0; p < kPhi; ++p) {
                const float phi = (p + 0.5f) * dp;
                sum += double(lobe.eval(wo, {st * std::cos(phi), st * std::sin(phi), ct}).r) * ct * st;
            }
        }
        return static_cast<float>(2 * sum * dt * dp);
    });
    return grid.at(mu, roughness);
}

float clearcoat_albedo(float mu, float roughness) {
    // The lobe's own (visible-normal) sampling, 64 x 64 stratified; a smooth coat is F(mu).
    static const AlbedoGrid grid([](float m, float r) {
        const ConductorLobe lobe = clearcoat_lobe(r);
        const Vector3 wo{std::sqrt(1 - m * m), 0, m};
        constexpr int kSide = 64;
        double sum = 0;
        for (int a = 0; a < kSide; ++a) {
            for (int b = 0; b < kSide; ++b) {
                const Sample2 u{(a + 0.5f) / kSide, (b + 0.5f) / kSide};
                const float uc = std::fmod(static_cast<float>(a * kSide + b) * 0.6180339887f, 1.0f);
                const auto s = lobe.sample(wo, uc, u);
                if (s && s->pdf > 0) sum += double(s->f.r) * std::abs(s->wi.z) / s->pdf;
            }
        }
        return static_cast<float>(sum / (kSide * kSide));
    });
    return grid.at(mu, roughness);
}

// ------------------------------------------------------------------------------- composite

void Bsdf::set_frame(Normal3 n) {
    n_ = to_vector(n);
    orthonormal_basis(n_, t_, b_);
}

Bsdf::Bsdf(Normal3 n, std::initializer_list<std::pair<Lobe, float>> lobes) {
    set_frame(n);
    float total = 0;
    for (const auto& [lobe, weight] : lobes) {
        if (!(weight > 0) || count_ == 3) continue;
        std::construct_at(&lobes_[static_cast<std::size_t>(count_)], lobe);  // raw storage until now
        weight_[static_cast<std::size_t>(count_)] = weight;
        total += weight;
        has_non_delta_ |= std::visit([](const auto& l) { return non_delta(l); }, lobe);
        ++count_;
    }
    for (int i = 0; i < count_; ++i) select_[static_cast<std::size_t>(i)] =
        weight_[static_cast<std::size_t>(i)] / total;
}

Color Bsdf::eval_lobes(Vector3 wo, Vector3 wi) const {
    Color f{0};
    for (int i = 0; i < count_; ++i) {
        const auto k = static_cast<std::size_t>(i);
        f += std::visit([&](const auto& l) { return l.eval(wo, wi); }, lobes_[k]) * weight_[k];
    }
    return f;
}

float Bsdf::pdf_lobes(Vector3 wo, Vector3 wi) const {
    float p = 0;
    for (int i = 0; i < count_; ++i) {
        const auto k = static_cast<std::size_t>(i);
        p += std::visit([&](const auto& l) { return l.pdf(wo, wi); }, lobes_[k]) * select_[k];
    }
    return p;
}

std::optional<BsdfSample> Bsdf::sample_lobes(Vector3 wo, float uc, Sample2 u) const {
    // Choose a lobe with uc, then reuse the remainder of uc inside it. One named result on
    // every path, as in sample().
    std::size_t k = 0;
    float lo = 0;
    while (k + 1 < static_cast<std::size_t>(count_) && uc >= lo + select_[k]) lo += select_[k++];
    const float uc_lobe = count_ == 0 ? 0 : std::clamp((uc - lo) / select_[k], 0.0f, 0x1.fffffep-1f);
    auto s = count_ == 0 ? std::optional<BsdfSample>{}
                         : std::visit([&](const auto& l) { return l.sample(wo, uc_lobe, u); }, lobes_[k]);
    if (!s) return s;
    if (s->specular || count_ == 1) {
        s->f = s->f * weight_[k];
        s->pdf *= select_[k];
    } else {
        const Vector3 wi = s->wi;
        Color f{0};
        float p = 0;
        for (int i = 0; i < count_; ++i) {
            const auto j = static_cast<std::size_t>(i);
            std::visit(
                [&](const auto& l) {
                    f += l.eval(wo, wi) * weight_[j];
                    p += l.pdf(wo, wi) * select_[j];
                },
                lobes_[j]);
        }
        s->f = f;
        s->pdf = p;
    }
    if (!(s->pdf > 0)) s.reset();
    return s;
}

// ----------------------------------------------------------------------------- glTF layers

void Bsdf::set_clearcoat(float weight, float roughness) {
    coat_weight_ = std::clamp(weight, 0.0f, 1.0f);
    coat_roughness_ = std::clamp(roughness, 0.0f, 1.0f);
    if (coat_weight_ > 0 && !clearcoat_lobe(coat_roughness_).ggx.smooth()) has_non_delta_ = true;
}

void Bsdf::set_sheen(Color color, float roughness) {
    sheen_ = SheenLobe{Color{std::clamp(color.r, 0.0f, 1.0f), std::clamp(color.g, 0.0f, 1.0f),
                             std::clamp(color.b, 0.0f, 1.0f)},
                       std::clamp(roughness, 0.0f, 1.0f)};
    if (sheen_.color.max_component() > 0) has_non_delta_ = true;
}

float Bsdf::coat_keep(Vector3 wo, Vector3 wi) const {
    if (!(coat_weight_ > 0)) return 1;
    return (1 - coat_weight_ * clearcoat_albedo(std::abs(wo.z), coat_roughness_)) *
           (1 - coat_weight_ * clearcoat_albedo(std::abs(wi.z), coat_roughness_));
}

float Bsdf::sheen_keep(Vector3 wo, Vector3 wi) const {
    const float m = sheen_.color.max_component();
    if (!(m > 0)) return 1;
    return (1 - m * sheen_albedo(std::abs(wo.z), sheen_.roughness)) *
           (1 - m * sheen_albedo(std::abs(wi.z), sheen_.roughness));
}

Bsdf::LayerWeights Bsdf::layer_weights(Vector3 wo) const {
    // Roughly each layer's share of the reflected energy, kept away from 0 and 1 so that every
    // part is sampled; what lies under nothing takes everything.
    const float mu = std::abs(wo.z);
    LayerWeights w;
    const bool sheen = sheen_.color.max_component() > 0;
    if (sheen) w.p_sheen = count_ == 0 ? 1 : std::clamp(sheen_.color.max_component() * sheen_albedo(mu, sheen_.roughness), 0.05f, 0.9f);
    if (coat_weight_ > 0)
        w.p_coat = count_ == 0 && !sheen ? 1 : std::clamp(coat_weight_ * clearcoat_albedo(mu, coat_roughness_), 0.05f, 0.9f);
    return w;
}

Color Bsdf::eval_local(Vector3 wo, Vector3 wi) const {
    Color f = eval_lobes(wo, wi);
    if (!layered()) return f;
    if (sheen_.color.max_component() > 0) f = f * sheen_keep(wo, wi) + sheen_.eval(wo, wi);
    if (coat_weight_ > 0) f = f * coat_keep(wo, wi) + clearcoat_lobe(coat_roughness_).eval(wo, wi) * coat_weight_;
    return f;
}

float Bsdf::pdf_local(Vector3 wo, Vector3 wi, const LayerWeights& w) const {
    float p = pdf_lobes(wo, wi) * (1 - w.p_sheen);
    if (w.p_sheen > 0) p += sheen_.pdf(wo, wi) * w.p_sheen;
    p *= 1 - w.p_coat;
    if (w.p_coat > 0) p += clearcoat_lobe(coat_roughness_).pdf(wo, wi) * w.p_coat;
    return p;
}

Color Bsdf::eval(Vector3 wo_w, Vector3 wi_w) const {
    const Vector3 wo = to_local(wo_w), wi = to_local(wi_w);
    return layered() ? eval_local(wo, wi) : eval_lobes(wo, wi);
}

float Bsdf::pdf(Vector3 wo_w, Vector3 wi_w) const {
    const Vector3 wo = to_local(wo_w), wi = to_local(wi_w);
    if (!layered()) return pdf_lobes(wo, wi);
    return pdf_local(wo, wi, layer_weights(wo));
}

std::optional<BsdfSample> Bsdf::sample(Vector3 wo_w, float uc, Sample2 u) const {
    const Vector3 wo = to_local(wo_w);
    // One named result returned on every path, so that it is built in the caller's object
    // (returning a temporary on one path made GCC copy the sample, read back over its pieces).
    std::optional<BsdfSample> s = layered() ? sample_layered(wo, uc, u) : sample_lobes(wo, uc, u);
    if (s) s->wi = to_world(reload(s->wi));
    return s;
}

std::optional<BsdfSample> Bsdf::sample_layered(Vector3 wo, float uc, Sample2 u) const {
    std::optional<BsdfSample> s;
    const LayerWeights w = layer_weights(wo);
    constexpr float kBelowOne = 0x1.fffffep-1f;
    if (uc < w.p_coat) {
        s = clearcoat_lobe(coat_roughness_).sample(wo, std::min(uc / w.p_coat, kBelowOne), u);
        if (s && s->specular) {
            s->f = s->f * coat_weight_;
            s->pdf *= w.p_coat;
        }
    } else {
        const float v = std::min((uc - w.p_coat) / (1 - w.p_coat), kBelowOne);
        if (v < w.p_sheen) {
            s = sheen_.sample(wo, v / w.p_sheen, u);
        } else {
            s = sample_lobes(wo, std::min((v - w.p_sheen) / (1 - w.p_sheen), kBelowOne), u);
            if (s && s->specular) {
                s->f = s->f * (coat_keep(wo, s->wi) * sheen_keep(wo, s->wi));
                s->pdf *= (1 - w.p_coat) * (1 - w.p_sheen);
            }
        }
    }
    if (s && !s->specular) {  // the whole of f and of the density in that direction
        s->f = eval_local(wo, s->wi);
        s->pdf = pdf_local(wo, s->wi, w);
    }
    if (s && !(s->pdf > 0)) s.reset();
    return s;
}

}  // namespace glint
