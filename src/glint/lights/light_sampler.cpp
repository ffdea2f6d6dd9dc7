#include "glint/lights/light_sampler.h"

#include <cmath>
#include <numbers>
#include <type_traits>

#include "glint/math/frame.h"
#include "glint/samplers/warp.h"
#include "glint/scene.h"

namespace glint {

namespace {

constexpr float kPi = std::numbers::pi_v<float>;

float luminance(Color c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; }

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

}  // namespace

void LightSampler::build(const Scene& scene, float radius) {
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
}

std::uint32_t LightSampler::pick(float u, float* pmf) const {
    const std::uint32_t i = distribution_.sample(u);
    if (pmf) *pmf = distribution_.pmf(i);
    return i;
}

std::optional<LightLiSample> LightSampler::sample_li(const Scene& scene, std::uint32_t light,
                                                     Point3 p, Sample2 u) const {
    if (light == environment()) {
        return std::visit(
            [&](const auto& b) -> std::optional<LightLiSample> {
                using T = std::decay_t<decltype(b)>;
                if constexpr (std::is_same_v<T, EnvironmentMap>) {
                    float pdf_uv = 0;
                    const Point2 uv = b.distribution.sample(u, &pdf_uv);
                    const float sin_theta = std::sin(uv.y * kPi);
                    if (pdf_uv <= 0 || sin_theta <= 0) return std::nullopt;
                    const Vector3 wi = EnvironmentMap::uv_to_direction(uv);
                    return LightLiSample{b.eval(wi), wi, pdf_uv / (2 * kPi * kPi * sin_theta),
                                         std::numeric_limits<float>::infinity()};
                } else {
                    const Vector3 wi = sample_uniform_sphere(u);
                    return LightLiSample{b.eval(wi), wi, kUniformSpherePdf,
                                         std::numeric_limits<float>::infinity()};
                }
            },
            scene.background);
    }
    return std::visit(
        [&](const auto& l) -> std::optional<LightLiSample> {
            using T = std::decay_t<decltype(l)>;
            if constexpr (std::is_same_v<T, DirectionalLight>) {
                if (!l.soft()) return LightLiSample{l.intensity, -l.direction, 1,
                                                    std::numeric_limits<float>::infinity(), true};
                const Vector3 wi = from_frame(-l.direction, sample_uniform_cone(u, l.one_minus_cos));
                return LightLiSample{l.intensity / (kPi * l.sin2_half_angle()), wi,
                                     uniform_cone_pdf(l.one_minus_cos),
                                     std::numeric_limits<float>::infinity()};
            } else if constexpr (std::is_same_v<T, AreaLight>) {
                Point3 q;
                Normal3 n;
                float pdf = 0;
                MaterialId material = 0;
                if (l.kind == ShapeKind::kSphere) {
                    const Sphere& s = scene.spheres[l.index];
                    material = s.material;
                    const float omc = sphere_cone(s, p);
                    if (omc > 0) {
                        const Vector3 axis = normalize(s.center - p);
                        const Vector3 wi = from_frame(axis, sample_uniform_cone(u, omc));
                        const auto t = s.intersect(Ray{p, wi});
                        // Grazing the silhouette, rounding can miss: take the closest approach.
                        q = p + wi * (t ? *t : dot(s.center - p, wi));
                        n = normalize(Normal3(q - s.center));
                        pdf = uniform_cone_pdf(omc);
                        if (!(scene.emission_of(material).two_sided || dot(n, wi) < 0)) return std::nullopt;
                        return LightLiSample{scene.light_radiance(l, material, q, n), wi, pdf, length(q - p), false, true, q, n};
                    }
                }
                float area = 1;
                const auto from = [&](const auto& shape) {
                    const AreaSample a = shape.sample_area(u);
                    q = a.p;
                    n = a.n;
                    area = shape.area();
                    material = shape.material;
                };
                switch (l.kind) {
                    case ShapeKind::kSphere: from(scene.spheres[l.index]); break;
                    case ShapeKind::kQuad: from(scene.quads[l.index]); break;
                    case ShapeKind::kDisk: from(scene.disks[l.index]); break;
                    case ShapeKind::kTriangle: from(scene.triangles[l.index]); break;
                    case ShapeKind::kMesh: from(scene.world_triangle(l.index, l.prim)); break;
                    case ShapeKind::kPlane: return std::nullopt;
                }
                const Vector3 d = q - p;
                const float dist2 = dot(d, d);
                if (!(dist2 > 0)) return std::nullopt;
                const float dist = std::sqrt(dist2);
                const Vector3 wi = d / dist;
                const float cos_l = dot(n, wi);  // < 0: the light faces p
                const Emission& e = scene.emission_of(material);
                if (!(e.two_sided ? cos_l != 0 : cos_l < 0)) return std::nullopt;
                pdf = dist2 / (std::abs(cos_l) * area);
                return LightLiSample{scene.light_radiance(l, material, q, n), wi, pdf, dist, false, true, q, n};
            } else {
                const LightSample s = l.sample(p);
                return LightLiSample{s.intensity, s.to_light, 1, s.distance, true};
            }
        },
        lights_[light]);
}

float LightSampler::pdf_li(const Scene& scene, std::uint32_t light, Point3 p, Vector3 wi,
                           Point3 on_light) const {
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
                return 1 + dot(wi, l.direction) <= l.one_minus_cos ? uniform_cone_pdf(l.one_minus_cos)
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
                        const Triangle t = scene.world_triangle(l.index, l.prim);
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

Color LightSampler::distant_radiance(const Scene& scene, std::uint32_t light, Vector3 d) const {
    if (light == environment()) return evaluate(scene.background, d);
    if (const auto* sun = std::get_if<DirectionalLight>(&lights_[light])) {
        if (sun->soft() && 1 + dot(d, sun->direction) <= sun->one_minus_cos)
            return sun->intensity / (kPi * sun->sin2_half_angle());
    }
    return Color{0};
}

}  // namespace glint
