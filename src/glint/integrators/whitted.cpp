#include <algorithm>

#include "glint/integrators/integrator.h"
#include "glint/materials/make_bsdf.h"

namespace glint {

Color WhittedIntegrator::direct(const Scene& scene, Point3 p, Normal3 n, Normal3 ng, Color k,
                                RayCounter& counter) const {
    Color d = k * settings_.ambient;
    for (const Light& light : scene.lights) {
        const LightSample ls = sample_light(light, p);
        const Float cos_theta = dot(n, ls.to_light);  // the article's -L.N
        if (cos_theta <= 0) continue;
        if (settings_.shadows) {
            ++counter.rays;
            if (scene.occluded_opaque(spawn_ray(p, ng, ls.to_light, ls.distance))) continue;
        }
        d += k * ls.intensity * cos_theta;
    }
    return d;
}

// The recursion colour = (1-s) d + s (d * r) is affine in r, so it unrolls into a loop:
// colour = a0 + b0 * (a1 + b1 * (a2 + ...)) with a = (1-s) d and b = s d. `weight` is the
// product of the b's so far. No recursion, so no stack depth limit on max_depth.
Color WhittedIntegrator::li(const Scene& scene, const Ray& camera_ray, SampleStream&, RayCounter& counter,
                            FirstHit* first) const {
    Color result{0};
    Color weight{1};
    Ray ray = camera_ray;
    for (int depth = 0;; ++depth) {
        ++counter.rays;
        const auto hit = scene.intersect_opaque(ray);
        if (!hit) {
            const Color bg = evaluate(scene.background, ray.direction);
            if (first && depth == 0) *first = {bg, {}, 0, false};
            return result + weight * bg;
        }
        const SurfaceInteraction si = scene.interaction(ray, *hit);
        // Shade with the normal facing the viewer. For every surface seen from its front (all of
        // the article's figures) this is the article's N; it keeps the back of a plane and the
        // inside of a sphere lit correctly instead of black. (On smooth-shaded meshes this is the
        // interpolated normal; rays leave off the true surface, si.n.)
        const Normal3 n = face_forward(si.ns, ray.direction);
        const ArticleView m = article_view(scene, si);  // the article's material as is
        const Color k = m.color;
        if (first && depth == 0) *first = {k, n, hit->t, true};
        const Color d = direct(scene, si.p, n, si.n, k, counter);
        const float s = m.shininess;
        if (s <= 0) return result + weight * d;
        result += weight * d * (1 - s);
        weight *= d * s;
        const Vector3 r = normalize(reflect(ray.direction, n));
        if (depth >= settings_.max_depth) {
            return result + weight * evaluate(scene.background, r);
        }
        ray = spawn_ray(si.p, si.n, r);
    }
}

}  // namespace glint
