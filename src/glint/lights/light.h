#pragma once
// Lights for the Whitted integrator: a closed set in a std::variant. Each alternative answers
// "from surface point p, which way is the light, how much arrives, and how far may a shadow ray
// go" (LightSample).
#include <limits>
#include <variant>

#include "glint/math/color.h"
#include "glint/math/vector.h"

namespace glint {

struct LightSample {
    Vector3 to_light;  ///< unit direction from the shaded point towards the light (the article's -L)
    Color intensity;   ///< what arrives at the point, before the cosine
    Float distance;    ///< how far a shadow ray must stay unoccluded (infinity for directional)
};

/// The article's directional light: light travels along the unit vector `direction` (L) with
/// intensity I everywhere.
struct DirectionalLight {
    Vector3 direction;
    Color intensity;
    LightSample sample(Point3) const {
        return {-direction, intensity, std::numeric_limits<Float>::infinity()};
    }
};

/// A point light: intensity I at distance 1, falling off as 1/d^2.
struct PointLight {
    Point3 position;
    Color intensity;
    LightSample sample(Point3 p) const {
        const Vector3 d = position - p;
        const Float dist2 = dot(d, d);
        const Float dist = std::sqrt(dist2);
        return {d / dist, intensity / dist2, dist};
    }
};

using Light = std::variant<DirectionalLight, PointLight>;

inline LightSample sample_light(const Light& light, Point3 p) {
    return std::visit([p](const auto& l) { return l.sample(p); }, light);
}

}  // namespace glint
