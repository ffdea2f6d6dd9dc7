#pragma once
// Two-phase intersection (pbrt, Tungsten, Mitsuba): traversal finds only the nearest t and which
// primitive (Hit); the full SurfaceInteraction is computed once, for the winner.
#include <cstdint>

#include "glint/math/vector.h"

namespace glint {

using MaterialId = std::uint32_t;

enum class ShapeKind : std::uint8_t { kSphere, kPlane, kQuad, kDisk, kTriangle };

struct Hit {
    Float t;
    ShapeKind kind;
    std::uint32_t index;  ///< into the scene's array of that kind
};

struct SurfaceInteraction {
    Point3 p;       ///< hit point
    Normal3 n;      ///< unit geometric normal as the shape defines it (outward for spheres)
    MaterialId material;
    Point2 uv;      ///< texture coordinates, by each shape's convention (shapes/*.h, uv_at)
};

}  // namespace glint
