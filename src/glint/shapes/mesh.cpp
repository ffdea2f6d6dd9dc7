#include "glint/shapes/mesh.h"

#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

namespace glint {

namespace {

bool finite(Point3 p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); }

}  // namespace

std::size_t validate_and_drop_degenerate(TriangleMesh& mesh) {
    const std::size_t nv = mesh.positions.size();
    if (mesh.indices.size() % 3 != 0)
        throw std::invalid_argument(fmt::format("{} indices is not a whole number of triangles", mesh.indices.size()));
    const auto check_count = [nv](std::size_t n, const char* what) {
        if (n != 0 && n != nv)
            throw std::invalid_argument(fmt::format("{} {} for {} positions", n, what, nv));
    };
    check_count(mesh.normals.size(), "normals");
    check_count(mesh.uvs.size(), "texture coordinates");
    check_count(mesh.tangents.size(), "tangents");
    check_count(mesh.colors.size(), "colours");
    check_count(mesh.alphas.size(), "alphas");
    for (const auto& set : mesh.more_uvs) check_count(set.size(), "texture coordinates");
    if (!mesh.face_materials.empty() && mesh.face_materials.size() != mesh.indices.size() / 3)
        throw std::invalid_argument(fmt::format("{} face materials for {} triangles",
                                                mesh.face_materials.size(), mesh.indices.size() / 3));
    for (std::size_t i = 0; i < mesh.indices.size(); ++i)
        if (mesh.indices[i] >= nv)
            throw std::invalid_argument(fmt::format("triangle {} uses vertex {}, but there are {} vertices",
                                                    i / 3, mesh.indices[i], nv));
    std::size_t kept = 0;
    const std::uint32_t n = mesh.triangle_count();
    for (std::uint32_t t = 0; t < n; ++t) {
        const auto [p0, p1, p2] = mesh.vertices(t);
        const Vector3 c = cross(p1 - p0, p2 - p0);
        if (!finite(p0) || !finite(p1) || !finite(p2) || !(dot(c, c) > 0)) continue;
        for (int k = 0; k < 3; ++k) mesh.indices[3 * kept + k] = mesh.indices[3 * t + k];
        if (!mesh.face_materials.empty()) mesh.face_materials[kept] = mesh.face_materials[t];
        ++kept;
    }
    mesh.indices.resize(3 * kept);
    if (!mesh.face_materials.empty()) mesh.face_materials.resize(kept);
    return n - kept;
}

}  // namespace glint
