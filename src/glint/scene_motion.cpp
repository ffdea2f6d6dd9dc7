// The moving parts of Scene (scene.h): analytic shapes that move over the shutter are tested,
// and their interactions computed, where they are stored (in object space), with the ray carried
// there by the inverse of their placement at the ray's time; the answers are carried back.
// (Instances need nothing of this: their placement at the time replaces their transform.)
#include <cmath>

#include "glint/scene.h"

namespace glint {

namespace {

// The ray in the frame where a moving shape is stored, its direction unit again (the shapes'
// tests need it): t along it is `scale` times t along the world ray.
struct StoredRay {
    Ray ray;
    Float scale;
};

StoredRay to_stored(const Transform& d, const Ray& r) {
    const Vector3 dir = d.to_object.apply(r.direction);
    const Float k = length(dir);
    return {Ray{d.to_object.apply(r.origin), dir / k, r.t_max * k, r.time}, k};
}

}  // namespace

const Motion* Scene::motion_of(ShapeKind kind, std::uint32_t index) const {
    if (kind == ShapeKind::kMesh) {
        const std::int32_t m = index < instances.size() ? instances[index].motion : -1;
        return m >= 0 ? &motions[static_cast<std::size_t>(m)] : nullptr;
    }
    const auto& v = shape_motion_[static_cast<std::size_t>(kind)];
    if (index >= v.size() || v[index] < 0) return nullptr;
    return &motions[static_cast<std::size_t>(v[index])];
}

void Scene::index_motion() {
    for (auto& v : shape_motion_) v.clear();
    has_motion_ = false;
    const auto count = [&](ShapeKind k) -> std::size_t {
        switch (k) {
            case ShapeKind::kSphere: return spheres.size();
            case ShapeKind::kQuad: return quads.size();
            case ShapeKind::kDisk: return disks.size();
            case ShapeKind::kTriangle: return triangles.size();
            default: return 0;
        }
    };
    for (const MovingShape& s : moving_shapes) {
        if (s.kind == ShapeKind::kPlane || s.kind == ShapeKind::kMesh || s.index >= count(s.kind) ||
            s.motion >= motions.size())
            throw std::out_of_range("a moving shape that does not exist");
        auto& v = shape_motion_[static_cast<std::size_t>(s.kind)];
        if (v.empty()) v.assign(count(s.kind), -1);
        v[s.index] = static_cast<std::int32_t>(s.motion);
        has_motion_ = has_motion_ || motions[s.motion].moves();
    }
    for (const std::int32_t m : light_motion) {
        if (m < 0) continue;
        if (static_cast<std::size_t>(m) >= motions.size()) throw std::out_of_range("a light's motion that does not exist");
        has_motion_ = has_motion_ || motions[static_cast<std::size_t>(m)].moves();
    }
    for (const Instance& in : instances) {
        if (in.motion < 0) continue;
        if (static_cast<std::size_t>(in.motion) >= motions.size())
            throw std::out_of_range("an instance's motion that does not exist");
        has_motion_ = has_motion_ || motions[static_cast<std::size_t>(in.motion)].moves();
    }
}

Bounds3 Scene::moving_bounds(std::uint32_t m, bool padded) const {
    const MovingShape& ms = moving_shapes[m];
    Bounds3 b;
    switch (ms.kind) {
        case ShapeKind::kSphere: b = ball_bounds(spheres[ms.index].center, spheres[ms.index].radius); break;
        case ShapeKind::kDisk: b = ball_bounds(disks[ms.index].center, disks[ms.index].radius); break;
        case ShapeKind::kQuad: b = quads[ms.index].bounds(); break;
        case ShapeKind::kTriangle:
            for (const Point3 p : {triangles[ms.index].p0, triangles[ms.index].p1, triangles[ms.index].p2}) b.extend(p);
            break;
        default: break;
    }
    // Padded where the shape's test runs, in its own frame, then swept.
    if (padded && padded_for_rounding(ms.kind)) b = padded_for_rounding(b);
    return motions[ms.motion].swept_bounds(b);
}

void Scene::closest_moving(std::uint32_t m, Ray& ray, std::optional<Hit>& best) const {
    const MovingShape& s = moving_shapes[m];
    const StoredRay local = to_stored(motions[s.motion].at(ray.time), ray);
    std::optional<Float> t;
    switch (s.kind) {
        case ShapeKind::kSphere: t = spheres[s.index].intersect(local.ray); break;
        case ShapeKind::kQuad: t = quads[s.index].intersect(local.ray); break;
        case ShapeKind::kDisk: t = disks[s.index].intersect(local.ray); break;
        case ShapeKind::kTriangle: {
            const Triangle& tr = triangles[s.index];
            if (const auto h = intersect_triangle(tr.p0, tr.p1, tr.p2, WatertightRay(local.ray))) t = h->t;
            break;
        }
        default: break;
    }
    if (!t) return;
    const Float world_t = *t / local.scale;
    if (!(world_t < ray.t_max)) return;
    ray.t_max = world_t;
    best = Hit{world_t, s.kind, s.index};
}

bool Scene::any_moving(std::uint32_t m, const Ray& ray) const {
    Ray r = ray;
    std::optional<Hit> h;
    closest_moving(m, r, h);
    return h.has_value();
}

SurfaceInteraction Scene::moving_interaction(const Motion& motion, const Ray& ray, const Hit& hit) const {
    const Transform d = motion.at(ray.time);
    const StoredRay local = to_stored(d, ray);
    Hit h = hit;
    h.t = hit.t * local.scale;
    SurfaceInteraction si = base_interaction(local.ray, h);
    si.p = d.point(si.p);
    si.n = normalize(d.normal(si.n));
    si.ns = si.n;
    return si;
}

}  // namespace glint
