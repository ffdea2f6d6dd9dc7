#pragma once
// The render-time scene: flat arrays indexed by ids, no names, no maps, no owning pointers.
// Shapes live in one array per kind so the intersection loops are typed (no per-primitive
// dispatch). There is no acceleration structure yet: the article's scenes have a handful of
// primitives, tested in a loop behind one bounding box around all the spheres (rays towards the
// sky skip them all); the BVH issue replaces this.
//
// After filling or changing the arrays, call commit() before tracing (as with Embree's
// rtcCommitScene): it computes what the intersection loops derive from them.
#include <optional>
#include <vector>

#include "glint/background.h"
#include "glint/math/bounds.h"
#include "glint/interaction.h"
#include "glint/lights/light.h"
#include "glint/materials/material.h"
#include "glint/shapes/plane.h"
#include "glint/shapes/sphere.h"
#include "glint/textures/texture.h"

namespace glint {

struct Scene {
    std::vector<Sphere> spheres;
    std::vector<Plane> planes;
    std::vector<Material> materials;
    std::vector<Texture> textures;
    std::vector<Light> lights;
    Background background = SkyBackground{};

    /// Computes the derived data (the spheres' bounds) from the arrays.
    void commit();

    /// Nearest hit in [kRayTMin, ray.t_max).
    std::optional<Hit> intersect(const Ray& ray) const;
    /// Whether anything lies in [kRayTMin, ray.t_max); stops at the first blocker.
    bool occluded(const Ray& ray) const;
    /// Phase two: the full interaction for the winning hit.
    SurfaceInteraction interaction(const Ray& ray, const Hit& hit) const;

private:
    Bounds3 sphere_bounds_;
    std::size_t committed_spheres_ = 0;
};

}  // namespace glint
