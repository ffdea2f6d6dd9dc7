#include "glint/shapes/polygon.h"

#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

namespace glint {

namespace {

struct P2 {
    double x, y;
};

// Twice the signed area of (a, b, c): > 0 when they turn counter-clockwise.
double turn(P2 a, P2 b, P2 c) { return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x); }

void fan(std::span<const std::uint32_t> c, std::vector<std::uint32_t>& out) {
    for (std::size_t k = 1; k + 1 < c.size(); ++k) out.insert(out.end(), {c[0], c[k], c[k + 1]});
}

}  // namespace

void triangulate_polygon(std::span<const std::uint32_t> corners, const std::vector<Point3>& positions,
                         std::vector<std::uint32_t>& out) {
    const std::size_t n = corners.size();
    if (n < 3) return;
    if (n == 3) return fan(corners, out);
    // The plane: Newell's normal (exact for planar polygons, the best fit for others), in double
    // so that coordinates near float max do not overflow.
    double nx = 0, ny = 0, nz = 0;
    for (std::size_t i = 0; i < n; ++i) {
        const Point3 a = positions[corners[i]], b = positions[corners[(i + 1) % n]];
        nx += (double(a.y) - b.y) * (double(a.z) + b.z);
        ny += (double(a.z) - b.z) * (double(a.x) + b.x);
        nz += (double(a.x) - b.x) * (double(a.y) + b.y);
    }
    if (!std::isfinite(nx + ny + nz) || (nx == 0 && ny == 0 && nz == 0)) return fan(corners, out);
    // Project along the normal's largest axis, mirrored so that the polygon turns counter-clockwise.
    const int drop = std::abs(nx) >= std::abs(ny) && std::abs(nx) >= std::abs(nz) ? 0 : std::abs(ny) >= std::abs(nz) ? 1 : 2;
    const double sign = (drop == 0 ? nx : drop == 1 ? ny : nz) > 0 ? 1.0 : -1.0;
    std::vector<P2> p(n);
    for (std::size_t i = 0; i < n; ++i) {
        const Point3 q = positions[corners[i]];
        const double u = drop == 0 ? q.y : drop == 1 ? q.z : q.x, v = drop == 0 ? q.z : drop == 1 ? q.x : q.y;
        p[i] = {u, v * sign};
    }
    bool convex = true;
    for (std::size_t i = 0; i < n && convex; ++i) convex = turn(p[(i + n - 1) % n], p[i], p[(i + 1) % n]) >= 0;
    if (convex || n > kMaxEarClipCorners) return fan(corners, out);

    // Ear clipping on a ring of the corners left; an ear is a convex corner whose triangle holds
    // no reflex corner (only reflex corners can be inside it).
    std::vector<std::size_t> prev(n), next(n);
    for (std::size_t i = 0; i < n; ++i) prev[i] = (i + n - 1) % n, next[i] = (i + 1) % n;
    const auto reflex = [&](std::size_t i) { return turn(p[prev[i]], p[i], p[next[i]]) <= 0; };
    const auto is_ear = [&](std::size_t i) {
        const std::size_t a = prev[i], c = next[i];
        if (turn(p[a], p[i], p[c]) <= 0) return false;
        for (std::size_t j = next[c]; j != a; j = next[j]) {
            if (!reflex(j)) continue;
            const P2 q = p[j];
            if ((q.x == p[a].x && q.y == p[a].y) || (q.x == p[i].x && q.y == p[i].y) || (q.x == p[c].x && q.y == p[c].y))
                continue;  // a repeated point, as where a polygon touches itself
            if (turn(p[a], p[i], q) >= 0 && turn(p[i], p[c], q) >= 0 && turn(p[c], p[a], q) >= 0) return false;
        }
        return true;
    };
    std::size_t left = n, i = 0, misses = 0;
    while (left > 3) {
        if (is_ear(i)) {
            out.insert(out.end(), {corners[prev[i]], corners[i], corners[next[i]]});
            next[prev[i]] = next[i];
            prev[next[i]] = prev[i];
            i = prev[i];
            --left;
            misses = 0;
        } else if (++misses > left) {
            break;  // no ear anywhere: not a simple polygon; fan the rest
        } else {
            i = next[i];
        }
    }
    // The last three corners (or the rest, fanned from the current corner).
    std::vector<std::uint32_t> rest;
    rest.reserve(left);
    std::size_t j = i;
    for (std::size_t k = 0; k < left; ++k, j = next[j]) rest.push_back(corners[j]);
    fan(rest, out);
}

std::size_t triangulate_faces(const std::vector<std::uint32_t>& counts, const std::vector<std::uint32_t>& corners,
                              const std::vector<Point3>& positions, std::vector<std::uint32_t>& out,
                              std::vector<std::uint32_t>* face_of) {
    std::size_t skipped = 0, at = 0;
    for (std::uint32_t f = 0; f < counts.size(); ++f) {
        const std::uint32_t c = counts[f];
        if (c > corners.size() - at)
            throw std::invalid_argument(
                fmt::format("face {} has {} vertices, but only {} indices remain", f, c, corners.size() - at));
        const std::span<const std::uint32_t> face(corners.data() + at, c);
        at += c;
        if (c < 3) {
            ++skipped;
            continue;
        }
        for (const std::uint32_t v : face)
            if (v >= positions.size())
                throw std::invalid_argument(fmt::format("face {} uses vertex {}; there are {}", f, v, positions.size()));
        const std::size_t before = out.size();
        triangulate_polygon(face, positions, out);
        if (face_of) face_of->insert(face_of->end(), (out.size() - before) / 3, f);
    }
    return skipped;
}

}  // namespace glint
