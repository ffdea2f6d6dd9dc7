#pragma once
// Loop subdivision of triangle meshes (Charles Loop, 1987), as pbrt's `loopsubdiv` shape asks:
// each level splits every triangle into four; new edge points are 3/8 of the edge's ends plus
// 1/8 of the two opposite corners (the midpoint on a boundary); old vertices move to
// (1 - n beta) v + beta (sum of neighbours), beta = 3/16 for valence 3 and 3/(8n) otherwise, or on
// a boundary to 3/4 v + 1/8 of their two boundary neighbours. Then, as pbrt-v4 does, every
// vertex is pushed to its position on the limit surface and given the limit surface's normal
// (subdivision.cpp, push_to_limit); without `to_limit`, the control mesh of the last level with
// area-weighted vertex normals.
#include <cstdint>
#include <vector>

#include "glint/math/vector.h"

namespace glint {

struct SubdividedMesh {
    std::vector<Point3> positions;
    std::vector<Normal3> normals;
    std::vector<std::uint32_t> indices;
};

/// `indices`: three per triangle, each < positions.size() (checked by the caller).
SubdividedMesh loop_subdivide(std::vector<Point3> positions, std::vector<std::uint32_t> indices, int levels,
                              bool to_limit = true);

}  // namespace glint
