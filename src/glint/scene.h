#pragma once
// The render-time scene: flat arrays indexed by ids, no names, no maps, no owning pointers.
// Shapes live in one array per kind so the intersection loops are typed (no per-primitive
// dispatch). There is no acceleration structure yet: the article's scenes have a handful of
// primitives, and a linear loop over them is what the BVH issue will replace.
#include <optional>
#include <vector>

#include "glint/background.h"
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

    /// Nearest hit in [kRayTMin, ray.t_max).
    std::optional<Hit> intersect(const Ray& ray) const;
    /// Whether anything lies in [kRayTMin, ray.t_max); stops at the first blocker.
    bool occluded(const Ray& ray) const;
    /// Phase two: the full interaction for the winning hit.
    SurfaceInteraction interaction(const Ray& ray, const Hit& hit) const;
};

}  // namespace glint
