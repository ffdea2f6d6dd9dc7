#include "glint/shapes/subdivision.h"

#include <algorithm>
#include <cmath>
#include <numbers>
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

// Area-weighted vertex normals.
std::vector<Normal3> face_normals(const std::vector<Point3>& positions, const std::vector<std::uint32_t>& indices) {
    std::vector<Vector3> sum(positions.size(), Vector3{0, 0, 0});
    for (std::size_t t = 0; t + 2 < indices.size(); t += 3) {
        const Point3 a = positions[indices[t]], b = positions[indices[t + 1]], c = positions[indices[t + 2]];
        const Vector3 n = cross(b - a, c - a);  // length: twice the area
        for (int k = 0; k < 3; ++k) sum[indices[t + k]] += n;
    }
    std::vector<Normal3> normals(positions.size());
    for (std::size_t v = 0; v < positions.size(); ++v) {
        const Float l = length(sum[v]);
        normals[v] = l > 0 ? Normal3{sum[v].x / l, sum[v].y / l, sum[v].z / l} : Normal3{0, 0, 1};
    }
    return normals;
}

// The one-ring of every vertex in order around it: each face (v, b, c) links b to c, and the
// links chain from a neighbour no link reaches (on a boundary) or from any (inside). Empty when
// the links do not form one chain (a non-manifold vertex).
struct Ring {
    std::vector<std::uint32_t> vertices;
    bool boundary = false;
};

std::vector<Ring> one_rings(std::size_t nv, const std::vector<std::uint32_t>& indices) {
    std::vector<std::vector<std::pair<std::uint32_t, std::uint32_t>>> links(nv);
    for (std::size_t t = 0; t + 2 < indices.size(); t += 3)
        for (int k = 0; k < 3; ++k)
            links[indices[t + k]].push_back({indices[t + (k + 1) % 3], indices[t + (k + 2) % 3]});
    std::vector<Ring> rings(nv);
    for (std::size_t v = 0; v < nv; ++v) {
        const auto& l = links[v];
        // (A vertex in more than 1,024 faces is left as it is: chaining is quadratic in them.)
        if (l.empty() || l.size() > 1024) continue;
        // The start: a `from` that is no link's `to` (a boundary vertex), else the first link's.
        std::uint32_t start = l[0].first;
        int starts = 0;
        for (const auto& link : l) {
            const std::uint32_t from = link.first;
            const bool reached = std::any_of(l.begin(), l.end(), [from](const auto& x) { return x.second == from; });
            if (!reached) start = from, ++starts;
        }
        if (starts > 1) continue;
        Ring r;
        r.boundary = starts == 1;
        std::uint32_t at = start;
        r.vertices.push_back(at);
        for (std::size_t step = 0; step < l.size(); ++step) {
            const auto next = std::find_if(l.begin(), l.end(), [&](const auto& x) { return x.first == at; });
            if (next == l.end()) break;
            at = next->second;
            if (!r.boundary && at == start) break;
            r.vertices.push_back(at);
        }
        // A proper ring has one vertex per link (inside) or one more (on a boundary).
        if (r.vertices.size() == l.size() + (r.boundary ? 1 : 0)) rings[v] = std::move(r);
    }
    return rings;
}

// pbrt-v4's last step (LoopSubdivide): every vertex moved to its limit position, inside by the
// mask (1 - n gamma) v + gamma (sum of the ring), gamma = 1 / (n + 3 / (8 beta)), on a boundary
// by 3/5 v + 1/5 of its two boundary neighbours; the normal is the cross product of the limit
// surface's two tangents (Hoppe et al. 1994's masks: cos and sin of 2 pi j / n round an inside
// ring; the boundary's chord and its valence-dependent cross tangent), turned to the side of the
// faces' normal. Vertices whose ring is not a single fan stay, with their faces' normal.
void push_to_limit(std::vector<Point3>& positions, const std::vector<std::uint32_t>& indices,
                   std::vector<Normal3>& normals) {
    const std::vector<Ring> rings = one_rings(positions.size(), indices);
    std::vector<Point3> limit = positions;
    for (std::size_t v = 0; v < positions.size(); ++v) {
        const Ring& r = rings[v];
        const auto n = r.vertices.size();
        if (n < 2 || (!r.boundary && n < 3)) continue;
        const Vector3 p = as_vector(positions[v]);
        Vector3 q;
        if (r.boundary) {
            q = p * 0.6f + (as_vector(positions[r.vertices.front()]) + as_vector(positions[r.vertices.back()])) * 0.2f;
        } else {
            const double beta = n == 3 ? 3.0 / 16 : 3.0 / (8.0 * double(n));
            const double gamma = 1 / (double(n) + 3 / (8 * beta));
            Vector3 sum{0, 0, 0};
            for (const std::uint32_t u : r.vertices) sum += as_vector(positions[u]);
            q = p * float(1 - double(n) * gamma) + sum * float(gamma);
        }
        limit[v] = Point3{q.x, q.y, q.z};
    }
    for (std::size_t v = 0; v < positions.size(); ++v) {
        const Ring& r = rings[v];
        const auto n = r.vertices.size();
        if (n < 2 || (!r.boundary && n < 3)) continue;
        const auto ring = [&](std::size_t j) { return as_vector(limit[r.vertices[j]]); };
        const Vector3 p = as_vector(limit[v]);
        Vector3 s{0, 0, 0}, t{0, 0, 0};
        if (!r.boundary) {
            for (std::size_t j = 0; j < n; ++j) {
                const double a = 2 * std::numbers::pi * double(j) / double(n);
                s += ring(j) * float(std::cos(a));
                t += ring(j) * float(std::sin(a));
            }
        } else {
            s = ring(n - 1) - ring(0);
            if (n == 2) {
                t = ring(0) + ring(1) - p * 2;
            } else if (n == 3) {
                t = ring(1) - p;
            } else if (n == 4) {
                t = ring(0) * -1 + ring(1) * 2 + ring(2) * 2 + ring(3) * -1 + p * -2;
            } else {
                const double theta = std::numbers::pi / double(n - 1);
                t = (ring(0) + ring(n - 1)) * float(std::sin(theta));
                for (std::size_t k = 1; k + 1 < n; ++k)
                    t += ring(k) * float((2 * std::cos(theta) - 2) * std::sin(double(k) * theta));
                t = -t;
            }
        }
        Vector3 nn = cross(s, t);
        const Float l = length(nn);
        if (!(l > 0) || !std::isfinite(l)) continue;
        nn = nn / l;
        const Normal3 faces = normals[v];
        if (nn.x * faces.x + nn.y * faces.y + nn.z * faces.z < 0) nn = -nn;
        normals[v] = Normal3{nn.x, nn.y, nn.z};
    }
    positions = std::move(limit);
}

}  // namespace

SubdividedMesh loop_subdivide(std::vector<Point3> positions, std::vector<std::uint32_t> indices, int levels,
                              bool to_limit) {
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
    out.normals = face_normals(positions, indices);
    if (to_limit) push_to_limit(positions, indices, out.normals);
    out.positions = std::move(positions);
    out.indices = std::move(indices);
    return out;
}

}  // namespace glint
