#pragma once
// Polygons of any corner count, convex or not, split into triangles (OBJ and PLY faces).
#include <cstdint>
#include <span>
#include <vector>

#include "glint/math/vector.h"

namespace glint {

/// Appends the triangles of one polygon (`corners` index `positions`) to `out`, with the
/// polygon's winding. A convex polygon becomes a fan from its first corner; a concave one is cut
/// by ear clipping in the plane of its Newell normal. A polygon that is not simple (its edges
/// cross) or has no area gets the fan for what ear clipping could not cut, so every polygon gives
/// exactly corners - 2 triangles and the call always ends. Concave polygons above
/// kMaxEarClipCorners corners are fanned (ear clipping is quadratic in the corners).
void triangulate_polygon(std::span<const std::uint32_t> corners, const std::vector<Point3>& positions,
                         std::vector<std::uint32_t>& out);
inline constexpr std::size_t kMaxEarClipCorners = 1 << 15;

/// triangulate_polygon for each face of a flat list (`counts[f]` corners each); faces with fewer
/// than three corners are skipped and counted in the return value. `face_of` receives, per
/// triangle, the face it came from. Throws std::invalid_argument if the counts overrun the list,
/// or a corner indexes past `positions`.
std::size_t triangulate_faces(const std::vector<std::uint32_t>& counts, const std::vector<std::uint32_t>& corners,
                              const std::vector<Point3>& positions, std::vector<std::uint32_t>& out,
                              std::vector<std::uint32_t>* face_of = nullptr);

}  // namespace glint
