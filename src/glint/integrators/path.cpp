#include <algorithm>
#include <cmath>

#include "glint/integrators/integrator.h"
#include "glint/materials/make_bsdf.h"

namespace glint {

namespace {

// Veach's power heuristic with beta = 2, for one sample from each of two strategies.
float power_heuristic(float pdf_a, float pdf_b) {
    const float a = pdf_a * pdf_a, b = pdf_b * pdf_b;
    if (std::isinf(a)) return 1;
    return a + b > 0 ? a / (a + b) : 0;
}

// Whether direction w lies on the same side of the shading surface as of the geometric one.
bool same_side(const SurfaceInteraction& si, Vector3 w) { return dot(si.n, w) * dot(si.ns, w) > 0; }

Color clamp_radiance(Color c, float max) {
    return {std::min(c.r, max), std::min(c.g, max), std::min(c.b, max)};
}

}  // namespace

// The loop of pbrt-v4's PathIntegrator, in our terms. At each vertex: add emission found by the
// previous BSDF sample (MIS-weighted against light sampling), sample one light (MIS-weighted
// against BSDF sampling), then continue along a BSDF sample. Sampler dimensions per bounce:
// (light choice, lobe choice), the light's 2D point, the BSDF's 2D direction, roulette.
Color PathIntegrator::li(const Scene& scene, const Ray& camera_ray, SampleStream& samples,
                         RayCounter& counter, FirstHit* first) const {
    const LightSampler& lights = scene.light_sampler();
    const bool use_light = settings_.strategy != LightStrategy::kBsdf && lights.count() > 0;
    const bool use_bsdf_hits = settings_.strategy != LightStrategy::kLight;
    Color radiance{0};
    Color beta{1};
    Ray ray = camera_ray;
    bool specular = true;   // the camera ray counts as specular: emission seen directly is kept
    float bsdf_pdf = 0;     // of the direction that led here
    Point3 prev_p{0, 0, 0};
    float eta_scale = 1;

    // Emission reached by a BSDF sample (or the camera): weighted against light sampling.
    const auto add_emission = [&](Color le, std::uint32_t light, Point3 on_light) {
        if (le.max_component() <= 0) return;
        if (specular) {
            radiance += beta * le;
            return;
        }
        if (!use_bsdf_hits) return;  // light sampling alone counts this light
        float w = 1;
        if (use_light && light != kNoLight) {
            const float light_pdf =
                lights.pmf(light) * lights.pdf_li(scene, light, prev_p, ray.direction, on_light);
            w = power_heuristic(bsdf_pdf, light_pdf);
        }
        radiance += beta * le * w;
    };

    for (int depth = 0;; ++depth) {
        ++counter.rays;
        const auto hit = scene.intersect(ray);
        if (!hit) {
            if (first && depth == 0) *first = {evaluate(scene.background, ray.direction), {}, 0, false};
            for (const std::uint32_t l : lights.distant())
                add_emission(lights.distant_radiance(scene, l, ray.direction), l, {});
            // A background that is no light (black has no power) still shows to the camera.
            if (lights.environment() == kNoLight && depth == 0)
                radiance += beta * evaluate(scene.background, ray.direction);
            break;
        }
        const SurfaceInteraction si = scene.interaction(ray, *hit);
        const Vector3 wo = -ray.direction;
        add_emission(scene.emitted(si, wo), lights.light_of(si.shape, si.shape_index, si.prim), si.p);
        if (first && depth == 0) {
            *first = {article_view(scene, si).color, face_forward(si.ns, ray.direction), hit->t, true};
        }
        if (depth >= settings_.max_depth) break;

        const Bsdf bsdf = make_bsdf(scene, si);
        const Sample2 choices = samples.next_2d();
        const Sample2 u_light = samples.next_2d();
        const Sample2 u_bsdf = samples.next_2d();
        const float u_rr = samples.next_1d();

        // Next-event estimation.
        if (use_light && bsdf.has_smooth_part()) {
            float pmf = 0;
            const std::uint32_t l = lights.pick(choices.x, &pmf);
            if (pmf > 0) {
                if (const auto ls = lights.sample_li(scene, l, si.p, u_light);
                    ls && ls->pdf > 0 && ls->L.max_component() > 0) {
                    // A direction on different sides of the shading and the true surface is
                    // refused (light would leak through a smooth-shaded mesh).
                    const Color f = same_side(si, ls->wi)
                                        ? bsdf.eval(wo, ls->wi) * std::abs(dot(si.ns, ls->wi))
                                        : Color{0};
                    if (f.max_component() > 0) {
                        ++counter.rays;
                        const Ray shadow =
                            ls->on_surface
                                ? spawn_ray_to(si.p, si.n, ls->p_light, ls->n_light)
                                : spawn_ray(si.p, si.n, ls->wi,
                                            std::isinf(ls->distance) ? ls->distance
                                                                     : ls->distance * (1 - 1e-4f));
                        if (!scene.occluded(shadow)) {
                            const float light_pdf = pmf * ls->pdf;
                            const float w = ls->delta || !use_bsdf_hits
                                                ? 1
                                                : power_heuristic(light_pdf, bsdf.pdf(wo, ls->wi));
                            radiance += beta * f * ls->L * (w / light_pdf);
                        }
                    }
                }
            }
        }

        // Continue the path.
        const auto bs = bsdf.sample(wo, choices.y, u_bsdf);
        if (!bs || bs->f.max_component() <= 0 || !same_side(si, bs->wi)) break;
        beta *= bs->f * (std::abs(dot(si.ns, bs->wi)) / bs->pdf);
        specular = bs->specular;
        bsdf_pdf = bs->pdf;
        prev_p = si.p;
        if (bs->eta != 1) eta_scale *= bs->eta * bs->eta;
        if (!is_finite(beta)) break;

        // Russian roulette on the throughput without the radiance scaling of refraction.
        const float rr = (beta * eta_scale).max_component();
        if (depth + 1 >= settings_.rr_depth && rr < 1) {
            const float q = std::max(0.0f, 1 - rr);
            if (u_rr < q) break;
            beta = beta / (1 - q);
        }
        ray = spawn_ray(si.p, si.n, bs->wi);
    }
    if (!is_finite(radiance)) return Color{0};
    return std::isinf(settings_.clamp) ? radiance : clamp_radiance(radiance, settings_.clamp);
}

}  // namespace glint
