#pragma once
// Two-phase intersection (pbrt, Tungsten, Mitsuba): traversal finds only the nearest t and which
// primitive (Hit); the full SurfaceInteraction is computed once, for the winner.
#include <cstdint>

#include "glint/math/vector.h"

namespace glint {

using MaterialId = std::uint32_t;

struct RayDifferential;  // ray.h

enum class ShapeKind : std::uint8_t { kSphere, kPlane, kQuad, kDisk, kTriangle, kMesh };

/// Whether a kind's test accepts a hit from a rounded hit point, so that the trees pad its box
/// (padded_for_rounding, math/bounds.h): spheres, quads and disks. Triangles' watertight test
/// accepts only rays through the exact triangle; planes are unbounded.
constexpr bool padded_for_rounding(ShapeKind k) {
    return k == ShapeKind::kSphere || k == ShapeKind::kQuad || k == ShapeKind::kDisk;
}

struct Hit {
    Float t;
    ShapeKind kind;
    std::uint32_t index;  ///< into the scene's array of that kind (kMesh: the instance)
    std::uint32_t prim = 0;  ///< kMesh: the triangle within the instance's mesh
    Float b1 = 0, b2 = 0;    ///< kMesh: barycentric weights of the triangle's 2nd and 3rd vertex
    /// kMesh, found by glint's own BVH: the triangle's object-space vertices in the packet the
    /// traversal tested (vertex i, axis a at [12 i + 4 a]: MeshHit::vertices), else null.
    const float* vertices = nullptr;
};

struct SurfaceInteraction {
    Point3 p;       ///< hit point
    Normal3 n;      ///< unit geometric normal as the shape defines it (outward for spheres)
    MaterialId material;
    ShapeKind shape;            ///< which shape was hit, so that Scene::uv can compute the
    std::uint32_t shape_index;  ///< texture coordinates only when a texture needs them
    Normal3 ns{0, 0, 0};        ///< unit shading normal (interpolated on meshes; n elsewhere)
    std::uint32_t prim = 0;     ///< kMesh: the triangle
    Point2 bary{};              ///< kMesh: (b1, b2)
    Float time = 0;             ///< the ray's time (moving shapes are placed at it)
    /// The path's offset rays, carried through specular bounces: textures read the pixel's
    /// footprint where they meet this surface; null: the camera's footprint model (camera.h).
    const RayDifferential* differential = nullptr;
};

}  // namespace glint
