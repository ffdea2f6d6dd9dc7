#include <algorithm>
#include <cmath>
#include <limits>

#include "glint/integrators/differentials.h"
#include "glint/integrators/integrator.h"
#include "glint/materials/make_bsdf.h"
#include "glint/media/transmittance.h"
#include "glint/samplers/warp.h"
#include "glint/spectra/rgb_spectrum.h"

namespace glint {

namespace {

// Whether direction w lies on the same side of the shading surface as of the geometric one.
bool same_side(const SurfaceInteraction& si, Vector3 w) { return dot(si.n, w) * dot(si.ns, w) > 0; }

Color clamp_radiance(Color c, float max) {
    return {std::min(c.r, max), std::min(c.g, max), std::min(c.b, max)};
}


// The shadow ray from a point inside a medium (no surface to step off) to a light sample.
Ray medium_shadow_ray(Point3 p, const LightLiSample& ls) {
    if (!ls.on_surface) {
        return Ray{p, ls.wi, std::isinf(ls.distance) ? ls.distance : ls.distance * (1 - 1e-4f)};
    }
    const Vector3 towards = ls.p_light - p;
    const Float offset_q = 1e-4f * std::max(Float(1), max_abs_component(ls.p_light));
    const Point3 end = ls.p_light + to_vector(ls.n_light) * (dot(ls.n_light, towards) <= 0 ? offset_q : -offset_q);
    const Vector3 d = end - p;
    const Float dist = length(d);
    return Ray{p, d / dist, dist * (1 - 1e-5f)};
}

// The density MIS weighs a layered BSDF's sample by (its sample carries the walk's own
// density): out of line, so that the common path keeps Bsdf::pdf inlined where it is used.
[[gnu::noinline]] float walk_pdf(const Bsdf& bsdf, Vector3 wo, Vector3 wi) { return bsdf.pdf(wo, wi); }

// A path may cross at most this many interface surfaces between two scattering events (and a
// shadow ray as many): a bound against a malformed scene, far above any real nesting.
constexpr int kMaxInterfaceCrossings = 256;

// The transmittance along a shadow ray through interface surfaces and the media between them;
// 0 when an opaque surface blocks it. `r` gathers the spectral-MIS ratios of ratio tracking.
Color shadow_transmittance(const Scene& scene, Ray ray, MediumId medium, HashRng& rng, int hero,
                           Color& r, std::uint64_t& rays, const Wavelengths* wl) {
    Color tr{1};
    for (int crossings = 0; crossings <= kMaxInterfaceCrossings; ++crossings) {
        const auto hit = scene.intersect(ray);
        if (hit && !scene.is_interface(scene.material_of(*hit))) return Color{0};
        if (medium != kNoMedium) {
            const Medium& m = scene.media[medium];
            const SpectralMedium sm = wl ? spectral_medium(m, *wl) : SpectralMedium{};
            tr *= estimate_transmittance(m, ray, hit ? hit->t : ray.t_max, rng, hero, r, wl ? &sm : nullptr);
            if (!(tr.max_component() > 0)) return Color{0};
        }
        if (!hit) return tr;
        const SurfaceInteraction si = scene.interaction(ray, *hit);
        if (const MediumInterface* mi = scene.medium_interface(si.material))
            medium = mi->side(dot(si.n, ray.direction));
        ++rays;
        ray = continue_ray(ray, si.p, si.n);
    }
    return Color{0};
}

}  // namespace

// The loop of pbrt-v4's PathIntegrator, in our terms, grown into its VolPathIntegrator where
// the scene has media. At each vertex: add emission found by the previous BSDF or phase sample
// (MIS-weighted against light sampling), sample one light (MIS-weighted against BSDF or phase
// sampling), then continue along a BSDF or phase sample. Sampler dimensions per scattering
// event: (light choice, lobe choice), the light's 2D point, the BSDF's or phase function's 2D
// direction, roulette. Media draw their numbers from a per-sample hash stream (HashRng) so that
// they shift no dimension: a scene whose media never collide renders bit for bit as without.
//
// Media (docs/architecture.md, "Volumes"): free flights by delta tracking against a majorant
// with a hero channel chosen per camera sample; `r_u` holds, per channel, the path's sampling
// density over the hero's, and every contribution is divided by its average (spectral MIS,
// the one-sample balance heuristic over the three channels). Lights and BSDF/phase samples are
// combined with the power heuristic on their directional densities, as on surfaces. Shadow rays
// cross interface surfaces and take the transmittance of each medium on the way (closed form in
// homogeneous media, ratio tracking in grids).
Color PathIntegrator::li(const Scene& scene, const Ray& camera_ray, SampleStream& samples,
                         RayCounter& counter, FirstHit* first) const {
    const LightSampler& lights = scene.light_sampler();
    const bool use_light = settings_.strategy != LightStrategy::kBsdf && lights.count() > 0;
    const bool use_bsdf_hits = settings_.strategy != LightStrategy::kLight;
    const bool media = scene.has_media();
    Color radiance{0};
    Color beta{1};
    Color r_u{1};           // spectral MIS: per channel, the path's density over the hero's
    Ray ray = camera_ray;
    const Float time = camera_ray.time;  // every ray of the path is traced at the camera ray's time
    bool specular = true;   // the camera ray counts as specular: emission seen directly is kept
    float bsdf_pdf = 0;     // of the direction that led here (BSDF or phase function)
    // Where the previous light sample was chosen (for the light's pmf when the BSDF or phase
    // sample then meets it): the point, its geometric normal (zero in a medium), and whether the
    // choice was by power alone (a homogeneous medium's, made before its point).
    Point3 prev_p{0, 0, 0};
    Normal3 prev_n{0, 0, 0};
    bool prev_by_power = false;
    float eta_scale = 1;
    // Texture filtering's offset rays (docs/textures.md): the camera's footprint model serves the
    // camera ray; from a perfectly specular bounce on, the path carries its own, until any other.
    std::optional<RayDifferential> differential;
    MediumId medium = scene.camera_medium;
    HashRng rng{media ? samples.stream_seed() : 0};
    const int hero = media ? std::min(2, static_cast<int>(rng.next() * 3)) : 0;
    // Spectral mode (spectra/spectrum.h): three wavelengths in the channels of every Color, the
    // scene's RGB values upsampled where the path reads them, the radiance to RGB at the end.
    // Built in place (assigned, it was copied over in 16-byte pieces across the fields' stores).
    Wavelengths wl_storage = settings_.spectral ? sample_wavelengths(samples.next_1d()) : Wavelengths{};
    const Wavelengths* wl = settings_.spectral ? &wl_storage : nullptr;
    // An emitter's radiance at the path's wavelengths: its own spectrum (Y = 1) times its RGB
    // stand-in's luminance, or its RGB upsampled as an illuminant.
    // The last RGB emitter's radiance at the path's wavelengths is kept (upsample_illuminant's
    // value, without its table lookup each time the path meets or samples that light again).
    // Only lights at a finite distance are remembered (`remember`): an environment's colour
    // changes with the direction and would only push the lamp's out.
    struct {
        Color rgb, value;
        bool valid = false;
    } last_emitter;
    const auto E = [&](Color rgb, const Spectrum* s = nullptr, bool remember = false) {
        if (!wl) return rgb;
        if (s) return s->at(*wl) * luminance(rgb);
        if (!remember) return upsample_illuminant(rgb, *wl);
        // Black (every surface that emits nothing) upsamples to 0 and would push the lamp's out.
        if (!(std::max({rgb.r, rgb.g, rgb.b}) > 0)) return Color{0};
        if (!last_emitter.valid || !(last_emitter.rgb == rgb)) {
            // The table lookup is paid once per thread for each new colour, not once per path.
            thread_local struct {
                Color rgb{-1};
                RgbIlluminant ready;
            } kept;
            if (!(kept.rgb == rgb)) kept = {rgb, RgbIlluminant(rgb)};
            // Field by field, the value returned from the register it was made in: the struct
            // written whole went through the stack and was read back across its pieces.
            const Color value = kept.ready.at(*wl);
            last_emitter.rgb = rgb;
            last_emitter.value = value;
            last_emitter.valid = true;
            return value;
        }
        return last_emitter.value;
    };

    int depth = 0;
    // Emission the camera sees directly, through nothing that scatters or attenuates: in spectral
    // mode its expectation over the wavelengths is known, the colour the film records for the
    // emitter's spectrum, so it is added as that colour after the film conversion. A light or a
    // sky seen directly then has no colour noise, as in RGB mode (docs/spectral.md).
    Color seen_rgb{0};
    const auto seen_exactly = [&](Color rgb, const Spectrum* s) {
        if (!wl || depth != 0 || !(beta == Color{1}) || !(r_u == Color{1})) return false;
        // An RGB emitter shines its colour upsampled as an illuminant, whose film colour is the
        // colour (within the upsampling's round trip, 1e-3); negative channels upsample as 0.
        const auto pos = [](float v) { return v > 0 ? v : 0.0f; };
        seen_rgb += s ? s->film_colour() * luminance(rgb) : Color{pos(rgb.r), pos(rgb.g), pos(rgb.b)};
        return true;
    };

    // Emission reached by a BSDF sample (or the camera): weighted against light sampling.
    // `rgb` and `s`: the emitter's colour and spectrum (null: its colour upsampled).
    // `on_surface`: an area light's (remembered by E), not a distant one's.
    const auto add_emission = [&](Color rgb, const Spectrum* s, std::uint32_t light, Point3 on_light, bool on_surface) {
        if (specular && seen_exactly(rgb, s)) return;
        const Color le = E(rgb, s, on_surface);
        if (le.max_component() <= 0) return;
        if (specular) {
            radiance += beta * le / average(r_u);
            return;
        }
        if (!use_bsdf_hits) return;  // light sampling alone counts this light
        float w = 1;
        if (use_light && light != kNoLight) {
            const float pick_pmf = prev_by_power ? lights.pmf(light) : lights.pmf(prev_p, prev_n, light);
            const float light_pdf = pick_pmf * lights.pdf_li(scene, light, prev_p, ray.direction, on_light, time);
            w = power_heuristic(bsdf_pdf, light_pdf);
        }
        radiance += beta * le * w / average(r_u);
    };

    // Next-event estimation from p: one light, its radiance times f (the BSDF with its cosine,
    // or the phase function) and the transmittance to it. `ng`: the surface's geometric normal
    // (null inside a medium).
    // `l`: the light, chosen with probability `pmf`.
    const auto next_event = [&](Color path_beta, Color path_r, Point3 p, const Normal3* ng,
                                const MediumInterface* mi, const auto& f_of, const auto& pdf_of,
                                std::uint32_t l, float pmf, Sample2 u_light) {
        if (!(pmf > 0)) return;
        const auto ls = lights.sample_li(scene, l, p, u_light, time);
        if (!ls || !(ls->pdf > 0) || ls->L.max_component() <= 0) return;
        const Color L = E(ls->L, ls->spectrum, std::isfinite(ls->distance));
        const Color f = f_of(ls->wi);
        if (f.max_component() <= 0) return;
        ++counter.rays;
        Ray shadow = !ng ? medium_shadow_ray(p, *ls)
                           : ls->on_surface
                               ? spawn_ray_to(p, *ng, ls->p_light, ls->n_light)
                               : spawn_ray(p, *ng, ls->wi,
                                           std::isinf(ls->distance) ? ls->distance
                                                                    : ls->distance * (1 - 1e-4f));
        shadow.time = time;
        Color tr{1}, r_l{1};
        if (!media) {
            if (scene.occluded(shadow)) return;
        } else {
            const MediumId start = ng && mi ? mi->side(dot(*ng, shadow.direction)) : medium;
            tr = shadow_transmittance(scene, shadow, start, rng, hero, r_l, counter.rays, wl);
            if (tr.max_component() <= 0) return;
        }
        const float light_pdf = pmf * ls->pdf;
        const float w = ls->delta || !use_bsdf_hits ? 1 : power_heuristic(light_pdf, pdf_of(ls->wi));
        radiance += path_beta * f * L * tr * (w / light_pdf) / average(path_r * r_l);
    };

    // The denoiser's features (`first`) come from the first surface that is not purely specular:
    // through a mirror or smooth glass, the surface seen in it (at the distance travelled), so that
    // edges seen through glass are edges in the features too; through fog, the surface along the
    // camera ray behind it. Interfaces between media are passed.
    bool want_features = first != nullptr;
    float feature_distance = 0;
    const auto features_along = [&](Ray line, auto h, float travelled) {
        for (int k = 0; k <= kMaxInterfaceCrossings; ++k) {
            if (!h) return FirstHit{evaluate(scene.background, line.direction), {}, 0, false};
            const SurfaceInteraction s = scene.interaction(line, *h);
            if (!scene.is_interface(s.material))
                return FirstHit{article_view(scene, s).color, face_forward(s.ns, line.direction), travelled + h->t, true};
            travelled += h->t;
            line = spawn_ray(s.p, s.n, line.direction);
            line.time = time;
            ++counter.rays;
            h = scene.intersect(line);
        }
        return FirstHit{};
    };

    int crossings = 0;  // interface surfaces passed since the last scattering event
    for (;;) {
        ++counter.rays;
        ray.time = time;
        const auto hit = scene.intersect(ray);

        // Through the medium up to the surface (or forever): delta tracking.
        if (medium != kNoMedium) {
            const Ray line = ray;  // the ray before the medium may turn it
            bool scattered = false, terminated = false;
            const float t_max = hit ? hit->t : std::numeric_limits<float>::infinity();
            const Medium& m = scene.media[medium];
            const SpectralMedium sm = wl ? spectral_medium(m, *wl) : SpectralMedium{};
            const SpectralMedium* smp = wl ? &sm : nullptr;
            // In a homogeneous medium that does not emit, absorption factors out of the
            // transmittance, exp(-sigma_t t) = exp(-sigma_s t) exp(-sigma_a t): free flights are
            // drawn by sigma_s alone and the absorption weighs the path in closed form, so that
            // coloured glass (sigma_s = 0) is exact Beer's law, not a coin toss per path.
            const auto* hm = std::get_if<HomogeneousMedium>(&m);
            // The homogeneous medium's coefficients at this path's wavelengths (its own in RGB).
            const Color hm_sigma_a = hm ? (wl ? sm.sigma_a : hm->sigma_a) : Color{0};
            const Color hm_sigma_s = hm ? (wl ? sm.sigma_s : hm->sigma_s) : Color{0};
            const bool weigh_absorption = hm && !(hm->Le.max_component() > 0);
            const Medium scattering_only =
                weigh_absorption ? Medium{HomogeneousMedium{Color{0}, hm_sigma_s, Color{0}, hm->phase}} : Medium{};
            // Direct light along the whole segment, as Cycles does: in a homogeneous medium one
            // light sample at a point drawn from the free-flight density truncated to the
            // segment, whether or not the path scatters in it (the path's own scattering events
            // then skip light sampling). Both are unbiased for their MIS-weighted parts, the
            // weights depending only on the directions; thin fog stops being a coin toss between
            // "scattered, lit" and "passed, dark".
            bool forced_nee = false;
            if (hm && use_light && depth < settings_.max_depth && hm_sigma_s.max_component() > 0) {
                const Color sigma = weigh_absorption ? hm_sigma_s : hm_sigma_a + hm_sigma_s;
                const float s_h = sigma[hero];
                if (s_h > 0) {
                    forced_nee = true;
                    const Sample2 choices = samples.next_2d();
                    const Sample2 u_light = samples.next_2d();
                    // Towards a point or spot light, the distance is drawn half the time by
                    // equiangular sampling (density ~ 1/r^2 to the light), and weighed by the
                    // mixture of the two densities (one-sample balance heuristic): near a light
                    // in fog the free-flight density alone leaves fireflies.
                    float pick_pmf = 0;
                    const std::uint32_t l = lights.pick(choices.x, &pick_pmf);
                    const std::optional<Point3> at = lights.position(l);
                    const std::optional<Equiangular> eq =
                        at ? Equiangular::make(ray, t_max, *at) : std::nullopt;
                    const Color p_hit = Color{1} - transmittance(sigma, t_max);
                    const float u_t = rng.next();
                    float t = 0;
                    if (eq && rng.next() < 0.5f) {
                        t = std::clamp(eq->sample(u_t), 0.0f, std::nextafter(t_max, 0.0f));
                    } else {
                        t = -std::log1p(-u_t * p_hit[hero]) / s_h;
                        if (!(t < t_max)) t = std::nextafter(t_max, 0.0f);
                    }
                    const Color T_s = transmittance(sigma, t);
                    const float w_eq = eq ? 0.5f : 0.0f;
                    const float eq_pdf = eq ? w_eq * eq->pdf(t) : 0.0f;
                    const auto density = [&](int c) {
                        return (p_hit[c] > 0 ? (1 - w_eq) * sigma[c] * T_s[c] / p_hit[c] : 0.0f) + eq_pdf;
                    };
                    const Color pdf{density(0), density(1), density(2)};
                    Color beta_f = beta * T_s * hm_sigma_s / pdf[hero];
                    if (weigh_absorption) beta_f *= transmittance(hm_sigma_a, t);
                    const Color r_f = r_u * pdf / pdf[hero];
                    const Vector3 wo = -ray.direction;
                    const HgPhase& phase = hm->phase;
                    const auto f = [&](Vector3 wi) { return Color{phase.p(wo, wi)}; };
                    const auto pdf_of = [&](Vector3 wi) { return phase.pdf(wo, wi); };
                    if (is_finite(beta_f) && is_finite(r_f))
                        next_event(beta_f, r_f, ray.at(t), nullptr, nullptr, f, pdf_of, l, pick_pmf, u_light);
                }
            }
            const Color T_maj = sample_t_maj(
                weigh_absorption ? scattering_only : m, ray, t_max, rng.next(), rng, hero,
                [&](Point3 p, const MediumPoint& mp, Color sigma_maj, Color T) {
                    if (depth <= settings_.max_depth && mp.Le.max_component() > 0) {
                        const float pdf = sigma_maj[hero] * T[hero];
                        const Color r_e = r_u * sigma_maj * T / pdf;
                        if (r_e.max_component() > 0)
                            radiance += beta * T * mp.sigma_a * mp.Le / (pdf * average(r_e));
                    }
                    const float p_absorb = mp.sigma_a[hero] / sigma_maj[hero];
                    const float p_scatter = mp.sigma_s[hero] / sigma_maj[hero];
                    const float u_event = rng.next();
                    if (u_event < p_absorb) {
                        terminated = true;
                        return false;
                    }
                    if (u_event < p_absorb + p_scatter) {
                        if (depth >= settings_.max_depth) {
                            terminated = true;
                            return false;
                        }
                        const float pdf = T[hero] * mp.sigma_s[hero];
                        if (weigh_absorption) beta *= transmittance(hm_sigma_a, length(p - ray.origin));
                        beta *= T * mp.sigma_s / pdf;
                        r_u *= T * mp.sigma_s / pdf;
                        if (beta.max_component() <= 0 || r_u.max_component() <= 0) {
                            terminated = true;
                            return false;
                        }
                        const HgPhase& phase = phase_of(m);
                        const Vector3 wo = -ray.direction;
                        const Sample2 choices = samples.next_2d();
                        const Sample2 u_light = samples.next_2d();
                        const Sample2 u_phase = samples.next_2d();
                        if (use_light && !forced_nee) {
                            const auto f = [&](Vector3 wi) { return Color{phase.p(wo, wi)}; };
                            const auto pdf_of = [&](Vector3 wi) { return phase.pdf(wo, wi); };
                            float pmf = 0;
                            const std::uint32_t l = lights.pick(p, Normal3{0, 0, 0}, choices.x, &pmf);
                            next_event(beta, r_u, p, nullptr, nullptr, f, pdf_of, l, pmf, u_light);
                        }
                        const PhaseSample ps = phase.sample(wo, u_phase);
                        beta *= Color{ps.p / ps.pdf};
                        specular = false;
                        differential.reset();
                        bsdf_pdf = ps.pdf;
                        prev_p = p;
                        prev_n = Normal3{0, 0, 0};
                        prev_by_power = forced_nee;
                        ray = Ray{p, ps.wi};
                        scattered = true;
                        return false;
                    }
                    // A null collision: on through the medium.
                    const Color sigma_n{std::max(sigma_maj.r - mp.sigma_a.r - mp.sigma_s.r, 0.0f),
                                        std::max(sigma_maj.g - mp.sigma_a.g - mp.sigma_s.g, 0.0f),
                                        std::max(sigma_maj.b - mp.sigma_a.b - mp.sigma_s.b, 0.0f)};
                    const float pdf = T[hero] * sigma_n[hero];
                    if (!(pdf > 0)) {
                        beta = Color{0};
                        return false;
                    }
                    beta *= T * sigma_n / pdf;
                    r_u *= T * sigma_n / pdf;
                    return beta.max_component() > 0 && r_u.max_component() > 0;
                },
                weigh_absorption ? nullptr : smp);
            if (want_features && (scattered || terminated)) {
                *first = features_along(line, hit, feature_distance);
                want_features = false;
            }
            if (terminated || !(beta.max_component() > 0) || !(r_u.max_component() > 0)) break;
            if (scattered) {
                ++depth;
                crossings = 0;
                if (!roulette(beta, eta_scale, r_u, depth, samples.next_1d())) break;
                continue;
            }
            if (!(T_maj[hero] > 0)) break;
            if (weigh_absorption) beta *= transmittance(hm_sigma_a, t_max);
            beta *= T_maj / T_maj[hero];
            r_u *= T_maj / T_maj[hero];
        }

        if (!hit) {
            if (want_features) *first = {evaluate(scene.background, ray.direction), {}, 0, false};
            for (const std::uint32_t l : lights.distant()) {
                // Seen by the camera (through perfect mirrors and glass), the environment is read
                // over the pixel's footprint; that term has no MIS weight to keep consistent.
                const bool seen = specular && l == lights.environment();
                const Float spread = differential ? differential->spread(ray.direction) : -1;
                add_emission(seen ? scene.background_seen(ray.direction, spread) : lights.distant_radiance(scene, l, ray.direction, time),
                             l == lights.environment() ? scene.background_spectrum() : scene.light_spectrum(l), l, {}, false);
            }
            // A background that is no light (black has no power) still shows to the camera.
            if (lights.environment() == kNoLight && depth == 0 &&
                !seen_exactly(scene.background_seen(ray.direction), scene.background_spectrum()))
                radiance += beta * E(scene.background_seen(ray.direction), scene.background_spectrum()) / average(r_u);
            break;
        }
        const SurfaceInteraction si = scene.interaction(ray, *hit, differential ? &*differential : nullptr);
        if (media && scene.is_interface(si.material)) {
            // No surface: change medium and go on in the same direction, no scattering event.
            if (const MediumInterface* mi = scene.medium_interface(si.material))
                medium = mi->side(dot(si.n, ray.direction));
            if (++crossings > kMaxInterfaceCrossings) break;
            if (want_features) feature_distance += hit->t;
            ray = spawn_ray(si.p, si.n, ray.direction);
            continue;
        }
        const Vector3 wo = -ray.direction;
        add_emission(scene.emitted(si, wo), scene.emission_of(si.material).spectrum.get(),
                     lights.light_of(si.shape, si.shape_index, si.prim), si.p, true);
        if (want_features) {
            *first = {article_view(scene, si).color, face_forward(si.ns, ray.direction), feature_distance + hit->t, true};
        }
        if (depth >= settings_.max_depth) break;

        bool dispersive = false;
        const Bsdf bsdf = make_bsdf(scene, si, wl, &dispersive);
        if (dispersive) terminate_secondary(wl_storage);  // the wavelengths stay: E's value holds
        if (bsdf.has_smooth_part()) want_features = false;
        const Sample2 choices = samples.next_2d();
        const Sample2 u_light = samples.next_2d();
        const Sample2 u_bsdf = samples.next_2d();
        const float u_rr = samples.next_1d();

        // Next-event estimation. A direction on different sides of the shading and the true
        // surface is refused (light would leak through a smooth-shaded mesh).
        if (use_light && bsdf.has_smooth_part()) {
            const auto f = [&](Vector3 wi) {
                return same_side(si, wi) ? bsdf.eval(wo, wi) * std::abs(dot(si.ns, wi)) : Color{0};
            };
            const auto pdf_of = [&](Vector3 wi) { return bsdf.pdf(wo, wi); };
            float pmf = 0;
            const std::uint32_t l = lights.pick(si.p, si.n, choices.x, &pmf);
            next_event(beta, r_u, si.p, &si.n, scene.medium_interface(si.material), f, pdf_of, l, pmf, u_light);
        }

        // Continue the path.
        const auto bs = bsdf.sample(wo, choices.y, u_bsdf);
        if (!bs || bs->f.max_component() <= 0 || !same_side(si, bs->wi)) break;
        beta *= bs->f * (std::abs(dot(si.ns, bs->wi)) / bs->pdf);
        specular = bs->specular;
        if (want_features) {
            if (bs->specular) feature_distance += hit->t;
            else want_features = false;
        }
        bsdf_pdf = bs->pdf_is_proportional ? walk_pdf(bsdf, wo, bs->wi) : bs->pdf;
        prev_p = si.p;
        prev_n = si.n;
        prev_by_power = false;
        if (bs->eta != 1) eta_scale *= bs->eta * bs->eta;
        if (!is_finite(beta)) break;
        if (media) {
            if (const MediumInterface* mi = scene.medium_interface(si.material))
                medium = mi->side(dot(si.n, bs->wi));
        }
        ++depth;
        crossings = 0;
        if (!roulette(beta, eta_scale, r_u, depth, u_rr)) break;
        // The next ray is written where the path keeps it (a `next` copied into `ray` went
        // through the stack in pieces and was read back whole: a failed store forward a bounce).
        const Vector3 incoming = ray.direction;
        ray = spawn_ray(si.p, si.n, bs->wi);
        if (scene.footprint && (differential || depth == 1)) {
            differential = bs->specular ? scatter_differential(scene, si, incoming, differential ? &*differential : nullptr,
                                                               bs->wi, bs->eta, ray.origin)
                                        : std::nullopt;
        }
    }
    if (wl) radiance = film_rgb(radiance, *wl) + seen_rgb;
    if (settings_.white_balance > 0) radiance = balance_(radiance);
    if (!is_finite(radiance)) return Color{0};
    return std::isinf(settings_.clamp) ? radiance : clamp_radiance(radiance, settings_.clamp);
}

// Russian roulette on the throughput without the radiance scaling of refraction (and, in
// media, as the spectral MIS estimate weighs it); false when the path dies. A path continues
// with probability min(1, sqrt(max throughput)), Cycles' rule, from rr_depth (5) bounces on:
// pbrt-v4's min(1, max throughput) from depth 1 ended paths early enough to cost the Cornell box
// 40 % and the materials scene 14 % in efficiency (1 / (variance x time), docs/benchmarks.md).
bool PathIntegrator::roulette(Color& beta, float eta_scale, Color r_u, int depth, float u) const {
    if (depth < settings_.rr_depth) return true;  // before the square root, not after it
    const float rr = std::sqrt((beta * eta_scale / average(r_u)).max_component());
    if (rr < 1) {
        const float q = std::max(0.0f, 1 - rr);
        if (u < q) return false;
        beta = beta / (1 - q);
    }
    return true;
}

}  // namespace glint
