#pragma once
// Indexed triangle meshes and their instances.
//
// A mesh is stored once, in its own (object) space; an Instance places it in the scene with a
// transform and may override its material. Many instances of one mesh share its vertex arrays
// and its bottom-level BVH (the two-level structure of Embree and pbrt: accel/scene_accel.h).
//
// Conventions: a triangle's geometric normal is (p1 - p0) x (p2 - p0), normalised, in object
// space, carried to world space by the inverse transpose (so a mirroring transform keeps the
// surface's front side). Per-vertex normals, when present, give the shading normal by
// barycentric interpolation; UVs likewise (without them, uv is the barycentric (b1, b2), as for
// the lone triangle shape). Tangents, when present, are glTF's: xyz the direction of +u and w = ±1
// the handedness of the bitangent (b = w n x t).
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "glint/interaction.h"
#include "glint/math/bounds.h"
#include "glint/math/color.h"
#include "glint/math/transform.h"
#include "glint/math/vector.h"

namespace glint {

struct TriangleMesh {
    std::vector<Point3> positions;
    std::vector<Normal3> normals;                  ///< empty, or one per position
    std::vector<Point2> uvs;                       ///< empty, or one per position
    std::vector<std::array<Float, 4>> tangents;    ///< empty, or one per position
    std::vector<Color> colors;                     ///< empty, or one per position (linear RGB)
    std::vector<std::uint32_t> indices;            ///< three per triangle
    std::vector<MaterialId> face_materials;        ///< empty (all `material`), or one per triangle
    MaterialId material = 0;
    std::string name;                              ///< for messages and `glint info`

    std::uint32_t triangle_count() const { return static_cast<std::uint32_t>(indices.size() / 3); }
    MaterialId material_of(std::uint32_t tri) const {
        return face_materials.empty() ? material : face_materials[tri];
    }
    std::array<Point3, 3> vertices(std::uint32_t tri) const {
        return {positions[indices[3 * tri]], positions[indices[3 * tri + 1]],
                positions[indices[3 * tri + 2]]};
    }
    Bounds3 bounds() const {
        Bounds3 b;
        for (const Point3& p : positions) b.extend(p);
        return b;
    }
    std::size_t memory_bytes() const {
        return positions.size() * sizeof(Point3) + normals.size() * sizeof(Normal3) +
               uvs.size() * sizeof(Point2) + tangents.size() * sizeof(tangents[0]) + colors.size() * sizeof(Color) +
               indices.size() * sizeof(std::uint32_t) + face_materials.size() * sizeof(MaterialId);
    }
};

/// Checks a mesh's arrays (index range, attribute counts) and drops the triangles that cannot be
/// hit: zero area, or a non-finite vertex. Returns how many were dropped; throws
/// std::invalid_argument naming what is wrong when the arrays disagree.
std::size_t validate_and_drop_degenerate(TriangleMesh& mesh);

/// Splits polygons (faces of any vertex count >= 3, given as counts and a flat index list)
/// into triangles by a fan from each face's first vertex; faces with fewer than three vertices
/// are skipped (counted in the return value).
std::size_t triangulate_fans(const std::vector<std::uint32_t>& counts,
                             const std::vector<std::uint32_t>& polygon_indices,
                             std::vector<std::uint32_t>& triangles_out,
                             std::vector<std::uint32_t>* face_of_triangle = nullptr);

struct Instance {
    std::uint32_t mesh = 0;
    Transform transform;
    std::optional<MaterialId> material;  ///< replaces every material of the mesh
};

}  // namespace glint
