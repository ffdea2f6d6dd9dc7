#pragma once
// The GGX (Trowbridge-Reitz) microfacet distribution, isotropic, in the local shading frame
// (+z the macro normal). alpha is the width (glTF: alpha = roughness^2). Formulas: Walter et
// al. 2007 (D, Smith G), Heitz 2014 (Lambda), Heitz 2018 (sampling visible normals).
#include <algorithm>
#include <cmath>
#include <numbers>

#include "glint/math/vector.h"
#include "glint/samplers/stratified.h"
#include "glint/samplers/warp.h"

namespace glint {

struct Ggx {
    float alpha;

    /// Below this width a surface is treated as perfectly smooth (a delta lobe).
    static constexpr float kSmooth = 1e-3f;
    bool smooth() const { return alpha < kSmooth; }

    /// Microfacet normal density D(m), normalised so that integral of D(m) cos(theta_m) = 1.
    float d(Vector3 m) const {
        const float c2 = m.z * m.z;
        if (c2 <= 0) return 0;
        const float a2 = alpha * alpha;
        const float t = c2 * (a2 - 1) + 1;  // cos^4 (1 + tan^2 / a^2) a^2 = ...
        return a2 / (std::numbers::pi_v<float> * t * t);
    }
    /// Smith's Lambda for direction w.
    float lambda(Vector3 w) const {
        const float c2 = w.z * w.z;
        if (c2 <= 0) return 1e30f;
        const float tan2 = std::max(0.0f, 1 - c2) / c2;
        return 0.5f * (std::sqrt(1 + alpha * alpha * tan2) - 1);
    }
    float g1(Vector3 w) const { return 1 / (1 + lambda(w)); }
    /// Height-correlated masking-shadowing.
    float g(Vector3 wo, Vector3 wi) const { return 1 / (1 + lambda(wo) + lambda(wi)); }
    /// Density of visible normals from wo (on either side; m.z > 0):
    /// G1(wo) max(0, wo.m) D(m) / |cos theta_o|, with wo mirrored to the upper side.
    float d_visible(Vector3 wo, Vector3 m) const {
        const float wm = wo.z < 0 ? -dot(wo, m) : dot(wo, m);
        if (wm <= 0 || wo.z == 0) return 0;
        return g1(wo) * wm * d(m) / std::abs(wo.z);
    }
    /// A microfacet normal distributed as d_visible(wo, .), for wo on either side; m.z > 0.
    Vector3 sample_visible(Vector3 wo, Sample2 u) const {
        Vector3 v = wo.z < 0 ? -wo : wo;
        // Stretch to the hemisphere configuration (alpha = 1).
        Vector3 vh = normalize(Vector3{alpha * v.x, alpha * v.y, v.z});
        // An orthonormal frame around vh (t1 perpendicular to z).
        const float len2 = vh.x * vh.x + vh.y * vh.y;
        const Vector3 t1 = len2 > 1e-14f ? Vector3{-vh.y, vh.x, 0} / std::sqrt(len2)
                                         : Vector3{1, 0, 0};
        const Vector3 t2 = cross(vh, t1);
        // A uniform disk point, warped towards the visible half of the projected hemisphere.
        const Point2 p = sample_uniform_disk_concentric(u);
        const float h = std::sqrt(std::max(0.0f, 1 - p.x * p.x));
        const float s = 0.5f * (1 + vh.z);
        const float py = (1 - s) * h + s * p.y;
        const float pz = std::sqrt(std::max(0.0f, 1 - p.x * p.x - py * py));
        const Vector3 nh = t1 * p.x + t2 * py + vh * pz;
        return normalize(Vector3{alpha * nh.x, alpha * nh.y, std::max(1e-6f, nh.z)});
    }
};

/// The mirror image of wo about the microfacet normal m.
inline Vector3 reflect_about(Vector3 wo, Vector3 m) { return m * (2 * dot(wo, m)) - wo; }

/// The half vector of a reflection or refraction pair (wo, wi) at an interface of relative index
/// eta (inside / outside), facing +z, and the index ratio etap crossed (1 for reflection). False
/// when the pair is impossible (grazing, or a microfacet seen from behind).
inline bool generalized_half(Vector3 wo, Vector3 wi, float eta, Vector3& wm, float& etap) {
    const float cos_o = wo.z, cos_i = wi.z;
    if (cos_o == 0 || cos_i == 0) return false;
    const bool reflect = cos_o * cos_i > 0;
    etap = reflect ? 1 : (cos_o > 0 ? eta : 1 / eta);
    wm = wi * etap + wo;
    if (dot(wm, wm) == 0) return false;
    wm = normalize(wm);
    if (wm.z < 0) wm = -wm;
    return !(dot(wm, wi) * cos_i < 0 || dot(wm, wo) * cos_o < 0);
}

}  // namespace glint
