#pragma once
// Phase functions: the angular distribution of light scattered inside a medium. Conventions as
// the BSDFs' (materials/bsdf.h): wo points back along the ray (towards the viewer), wi towards
// the light, both unit and leaving the scattering point; p(wo, wi) integrates to 1 over the
// sphere of wi, and sampling is exact (the sampled direction's density is p itself, so the
// weight p / pdf is 1).
#include <cmath>
#include <numbers>

#include "glint/math/frame.h"
#include "glint/math/vector.h"
#include "glint/samplers/stratified.h"

namespace glint {

struct PhaseSample {
    Vector3 wi;
    float p = 0;    ///< p(wo, wi)
    float pdf = 0;  ///< equal to p (exact sampling)
};

/// Henyey and Greenstein (1941): one parameter g in (-1, 1), the mean cosine of the scattering
/// angle; g = 0 is isotropic, g > 0 forward scattering (wi near -wo), g < 0 backward.
///   p = (1 - g^2) / (4 pi (1 + g^2 + 2 g cos)^(3/2)),  cos = wo . wi
struct HgPhase {
    float g = 0;

    static float eval_cos(float cos_theta, float g) {
        const float denom = 1 + g * g + 2 * g * cos_theta;
        return std::numbers::inv_pi_v<float> / 4 * (1 - g * g) / (denom * std::sqrt(std::max(denom, 0.0f)));
    }
    float p(Vector3 wo, Vector3 wi) const { return eval_cos(dot(wo, wi), g); }
    float pdf(Vector3 wo, Vector3 wi) const { return p(wo, wi); }

    /// Inverts the cumulative distribution of cos(wo, wi) in closed form (in double, so that
    /// g near +-1 keeps its precision); the azimuth about wo is uniform.
    PhaseSample sample(Vector3 wo, Sample2 u) const {
        double cos_theta;
        if (std::abs(g) < 1e-3f) {
            cos_theta = 1 - 2 * double(u.x);
        } else {
            const double gd = g;
            const double s = (1 - gd * gd) / (1 + gd - 2 * gd * double(u.x));
            cos_theta = -(1 + gd * gd - s * s) / (2 * gd);
        }
        cos_theta = std::clamp(cos_theta, -1.0, 1.0);
        const double sin_theta = std::sqrt(std::max(0.0, 1 - cos_theta * cos_theta));
        const double phi = 2 * std::numbers::pi * double(u.y);
        Vector3 t, b;
        orthonormal_basis(wo, t, b);
        const Vector3 wi = normalize(t * float(sin_theta * std::cos(phi)) +
                                     b * float(sin_theta * std::sin(phi)) + wo * float(cos_theta));
        const float p = eval_cos(static_cast<float>(cos_theta), g);
        return {wi, p, p};
    }
};

}  // namespace glint
