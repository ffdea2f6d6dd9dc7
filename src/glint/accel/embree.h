#pragma once
// Embree 3 as a second acceleration backend (`--accel embree`, built with -DGLINT_EMBREE=ON).
// It mirrors glint's two levels: one Embree scene per mesh (triangle geometry, high-quality
// build), instanced into a top-level scene with each instance's transform; the lone triangles are
// one more triangle geometry, and spheres, quads and disks are user geometries whose callbacks
// call glint's own intersection routines. Hits come back as glint Hits (same kinds, indices and
// barycentrics), so everything after traversal is shared.
//
// Alpha cut-outs: the meshes some instance masks get Embree filter functions that ask
// Scene::alpha_keeps; the scene and the world ray reach them through an extended intersect
// context.
//
// Embree's triangle test is not watertight (glint's is); images agree within float noise.
#include <cstddef>
#include <optional>

#include "glint/interaction.h"
#include "glint/ray.h"

namespace glint {

struct Scene;

class EmbreeAccel {
public:
    /// Builds from a scene whose arrays are filled (called by Scene::commit). Throws
    /// std::runtime_error with Embree's message if Embree fails.
    explicit EmbreeAccel(const Scene& scene);
    ~EmbreeAccel();
    EmbreeAccel(const EmbreeAccel&) = delete;
    EmbreeAccel& operator=(const EmbreeAccel&) = delete;

    /// Lowers ray.t_max and sets best for a hit nearer than ray.t_max.
    void closest(const Scene& scene, Ray& ray, std::optional<Hit>& best) const;
    bool occluded(const Scene& scene, const Ray& ray) const;
    /// Bytes Embree allocated for this scene (its memory monitor's count).
    std::size_t memory_bytes() const;

private:
    struct Impl;
    Impl* impl_;
};

}  // namespace glint
