#include "glint/integrators/differentials.h"

#include <cmath>

#include "glint/materials/fresnel.h"

namespace glint {

std::optional<RayDifferential> scatter_differential(const Scene& scene, const SurfaceInteraction& si, Vector3 d,
                                                    const RayDifferential* in, Vector3 wi, float eta, Point3 from) {
    if (!scene.footprint) return std::nullopt;
    Vector3 dpdx, dpdy;
    RayDifferential incoming;
    if (in) {
        if (!in->at(si.p, si.n, dpdx, dpdy)) return std::nullopt;
        incoming = *in;
    } else {
        if (!scene.footprint->at(si.p, si.n, dpdx, dpdy)) return std::nullopt;
        incoming = scene.footprint->differential(si.p, dpdx, dpdy);
    }
    const Vector3 wo = -d;
    const bool transmit = dot(si.n, wi) * dot(si.n, wo) < 0;
    const Vector3 ns = to_vector(si.ns);
    // The normal on the side the path's own ray came from, for the refraction.
    const Float side = dot(wo, ns) >= 0 ? 1 : -1;
    // The shading normal at an offset point: si.ns turned as the surface's own normal turns from
    // si.p to there (zero on flat shapes), so that a normal map's bend is kept.
    const Vector3 n0 = to_vector(scene.smooth_normal_at(si, si.p));
    const auto turn = [&](Vector3 dp, Vector3 v, Vector3& out) {
        Vector3 dn = to_vector(scene.smooth_normal_at(si, si.p + dp)) - n0;
        if (!is_finite(dn)) dn = Vector3{0, 0, 0};
        const Vector3 n = normalize(ns + dn) * side;
        const Float len = length(v);
        if (!(len > 0) || !is_finite(n)) return false;
        const Vector3 u = v / len;
        if (!transmit) {
            out = reflect(u, Normal3(n));
        } else {
            float crossed = 1;
            if (!(dot(u, n) < 0) || !refract(-u, n, eta, out, crossed)) return false;
        }
        return is_finite(out);
    };
    RayDifferential out{from + dpdx, from + dpdy, {}, {}};
    if (!turn(dpdx, incoming.dx, out.dx) || !turn(dpdy, incoming.dy, out.dy)) return std::nullopt;
    return out;
}

}  // namespace glint
