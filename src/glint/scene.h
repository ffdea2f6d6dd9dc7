#pragma once
// The render-time scene: flat arrays indexed by ids, no names, no maps, no owning pointers.
// Shapes live in one array per kind so the intersection loops are typed (no per-primitive
// dispatch). There is no acceleration structure yet: the article's scenes have a handful of
// primitives, tested in loops behind one bounding box around all the bounded shapes (rays towards
// the sky skip them all; planes are unbounded and tested first); the BVH issue replaces this.
//
// After filling or changing the arrays, call commit() before tracing (as with Embree's
// rtcCommitScene): it computes what the intersection loops derive from them.
#include <optional>
#include <vector>

#include "glint/background.h"
#include "glint/math/bounds.h"
#include "glint/interaction.h"
#include "glint/lights/light.h"
#include "glint/lights/light_sampler.h"
#include "glint/materials/material.h"
#include "glint/shapes/disk.h"
#include "glint/shapes/plane.h"
#include "glint/shapes/quad.h"
#include "glint/shapes/sphere.h"
#include "glint/shapes/triangle.h"
#include "glint/textures/texture.h"

namespace glint {

struct Scene {
    std::vector<Sphere> spheres;
    std::vector<Plane> planes;
    std::vector<Quad> quads;
    std::vector<Disk> disks;
    std::vector<Triangle> triangles;
    std::vector<Material> materials;
    std::vector<Emission> emission;  ///< per material; missing entries emit nothing
    std::vector<Texture> textures;
    std::vector<Image> images;
    std::vector<Light> lights;
    Background background = SkyBackground{};

    /// Computes the derived data (the bounds of the bounded shapes, which textures read uv) from
    /// the arrays.
    void commit();

    /// Nearest hit in [kRayTMin, ray.t_max).
    std::optional<Hit> intersect(const Ray& ray) const;
    /// Whether anything lies in [kRayTMin, ray.t_max); stops at the first blocker.
    bool occluded(const Ray& ray) const;
    /// The colour of texture `id` at a surface point. The uv is computed only for textures
    /// that read it (an atan2 and an acos per sphere hit otherwise wasted).
    Color texture(TextureId id, const SurfaceInteraction& si) const {
        // The article's textures inline; the rest go through the general (recursive) evaluate.
        const Texture& t = textures[id];
        if (const auto* c = std::get_if<ConstantTexture>(&t)) return c->value;
        if (const auto* k = std::get_if<CheckerTexture>(&t)) return k->eval(si.p);
        return evaluate(textures, images, id, {si.p, texture_needs_uv_[id] ? uv(si) : Point2{}});
    }
    const Emission& emission_of(MaterialId m) const {
        static const Emission kNone;
        return m < emission.size() ? emission[m] : kNone;
    }
    /// Radiance the surface at si emits towards wo (unit, pointing away from the surface).
    Color emitted(const SurfaceInteraction& si, Vector3 wo) const {
        const Emission& e = emission_of(si.material);
        if (!e.emits()) return Color{0};
        return e.two_sided || dot(si.n, wo) > 0 ? e.radiance : Color{0};
    }
    /// Every light, for the path tracer; built by commit().
    const LightSampler& light_sampler() const { return light_sampler_; }

    /// Texture coordinates of a surface point, by the hit shape's convention (shapes/*.h).
    Point2 uv(const SurfaceInteraction& si) const;

    /// Phase two: the full interaction for the winning hit.
    SurfaceInteraction interaction(const Ray& ray, const Hit& hit) const;

private:
    std::size_t bounded_count() const {
        return spheres.size() + quads.size() + disks.size() + triangles.size();
    }
    Bounds3 bounds_;  ///< around every sphere, quad, disk and triangle
    bool any_bounded_ = false;  ///< set by commit(): any sphere, quad, disk or triangle
    bool any_flat_ = false;     ///< set by commit(): any quad, disk or triangle
    std::vector<char> texture_needs_uv_;  ///< per texture, set by commit()
    std::size_t committed_count_ = 0;
    LightSampler light_sampler_;
};

}  // namespace glint
