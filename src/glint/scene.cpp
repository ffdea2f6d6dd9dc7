#include "glint/scene.h"

#include <algorithm>
#include <cassert>
#include <type_traits>

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

// Triangles share the per-ray part of the watertight test.
void closest_hit_triangles(const std::vector<Triangle>& triangles, Ray& ray, std::optional<Hit>& best) {
    if (triangles.empty()) return;
    WatertightRay r(ray);
    const std::uint32_t n = static_cast<std::uint32_t>(triangles.size());
    for (std::uint32_t i = 0; i < n; ++i) {
        if (auto t = triangles[i].intersect(r)) {
            r.t_max = ray.t_max = *t;
            best = Hit{*t, ShapeKind::kTriangle, i};
        }
    }
}

bool any_hit_triangles(const std::vector<Triangle>& triangles, const Ray& ray) {
    if (triangles.empty()) return false;
    const WatertightRay r(ray);
    for (const Triangle& t : triangles)
        if (t.intersect(r)) return true;
    return false;
}

}  // namespace

void Scene::commit() {
    bounds_ = Bounds3{};
    const auto extend_ball = [this](Point3 center, Float radius) {
        const Vector3 r{radius, radius, radius};
        bounds_.extend(center - r);
        bounds_.extend(center + r);
    };
    for (const Sphere& s : spheres) extend_ball(s.center, s.radius);
    for (const Quad& q : quads) {
        bounds_.extend(q.corner);
        bounds_.extend(q.corner + q.edge1);
        bounds_.extend(q.corner + q.edge2);
        bounds_.extend(q.corner + q.edge1 + q.edge2);
    }
    for (const Disk& d : disks) extend_ball(d.center, d.radius);  // a disk lies in its ball
    for (const Triangle& t : triangles) {
        bounds_.extend(t.p0);
        bounds_.extend(t.p1);
        bounds_.extend(t.p2);
    }
    committed_count_ = bounded_count();
    const float radius =
        bounds_.empty() ? 1.0f : 0.5f * length(bounds_.hi - bounds_.lo);
    light_sampler_.build(*this, std::max(radius, 1e-3f));
    any_bounded_ = committed_count_ > 0;
    any_flat_ = !quads.empty() || !disks.empty() || !triangles.empty();
    // Which textures read uv: images, and whatever combines one. Children come before their
    // parents (build adds them first), so one forward pass settles every entry.
    texture_needs_uv_.assign(textures.size(), false);
    for (std::size_t i = 0; i < textures.size(); ++i) {
        const auto needs = [this](TextureId id) { return static_cast<bool>(texture_needs_uv_[id]); };
        texture_needs_uv_[i] = std::visit(
            [&](const auto& t) -> bool {
                using T = std::decay_t<decltype(t)>;
                if constexpr (std::is_same_v<T, ImageTexture>) return true;
                if constexpr (std::is_same_v<T, ScaleTexture>) return needs(t.texture) || needs(t.factor);
                if constexpr (std::is_same_v<T, MixTexture>)
                    return needs(t.a) || needs(t.b) || needs(t.amount);
                return false;
            },
            textures[i]);
    }
}

std::optional<Hit> Scene::intersect(const Ray& ray_in) const {
    assert(committed_count_ == bounded_count() && "Scene::commit() not called");
    Ray ray = ray_in;
    std::optional<Hit> best;
    // Planes first: a plane hit shortens t_max, which the box test and the rest then use.
    closest_hit<ShapeKind::kPlane>(planes, ray, best);
    if (any_bounded_ && bounds_.hit(ray, reciprocal(ray.direction))) {
        closest_hit<ShapeKind::kSphere>(spheres, ray, best);
        if (any_flat_) {  // the article's scenes have none: skip three empty loops per ray
            closest_hit<ShapeKind::kQuad>(quads, ray, best);
            closest_hit<ShapeKind::kDisk>(disks, ray, best);
            closest_hit_triangles(triangles, ray, best);
        }
    }
    return best;
}

bool Scene::occluded(const Ray& ray) const {
    assert(committed_count_ == bounded_count() && "Scene::commit() not called");
    if (any_hit(planes, ray)) return true;
    if (!any_bounded_ || !bounds_.hit(ray, reciprocal(ray.direction))) return false;
    return any_hit(spheres, ray) ||
           (any_flat_ && (any_hit(quads, ray) || any_hit(disks, ray) || any_hit_triangles(triangles, ray)));
}

SurfaceInteraction Scene::interaction(const Ray& ray, const Hit& hit) const {
    const Point3 p = ray.at(hit.t);
    switch (hit.kind) {
        case ShapeKind::kSphere: {
            const Sphere& s = spheres[hit.index];
            return {p, s.normal_at(p), s.material, hit.kind, hit.index};
        }
        case ShapeKind::kPlane: {
            const Plane& pl = planes[hit.index];
            return {pl.project(p), pl.normal, pl.material, hit.kind, hit.index};
        }
        // Flat shapes snap the point onto their plane, like planes (math/snap.h).
        case ShapeKind::kQuad: {
            const Quad& q = quads[hit.index];
            return {snap_to_plane(p, q.corner, q.normal()), q.normal(), q.material, hit.kind,
                    hit.index};
        }
        case ShapeKind::kDisk: {
            const Disk& d = disks[hit.index];
            return {snap_to_plane(p, d.center, d.normal), d.normal, d.material, hit.kind, hit.index};
        }
        case ShapeKind::kTriangle: {
            const Triangle& t = triangles[hit.index];
            return {snap_to_plane(p, t.p0, t.normal()), t.normal(), t.material, hit.kind,
                    hit.index};
        }
    }
    return {p, Normal3{0, 1, 0}, 0, hit.kind, hit.index};  // unreachable: every kind is covered
}

Point2 Scene::uv(const SurfaceInteraction& si) const {
    switch (si.shape) {
        case ShapeKind::kSphere: return spheres[si.shape_index].uv_at(si.p);
        case ShapeKind::kPlane: return planes[si.shape_index].uv_at(si.p);
        case ShapeKind::kQuad: return quads[si.shape_index].uv_at(si.p);
        case ShapeKind::kDisk: return disks[si.shape_index].uv_at(si.p);
        case ShapeKind::kTriangle: return triangles[si.shape_index].uv_at(si.p);
    }
    return {};
}

}  // namespace glint
