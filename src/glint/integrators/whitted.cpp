#include <algorithm>
#include <stdexcept>

#include "glint/integrators/integrator.h"
#include "glint/materials/make_bsdf.h"

namespace glint {

void Integrator::li_packet(const Scene&, const Ray*, int, Color*, RayCounter&) const {
    throw std::logic_error("this integrator does not trace packets");
}

Color WhittedIntegrator::direct(const Scene& scene, Point3 p, Normal3 n, Normal3 ng, Color k,
                                RayCounter& counter, Float time) const {
    Color d = k * settings_.ambient;
    for (std::size_t i = 0; i < scene.lights.size(); ++i) {
        const LightSample ls = scene.has_motion() ? sample_light(scene.light_at(i, time), p) : sample_light(scene.lights[i], p);
        const Float cos_theta = dot(n, ls.to_light);  // the article's -L.N
        if (cos_theta <= 0) continue;
        if (settings_.shadows) {
            ++counter.rays;
            Ray shadow = spawn_ray(p, ng, ls.to_light, ls.distance);
            shadow.time = time;
            if (scene.occluded_opaque(shadow)) continue;
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
        const Color d = direct(scene, si.p, n, si.n, k, counter, ray.time);
        const float s = m.shininess;
        if (s <= 0) return result + weight * d;
        result += weight * d * (1 - s);
        weight *= d * s;
        const Vector3 r = normalize(reflect(ray.direction, n));
        if (depth >= settings_.max_depth) {
            return result + weight * evaluate(scene.background, r);
        }
        const Float time = ray.time;
        ray = spawn_ray(si.p, si.n, r);
        ray.time = time;
    }
}

// li above for up to 16 camera rays at once: the same loop, each step taken for every live path
// before the next, so that the scene answers the camera rays, then the shadow rays of each
// light, then the reflected rays, as packets. Every path does exactly li's arithmetic in li's
// order (d summed over the lights in order; result and weight updated as there), so each colour
// is li's to the bit.
void WhittedIntegrator::li_packet(const Scene& scene, const Ray* camera_rays, int n, Color* out,
                                  RayCounter& counter) const {
    constexpr int kN = Scene::kPacketSize;
    // Per pixel, where it stays: paths are referred to by index (moving them as the packet
    // shrinks cost more than the shading).
    struct Path {
        Color result{0}, weight{1}, k, d;
        Point3 p;
        Normal3 n, ng;
        float s = 0;
    };
    Path paths[kN];
    Ray rays[kN];  // rays[j] belongs to path live[j]
    int live[kN];
    std::optional<Hit> hits[kN];
    Ray shadow[kN];
    int lit[kN];
    Color arriving[kN];
    int count = n;
    for (int j = 0; j < n; ++j) live[j] = j, rays[j] = camera_rays[j];
    for (int depth = 0; count > 0; ++depth) {
        counter.rays += static_cast<std::uint64_t>(count);
        scene.intersect_opaque(rays, count, hits);
        // Shade the hits; a miss ends its path. The live list stays in pixel order.
        int shaded = 0;
        for (int j = 0; j < count; ++j) {
            const int i = live[j];
            Path& path = paths[i];
            if (!hits[j]) {
                out[i] = path.result + path.weight * evaluate(scene.background, rays[j].direction);
                continue;
            }
            const SurfaceInteraction si = scene.interaction(rays[j], *hits[j]);
            path.n = face_forward(si.ns, rays[j].direction);
            path.ng = si.n;
            path.p = si.p;
            const ArticleView m = article_view(scene, si);
            path.k = m.color;
            path.s = m.shininess;
            path.d = path.k * settings_.ambient;
            if (shaded != j) rays[shaded] = rays[j];
            live[shaded++] = i;
        }
        count = shaded;
        for (const Light& light : scene.lights) {
            int m = 0;
            for (int j = 0; j < count; ++j) {
                const Path& path = paths[live[j]];
                const LightSample ls = sample_light(light, path.p);
                const Float cos_theta = dot(path.n, ls.to_light);
                if (cos_theta <= 0) continue;
                arriving[m] = path.k * ls.intensity * cos_theta;
                lit[m] = live[j];
                if (settings_.shadows) shadow[m] = spawn_ray(path.p, path.ng, ls.to_light, ls.distance);
                ++m;
            }
            std::uint32_t blocked = 0;
            if (settings_.shadows && m > 0) {
                counter.rays += static_cast<std::uint64_t>(m);
                blocked = scene.occluded_opaque(shadow, m);
            }
            for (int q = 0; q < m; ++q)
                if (!(blocked >> q & 1)) paths[lit[q]].d += arriving[q];
        }
        // Reflect: the paths that go on stay at the front of the list, in order.
        int next = 0;
        for (int j = 0; j < count; ++j) {
            const int i = live[j];
            Path& path = paths[i];
            const Color d = path.d;
            const float s = path.s;
            if (s <= 0) {
                out[i] = path.result + path.weight * d;
                continue;
            }
            path.result += path.weight * d * (1 - s);
            path.weight *= d * s;
            const Vector3 r = normalize(reflect(rays[j].direction, path.n));
            if (depth >= settings_.max_depth) {
                out[i] = path.result + path.weight * evaluate(scene.background, r);
                continue;
            }
            rays[next] = spawn_ray(path.p, path.ng, r);
            live[next++] = i;
        }
        count = next;
    }
}

}  // namespace glint
