#pragma once
#include <cmath>
#include <cstring>
#include <optional>

#include "glint/interaction.h"
#include "glint/ray.h"
#include "glint/samplers/warp.h"
#include "glint/shapes/area_sample.h"

namespace glint {

/// What the watertight test derives from the ray alone (the axis permutation and the shear),
/// computed once per ray rather than once per triangle.
struct WatertightRay {
    Point3 origin;
    int kx, ky, kz;
    Float sx, sy, sz;
    Float t_max;
    WatertightRay() = default;  ///< unusable until assigned (for scenes with no lone triangles)
    explicit WatertightRay(const Ray& ray);
};

/// WatertightRay's axes for a direction of magnitudes (ax, ay, az) whose components below zero
/// are the bits of `negative` (x in bit 0): the largest becomes z (the first of equals); x and y
/// follow cyclically and swap when that component is negative, to keep the triangle's winding.
/// Selects, not branches: a diffuse bounce's direction is random, and branches here mispredicted
/// their way to 6 % of a Cornell box render.
/// The first axis of largest |d| (the rule's z), from |d|'s components.
inline int watertight_kz(Float ax, Float ay, Float az) {
    const int y_wins = ay > ax, z_wins = az > (ay > ax ? ay : ax);
    return y_wins + z_wins * (2 - y_wins);
}
inline void watertight_axes(Float ax, Float ay, Float az, int negative, int& kx, int& ky, int& kz) {
    kz = watertight_kz(ax, ay, az);
    const int next = kz == 2 ? 0 : kz + 1, after = 3 - kz - next;
    const int swap = (next ^ after) & -((negative >> kz) & 1);  // next ^ after, or 0
    kx = next ^ swap;
    ky = after ^ swap;
}

/// A hit on a triangle: the distance and the barycentric weights of p1 and p2.
struct TriangleHit {
    Float t, b1, b2;
};

/// Watertight ray-triangle intersection (Woop, Benthin and Wald, JCGT 2013): the triangle is
/// moved into a frame where the ray runs along +z from the origin, and the hit is decided by the
/// signs of three 2D edge functions, recomputed in double when one is exactly zero. Rays through
/// a shared edge or vertex hit at least one of the triangles that share it. Hits count in
/// [kRayTMin, ray.t_max).
std::optional<TriangleHit> intersect_triangle(Point3 p0, Point3 p1, Point3 p2, const WatertightRay& ray);

static_assert(sizeof(Point3) == 3 * sizeof(Float), "intersect_triangle reads a point as three floats");

/// A triangle p0 p1 p2, facing along (p1 - p0) x (p2 - p0).
struct Triangle {
    Point3 p0, p1, p2;
    MaterialId material = 0;

    /// intersect_triangle's distance.
    std::optional<Float> intersect(const WatertightRay& ray) const {
        const auto h = intersect_triangle(p0, p1, p2, ray);
        return h ? std::optional<Float>(h->t) : std::nullopt;
    }
    std::optional<Float> intersect(const Ray& ray) const { return intersect(WatertightRay(ray)); }

    /// The barycentric coordinates (b1, b2) of p: p = p0 + b1 (p1 - p0) + b2 (p2 - p0). (Meshes
    /// with per-vertex UVs come with the mesh importers.)
    Point2 uv_at(Point3 p) const {
        const Vector3 e1 = p1 - p0, e2 = p2 - p0, w = p - p0;
        const Float d11 = dot(e1, e1), d12 = dot(e1, e2), d22 = dot(e2, e2);
        const Float w1 = dot(w, e1), w2 = dot(w, e2);
        const Float inv = 1 / (d11 * d22 - d12 * d12);
        return {(d22 * w1 - d12 * w2) * inv, (d11 * w2 - d12 * w1) * inv};
    }

