#include "glint/integrators/integrator.h"

namespace glint {

namespace {
Color surface_color(const Scene& scene, const SurfaceInteraction& si) {
    const auto& m = std::get<ArticleMaterial>(scene.materials[si.material]);
    return scene.texture(m.color, si);
}
}  // namespace

Color FlatIntegrator::li(const Scene& scene, const Ray& ray, RayCounter& counter) const {
    ++counter.rays;
    const auto hit = scene.intersect(ray);
    if (!hit) return evaluate(scene.background, ray.direction);
    return surface_color(scene, scene.interaction(ray, *hit));
}

Color NormalsIntegrator::li(const Scene& scene, const Ray& ray, RayCounter& counter) const {
    ++counter.rays;
    const auto hit = scene.intersect(ray);
    if (!hit) return evaluate(scene.background, ray.direction);
    const Normal3 n = scene.interaction(ray, *hit).n;
    return Color{(n.x + 1) / 2, (n.y + 1) / 2, (n.z + 1) / 2};
}

}  // namespace glint
