#pragma once
// Ray differentials through perfectly specular bounces, for texture filtering (docs/textures.md).
#include <optional>

#include "glint/ray.h"
#include "glint/scene.h"

namespace glint {

/// The offset rays a path carries on after a perfectly specular reflection or refraction at si
/// into unit direction wi (eta: the relative index crossed, n_t / n_i; 1 for a reflection). The
/// path arrived along unit direction d with offset rays `in`, or, for null, is the camera's ray,
/// whose offset rays come from the camera's footprint model. The offset rays leave from where
/// they met si's tangent plane, turned about the shading normal there: si.ns plus the surface's
/// own change of normal (Scene::smooth_normal_at), so a curved mirror spreads them and a flat one
/// keeps the mirror image's footprint. Empty where an offset ray runs parallel to the plane, or
/// is totally reflected where the path's own ray refracts; textures further on then read the
/// camera's model, as they do after any bounce that is not specular (pbrt-v4's rule).
///
/// `from`: the origin of the path's next ray (spawn_ray pushes it off the surface); the offset rays
/// are pushed with it, so that the push does not show in the footprint further on.
std::optional<RayDifferential> scatter_differential(const Scene& scene, const SurfaceInteraction& si, Vector3 d,
                                                    const RayDifferential* in, Vector3 wi, float eta, Point3 from);

}  // namespace glint
