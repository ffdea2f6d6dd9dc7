#pragma once
// Materials: a closed set (std::variant of plain structs). Colours come from textures (ids into
// the scene's texture array); scalar parameters are constants. Each material turns into a Bsdf
// at a hit (make_bsdf in materials/make_bsdf.h). Emission is not a material kind: any material
// may emit (Scene::emission, parallel to the materials).
#include <array>
#include <memory>
#include <optional>
#include <variant>

#include "glint/materials/bsdf.h"
#include "glint/spectra/spectrum.h"
#include "glint/textures/texture.h"

namespace glint {

/// The article's material: a colour K (from a texture) and a shininess s in [0,1] that blends
/// diffuse shading d with the reflected colour: (1-s) d + s (d * r). Under the path tracer it is
/// the matching mix of a diffuse lobe of albedo (1 - s) K and a perfect mirror of reflectance
/// s K (the article's d * r: reflections tinted by the surface colour).
struct ArticleMaterial {
    TextureId color;
    Float shininess = 0;
};

/// Lambertian reflection.
struct DiffuseMaterial {
    TextureId albedo;
};

/// A metal. `lobe` holds the complex index (a preset or eta/k) and the GGX width; when
/// `reflectance` is set, the Fresnel term is Schlick's with that texture as f0 instead.
/// In spectral mode, `eta_spectrum` and `k_spectrum` (a named metal's measured index) replace
/// lobe.eta and lobe.k, which are then their values at 650, 550 and 450 nm.
struct ConductorMaterial {
    ConductorLobe lobe;
    std::optional<TextureId> reflectance;
    std::shared_ptr<const Spectrum> eta_spectrum, k_spectrum;
    /// With them: the Fresnel average (multiple scattering) by wavelength, tabulated at build.
    std::shared_ptr<const PiecewiseLinearSpectrum> f_avg_spectrum;
};

/// Glass (smooth or rough, optionally a thin sheet). `ior`: the index by wavelength (spectral
/// mode; a non-constant one disperses), lobe.eta its value at 587.56 nm for RGB mode.
struct DielectricMaterial {
    DielectricLobe lobe;
    std::shared_ptr<const Spectrum> ior;
};

/// A diffuse base under a dielectric coat.
struct PlasticMaterial {
    TextureId albedo;
    PlasticLobe coat;  ///< eta, width and the precomputed internal reflectance; albedo set per hit
};

/// pbrt-v4's coateddiffuse and coatedconductor: a dielectric coat over a diffuse or a conductor
/// base with a slab between (LayeredLobe, evaluated by random walks). `base`: the diffuse
/// base's albedo; a metal base has its complex index relative to the coat (eta, k), or a
/// `reflectance` texture turned into one per hit as pbrt-v4 does.
struct CoatedMaterial {
    LayeredParams layer;
    TextureId base = 0;
    Color eta{1}, k{0};
    std::optional<TextureId> reflectance;
    std::shared_ptr<const Spectrum> eta_spectrum, k_spectrum;  ///< spectral mode, absolute (not over the coat)
};

/// glTF 2.0 metallic-roughness: mix(dielectric, metal, metallic), where the metal is GGX with
/// Schlick's Fresnel and f0 = base colour, and the dielectric is a plastic of base colour under
/// a coat of index ior, or, in proportion `transmission`, rough glass tinted by the base colour.
/// alpha = roughness^2, as glTF specifies.
struct PbrMaterial {
    TextureId base_color;
    float metallic = 1;
    float roughness = 1;
    float transmission = 0;
    float ior = 1.5f;
    float fdr_inside = 0;  ///< of the coat, precomputed
    /// glTF's metallicRoughnessTexture: blue scales metallic, green scales roughness.
    std::optional<TextureId> metallic_roughness;
    /// glTF's KHR_materials_clearcoat (weight in red, roughness in green), KHR_materials_sheen
    /// (colour; roughness in red) and KHR_materials_specular (weight in red; colour), factors
    /// folded into the textures. Absent: no coat, no sheen, specular 1 and white.
    std::optional<TextureId> clearcoat, clearcoat_roughness, sheen, sheen_roughness, specular, specular_color;
    /// Spectral mode: the transmitted part's index by wavelength (KHR_materials_dispersion).
    std::shared_ptr<const Spectrum> ior_spectrum;
};

/// pbrt's diffusetransmission: Lambertian reflection of `reflectance` on the side light comes
/// from and Lambertian transmission of `transmittance` to the other (leaves, paper, lampshades).
struct DiffuseTransmissionMaterial {
    TextureId reflectance, transmittance;
};

/// pbrt's mix: at each surface point one of two materials, the second with probability
/// `amount` (the texture's channel mean), chosen by a hash of the point, so the choice is the
/// same for every sample that lands there and on every thread. Resolved by
/// Scene::surface_material before anything else looks at the material.
struct MixMaterial {
    std::array<MaterialId, 2> materials{};
    TextureId amount = 0;
};

/// No surface at all: a boundary that only changes the medium a ray is in (a smoke box that
/// does not refract). The path tracer passes through it without a scattering event; Whitted and
/// the debug views do not see it.
struct InterfaceMaterial {};

using Material = std::variant<ArticleMaterial, DiffuseMaterial, ConductorMaterial,
                              DielectricMaterial, PlasticMaterial, PbrMaterial, InterfaceMaterial,
                              DiffuseTransmissionMaterial, MixMaterial, CoatedMaterial>;

/// Light a surface emits, in radiance, on the side its normal faces (both when two_sided).
struct Emission {
    Color radiance{0};
    bool two_sided = false;
    std::optional<TextureId> texture;  ///< multiplies radiance (glTF's emissiveTexture)
    /// Spectral mode: the emitted spectrum (Y = 1) times luminance(radiance), instead of the
    /// radiance upsampled (a black body, a standard illuminant); radiance is then its colour.
    std::shared_ptr<const Spectrum> spectrum;
    bool emits() const { return radiance.max_component() > 0; }
};
/// What a material without an emission entry emits (nothing): a namespace-scope constant, so that
/// reading it costs no guard of a function-local static.
inline const Emission kNoEmission{};

/// A tangent-space normal map on a material (glTF's normalTexture): texel (r, g, b) in [0, 1]
/// is the normal (2r - 1) s, (2g - 1) s, 2b - 1 in the frame (tangent, bitangent, normal).
struct NormalMap {
    TextureId texture;
    float scale = 1;
};

}  // namespace glint
