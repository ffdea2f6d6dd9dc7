#include "glint/scene.h"

#include <cassert>

#include "glint/math/snap.h"

namespace glint {

namespace {

// The typed loops: one per shape kind, no per-primitive dispatch.
template <ShapeKind kKind, typename Shape>
void closest_hit(const std::vector<Shape>& shapes, Ray& ray, std::optional<Hit>& best) {
    for (std::uint32_t i = 0; i < shapes.size(); ++i) {
        if (auto t = shapes[i].intersect(ray)) {
            ray.t_max = *t;
            best = Hit{*t, kKind, i};
        }
    }
}

template <typename Shape>
bool any_hit(const std::vector<Shape>& shapes, const Ray& ray) {
    for (const Shape& s : shapes)
        if (s.intersect(ray)) return true;
    return false;
}

}  // namespace

void Scene::commit() {
    bounds_ = Bounds3{};
    for (const Sphere& s : spheres) {
        const Vector3 r{s.radius, s.radius, s.radius};
        bounds_.extend(s.center - r);
        bounds_.extend(s.center + r);
    }
    for (const Quad& q : quads) {
        bounds_.extend(q.corner);
        bounds_.extend(q.corner + q.edge1);
        bounds_.extend(q.corner + q.edge2);
        bounds_.extend(q.corner + q.edge1 + q.edge2);
    }
    for (const Disk& d : disks) {
        // The disk lies in the sphere of its radius.
        const Vector3 r{d.radius, d.radius, d.radius};
        bounds_.extend(d.center - r);
        bounds_.extend(d.center + r);
    }
    for (const Triangle& t : triangles) {
        bounds_.extend(t.p0);
        bounds_.extend(t.p1);
        bounds_.extend(t.p2);
    }
    committed_count_ = bounded_count();
}

std::optional<Hit> Scene::intersect(const Ray& ray_in) const {
    assert(committed_count_ == bounded_count() && "Scene::commit() not called");
    Ray ray = ray_in;
    std::optional<Hit> best;
    // Planes first: a plane hit shortens t_max, which the box test and the rest then use.
    closest_hit<ShapeKind::kPlane>(planes, ray, best);
    if (bounded_count() > 0 && bounds_.hit(ray, reciprocal(ray.direction))) {
        closest_hit<ShapeKind::kSphere>(spheres, ray, best);
        closest_hit<ShapeKind::kQuad>(quads, ray, best);
        closest_hit<ShapeKind::kDisk>(disks, ray, best);
        closest_hit<ShapeKind::kTriangle>(triangles, ray, best);
    }
    return best;
}

bool Scene::occluded(const Ray& ray) const {
    assert(committed_count_ == bounded_count() && "Scene::commit() not called");
    if (any_hit(planes, ray)) return true;
    if (bounded_count() == 0 || !bounds_.hit(ray, reciprocal(ray.direction))) return false;
    return any_hit(spheres, ray) || any_hit(quads, ray) || any_hit(disks, ray) ||
           any_hit(triangles, ray);
}

SurfaceInteraction Scene::interaction(const Ray& ray, const Hit& hit) const {
    const Point3 p = ray.at(hit.t);
    switch (hit.kind) {
        case ShapeKind::kSphere: {
            const Sphere& s = spheres[hit.index];
            return {p, s.normal_at(p), s.material, s.uv_at(p)};
        }
        case ShapeKind::kPlane: {
            const Plane& pl = planes[hit.index];
            const Point3 q = pl.project(p);
            return {q, pl.normal, pl.material, pl.uv_at(q)};
        }
        // Flat shapes snap the point onto their plane, like planes (math/snap.h).
        case ShapeKind::kQuad: {
            const Quad& q = quads[hit.index];
            const Point3 s = snap_to_plane(p, q.corner, q.normal());
            return {s, q.normal(), q.material, q.uv_at(s)};
        }
        case ShapeKind::kDisk: {
            const Disk& d = disks[hit.index];
            const Point3 s = snap_to_plane(p, d.center, d.normal);
            return {s, d.normal, d.material, d.uv_at(s)};
        }
        case ShapeKind::kTriangle: {
            const Triangle& t = triangles[hit.index];
            const Point3 s = snap_to_plane(p, t.p0, t.normal());
            return {s, t.normal(), t.material, t.uv_at(s)};
        }
    }
    return {p, Normal3{0, 1, 0}, 0, {}};  // unreachable: the switch covers every ShapeKind
}

}  // namespace glint
