#pragma once
// Transmittance estimators along a ray segment inside one medium, for shadow rays.
#include <cstdint>

#include "glint/media/medium.h"

namespace glint {

/// Ratio tracking (Novak et al. 2014) in the null-scattering form with spectral MIS: tentative
/// collisions at the hero channel's majorant, each multiplying the estimate by
/// T_maj sigma_n / pdf and `r` (the per-channel density over the hero's) by T_maj sigma_maj / pdf;
/// the unbiased transmittance estimate is the returned value over average(r). Estimates below
/// 0.05 go through Russian roulette (kept with probability 1/4). `majorant_scale` >= 1 inflates
/// the majorant (tests use it to make homogeneous media track; 1 otherwise).
Color ratio_tracking(const Medium& medium, const Ray& ray, float t_end, HashRng& rng, int hero,
                     Color& r, float majorant_scale = 1, const SpectralMedium* sm = nullptr);

/// The transmittance a shadow ray needs: exp(-sigma_t d) in closed form in a homogeneous medium
/// (no variance, r untouched), ratio tracking in a grid. `sm`: spectral mode's coefficients.
Color estimate_transmittance(const Medium& medium, const Ray& ray, float t_end, HashRng& rng,
                             int hero, Color& r, const SpectralMedium* sm = nullptr);

}  // namespace glint
