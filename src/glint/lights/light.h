#pragma once
// Lights: a closed set in a std::variant. The article's integrator asks each delta light
// "from p, which way, how much arrives, how far may a shadow ray go" (sample_light below); the
// path tracer samples every kind, area lights included, through lights/light_sampler.h.
#include <cmath>
#include <limits>
#include <variant>

#include "glint/interaction.h"
#include "glint/math/color.h"
#include "glint/math/vector.h"

namespace glint {

struct LightSample {
    Vector3 to_light;  ///< unit direction from the shaded point towards the light (the article's -L)
    Color intensity;   ///< what arrives at the point, before the cosine
    Float distance;    ///< how far a shadow ray must stay unoccluded (infinity for directional)
};

/// The article's directional light: light travels along the unit vector `direction` (L) with
/// irradiance `intensity` (I) on a surface facing it. With an angular diameter it is a soft sun:
/// a disk of uniform radiance I / (pi sin^2(diameter / 2)) around -L, which gives the same
/// irradiance at normal incidence.
struct DirectionalLight {
    Vector3 direction;
    Color intensity;
    Float one_minus_cos = 0;  ///< 1 - cos(diameter / 2) = 2 sin^2(diameter / 4); 0: a delta
    bool soft() const { return one_minus_cos > 0; }
    Float sin2_half_angle() const { return one_minus_cos * (2 - one_minus_cos); }
    LightSample sample(Point3) const {
        return {-direction, intensity, std::numeric_limits<Float>::infinity()};
    }
};

/// A point light: intensity I (W/sr), falling off as 1/d^2.
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

/// A spot light: a point light restricted to a cone around `direction`, full intensity inside
/// cos_inner, none outside cos_outer, and a smoothstep between (pbrt-v4's falloff).
struct SpotLight {
    Point3 position;
    Vector3 direction;  ///< unit, where the cone points
    Color intensity;
    Float cos_inner, cos_outer;
    Float falloff(Vector3 from_light) const {
        const Float c = dot(from_light, direction);
        if (c >= cos_inner) return 1;
        if (c <= cos_outer) return 0;
        const Float t = (c - cos_outer) / (cos_inner - cos_outer);
        return t * t * (3 - 2 * t);
    }
    LightSample sample(Point3 p) const {
        const Vector3 d = position - p;
        const Float dist2 = dot(d, d);
        const Float dist = std::sqrt(dist2);
        const Vector3 w = d / dist;
        return {w, intensity * (falloff(-w) / dist2), dist};
    }
};

/// A shape whose material emits (Scene::emission): made by Scene::commit, one per emitting
/// sphere, quad, disk, triangle and mesh triangle. (Emitting planes are infinite: they are seen, not sampled.)
struct AreaLight {
    ShapeKind kind;
    std::uint32_t index;     ///< kMesh: the instance
    std::uint32_t prim = 0;  ///< kMesh: the triangle
    LightSample sample(Point3) const { return {{0, 1, 0}, Color{0}, 0}; }  // not for Whitted
};

using Light = std::variant<DirectionalLight, PointLight, SpotLight, AreaLight>;

/// For the article's integrator: area lights contribute nothing; a soft sun is its centre.
inline LightSample sample_light(const Light& light, Point3 p) {
    return std::visit([p](const auto& l) { return l.sample(p); }, light);
}

}  // namespace glint
