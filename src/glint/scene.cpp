#include "glint/scene.h"

#include <cassert>

namespace glint {

void Scene::commit() {
    sphere_bounds_ = Bounds3{};
    for (const Sphere& s : spheres) {
        const Vector3 r{s.radius, s.radius, s.radius};
        sphere_bounds_.extend(s.center - r);
        sphere_bounds_.extend(s.center + r);
    }
    committed_spheres_ = spheres.size();
}

std::optional<Hit> Scene::intersect(const Ray& ray_in) const {
    assert(committed_spheres_ == spheres.size() && "Scene::commit() not called");
    Ray ray = ray_in;
    std::optional<Hit> best;
    // Planes first: a plane hit shortens t_max, which the box test and the spheres then use.
    for (std::uint32_t i = 0; i < planes.size(); ++i) {
        if (auto t = planes[i].intersect(ray)) {
            ray.t_max = *t;
            best = Hit{*t, ShapeKind::kPlane, i};
        }
    }
    if (!spheres.empty() && sphere_bounds_.hit(ray, reciprocal(ray.direction))) {
        for (std::uint32_t i = 0; i < spheres.size(); ++i) {
            if (auto t = spheres[i].intersect(ray)) {
                ray.t_max = *t;
                best = Hit{*t, ShapeKind::kSphere, i};
            }
        }
    }
    return best;
}

bool Scene::occluded(const Ray& ray) const {
    assert(committed_spheres_ == spheres.size() && "Scene::commit() not called");
    for (const Plane& p : planes)
        if (p.intersect(ray)) return true;
    if (spheres.empty() || !sphere_bounds_.hit(ray, reciprocal(ray.direction))) return false;
    for (const Sphere& s : spheres)
        if (s.intersect(ray)) return true;
    return false;
}

SurfaceInteraction Scene::interaction(const Ray& ray, const Hit& hit) const {
    const Point3 p = ray.at(hit.t);
    switch (hit.kind) {
        case ShapeKind::kSphere: {
            const Sphere& s = spheres[hit.index];
            return {p, s.normal_at(p), s.material};
        }
        case ShapeKind::kPlane: {
            const Plane& pl = planes[hit.index];
            return {pl.project(p), pl.normal, pl.material};
        }
    }
    return {p, Normal3{0, 1, 0}, 0};  // unreachable: the switch covers every ShapeKind
}

}  // namespace glint
