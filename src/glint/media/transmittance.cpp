#include "glint/media/transmittance.h"

#include <algorithm>

namespace glint {


Color ratio_tracking(const Medium& medium, const Ray& ray, float t_end, HashRng& rng, int hero,
                     Color& r, float majorant_scale, const SpectralMedium* sm) {
    Color tr{1};
    const auto step = [&](Point3, const MediumPoint& mp, Color sigma_maj, Color T_maj) {
        const Color sigma_n{std::max(sigma_maj.r - mp.sigma_a.r - mp.sigma_s.r, 0.0f),
                            std::max(sigma_maj.g - mp.sigma_a.g - mp.sigma_s.g, 0.0f),
                            std::max(sigma_maj.b - mp.sigma_a.b - mp.sigma_s.b, 0.0f)};
        const float pdf = T_maj[hero] * sigma_maj[hero];
        tr *= T_maj * sigma_n / pdf;
        r *= T_maj * sigma_maj / pdf;
        const float estimate = (tr / average(r)).max_component();
        if (estimate < 0.05f) {
            if (rng.next() < 0.75f) tr = Color{0};
            else tr = tr / 0.25f;
        }
        return tr.max_component() > 0;
    };
    Color T_maj;
    if (majorant_scale != 1) {
        // Only homogeneous media are inflated (a test device): a single segment, as sample_t_maj
        // would walk it, with the bound raised.
        const auto& h = std::get<HomogeneousMedium>(medium);
        const Color sigma_t = h.sigma_a + h.sigma_s;
        const Medium wide = HomogeneousMedium{sigma_t * majorant_scale, Color{0}, Color{0}, h.phase};
        // Collisions are drawn against the inflated medium; each is evaluated with the true one.
        const MediumPoint truth{h.sigma_a, h.sigma_s, h.Le};
        T_maj = sample_t_maj(wide, ray, t_end, rng.next(), rng, hero,
                             [&](Point3 p, const MediumPoint&, Color sigma_maj, Color T) {
                                 return step(p, truth, sigma_maj, T);
                             });
    } else {
        T_maj = sample_t_maj(medium, ray, t_end, rng.next(), rng, hero, step, sm);
    }
    if (tr.max_component() <= 0 || !(T_maj[hero] > 0)) return Color{0};
    tr *= T_maj / T_maj[hero];
    r *= T_maj / T_maj[hero];
    return tr;
}

Color estimate_transmittance(const Medium& medium, const Ray& ray, float t_end, HashRng& rng,
                             int hero, Color& r, const SpectralMedium* sm) {
    if (const auto* h = std::get_if<HomogeneousMedium>(&medium))
        return transmittance(sm ? sm->sigma_a + sm->sigma_s : h->sigma_a + h->sigma_s, t_end);
    return ratio_tracking(medium, ray, t_end, rng, hero, r, 1, sm);
}

}  // namespace glint
