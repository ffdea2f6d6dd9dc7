#include "glint/lights/light_sampler.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <type_traits>

#include "glint/math/frame.h"
#include "glint/samplers/warp.h"
#include "glint/scene.h"

namespace glint {

namespace {

constexpr float kPi = std::numbers::pi_v<float>;


// v expressed in the frame whose z axis is the unit vector `axis`, mapped to world space.
Vector3 from_frame(Vector3 axis, Vector3 v) {
    Vector3 t, b;
    orthonormal_basis(axis, t, b);
    return t * v.x + b * v.y + axis * v.z;
}

// The cone of directions from p that a sphere subtends: 1 - cos(theta_max), computed without
// cancellation (sin^2 / (1 + cos)). Negative when p is inside.
float sphere_cone(const Sphere& s, Point3 p) {
    const float d2 = dot(p - s.center, p - s.center);
    const float r2 = s.radius * s.radius;
    if (d2 <= r2 * 1.0001f) return -1;
    const float sin2 = r2 / d2;
    return sin2 / (1 + std::sqrt(std::max(0.0f, 1 - sin2)));
}

float env_power_density(const Background& bg) {
    return std::visit(
        [](const auto& b) -> float {
            using T = std::decay_t<decltype(b)>;
            if constexpr (std::is_same_v<T, SkyBackground>) {
                return luminance((b.horizon + b.zenith) * 0.5f);  // the sphere's mean
            } else if constexpr (std::is_same_v<T, ConstantBackground>) {
                return luminance(b.color);
            } else {
                double sum = 0, weight = 0;
                for (int y = 0; y < b.image.height; ++y) {
                    const double s = std::sin((y + 0.5) / b.image.height * std::numbers::pi);
                    for (int x = 0; x < b.image.width; ++x) sum += s * luminance(b.image.texel(x, y));
                    weight += s * b.image.width;
                }
                return weight > 0 ? static_cast<float>(sum / weight) * b.scale : 0.0f;
            }
        },
        bg);
}

// How much a moving analytic shape's area grows from where it is stored (object space) to where
// it is at the shutter's opening: k^2 for its similarity of scale k (1 for everything else).
float placed_area_scale(const Scene& scene, ShapeKind kind, std::uint32_t index) {
    if (kind == ShapeKind::kMesh) return 1;
    const Motion* m = scene.motion_of(kind, index);
    if (!m) return 1;
    const float k = length(m->key(0).vector({1, 0, 0}));
    return k * k;
}

// A directional light's direction at `time`: it may turn over the shutter (Scene::light_at).
Vector3 sun_direction(const Scene& scene, std::uint32_t light, const DirectionalLight& sun, Float time) {
    if (light < scene.light_motion.size() && scene.light_motion[light] >= 0)
        return std::get<DirectionalLight>(scene.light_at(light, time)).direction;
    return sun.direction;
}

// Where a light is and which way it shines, for the BVH (lights/light_bvh.h). Distant lights
// have no place: phi 0 leaves them out.
LightBounds light_bounds(const Scene& scene, const Light& light) {
    return std::visit(
        [&](const auto& l) -> LightBounds {
            using T = std::decay_t<decltype(l)>;
            LightBounds b;
            if constexpr (std::is_same_v<T, PointLight>) {
                b.box.extend(l.position);
                b.phi = luminance(l.intensity);
                b.cos_o = -1;  // every direction
            } else if constexpr (std::is_same_v<T, SpotLight>) {
                b.box.extend(l.position);
                b.phi = luminance(l.intensity);
                b.w = l.direction;
                b.cos_o = l.cos_inner;
                b.cos_e = std::cos(std::max(0.0f, std::acos(std::clamp(l.cos_outer, -1.0f, 1.0f)) -
                                                      std::acos(std::clamp(l.cos_inner, -1.0f, 1.0f))));
            } else if constexpr (std::is_same_v<T, AreaLight>) {
                const auto flat = [&](auto points, Normal3 n, float area, MaterialId material) {
                    for (const Point3& q : points) b.box.extend(q);
                    const Emission& e = scene.emission_of(material);
                    b.phi = luminance(e.radiance) * area;  // its intensity seen face on
                    b.w = to_vector(n);
                    b.two_sided = e.two_sided;
                };
                switch (l.kind) {
                    case ShapeKind::kSphere: {
                        const Sphere& s = scene.spheres[l.index];
                        const Vector3 r{s.radius, s.radius, s.radius};
                        b.box.extend(s.center - r);
                        b.box.extend(s.center + r);
                        b.phi = luminance(scene.emission_of(s.material).radiance) * kPi * s.radius * s.radius;
                        b.cos_o = -1;
                        break;
                    }
                    case ShapeKind::kQuad: {
                        const Quad& q = scene.quads[l.index];
                        flat(std::array{q.corner, q.corner + q.edge1, q.corner + q.edge2, q.corner + q.edge1 + q.edge2},
                             q.normal(), q.area(), q.material);
                        break;
                    }
                    case ShapeKind::kDisk: {
                        const Disk& d = scene.disks[l.index];
                        const Normal3 n = d.normal;
                        const Vector3 e{d.radius * std::sqrt(std::max(0.0f, 1 - n.x * n.x)),
                                        d.radius * std::sqrt(std::max(0.0f, 1 - n.y * n.y)),
                                        d.radius * std::sqrt(std::max(0.0f, 1 - n.z * n.z))};
                        flat(std::array{d.center - e, d.center + e}, n, d.area(), d.material);
                        break;
                    }
                    case ShapeKind::kTriangle: {
                        const Triangle& t = scene.triangles[l.index];
                        flat(std::array{t.p0, t.p1, t.p2}, t.normal(), t.area(), t.material);
                        break;
                    }
                    case ShapeKind::kMesh: {
                        const Triangle t = scene.world_triangle(l.index, l.prim);
                        flat(std::array{t.p0, t.p1, t.p2}, t.normal(), t.area(), t.material);
                        if (scene.motion_of(l.kind, l.index)) {  // swept below, from object space
                            const Instance& in = scene.instances[l.index];
                            const auto [p0, p1, p2] = scene.meshes[in.mesh].vertices(l.prim);
                            b.box = Bounds3{};
                            for (const Point3& q : {p0, p1, p2}) b.box.extend(q);
                        }
                        break;
                    }
                    case ShapeKind::kPlane: break;
                }
            }
            if constexpr (std::is_same_v<T, AreaLight>) {
                // A moving light (its box in object space) is bounded over the whole shutter,
                // facing every way.
                if (const Motion* m = scene.motion_of(l.kind, l.index)) {
                    b.box = m->swept_bounds(b.box);
                    b.phi *= placed_area_scale(scene, l.kind, l.index);
                    b.cos_o = -1;
                    b.two_sided = true;
                }
            }
            if (!is_finite(b.w) || !(dot(b.w, b.w) > 0)) b.w = {0, 0, 1}, b.cos_o = -1;
            return b;
        },
        light);
}

}  // namespace

void LightSampler::build(const Scene& scene, float radius, LightSamplerKind sampler_kind) {
    kind_ = sampler_kind;
    lights_ = scene.lights;
    for (auto& v : shape_light_) v.clear();
    const auto add_area = [&](ShapeKind kind, const auto& shapes) {
        auto& map = shape_light_[static_cast<std::size_t>(kind)];
        for (std::uint32_t i = 0; i < shapes.size(); ++i) {
            if (!scene.emission_of(shapes[i].material).emits()) continue;
            if (map.empty()) map.assign(shapes.size(), kNoLight);
            map[i] = static_cast<std::uint32_t>(lights_.size());
            lights_.emplace_back(AreaLight{kind, i});
        }
    };
    add_area(ShapeKind::kSphere, scene.spheres);
    add_area(ShapeKind::kQuad, scene.quads);
    add_area(ShapeKind::kDisk, scene.disks);
    add_area(ShapeKind::kTriangle, scene.triangles);
    instance_first_.assign(scene.instances.size(), kNoLight);
    mesh_light_.clear();
    for (std::uint32_t i = 0; i < scene.instances.size(); ++i) {
        const TriangleMesh& m = scene.meshes[scene.instances[i].mesh];
        for (std::uint32_t t = 0; t < m.triangle_count(); ++t) {
            if (!scene.emission_of(scene.instance_material(i, t)).emits()) continue;
            if (instance_first_[i] == kNoLight) {
                instance_first_[i] = static_cast<std::uint32_t>(mesh_light_.size());
                mesh_light_.resize(mesh_light_.size() + m.triangle_count(), kNoLight);
            }
            mesh_light_[instance_first_[i] + t] = static_cast<std::uint32_t>(lights_.size());
            lights_.emplace_back(AreaLight{ShapeKind::kMesh, i, t});
        }
    }

    const float disk_area = kPi * radius * radius;
    std::vector<float> power;
    distant_.clear();
    for (std::uint32_t i = 0; i < lights_.size(); ++i) {
        power.push_back(std::visit(
            [&](const auto& l) -> float {
                using T = std::decay_t<decltype(l)>;
                if constexpr (std::is_same_v<T, DirectionalLight>) {
                    if (l.soft()) distant_.push_back(i);
                    return disk_area * luminance(l.intensity);
                } else if constexpr (std::is_same_v<T, PointLight>) {
                    return 4 * kPi * luminance(l.intensity);
                } else if constexpr (std::is_same_v<T, SpotLight>) {
                    return 2 * kPi * luminance(l.intensity) *
                           (1 - 0.5f * (l.cos_inner + l.cos_outer));
                } else {
                    static_assert(std::is_same_v<T, AreaLight>);
                    float area = 0;
                    MaterialId material = 0;
                    switch (l.kind) {
                        case ShapeKind::kSphere: area = scene.spheres[l.index].area(); material = scene.spheres[l.index].material; break;
                        case ShapeKind::kQuad: area = scene.quads[l.index].area(); material = scene.quads[l.index].material; break;
                        case ShapeKind::kDisk: area = scene.disks[l.index].area(); material = scene.disks[l.index].material; break;
                        case ShapeKind::kTriangle: area = scene.triangles[l.index].area(); material = scene.triangles[l.index].material; break;
                        case ShapeKind::kMesh: {
                            const Triangle t = scene.world_triangle(l.index, l.prim);
                            area = t.area();
                            material = t.material;
                            break;
                        }
                        case ShapeKind::kPlane: break;
                    }
                    area *= placed_area_scale(scene, l.kind, l.index);
                    const Emission& e = scene.emission_of(material);
                    return kPi * area * luminance(e.radiance) * (e.two_sided ? 2.0f : 1.0f);
                }
            },
            lights_[i]));
    }
    const float env = env_power_density(scene.background);
    env_ = env > 0;
    if (env_) {
        power.push_back(4 * kPi * disk_area * env);
        distant_.push_back(static_cast<std::uint32_t>(lights_.size()));
    }
    if (power.empty()) power.push_back(0);  // no lights: count() is 0 and nothing is picked
    distribution_ = Distribution1D(power);

    bvh_ = LightBvh{};
    distant_lights_.clear();
    distant_slot_.assign(count(), kNoLight);
    p_distant_ = 0;
    if (kind_ != LightSamplerKind::kBvh) return;
    std::vector<LightBounds> bounds(lights_.size());
    std::vector<float> distant_power;
    for (std::uint32_t i = 0; i < lights_.size(); ++i) {
        if (std::holds_alternative<DirectionalLight>(lights_[i])) {
            distant_slot_[i] = static_cast<std::uint32_t>(distant_lights_.size());
            distant_lights_.push_back(i);
            distant_power.push_back(power[i]);
        } else {
            bounds[i] = light_bounds(scene, lights_[i]);
            if (i < scene.light_motion.size() && scene.light_motion[i] >= 0) {
                // Over the whole shutter: the keys carry the light from the origin; a spot that
                // turns may shine anywhere.
                const Motion& m = scene.motions[static_cast<std::size_t>(scene.light_motion[i])];
                Bounds3 origin;
                origin.extend(Point3{0, 0, 0});
                bounds[i].box = m.swept_bounds(origin);
                for (std::size_t k = 0; k < m.key_count(); ++k) {
                    if (!(m.key(k).vector(bounds[i].w) == bounds[i].w)) {
                        bounds[i].cos_o = -1;
                        bounds[i].cos_e = 0;
                    }
                }
            }
        }
    }
    if (env_) {
        distant_slot_[lights_.size()] = static_cast<std::uint32_t>(distant_lights_.size());
        distant_lights_.push_back(static_cast<std::uint32_t>(lights_.size()));
        distant_power.push_back(power.back());
    }
    bvh_.build(bounds);
    if (!distant_lights_.empty()) {
        const auto n = static_cast<float>(distant_lights_.size());
        p_distant_ = bvh_.empty() ? 1.0f : n / (n + 1);
        distant_distribution_ = Distribution1D(distant_power);
    }
}

std::uint32_t LightSampler::pick(float u, float* pmf) const {
    const std::uint32_t i = distribution_.sample(u);
    if (pmf) *pmf = distribution_.pmf(i);
    return i;
}

std::uint32_t LightSampler::pick(Point3 p, Normal3 n, float u, float* pmf) const {
    if (kind_ == LightSamplerKind::kPower) return pick(u, pmf);
    constexpr float kOneMinusEpsilon = 0x1.fffffep-1f;
    if (u < p_distant_) {
        const std::uint32_t i = distant_distribution_.sample(std::min(u / p_distant_, kOneMinusEpsilon));
        *pmf = p_distant_ * distant_distribution_.pmf(i);
        return distant_lights_[i];
    }
    float bvh_pmf = 0;
    const std::uint32_t l =
        bvh_.sample(p, n, std::min((u - p_distant_) / (1 - p_distant_), kOneMinusEpsilon), &bvh_pmf);
    *pmf = (1 - p_distant_) * bvh_pmf;
    return l;
}

float LightSampler::pmf(Point3 p, Normal3 n, std::uint32_t light) const {
    if (kind_ == LightSamplerKind::kPower) return pmf(light);
    if (light < distant_slot_.size() && distant_slot_[light] != kNoLight)
        return p_distant_ * distant_distribution_.pmf(distant_slot_[light]);
    return (1 - p_distant_) * bvh_.pmf(p, n, light);
}

std::optional<LightLiSample> LightSampler::sample_li(const Scene& scene, std::uint32_t light,
                                                     Point3 p, Sample2 u, Float time) const {
    // A moving analytic shape is sampled where it is stored (object space), from the point
    // carried there; its placement is a similarity, which keeps solid angles (and so the
    // density) as they are.
    if (const auto* area = light < lights_.size() ? std::get_if<AreaLight>(&lights_[light]) : nullptr;
        area && area->kind != ShapeKind::kMesh && scene.has_motion()) {
        if (const Motion* m = scene.motion_of(area->kind, area->index)) {
            const Transform d = m->at(time);
            auto ls = sample_li_stored(scene, light, d.to_object.apply(p), u, time);
            if (!ls) return ls;
            ls->p_light = d.point(ls->p_light);
            ls->n_light = normalize(d.normal(ls->n_light));
            const Vector3 to = ls->p_light - p;
            ls->distance = length(to);
            ls->wi = to / ls->distance;
            // An emission texture is read at the moved point (Scene::uv carries it back).
            MaterialId material = 0;
            switch (area->kind) {
                case ShapeKind::kSphere: material = scene.spheres[area->index].material; break;
                case ShapeKind::kQuad: material = scene.quads[area->index].material; break;
                case ShapeKind::kDisk: material = scene.disks[area->index].material; break;
                case ShapeKind::kTriangle: material = scene.triangles[area->index].material; break;
                default: break;
            }
            ls->L = scene.light_radiance(*area, material, ls->p_light, ls->n_light, time);
            return ls;
        }
    }
    return sample_li_stored(scene, light, p, u, time);
}

// The sample is written field by field into the caller's object (the optional below is the
// return value itself): built as a temporary and copied, its mixed float and byte fields went
// through the stack in pieces and were read back 16 bytes at a time, a failed store-to-load
// forward each (docs/performance.md, step 5).
std::optional<LightLiSample> LightSampler::sample_li_stored(const Scene& scene, std::uint32_t light, Point3 p,
                                                            Sample2 u, Float time) const {
    std::optional<LightLiSample> result{std::in_place};
    if (!sample_li_into(scene, light, p, u, time, *result)) result.reset();
    return result;
}

bool LightSampler::sample_li_into(const Scene& scene, std::uint32_t light, Point3 p, Sample2 u, Float time,
                                  LightLiSample& s) const {
    constexpr float kInfinity = std::numeric_limits<float>::infinity();
    if (light == environment()) {
        s.distance = kInfinity;
        s.spectrum = scene.background_spectrum();
        return std::visit(
            [&](const auto& b) {
                using T = std::decay_t<decltype(b)>;
                if constexpr (std::is_same_v<T, EnvironmentMap>) {
                    float pdf_uv = 0;
                    const Point2 uv = b.distribution.sample(u, &pdf_uv);
                    const float sin_theta = std::sin(uv.y * kPi);
                    if (pdf_uv <= 0 || sin_theta <= 0) return false;
                    s.wi = EnvironmentMap::uv_to_direction(uv);
                    s.L = b.eval(s.wi);
                    s.pdf = pdf_uv / (2 * kPi * kPi * sin_theta);
                } else {
                    s.wi = sample_uniform_sphere(u);
                    s.L = b.eval(s.wi);
                    s.pdf = kUniformSpherePdf;
                }
                return true;
            },
            scene.background);
    }
    // A moving point or spot light where it is at `time` (a copy only then).
    const Light* chosen = light < lights_.size() ? &lights_[light] : nullptr;
    Light moved;
    if (light < scene.light_motion.size() && scene.light_motion[light] >= 0) {
        moved = scene.light_at(light, time);
        chosen = &moved;
    }
    const bool found = std::visit(
        [&](const auto& l) {
            using T = std::decay_t<decltype(l)>;
            if constexpr (std::is_same_v<T, DirectionalLight>) {
                s.distance = kInfinity;
                if (!l.soft()) {
                    s.L = l.intensity;
                    s.wi = -l.direction;
                    s.pdf = 1;
                    s.delta = true;
                    return true;
                }
                s.wi = from_frame(-l.direction, sample_uniform_cone(u, l.one_minus_cos));
                s.L = l.intensity / (kPi * l.sin2_half_angle());
                s.pdf = uniform_cone_pdf(l.one_minus_cos);
                return true;
            } else if constexpr (std::is_same_v<T, AreaLight>) {
                s.on_surface = true;
                MaterialId material = 0;
                if (l.kind == ShapeKind::kSphere) {
                    const Sphere& sphere = scene.spheres[l.index];
                    material = sphere.material;
                    const float omc = sphere_cone(sphere, p);
                    if (omc > 0) {
                        const Vector3 axis = normalize(sphere.center - p);
                        const Vector3 wi = from_frame(axis, sample_uniform_cone(u, omc));
                        const auto t = sphere.intersect(Ray{p, wi});
                        // Grazing the silhouette, rounding can miss: take the closest approach.
                        const Point3 q = p + wi * (t ? *t : dot(sphere.center - p, wi));
                        const Normal3 n = normalize(Normal3(q - sphere.center));
                        const Emission& e = scene.emission_of(material);
                        if (!(e.two_sided || dot(n, wi) < 0)) return false;
                        s.L = scene.light_radiance(l, material, q, n, time);
                        s.wi = wi;
                        s.pdf = uniform_cone_pdf(omc);
                        s.distance = length(q - p);
                        s.p_light = q;
                        s.n_light = n;
                        s.spectrum = e.spectrum.get();
                        return true;
                    }
                }
                // The point and normal go straight to the sample (through a local AreaSample
                // merged across the cases, GCC moved them in overlapping pieces again).
                float area = 1;
                const auto from = [&](const auto& shape) {
                    const AreaSample a = shape.sample_area(u);
                    s.p_light = a.p;
                    s.n_light = a.n;
                    area = shape.area();
                    material = shape.material;
                };
                switch (l.kind) {
                    case ShapeKind::kSphere: from(scene.spheres[l.index]); break;
                    case ShapeKind::kQuad: from(scene.quads[l.index]); break;
                    case ShapeKind::kDisk: from(scene.disks[l.index]); break;
                    case ShapeKind::kTriangle: from(scene.triangles[l.index]); break;
                    case ShapeKind::kMesh: from(scene.world_triangle(l.index, l.prim, time)); break;
                    case ShapeKind::kPlane: return false;
                }
                const Vector3 d = s.p_light - p;
                const float dist2 = dot(d, d);
                if (!(dist2 > 0)) return false;
                const float dist = std::sqrt(dist2);
                const Vector3 wi = d / dist;
                const float cos_l = dot(s.n_light, wi);  // < 0: the light faces p
                const Emission& e = scene.emission_of(material);
                if (!(e.two_sided ? cos_l != 0 : cos_l < 0)) return false;
                s.L = scene.light_radiance(l, material, s.p_light, s.n_light, time);
                s.wi = wi;
                s.pdf = dist2 / (std::abs(cos_l) * area);
                s.distance = dist;
                s.spectrum = e.spectrum.get();
                return true;
            } else {
                const LightSample ps = l.sample(p);
                s.L = ps.intensity;
                s.wi = ps.to_light;
                s.pdf = 1;
                s.distance = ps.distance;
                s.delta = true;
                return true;
            }
        },
        *chosen);
    if (found && !s.spectrum) s.spectrum = scene.light_spectrum(light);
    return found;
}

float LightSampler::pdf_li(const Scene& scene, std::uint32_t light, Point3 p, Vector3 wi,
                           Point3 on_light, Float time) const {
    if (const auto* area = light < lights_.size() ? std::get_if<AreaLight>(&lights_[light]) : nullptr;
        area && area->kind != ShapeKind::kMesh && scene.has_motion()) {
        if (const Motion* m = scene.motion_of(area->kind, area->index)) {
            const Transform d = m->at(time);
            return pdf_li_stored(scene, light, d.to_object.apply(p), normalize(d.to_object.apply(wi)),
                                 d.to_object.apply(on_light), time);
        }
    }
    return pdf_li_stored(scene, light, p, wi, on_light, time);
}

float LightSampler::pdf_li_stored(const Scene& scene, std::uint32_t light, Point3 p, Vector3 wi, Point3 on_light,
                                  Float time) const {
    if (light == environment()) {
        return std::visit(
            [&](const auto& b) -> float {
                using T = std::decay_t<decltype(b)>;
                if constexpr (std::is_same_v<T, EnvironmentMap>) {
                    const Point2 uv = EnvironmentMap::direction_to_uv(wi);
                    const float sin_theta = std::sin(uv.y * kPi);
                    if (!(sin_theta > 0)) return 0;
                    return b.distribution.pdf(uv) / (2 * kPi * kPi * sin_theta);
                } else {
                    return kUniformSpherePdf;
                }
            },
            scene.background);
    }
    return std::visit(
        [&](const auto& l) -> float {
            using T = std::decay_t<decltype(l)>;
            if constexpr (std::is_same_v<T, DirectionalLight>) {
                if (!l.soft()) return 0;
                return 1 + dot(wi, sun_direction(scene, light, l, time)) <= l.one_minus_cos
                           ? uniform_cone_pdf(l.one_minus_cos)
                           : 0;
            } else if constexpr (std::is_same_v<T, AreaLight>) {
                float area = 1;
                Normal3 n{0, 1, 0};
                switch (l.kind) {
                    case ShapeKind::kSphere: {
                        const Sphere& s = scene.spheres[l.index];
                        const float omc = sphere_cone(s, p);
                        if (omc > 0) return uniform_cone_pdf(omc);
                        area = s.area();
                        n = s.normal_at(on_light);
                        break;
                    }
                    case ShapeKind::kQuad: area = scene.quads[l.index].area(); n = scene.quads[l.index].normal(); break;
                    case ShapeKind::kDisk: area = scene.disks[l.index].area(); n = scene.disks[l.index].normal; break;
                    case ShapeKind::kTriangle: area = scene.triangles[l.index].area(); n = scene.triangles[l.index].normal(); break;
                    case ShapeKind::kMesh: {
                        const Triangle t = scene.world_triangle(l.index, l.prim, time);
                        area = t.area();
                        n = t.normal();
                        break;
                    }
                    case ShapeKind::kPlane: return 0;
                }
                const Vector3 d = on_light - p;
                const float cos_l = std::abs(dot(n, wi));
                return cos_l > 0 ? dot(d, d) / (cos_l * area) : 0;
            } else {
                return 0;  // delta lights are never hit
            }
        },
        lights_[light]);
}

Color LightSampler::distant_radiance(const Scene& scene, std::uint32_t light, Vector3 d, Float time) const {
    if (light == environment()) return evaluate(scene.background, d);
    if (const auto* sun = std::get_if<DirectionalLight>(&lights_[light])) {
        if (sun->soft() && 1 + dot(d, sun_direction(scene, light, *sun, time)) <= sun->one_minus_cos)
            return sun->intensity / (kPi * sun->sin2_half_angle());
    }
    return Color{0};
}

}  // namespace glint
