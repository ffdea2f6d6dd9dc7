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
#include <type_traits>
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
    std::vector<Float> alphas;                     ///< empty (opaque), or one per position
    /// Texture coordinate sets 1, 2, ... (glTF TEXCOORD_1 and up); each empty or one per position.
    std::vector<std::vector<Point2>> more_uvs;
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
    /// b0 a + b1 b + b2 c (b0 = 1 - b1 - b2), axis by axis, for points and normals: what
    /// interpolate computes for them, also for vertices that come from elsewhere (a BVH packet).
    template <typename T>
    static T mix_xyz(const T& a, const T& b, const T& c, Float b1, Float b2) {
        const Float b0 = 1 - b1 - b2;
        return T{b0 * a.x + b1 * b.x + b2 * c.x, b0 * a.y + b1 * b.y + b2 * c.y, b0 * a.z + b1 * b.z + b2 * c.z};
    }
    /// A per-vertex attribute (positions, normals, uvs, colours, tangents) of triangle `tri` at
    /// barycentric (b1, b2): b0 a0 + b1 a1 + b2 a2.
    template <typename T>
    T interpolate(const std::vector<T>& attribute, std::uint32_t tri, Float b1, Float b2) const {
        const T& a = attribute[indices[3 * tri]];
        const T& b = attribute[indices[3 * tri + 1]];
        const T& c = attribute[indices[3 * tri + 2]];
        const Float b0 = 1 - b1 - b2;
        const auto mix = [&](Float x, Float y, Float z) { return b0 * x + b1 * y + b2 * z; };
        if constexpr (std::is_same_v<T, Float>) {
            return mix(a, b, c);
        } else if constexpr (std::is_same_v<T, Point2>) {
            return {mix(a.x, b.x, c.x), mix(a.y, b.y, c.y)};
        } else if constexpr (std::is_same_v<T, Color>) {
            return {mix(a.r, b.r, c.r), mix(a.g, b.g, c.g), mix(a.b, b.b, c.b)};
        } else if constexpr (std::is_same_v<T, std::array<Float, 4>>) {
            return {mix(a[0], b[0], c[0]), mix(a[1], b[1], c[1]), mix(a[2], b[2], c[2]), mix(a[3], b[3], c[3])};
        } else {  // Point3, Normal3
            return mix_xyz(a, b, c, b1, b2);
        }
    }
    Bounds3 bounds() const {
        Bounds3 b;
        for (const Point3& p : positions) b.extend(p);
        return b;
    }
    std::size_t memory_bytes() const {
        return positions.size() * sizeof(Point3) + normals.size() * sizeof(Normal3) +
               uvs.size() * sizeof(Point2) + tangents.size() * sizeof(tangents[0]) + colors.size() * sizeof(Color) +
               indices.size() * sizeof(std::uint32_t) + face_materials.size() * sizeof(MaterialId) +
               alphas.size() * sizeof(Float) + more_uv_count() * sizeof(Point2);
    }
    std::size_t more_uv_count() const {
        std::size_t n = 0;
        for (const auto& set : more_uvs) n += set.size();
        return n;
    }
};

/// Checks a mesh's arrays (index range, attribute counts) and drops the triangles that cannot be
/// hit: zero area, or a non-finite vertex. Returns how many were dropped; throws
/// std::invalid_argument naming what is wrong when the arrays disagree.
std::size_t validate_and_drop_degenerate(TriangleMesh& mesh);

struct Instance {
    std::uint32_t mesh = 0;
    Transform transform;
    std::optional<MaterialId> material;  ///< replaces every material of the mesh
    std::int32_t alpha = -1;             ///< a cut-out: an index into Scene::alpha_masks
    /// Placed over the shutter by Scene::motions[motion] (object-to-world keys; `transform` is
    /// then the first); -1: still.
    std::int32_t motion = -1;
};

}  // namespace glint