    Normal3 normal() const { return Normal3(normalize(cross(p1 - p0, p2 - p0))); }
    Float area() const { return Float(0.5) * length(cross(p1 - p0, p2 - p0)); }
    AreaSample sample_area(Sample2 u) const {
        const Point2 b = sample_uniform_triangle(u);
        const Vector3 e1 = p1 - p0, e2 = p2 - p0;
        // p = b0 p0 + b1 p1 + b2 p2 = p0 + b1 e1 + b2 e2
        return {p0 + e1 * b.y + e2 * (1 - b.x - b.y), normal()};
    }
};

namespace triangle_detail {

/// The watertight test's end, shared by its scalar and SSE forms: from edge functions u, v, w
/// that do not differ in sign and the vertices' sheared z (az = sz a.z, ...), the determinant,
/// the range test on t det (so that only hits pay for the division) and the hit.
inline std::optional<TriangleHit> hit_from_edges(Float u, Float v, Float w, Float az, Float bz, Float cz, Float t_max) {
    const Float det = u + v + w;
    if (det == 0) return std::nullopt;
    const Float t_scaled = u * az + v * bz + w * cz;  // t * det
    if (det > 0 ? !(t_scaled >= kRayTMin * det && t_scaled < t_max * det)
                : !(t_scaled <= kRayTMin * det && t_scaled > t_max * det))
        return std::nullopt;
    const Float t = t_scaled / det;
    if (!(t >= kRayTMin && t < t_max)) return std::nullopt;  // rounding at the ends
    const Float inv_det = 1 / det;
    return TriangleHit{t, v * inv_det, w * inv_det};
}

/// The watertight test on the vertices relative to the ray's origin, permuted so that the ray's
/// main axis is z (intersect_triangle's body).
inline std::optional<TriangleHit> intersect_permuted(Vector3 a, Vector3 b, Vector3 c, const WatertightRay& r) {
    const Float sx = r.sx, sy = r.sy, sz = r.sz;
    const Float ax = a.x - sx * a.z, ay = a.y - sy * a.z;
    const Float bx = b.x - sx * b.z, by = b.y - sy * b.z;
    const Float cx = c.x - sx * c.z, cy = c.y - sy * c.z;

    Float u = cx * by - cy * bx;
    Float v = ax * cy - ay * cx;
    Float w = bx * ay - by * ax;
    if (u == 0 || v == 0 || w == 0) {  // on an edge in float: decide in double
        u = static_cast<Float>(static_cast<double>(cx) * by - static_cast<double>(cy) * bx);
        v = static_cast<Float>(static_cast<double>(ax) * cy - static_cast<double>(ay) * cx);
        w = static_cast<Float>(static_cast<double>(bx) * ay - static_cast<double>(by) * ax);
    }
    if ((u < 0 || v < 0 || w < 0) && (u > 0 || v > 0 || w > 0)) return std::nullopt;
    return hit_from_edges(u, v, w, sz * a.z, sz * b.z, sz * c.z, r.t_max);
}

}  // namespace triangle_detail

inline std::optional<TriangleHit> intersect_triangle(Point3 p0, Point3 p1, Point3 p2,
                                                     const WatertightRay& r) {
    const auto permuted = [&r](Point3 p) {
        const Float v[3] = {p.x - r.origin.x, p.y - r.origin.y, p.z - r.origin.z};
        return Vector3{v[r.kx], v[r.ky], v[r.kz]};
    };
    return triangle_detail::intersect_permuted(permuted(p0), permuted(p1), permuted(p2), r);
}

/// The same test (the same operations, so the same bits) reading each vertex's coordinates by
/// index where the triangle is stored: no copy of the vertices to permute them.
inline std::optional<TriangleHit> intersect_triangle(const Triangle& t, const WatertightRay& r) {
    Float o[3];
    std::memcpy(o, &r.origin, sizeof o);
    const auto permuted = [&](const Point3& p) {
        Float v[3];
        std::memcpy(v, &p, sizeof v);
        return Vector3{v[r.kx] - o[r.kx], v[r.ky] - o[r.ky], v[r.kz] - o[r.kz]};
    };
    return triangle_detail::intersect_permuted(permuted(t.p0), permuted(t.p1), permuted(t.p2), r);
}

}  // namespace glint
