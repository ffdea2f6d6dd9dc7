#pragma once
// Materials at a hit: the Bsdf the path tracer samples, and the simpler views the article's
// integrators and the AOVs use.
#include "glint/materials/bsdf.h"
#include "glint/scene.h"
#include "glint/spectra/spectrum.h"

namespace glint {

/// The material of `si` as a Bsdf in the frame of the shape's normal. With `wl` (spectral mode)
/// its colours are spectra at those wavelengths (spectra/rgb_spectrum.h) and `dispersive` is set
/// when its index depends on the wavelength (the lobe then holds the hero wavelength's index).
Bsdf make_bsdf(const Scene& scene, const SurfaceInteraction& si, const Wavelengths* wl = nullptr,
               bool* dispersive = nullptr);

/// The article's (colour, shininess) for any material, for `whitted` and `flat`: a diffuse
/// material is (albedo, 0); a metal (its normal-incidence reflectance, 1 - roughness); glass
/// (its tint, its normal-incidence reflectance); plastic (its albedo, its coat's normal-incidence
/// reflectance); pbr (base colour, metallic).
struct ArticleView {
    Color color;
    float shininess;
};
ArticleView article_view(const Scene& scene, const SurfaceInteraction& si);

}  // namespace glint
