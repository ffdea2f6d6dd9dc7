#include "glint/shapes/subdivision.h"

#include <algorithm>
#include <unordered_map>

namespace glint {

namespace {

struct EdgeInfo {
    std::uint32_t new_vertex = 0;
    std::uint32_t opposite[2] = {0, 0};
    int faces = 0;
};

std::uint64_t edge_key(std::uint32_t a, std::uint32_t b) {
    return (std::uint64_t(std::min(a, b)) << 32) | std::max(a, b);
}

Vector3 as_vector(Point3 p) { return {p.x, p.y, p.z}; }

}  // namespace

SubdividedMesh loop_subdivide(std::vector<Point3> positions, std::vector<std::uint32_t> indices, int levels) {
    for (int level = 0; level < levels; ++level) {
        const std::size_t nv = positions.size(), nt = indices.size() / 3;
        std::unordered_map<std::uint64_t, EdgeInfo> edges;
        edges.reserve(nt * 3);
        for (std::size_t t = 0; t < nt; ++t)
            for (int e = 0; e < 3; ++e) {
                const std::uint32_t a = indices[3 * t + e], b = indices[3 * t + (e + 1) % 3], c = indices[3 * t + (e + 2) % 3];
                EdgeInfo& info = edges[edge_key(a, b)];
                if (info.faces < 2) info.opposite[info.faces] = c;
                ++info.faces;
            }
        // Neighbours of every vertex, and which of them lie across boundary edges.
        std::vector<Vector3> neighbour_sum(nv, Vector3{0, 0, 0}), boundary_sum(nv, Vector3{0, 0, 0});
        std::vector<int> valence(nv, 0), boundary_count(nv, 0);
        for (const auto& [key, info] : edges) {
            const auto a = std::uint32_t(key >> 32), b = std::uint32_t(key & 0xffffffffu);
            neighbour_sum[a] += as_vector(positions[b]);
            neighbour_sum[b] += as_vector(positions[a]);
            ++valence[a], ++valence[b];
            if (info.faces != 2) {
                boundary_sum[a] += as_vector(positions[b]);
                boundary_sum[b] += as_vector(positions[a]);
                ++boundary_count[a], ++boundary_count[b];
            }
        }
        std::vector<Point3> next(nv);
        for (std::size_t v = 0; v < nv; ++v) {
            const Vector3 p = as_vector(positions[v]);
            Vector3 q = p;
            if (boundary_count[v] == 2) {
                q = p * 0.75f + boundary_sum[v] * 0.125f;
            } else if (boundary_count[v] == 0 && valence[v] >= 3) {
                const int n = valence[v];
                const float beta = n == 3 ? 3.0f / 16 : 3.0f / (8.0f * float(n));
                q = p * (1 - float(n) * beta) + neighbour_sum[v] * beta;
            }  // corners and non-manifold vertices stay
            next[v] = Point3{q.x, q.y, q.z};
        }
        for (auto& [key, info] : edges) {
            const auto a = std::uint32_t(key >> 32), b = std::uint32_t(key & 0xffffffffu);
            const Vector3 pa = as_vector(positions[a]), pb = as_vector(positions[b]);
            Vector3 q = (pa + pb) * 0.5f;
            if (info.faces == 2)
                q = (pa + pb) * 0.375f + (as_vector(positions[info.opposite[0]]) + as_vector(positions[info.opposite[1]])) * 0.125f;
            info.new_vertex = static_cast<std::uint32_t>(next.size());
            next.push_back(Point3{q.x, q.y, q.z});
        }
        std::vector<std::uint32_t> split;
        split.reserve(indices.size() * 4);
        for (std::size_t t = 0; t < nt; ++t) {
            const std::uint32_t a = indices[3 * t], b = indices[3 * t + 1], c = indices[3 * t + 2];
            const std::uint32_t ab = edges[edge_key(a, b)].new_vertex, bc = edges[edge_key(b, c)].new_vertex,
                                ca = edges[edge_key(c, a)].new_vertex;
            split.insert(split.end(), {a, ab, ca, ab, b, bc, ca, bc, c, ab, bc, ca});
        }
        positions = std::move(next);
        indices = std::move(split);
    }
    SubdividedMesh out;
    out.normals.assign(positions.size(), Normal3{0, 0, 0});
    std::vector<Vector3> sum(positions.size(), Vector3{0, 0, 0});
    for (std::size_t t = 0; t + 2 < indices.size(); t += 3) {
        const Point3 a = positions[indices[t]], b = positions[indices[t + 1]], c = positions[indices[t + 2]];
        const Vector3 n = cross(b - a, c - a);  // length: twice the area
        for (int k = 0; k < 3; ++k) sum[indices[t + k]] += n;
    }
    for (std::size_t v = 0; v < positions.size(); ++v) {
        const Float l = length(sum[v]);
        out.normals[v] = l > 0 ? Normal3{sum[v].x / l, sum[v].y / l, sum[v].z / l} : Normal3{0, 0, 1};
    }
    out.positions = std::move(positions);
    out.indices = std::move(indices);
    return out;
}

}  // namespace glint
