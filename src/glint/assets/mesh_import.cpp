#include "glint/assets/mesh_import.h"

#include "glint/base/diagnostics.h"
#include "glint/base/limits.h"

#include <climits>
#include <cctype>
#include <fstream>
#include <string_view>

#include <fmt/format.h>

namespace glint {

std::optional<MeshFormat> mesh_format(const std::filesystem::path& path) {
    std::string ext = path.extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (ext == ".ply") return MeshFormat::kPly;
    if (ext == ".gz") {  // a gzip-compressed PLY (pbrt-v4's scenes ship them)
        std::string inner = path.stem().extension().string();
        for (char& c : inner) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
        if (inner == ".ply") return MeshFormat::kPly;
    }
    if (ext == ".obj") return MeshFormat::kObj;
    if (ext == ".gltf") return MeshFormat::kGltf;
    if (ext == ".glb") return MeshFormat::kGlb;
    // No mesh extension: a binary glTF or a PLY is known by its first bytes (a file the read
    // gate refuses is not opened here; reading it says why).
    if (!why_not_readable(path).empty()) return std::nullopt;
    std::ifstream in(path, std::ios::binary);
    char head[5] = {};
    if (!in.read(head, 5)) return std::nullopt;
    const std::string_view h(head, 5);
    if (h.substr(0, 4) == "glTF") return MeshFormat::kGlb;
    if (h.substr(0, 4) == "ply\n" || h == "ply\r\n") return MeshFormat::kPly;
    return std::nullopt;
}

std::string mesh_size_error(long long vertices, long long triangles) {
    // A count past long long's range arrives negative: over the limit too.
    if (vertices < 0 || vertices > limit(Limit::kVertices)) return over_limit(Limit::kVertices, vertices < 0 ? LLONG_MAX : vertices);
    if (triangles < 0 || triangles > limit(Limit::kTriangles))
        return over_limit(Limit::kTriangles, triangles < 0 ? LLONG_MAX : triangles);
    // 44 bytes a vertex (position, normal, uv, colour), 80 a triangle (indices, material, the
    // BVH's share, the intersection kernels' copy).
    return charge_memory(44 * vertices + 80 * triangles, fmt::format("a mesh of {} vertices and {} triangles", vertices, triangles));
}

ImportedFile import_mesh_file(const std::filesystem::path& path, double time, const std::vector<double>& motion_times) {
    const auto format = mesh_format(path);
    if (!format)
        throw IoError(fmt::format("{}: unknown mesh format '{}' (known: .obj, .ply, .ply.gz, .gltf, .glb)", path.string(),
                                  path.extension().string()));
    switch (*format) {
        case MeshFormat::kPly: return import_ply(path);
        case MeshFormat::kObj: return import_obj(path);
        case MeshFormat::kGltf:
        case MeshFormat::kGlb: return import_gltf(path, "", time, motion_times);
    }
    return {};  // unreachable: every format is covered
}

}  // namespace glint
