#include <optional>

#include "glint/integrators/integrator.h"
#include "glint/materials/make_bsdf.h"

namespace glint {

namespace {
Color surface_color(const Scene& scene, const SurfaceInteraction& si) {
    return article_view(scene, si).color;
}

// The first intersection of both debug views, with the AOVs filled in.
std::optional<SurfaceInteraction> first_hit(const Scene& scene, const Ray& ray,
                                            RayCounter& counter, FirstHit* first) {
    ++counter.rays;
    const auto hit = scene.intersect_opaque(ray);
    if (!hit) {
        if (first) *first = {evaluate(scene.background, ray.direction), {}, 0, false};
        return std::nullopt;
    }
    const SurfaceInteraction si = scene.interaction(ray, *hit);
    if (first) *first = {surface_color(scene, si), si.ns, hit->t, true};
    return si;
}
}  // namespace

Color FlatIntegrator::li(const Scene& scene, const Ray& ray, SampleStream&, RayCounter& counter,
                         FirstHit* first) const {
    const auto si = first_hit(scene, ray, counter, first);
    if (!si) return evaluate(scene.background, ray.direction);
    return surface_color(scene, *si);
}

Color NormalsIntegrator::li(const Scene& scene, const Ray& ray, SampleStream&, RayCounter& counter,
                            FirstHit* first) const {
    const auto si = first_hit(scene, ray, counter, first);
    if (!si) return evaluate(scene.background, ray.direction);
    const Normal3 n = si->ns;  // the shading normal (interpolated on smooth meshes)
    return Color{(n.x + 1) / 2, (n.y + 1) / 2, (n.z + 1) / 2};
}

}  // namespace glint
