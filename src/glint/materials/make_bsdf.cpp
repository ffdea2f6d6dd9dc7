#include "glint/materials/make_bsdf.h"

#include <algorithm>
#include <cmath>
#include <type_traits>

#include "glint/materials/fresnel.h"
#include "glint/spectra/rgb_spectrum.h"

namespace glint {

namespace {

float f0_dielectric(float eta) { return fresnel_dielectric(1, eta); }

Color clamp01(Color c) {
    return {std::clamp(c.r, 0.0f, 1.0f), std::clamp(c.g, 0.0f, 1.0f), std::clamp(c.b, 0.0f, 1.0f)};
}

// A conductor's Fresnel average 2 int F(mu) mu dmu for the multiple-scattering term, at the
// path's wavelengths: 6-point Gauss-Legendre (F is smooth in mu; make_conductor's 256 midpoint
// steps are for the build, not each hit).
Color conductor_f_avg(const ConductorLobe& c) {
    static constexpr float kX[6] = {0.0337652429f, 0.1693953068f, 0.3806904070f, 0.6193095930f, 0.8306046932f, 0.9662347571f};
    static constexpr float kW[6] = {0.0856622462f, 0.1803807865f, 0.2339569673f, 0.2339569673f, 0.1803807865f, 0.0856622462f};
    Color sum{0};
    for (int i = 0; i < 6; ++i) sum += c.fresnel(kX[i]) * (2 * kX[i] * kW[i]);
    return sum;
}

}  // namespace

Bsdf make_bsdf(const Scene& scene, const SurfaceInteraction& si, const Wavelengths* wl, bool* dispersive) {
    // A colour read where the path is: unchanged in RGB mode, a reflectance spectrum's values
    // at the path's wavelengths in spectral mode.
    const auto R = [wl](Color c) { return wl ? upsample_reflectance(c, *wl) : c; };
    // A constant given as a reflectance spectrum is read as it is.
    const auto tex = [&](TextureId id) {
        if (wl) {
            if (const Spectrum* s = scene.texture_spectrum(id)) return s->at(*wl);
            if (const RgbReflectance* r = scene.texture_reflectance(id)) return r->at(*wl);
        }
        return R(scene.texture(id, si));
    };
    return std::visit(
        [&](const auto& m) -> Bsdf {
            using T = std::decay_t<decltype(m)>;
            if constexpr (std::is_same_v<T, ArticleMaterial>) {
                const Color k = tex(m.color);
                const float s = m.shininess;
                ConductorLobe mirror;  // smooth, constant reflectance K; weighted by s
                mirror.eta = k;
                return Bsdf(si.ns, {{DiffuseLobe{k}, 1 - s}, {mirror, s}});
            } else if constexpr (std::is_same_v<T, DiffuseMaterial>) {
                return Bsdf(si.ns, DiffuseLobe{tex(m.albedo)});
            } else if constexpr (std::is_same_v<T, ConductorMaterial>) {
                if (!m.reflectance) {
                    if (!wl || m.lobe.kind == ConductorLobe::FresnelKind::kSchlick) {
                        ConductorLobe lobe = m.lobe;
                        if (wl) lobe.eta = R(lobe.eta), lobe.f_avg = lobe.eta + (Color{1} - lobe.eta) * (1.0f / 21);
                        return Bsdf(si.ns, lobe);
                    }
                    // The complex index at the path's wavelengths: measured, or the RGB upsampled.
                    ConductorLobe lobe = m.lobe;
                    if (lobe.kind == ConductorLobe::FresnelKind::kComplex) {
                        lobe.eta = m.eta_spectrum ? m.eta_spectrum->at(*wl) : upsample_unbounded(m.lobe.eta, *wl);
                        lobe.k = m.k_spectrum ? m.k_spectrum->at(*wl) : upsample_unbounded(m.lobe.k, *wl);
                    } else {
                        lobe.eta = R(lobe.eta);
                    }
                    if (!lobe.ggx.smooth())
                        lobe.f_avg = m.f_avg_spectrum ? m.f_avg_spectrum->at(*wl) : conductor_f_avg(lobe);
                    return Bsdf(si.ns, lobe);
                }
                ConductorLobe lobe = m.lobe;
                lobe.kind = ConductorLobe::FresnelKind::kSchlick;
                lobe.eta = tex(*m.reflectance);
                lobe.f_avg = lobe.eta + (Color{1} - lobe.eta) * (1.0f / 21);  // closed form
                return Bsdf(si.ns, lobe);
            } else if constexpr (std::is_same_v<T, DielectricMaterial>) {
                if (!wl) return Bsdf(si.ns, m.lobe);
                DielectricLobe lobe = m.lobe;
                lobe.tint = R(lobe.tint);
                if (m.ior && !m.ior->constant()) {
                    // Dispersion: the hero wavelength's index; the caller drops the others.
                    lobe.eta = (*m.ior)(wl->lambda[0]);
                    if (dispersive) *dispersive = true;
                }
                return Bsdf(si.ns, lobe);
            } else if constexpr (std::is_same_v<T, PlasticMaterial>) {
                PlasticLobe lobe = m.coat;
                lobe.albedo = tex(m.albedo);
                return Bsdf(si.ns, lobe);
            } else if constexpr (std::is_same_v<T, CoatedMaterial>) {
                LayeredLobe lobe{&m.layer, m.eta, m.k, wl ? R(m.layer.albedo) : m.layer.albedo};
                if (!m.layer.conductor_base) {
                    lobe.base = clamp01(tex(m.base));
                } else if (m.reflectance) {
                    // pbrt-v4's form: the complex index of eta 1 and k = 2 sqrt(r) / sqrt(1 - r),
                    // whose normal-incidence reflectance is r, relative to the coat (both
                    // divided by its index).
                    const Color r = clamp01(tex(*m.reflectance));
                    const auto k = [](float v) { v = std::min(v, 0.9999f); return 2 * std::sqrt(v) / std::sqrt(1 - v); };
                    lobe.base = Color{1 / m.layer.eta};
                    lobe.k = Color{k(r.r), k(r.g), k(r.b)} / m.layer.eta;
                } else if (wl) {
                    lobe.base = (m.eta_spectrum ? m.eta_spectrum->at(*wl) : upsample_unbounded(m.eta * m.layer.eta, *wl)) / m.layer.eta;
                    lobe.k = (m.k_spectrum ? m.k_spectrum->at(*wl) : upsample_unbounded(m.k * m.layer.eta, *wl)) / m.layer.eta;
                }
                return Bsdf(si.ns, lobe);  // alone: see LayeredLobe
            } else if constexpr (std::is_same_v<T, InterfaceMaterial> || std::is_same_v<T, MixMaterial>) {
                return Bsdf();  // no lobes: nothing scatters (the integrators pass through)
            } else if constexpr (std::is_same_v<T, DiffuseTransmissionMaterial>) {
                // Each lobe chosen in proportion to its largest channel.
                const Color r = tex(m.reflectance), t = tex(m.transmittance);
                const float wr = r.max_component(), wt = t.max_component();
                return Bsdf(si.ns, {{DiffuseLobe{wr > 0 ? r / wr : Color{0}}, wr},
                                   {DiffuseTransmissionLobe{wt > 0 ? t / wt : Color{0}}, wt}});
            } else {
                static_assert(std::is_same_v<T, PbrMaterial>);
                const Color base = tex(m.base_color);
                float metallic = m.metallic, roughness = m.roughness;
                if (m.metallic_roughness) {
                    const Color mr = scene.texture(*m.metallic_roughness, si);
                    metallic *= mr.b;
                    roughness *= mr.g;
                }
                const float alpha = roughness * roughness;
                ConductorLobe metal;
                metal.kind = ConductorLobe::FresnelKind::kSchlick;
                metal.eta = base;
                metal.f_avg = base + (Color{1} - base) * (1.0f / 21);
                metal.ggx = Ggx{alpha};
                PlasticLobe plastic;
                plastic.albedo = base;
                plastic.eta = m.ior;
                plastic.ggx = Ggx{alpha};
                plastic.fdr_inside = m.fdr_inside;
                if (m.specular) plastic.specular_weight = std::clamp(scene.texture(*m.specular, si).r, 0.0f, 1.0f);
                if (m.specular_color) plastic.specular_color = tex(*m.specular_color);
                DielectricLobe glass;
                glass.eta = m.ior;
                if (wl && m.ior_spectrum && m.transmission > 0 && metallic < 1) {
                    glass.eta = (*m.ior_spectrum)(wl->lambda[0]);  // the hero's; the caller drops the rest
                    if (dispersive) *dispersive = true;
                }
                glass.ggx = Ggx{alpha};
                glass.tint = base;
                const float dielectric = 1 - metallic;
                Bsdf b(si.ns, {{metal, metallic},
                               {plastic, dielectric * (1 - m.transmission)},
                               {glass, dielectric * m.transmission}});
                if (m.sheen) {
                    const Color c = tex(*m.sheen);
                    if (c.max_component() > 0)
                        b.set_sheen(c, m.sheen_roughness ? scene.texture(*m.sheen_roughness, si).r : 0);
                }
                if (m.clearcoat) {
                    const float w = scene.texture(*m.clearcoat, si).r;
                    if (w > 0) b.set_clearcoat(w, m.clearcoat_roughness ? scene.texture(*m.clearcoat_roughness, si).g : 0);
                }
                return b;
            }
        },
        scene.materials[scene.surface_material(si)]);
}

ArticleView article_view(const Scene& scene, const SurfaceInteraction& si) {
    return std::visit(
        [&](const auto& m) -> ArticleView {
            using T = std::decay_t<decltype(m)>;
            if constexpr (std::is_same_v<T, ArticleMaterial>) {
                return {scene.texture(m.color, si), m.shininess};
            } else if constexpr (std::is_same_v<T, DiffuseMaterial>) {
                return {scene.texture(m.albedo, si), 0};
            } else if constexpr (std::is_same_v<T, ConductorMaterial>) {
                const Color f0 = m.reflectance ? scene.texture(*m.reflectance, si)
                                               : m.lobe.fresnel(1);
                return {f0, 1 - std::sqrt(m.lobe.ggx.alpha)};
            } else if constexpr (std::is_same_v<T, DielectricMaterial>) {
                return {m.lobe.tint, f0_dielectric(m.lobe.eta)};
            } else if constexpr (std::is_same_v<T, PlasticMaterial>) {
                return {scene.texture(m.albedo, si), f0_dielectric(m.coat.eta)};
            } else if constexpr (std::is_same_v<T, CoatedMaterial>) {
                if (!m.layer.conductor_base) return {scene.texture(m.base, si), f0_dielectric(m.layer.eta)};
                return {m.reflectance ? scene.texture(*m.reflectance, si) : fresnel_conductor(1, m.eta, m.k),
                        1 - std::sqrt(m.layer.metal.alpha)};
            } else if constexpr (std::is_same_v<T, InterfaceMaterial> || std::is_same_v<T, MixMaterial>) {
                return {Color{0}, 0};
            } else if constexpr (std::is_same_v<T, DiffuseTransmissionMaterial>) {
                return {scene.texture(m.reflectance, si), 0};
            } else {
                return {scene.texture(m.base_color, si), m.metallic};
            }
        },
        scene.materials[scene.surface_material(si)]);
}

}  // namespace glint
