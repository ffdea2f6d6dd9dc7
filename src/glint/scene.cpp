#include "glint/scene.h"

#include <bit>
#include <numbers>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <type_traits>

#include <xmmintrin.h>

#include "glint/accel/embree.h"
#include "glint/math/snap.h"
#include "glint/samplers/hash.h"
#include "glint/shapes/triangle_sse.h"

namespace glint {

namespace {

// The typed loops: one per shape kind, no per-primitive dispatch.
template <ShapeKind kKind, typename Shape>
void closest_hit(const std::vector<Shape>& shapes, Ray& ray, std::optional<Hit>& best) {
    for (std::uint32_t i = 0; i < shapes.size(); ++i) {
        if (auto t = shapes[i].intersect(ray)) {
            ray.t_max = *t;
            best = Hit{*t, kKind, i};
        }
    }
}

template <typename Shape>
bool any_hit(const std::vector<Shape>& shapes, const Ray& ray) {
    for (const Shape& s : shapes)
        if (s.intersect(ray)) return true;
    return false;
}

// Triangles share the per-ray part of the watertight test.
void closest_hit_triangles(const std::vector<Triangle>& triangles, Ray& ray, std::optional<Hit>& best) {
    if (triangles.empty()) return;
    WatertightRay r(ray);
    const std::uint32_t n = static_cast<std::uint32_t>(triangles.size());
    for (std::uint32_t i = 0; i < n; ++i) {
        if (auto t = triangles[i].intersect(r)) {
            r.t_max = ray.t_max = *t;
            best = Hit{*t, ShapeKind::kTriangle, i};
        }
    }
}

bool any_hit_triangles(const std::vector<Triangle>& triangles, const Ray& ray) {
    if (triangles.empty()) return false;
    const WatertightRay r(ray);
    for (const Triangle& t : triangles)
        if (t.intersect(r)) return true;
    return false;
}

// Top-level primitive references: the kind in the top 3 bits, the index below.
constexpr int kRefShift = 29;
constexpr std::uint32_t kRefMask = (1u << kRefShift) - 1;
// The kind bits of a moving analytic shape's reference (its index is into Scene::moving_shapes).
constexpr std::uint32_t kMovingRef = 7;
std::uint32_t make_ref(ShapeKind k, std::uint32_t i) { return static_cast<std::uint32_t>(k) << kRefShift | i; }

template <typename Shape>
void closest_one(const Shape& s, ShapeKind kind, std::uint32_t i, Ray& ray, std::optional<Hit>& best) {
    if (auto t = s.intersect(ray)) {
        ray.t_max = *t;
        best = Hit{*t, kind, i};
    }
}

}  // namespace

const char* accel_name(AccelKind kind) {
    switch (kind) {
        case AccelKind::kBvh: return "bvh";
        case AccelKind::kSbvh: return "sbvh";
        case AccelKind::kEmbree: return "embree";
    }
    return "?";
}

void Scene::commit() {
    if (bounded_count() > kRefMask) throw std::length_error("too many shapes and instances for one scene");
    index_motion();
    constant_reflectance_.assign(textures.size(), std::nullopt);
    for (std::size_t t = 0; t < textures.size(); ++t)
        if (const auto* c = std::get_if<ConstantTexture>(&textures[t])) constant_reflectance_[t].emplace(c->value);
    triangle_normals_.resize(triangles.size());
    for (std::size_t t = 0; t < triangles.size(); ++t) triangle_normals_[t] = triangles[t].normal();
    // Bottom level: one BVH per mesh (not built when Embree replaces both levels, so that what
    // the Embree backend's build costs is Embree's alone).
    const bool ours = accel != AccelKind::kEmbree;
    BvhBuildOptions mesh_options;
    mesh_options.spatial_splits = accel == AccelKind::kSbvh;
    mesh_bvhs_.assign(ours ? meshes.size() : 0, MeshBvh{});
    const SimdIsa isa = mesh_isa ? *mesh_isa : default_simd_isa();
    for (std::size_t m = 0; m < mesh_bvhs_.size(); ++m) mesh_bvhs_[m].build(meshes[m], mesh_options, isa);
    // Spheres alone (beside planes), a few dozen at most: every sphere tested at once in SIMD
    // lanes, no traversal (accel/sphere_set.h).
    sphere_set_ = SphereSet{};
    if (ours && !spheres.empty() && spheres.size() <= SphereSet::kMaxSpheres && quads.empty() && disks.empty() &&
        triangles.empty() && instances.empty() && moving_shapes.empty())
        sphere_set_.build(spheres, isa);
    const auto mesh_bounds = [&](std::uint32_t m) {
        if (ours) return mesh_bvhs_[m].bounds();
        Bounds3 b;  // the triangles' (as the BVH's; unused vertices left out)
        for (std::uint32_t t = 0; t < meshes[m].triangle_count(); ++t)
            for (const Point3& p : meshes[m].vertices(t))
                if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) b.extend(p);
        return b;
    };

    // Top level: every bounded shape and every instance.
    std::vector<Bounds3> boxes;
    std::vector<std::uint32_t> refs;
    boxes.reserve(bounded_count());
    refs.reserve(bounded_count());
    // The scene's extent is the union of the exact boxes; the tree's boxes of spheres, quads and
    // disks are padded for their tests' rounding (math/bounds.h), so that the tree culls no hit
    // the shape's own test accepts.
    Bounds3 extent;
    const auto include = [&](const Bounds3& b) {
        if (!b.finite()) return;  // as the tree skips it
        extent.extend(b.lo);
        extent.extend(b.hi);
    };
    // A moving shape enters once, as a moving reference bounded over the whole shutter.
    const auto add = [&](ShapeKind k, std::uint32_t i, const Bounds3& b) {
        if (k != ShapeKind::kMesh && motion_of(k, i)) return;
        boxes.push_back(padded_for_rounding(k) ? padded_for_rounding(b) : b);
        refs.push_back(make_ref(k, i));
        include(b);
    };
    for (std::uint32_t i = 0; i < spheres.size(); ++i)
        add(ShapeKind::kSphere, i, ball_bounds(spheres[i].center, spheres[i].radius));
    for (std::uint32_t i = 0; i < quads.size(); ++i) add(ShapeKind::kQuad, i, quads[i].bounds());
    for (std::uint32_t i = 0; i < disks.size(); ++i)
        add(ShapeKind::kDisk, i, ball_bounds(disks[i].center, disks[i].radius));
    for (std::uint32_t i = 0; i < triangles.size(); ++i) {
        Bounds3 b;
        b.extend(triangles[i].p0);
        b.extend(triangles[i].p1);
        b.extend(triangles[i].p2);
        add(ShapeKind::kTriangle, i, b);
    }
    for (std::uint32_t i = 0; i < instances.size(); ++i) {
        const Instance& inst = instances[i];
        if (inst.mesh >= meshes.size()) throw std::out_of_range("instance of a mesh that does not exist");
        const Bounds3 local = mesh_bounds(inst.mesh);
        const Motion* moving = motion_of(ShapeKind::kMesh, i);
        add(ShapeKind::kMesh, i,
            local.empty() ? Bounds3{} : moving ? moving->swept_bounds(local) : inst.transform.bounds(local));
    }
    for (std::uint32_t m = 0; m < moving_shapes.size(); ++m) {
        boxes.push_back(moving_bounds(m));
        refs.push_back(kMovingRef << kRefShift | m);
        include(moving_bounds(m, false));
    }
    BvhBuildOptions top_options;
    // Leaves of two (measured best on the Cornell box, docs/performance.md), but an instance
    // costs far more to enter than a node test: it has a leaf of its own, so that its box is
    // tested before its transform and traversal set-up are paid.
    top_options.max_leaf_size = 2;
    std::vector<std::uint8_t> alone(refs.size());
    for (std::size_t i = 0; i < refs.size(); ++i)
        alone[i] = (refs[i] >> kRefShift) == static_cast<std::uint32_t>(ShapeKind::kMesh);
    top_options.alone = alone;
    top_.build(boxes, top_options);
    top_refs_.resize(top_.order().size());
    for (std::size_t i = 0; i < top_refs_.size(); ++i) top_refs_[i] = refs[top_.order()[i]];
    bounds_ = extent;

    embree_.reset();
    if (accel == AccelKind::kEmbree) {
#if GLINT_EMBREE
        embree_ = std::make_shared<const EmbreeAccel>(*this);
#else
        throw std::runtime_error("this glint was built without Embree (configure with -DGLINT_EMBREE=ON)");
#endif
    }
    committed_count_ = bounded_count();
    has_interfaces_ = std::any_of(materials.begin(), materials.end(), [](const Material& m) {
        return std::holds_alternative<InterfaceMaterial>(m);
    });
    has_media_ = !media.empty() || has_interfaces_ ||
                 std::any_of(medium_interfaces.begin(), medium_interfaces.end(),
                             [](const auto& m) { return m.has_value(); });

    const float radius = bounds_.empty() ? 1.0f : 0.5f * length(bounds_.hi - bounds_.lo);
    light_sampler_.build(*this, std::max(radius, 1e-3f), light_sampling);
    // What each texture reads: uv (images), the vertex colour, or what its children read.
    // Children come before their parents (build adds them first), so one forward pass settles
    // every entry.
    texture_reads_.assign(textures.size(), 0);
    for (std::size_t i = 0; i < textures.size(); ++i) {
        texture_reads_[i] = std::visit(
            [&](const auto& t) -> std::uint8_t {
                using T = std::decay_t<decltype(t)>;
                if constexpr (std::is_same_v<T, ImageTexture>) {
                    const std::uint8_t filtered = t.filtered() ? kReadsFootprint : 0;
                    return std::uint8_t((t.uv_set == 0 ? kReadsUv : kReadsUv | kReadsMoreUvs) | filtered);
                }
                if constexpr (std::is_same_v<T, CheckerTexture>) return std::uint8_t(t.on_uv ? kReadsUv | kReadsFootprint : kReadsFootprint);
                if constexpr (std::is_same_v<T, VertexColorTexture>) return kReadsVertexColor;
                if constexpr (std::is_same_v<T, ScaleTexture>)
                    return texture_reads_[t.texture] | texture_reads_[t.factor];
                if constexpr (std::is_same_v<T, MixTexture>)
                    return texture_reads_[t.a] | texture_reads_[t.b] | texture_reads_[t.amount];
                return 0;
            },
            textures[i]);
    }
    // The environment map's pyramid, for what the camera sees of it (background_seen).
    env_pyramid_ = MipPyramid{};
    if (const auto* env = std::get_if<EnvironmentMap>(&background); env && footprint)
        env_pyramid_ = MipPyramid::build(env->image);
    // The pyramids of the images that filtered textures read (a third more texels each).
    pyramids_.assign(images.size(), MipPyramid{});
    for (const Texture& t : textures) {
        const auto* image = std::get_if<ImageTexture>(&t);
        if (!image || !image->filtered() || image->image >= images.size()) continue;
        MipPyramid& p = pyramids_[image->image];
        if (p.levels.empty()) p = MipPyramid::build(images[image->image]);
    }
}

namespace {

struct AlphaContext {
    const Scene* scene;
    std::uint32_t instance;
    const Ray* ray;
};

bool alpha_filter(const void* context, std::uint32_t prim, float b1, float b2) {
    const auto* c = static_cast<const AlphaContext*>(context);
    return c->scene->alpha_keeps(c->instance, prim, b1, b2, *c->ray);
}

}  // namespace

float Scene::mask_alpha(std::uint32_t instance, std::uint32_t prim, float b1, float b2) const {
    const Instance& inst = instances[instance];
    const AlphaMask& mask = alpha_masks[static_cast<std::size_t>(inst.alpha)];
    const TriangleMesh& mesh = meshes[inst.mesh];
    const auto [p0, p1, p2] = mesh.vertices(prim);
    SurfaceInteraction si;
    si.p = inst.transform.point(p0 + ((p1 - p0) * b1 + (p2 - p0) * b2));
    si.shape = ShapeKind::kMesh;
    si.shape_index = instance;
    si.prim = prim;
    si.bary = {b1, b2};
    si.material = inst.material.value_or(mesh.material_of(prim));
    return average(texture(mask.texture, si));
}

float Scene::alpha_coverage(std::uint32_t instance, std::uint32_t prim, float b1, float b2) const {
    const Instance& inst = instances[instance];
    if (inst.alpha < 0) return 1;
    const AlphaMask& mask = alpha_masks[static_cast<std::size_t>(inst.alpha)];
    const float a = mask_alpha(instance, prim, b1, b2);
    if (!mask.stochastic) return a >= mask.cutoff ? 1.0f : 0.0f;
    return a > 0 ? std::min(a, 1.0f) : 0.0f;
}

bool Scene::alpha_keeps(std::uint32_t instance, std::uint32_t prim, float b1, float b2, const Ray& ray) const {
    const Instance& inst = instances[instance];
    if (inst.alpha < 0) return true;
    const AlphaMask& mask = alpha_masks[static_cast<std::size_t>(inst.alpha)];
    const float a = mask_alpha(instance, prim, b1, b2);
    if (!mask.stochastic) return a >= mask.cutoff;
    if (a >= 1) return true;
    if (!(a > 0)) return false;
    std::uint32_t h = prim;
    for (const float v : {ray.origin.x, ray.origin.y, ray.origin.z, ray.direction.x, ray.direction.y, ray.direction.z})
        h = hash_combine(h, std::bit_cast<std::uint32_t>(v));
    return to_unit_float(h) < a;
}

std::optional<MeshHit> Scene::closest_instance(std::uint32_t i, const Ray& ray) const {
    const Instance& inst = instances[i];
    const Ray local = inst.motion < 0 ? object_ray(inst.transform, ray) : object_ray(placement(i, ray.time), ray);
    if (inst.alpha >= 0) {
        const AlphaContext context{this, i, &ray};
        const HitFilter filter{alpha_filter, &context};
        return mesh_bvhs_[inst.mesh].closest(local, &filter);
    }
    return mesh_bvhs_[inst.mesh].closest(local);
}

bool Scene::any_instance(std::uint32_t i, const Ray& ray) const {
    const Instance& inst = instances[i];
    const Ray local = inst.motion < 0 ? object_ray(inst.transform, ray) : object_ray(placement(i, ray.time), ray);
    if (inst.alpha >= 0) {
        const AlphaContext context{this, i, &ray};
        const HitFilter filter{alpha_filter, &context};
        return mesh_bvhs_[inst.mesh].any(local, &filter);
    }
    return mesh_bvhs_[inst.mesh].any(local);
}

void Scene::closest_top(std::uint32_t ref, Ray& ray, const WatertightRaySse& wr, std::optional<Hit>& best) const {
    const std::uint32_t i = ref & kRefMask;
    if ((ref >> kRefShift) == kMovingRef) return closest_moving(i, ray, best);
    switch (static_cast<ShapeKind>(ref >> kRefShift)) {
        case ShapeKind::kSphere: closest_one(spheres[i], ShapeKind::kSphere, i, ray, best); break;
        case ShapeKind::kQuad: closest_one(quads[i], ShapeKind::kQuad, i, ray, best); break;
        case ShapeKind::kDisk: closest_one(disks[i], ShapeKind::kDisk, i, ray, best); break;
        case ShapeKind::kTriangle: {
            if (const auto h = intersect_triangle_sse(triangles[i], wr, ray.t_max)) {
                ray.t_max = h->t;
                best = Hit{h->t, ShapeKind::kTriangle, i};
            }
            break;
        }
        case ShapeKind::kMesh:
            if (const auto h = closest_instance(i, ray)) {
                ray.t_max = h->hit.t;
                best = Hit{h->hit.t, ShapeKind::kMesh, i, h->prim, h->hit.b1, h->hit.b2, h->vertices};
            }
            break;
        case ShapeKind::kPlane: break;
    }
}

bool Scene::any_top(std::uint32_t ref, const Ray& ray, const WatertightRaySse& wr) const {
    const std::uint32_t i = ref & kRefMask;
    if ((ref >> kRefShift) == kMovingRef) return any_moving(i, ray);
    switch (static_cast<ShapeKind>(ref >> kRefShift)) {
        case ShapeKind::kSphere: return spheres[i].intersect(ray).has_value();
        case ShapeKind::kQuad: return quads[i].intersect(ray).has_value();
        case ShapeKind::kDisk: return disks[i].intersect(ray).has_value();
        case ShapeKind::kTriangle:
            return intersect_triangle_sse(triangles[i], wr, ray.t_max).has_value();
        case ShapeKind::kMesh: return any_instance(i, ray);
        case ShapeKind::kPlane: return false;
    }
    return false;
}

namespace {

// The ray a query works on, read field by field and written whole: its caller has just written
// it in pieces (spawn_ray's fields, then the path's time), and a 16-byte load across several of
// those stores cannot take their data until they reach the cache (a failed store forward, 7-8 %
// of Scene::intersect's samples on the Cornell box and the bunny; docs/performance.md, step 16).
// Each volatile read is one 4-byte load, which takes its data from the store that wrote it; the
// copy is written as two 16-byte halves, which the set-ups' loads (WatertightRaySse's origin)
// then take whole.
Ray read_ray(const Ray& r) {
    static_assert(sizeof(Ray) == 8 * sizeof(float) && offsetof(Ray, time) == 7 * sizeof(float));
    const auto* f = reinterpret_cast<const volatile float*>(&r);
    const __m128 lo = _mm_setr_ps(f[0], f[1], f[2], f[3]);
    const __m128 hi = _mm_setr_ps(f[4], f[5], f[6], f[7]);
    Ray out;
    _mm_storeu_ps(reinterpret_cast<float*>(&out), lo);
    _mm_storeu_ps(reinterpret_cast<float*>(&out) + 4, hi);
    return out;
}

}  // namespace

std::optional<Hit> Scene::intersect(const Ray& ray_in) const {
    assert(committed_count_ == bounded_count() && "Scene::commit() not called");
    Ray ray = read_ray(ray_in);
    std::optional<Hit> best;
    // Planes first: a plane hit shortens t_max, which the traversal then uses.
    closest_hit<ShapeKind::kPlane>(planes, ray, best);
#if GLINT_EMBREE
    if (embree_) {
        embree_->closest(*this, ray, best);
        return best;
    }
#endif
    if (!sphere_set_.empty()) {
        float t;
        std::uint32_t i;
        if (sphere_set_.closest(ray, t, i)) best = Hit{t, ShapeKind::kSphere, i};
        return best;
    }
    if (top_.empty()) return best;
    // The lone triangles' shared set-up (a mesh's triangles have their own, in object space).
    WatertightRaySse wr;
    if (!triangles.empty()) wr = WatertightRaySse(ray);
    top_.closest(BvhRay(ray), ray.t_max, [&](std::uint32_t first, std::uint32_t count) {
        for (std::uint32_t k = first; k < first + count; ++k) closest_top(top_refs_[k], ray, wr, best);
    });
    return best;
}

bool Scene::occluded(const Ray& ray) const {
    assert(committed_count_ == bounded_count() && "Scene::commit() not called");
    if (any_hit(planes, ray)) return true;
#if GLINT_EMBREE
    if (embree_) return embree_->occluded(*this, ray);
#endif
    if (!sphere_set_.empty()) return sphere_set_.any(ray);
    if (top_.empty()) return false;
    WatertightRaySse wr;
    if (!triangles.empty()) wr = WatertightRaySse(ray);
    return top_.any(BvhRay(ray), ray.t_max, [&](std::uint32_t first, std::uint32_t count) {
        for (std::uint32_t k = first; k < first + count; ++k)
            if (any_top(top_refs_[k], ray, wr)) return true;
        return false;
    });
}

std::optional<Hit> Scene::intersect_brute_force(const Ray& ray_in) const {
    Ray ray = ray_in;
    std::optional<Hit> best;
    closest_hit<ShapeKind::kPlane>(planes, ray, best);
    if (moving_shapes.empty()) {
        closest_hit<ShapeKind::kSphere>(spheres, ray, best);
        closest_hit<ShapeKind::kQuad>(quads, ray, best);
        closest_hit<ShapeKind::kDisk>(disks, ray, best);
        closest_hit_triangles(triangles, ray, best);
    } else {  // the still shapes, then each moving one where it is at the ray's time
        const auto each = [&](ShapeKind kind, const auto& shapes) {
            for (std::uint32_t i = 0; i < shapes.size(); ++i) {
                if (motion_of(kind, i)) continue;
                if (const auto t = shapes[i].intersect(ray)) {
                    ray.t_max = *t;
                    best = Hit{*t, kind, i};
                }
            }
        };
        each(ShapeKind::kSphere, spheres);
        each(ShapeKind::kQuad, quads);
        each(ShapeKind::kDisk, disks);
        each(ShapeKind::kTriangle, triangles);
        for (std::uint32_t m = 0; m < moving_shapes.size(); ++m) closest_moving(m, ray, best);
    }
    for (std::uint32_t i = 0; i < instances.size(); ++i) {
        const Instance& inst = instances[i];
        const TriangleMesh& m = meshes[inst.mesh];
        WatertightRay wr(object_ray(placement(i, ray.time), ray));
        for (std::uint32_t t = 0; t < m.triangle_count(); ++t) {
            const auto [p0, p1, p2] = m.vertices(t);
            if (const auto h = intersect_triangle(p0, p1, p2, wr); h && alpha_keeps(i, t, h->b1, h->b2, ray_in)) {
                wr.t_max = ray.t_max = h->t;
                best = Hit{h->t, ShapeKind::kMesh, i, t, h->b1, h->b2};
            }
        }
    }
    return best;
}

bool Scene::occluded_brute_force(const Ray& ray) const {
    if (!moving_shapes.empty()) {
        // The closest hit's answer, each shape where it is at the ray's time (a reference only).
        const auto h = intersect_brute_force(ray);
        return h.has_value();
    }
    if (any_hit(planes, ray) || any_hit(spheres, ray) || any_hit(quads, ray) || any_hit(disks, ray) ||
        any_hit_triangles(triangles, ray))
        return true;
    for (std::uint32_t i = 0; i < instances.size(); ++i) {
        const Instance& inst = instances[i];
        const TriangleMesh& m = meshes[inst.mesh];
        const WatertightRay wr(object_ray(placement(i, ray.time), ray));
        for (std::uint32_t t = 0; t < m.triangle_count(); ++t) {
            const auto [p0, p1, p2] = m.vertices(t);
            if (const auto h = intersect_triangle(p0, p1, p2, wr); h && alpha_keeps(i, t, h->b1, h->b2, ray))
                return true;
        }
    }
    return false;
}

MaterialId Scene::material_of(const Hit& hit) const {
    switch (hit.kind) {
        case ShapeKind::kSphere: return spheres[hit.index].material;
        case ShapeKind::kPlane: return planes[hit.index].material;
        case ShapeKind::kQuad: return quads[hit.index].material;
        case ShapeKind::kDisk: return disks[hit.index].material;
        case ShapeKind::kTriangle: return triangles[hit.index].material;
        case ShapeKind::kMesh: return instance_material(hit.index, hit.prim);
    }
    return 0;
}

// Interfaces are rare: a scene without them takes the plain query; with them, the ray starts
// again past each interface it meets (a bounded number of times: a ray cannot cross more than
// a few thousand boundaries in a sane scene, and a malformed one must not hang).
std::optional<Hit> Scene::intersect_opaque(const Ray& ray_in) const {
    if (!has_interfaces_) return intersect(ray_in);
    Ray ray = ray_in;
    Float travelled = 0;
    for (int crossings = 0; crossings < 4096; ++crossings) {
        auto hit = intersect(ray);
        if (!hit || !is_interface(material_of(*hit))) {
            if (hit) hit->t += travelled;
            return hit;
        }
        const Point3 p = ray.at(hit->t);
        const Normal3 n = interaction(ray, *hit).n;
        travelled += hit->t;
        ray = continue_ray(ray, p, n);
    }
    return std::nullopt;
}

bool Scene::occluded_opaque(const Ray& ray) const {
    if (!has_interfaces_) return occluded(ray);
    return intersect_opaque(ray).has_value();
}

void Scene::intersect_opaque(const Ray* rays, int n, std::optional<Hit>* hits) const {
    assert(n >= 0 && n <= kPacketSize);
    if (sphere_set_.empty() || has_interfaces_) {
        for (int k = 0; k < n; ++k) hits[k] = intersect_opaque(rays[k]);
        return;
    }
    // As intersect(): the planes first, ray by ray, shortening t_max; then the spheres.
    RayPacket packet;
    for (int k = 0; k < n; ++k) {
        Ray ray = rays[k];
        hits[k].reset();
        closest_hit<ShapeKind::kPlane>(planes, ray, hits[k]);
        packet.set(k, ray);
    }
    packet.pad(n);
    PacketHits found;
    sphere_set_.closest(packet, n, found);
    for (int k = 0; k < n; ++k)
        if (found.index[k] >= 0)
            hits[k] = Hit{found.t[k], ShapeKind::kSphere, static_cast<std::uint32_t>(found.index[k])};
}

std::uint32_t Scene::occluded_opaque(const Ray* rays, int n) const {
    assert(n >= 0 && n <= kPacketSize);
    std::uint32_t blocked = 0;
    if (sphere_set_.empty() || has_interfaces_) {
        for (int k = 0; k < n; ++k)
            if (occluded_opaque(rays[k])) blocked |= 1u << k;
        return blocked;
    }
    RayPacket packet;
    for (int k = 0; k < n; ++k) {
        packet.set(k, rays[k]);
        if (any_hit(planes, rays[k])) {
            blocked |= 1u << k;
            packet.t_max[k] = 0;  // settled: the spheres need not be asked
        }
    }
    packet.pad(n);
    return blocked | sphere_set_.any(packet, n);
}

bool Scene::flip_mesh_normal(const TriangleMesh& m, std::uint32_t prim, Vector3 ng) const {
    if (m.normals.empty()) return false;
    const Vector3 sum = to_vector(m.normals[m.indices[3 * prim]]) +
                        to_vector(m.normals[m.indices[3 * prim + 1]]) +
                        to_vector(m.normals[m.indices[3 * prim + 2]]);
    return dot(sum, ng) < 0;
}

Triangle Scene::world_triangle(std::uint32_t inst, std::uint32_t prim, Float time) const {
    const Instance& in = instances[inst];
    const TriangleMesh& m = meshes[in.mesh];
    const auto [p0, p1, p2] = m.vertices(prim);
    const Transform x = placement(inst, time);
    Triangle t{x.point(p0), x.point(p1), x.point(p2), instance_material(inst, prim)};
    // The object-space normal carried by the inverse transpose keeps the front side; the
    // winding of the transformed vertices flips under a mirror. Rewind to match.
    if (x.flips() != flip_mesh_normal(m, prim, cross(p1 - p0, p2 - p0))) std::swap(t.p1, t.p2);
    return t;
}

Color Scene::background_seen(Vector3 d, Float spread) const {
    const auto* env = std::get_if<EnvironmentMap>(&background);
    if (!env || !footprint || env_pyramid_.levels.empty()) return evaluate(background, d);
    if (spread < 0 && footprint->orthographic) return evaluate(background, d);
    const Point2 uv = EnvironmentMap::direction_to_uv(d);
    if (!(std::isfinite(uv.x) && std::isfinite(uv.y))) return Color{0};
    // The pixel's angle (given, or at the image's centre), in units of the map's width (2 pi around).
    const Float angle = spread >= 0 ? spread : length(footprint->h_step) / footprint->near * footprint->scale;
    const Float width = angle / (2 * std::numbers::pi_v<Float>);
    return trilinear(env->image, env_pyramid_, {uv.x, 1 - uv.y}, width, WrapMode::kRepeat, WrapMode::kClamp) * env->scale;
}

Color Scene::light_radiance(const AreaLight& l, MaterialId material, Point3 q, Normal3 n, Float time) const {
    const Emission& e = emission_of(material);
    const bool masked = l.kind == ShapeKind::kMesh && instances[l.index].alpha >= 0;
    if (!e.texture && !masked) return e.radiance;
    SurfaceInteraction si{q, n, material, l.kind, l.index};
    si.ns = n;
    si.time = time;
    if (l.kind == ShapeKind::kMesh) {
        si.prim = l.prim;
        si.bary = mesh_barycentrics(l.index, l.prim, q, time);
    }
    const Color radiance = e.texture ? e.radiance * texture(*e.texture, si) : e.radiance;
    // Holes cut by an alpha mask emit nothing: a light sample there counts the mask's coverage
    // (a cutoff mask's 0 or 1, a stochastic one's alpha: what rays that meet the point see on
    // average).
    return masked ? radiance * alpha_coverage(l.index, l.prim, si.bary.x, si.bary.y) : radiance;
}

std::size_t Scene::accel_memory_bytes() const {
#if GLINT_EMBREE
    if (embree_) return embree_->memory_bytes();
#endif
    std::size_t bytes = top_.memory_bytes() + top_refs_.size() * sizeof(std::uint32_t) + sphere_set_.memory_bytes();
    for (const MeshBvh& b : mesh_bvhs_) bytes += b.memory_bytes();
    return bytes;
}

MaterialId Scene::surface_material(const SurfaceInteraction& si) const {
    MaterialId m = si.material;
    for (int depth = 0; depth < 16 && m < materials.size(); ++depth) {
        const auto* mix = std::get_if<MixMaterial>(&materials[m]);
        if (!mix) break;
        const float amount = average(texture(mix->amount, si));
        // A uniform number from the point's bits and the mix (so nested mixes decide apart).
        std::uint32_t h = m;
        for (const float c : {si.p.x, si.p.y, si.p.z}) h = hash_combine(h, std::bit_cast<std::uint32_t>(c));
        m = mix->materials[to_unit_float(h) < amount ? 1 : 0];
    }
    return m;
}

SurfaceInteraction Scene::interaction(const Ray& ray, const Hit& hit, const RayDifferential* differential) const {
    const Motion* moving = has_motion_ && hit.kind != ShapeKind::kMesh ? motion_of(hit.kind, hit.index) : nullptr;
    SurfaceInteraction si = moving ? moving_interaction(*moving, ray, hit) : base_interaction(ray, hit);
    si.time = ray.time;
    si.differential = differential;
    // base_interaction gave every shape its shading normal (ns = n but on meshes): copying n
    // here read back whole the floats it had just stored one by one (a failed store forward on
    // every bounce).
    if (hit.kind == ShapeKind::kMesh && si.material < normal_maps.size() && normal_maps[si.material])
        apply_normal_map(si, ray);
    return si;
}

void Scene::apply_normal_map(SurfaceInteraction& si, const Ray& ray) const {
    const Instance& inst = instances[si.shape_index];
    const Transform place = placement(si.shape_index, si.time);
    const TriangleMesh& m = meshes[inst.mesh];
    if (m.uvs.empty()) return;  // no texture space to read the map in
    const NormalMap& map = *normal_maps[si.material];
    const std::uint32_t i0 = m.indices[3 * si.prim], i1 = m.indices[3 * si.prim + 1], i2 = m.indices[3 * si.prim + 2];
    // The tangent (direction of +u): the mesh's smoothed tangents if it has them, else the
    // triangle's dp/du. The bitangent is n x t, turned to point along +v: its handedness comes
    // from the triangle's uv orientation in glint's own uv convention (v up), which is
    // unambiguous, rather than from a file's tangent w (whose meaning depends on the file's
    // frame and uv conventions).
    const Vector3 e1 = m.positions[i1] - m.positions[i0], e2 = m.positions[i2] - m.positions[i0];
    const Point2 u0 = m.uvs[i0], u1 = m.uvs[i1], u2 = m.uvs[i2];
    const Float du1 = u1.x - u0.x, dv1 = u1.y - u0.y, du2 = u2.x - u0.x, dv2 = u2.y - u0.y;
    const Float det = du1 * dv2 - dv1 * du2;
    if (!(std::abs(det) > 0)) return;
    const Vector3 dpdu = (e1 * dv2 - e2 * dv1) / det, dpdv = (e2 * du1 - e1 * du2) / det;
    Vector3 t = place.vector(dpdu);
    if (!m.tangents.empty()) {
        const auto tan = m.interpolate(m.tangents, si.prim, si.bary.x, si.bary.y);
        t = place.vector(Vector3{tan[0], tan[1], tan[2]});
    }
    const Vector3 n = to_vector(si.ns);
    t = t - n * dot(n, t);  // Gram-Schmidt against the shading normal
    const Float len = length(t);
    if (!(len > 0) || !std::isfinite(len)) return;
    t = t / len;
    Vector3 b = cross(n, t);
    if (dot(b, place.vector(dpdv)) < 0) b = -b;
    const Color c = texture(map.texture, si);
    const Vector3 local{(2 * c.r - 1) * map.scale, (2 * c.g - 1) * map.scale, 2 * c.b - 1};
    const Vector3 bent = t * local.x + b * local.y + n * local.z;
    const Float bl = length(bent);
    if (!(bl > 0) || !std::isfinite(bl)) return;
    const Normal3 ns(bent / bl);
    // As for interpolated normals: only where the viewer sees the same side of both.
    if (dot(ns, ray.direction) * dot(si.n, ray.direction) > 0) si.ns = ns;
}

SurfaceInteraction Scene::base_interaction(const Ray& ray, const Hit& hit) const {
    const Point3 p = ray.at(hit.t);
    switch (hit.kind) {
        case ShapeKind::kSphere: {
            const Sphere& s = spheres[hit.index];
            const Normal3 n = s.normal_at(p);
            return {p, n, s.material, hit.kind, hit.index, n};
        }
        case ShapeKind::kPlane: {
            const Plane& pl = planes[hit.index];
            return {pl.project(p), pl.normal, pl.material, hit.kind, hit.index, pl.normal};
        }
        // Flat shapes snap the point onto their plane, like planes (math/snap.h).
        case ShapeKind::kQuad: {
            const Quad& q = quads[hit.index];
            const Normal3 n = q.normal();
            return {snap_to_plane(p, q.corner, n), n, q.material, hit.kind, hit.index, n};
        }
        case ShapeKind::kDisk: {
            const Disk& d = disks[hit.index];
            return {snap_to_plane(p, d.center, d.normal), d.normal, d.material, hit.kind, hit.index, d.normal};
        }
        case ShapeKind::kTriangle: {
            const Triangle& t = triangles[hit.index];
            // The normal kept at commit (the same floats); a hit found before commit (the
            // brute-force reference needs none) computes it.
            const Normal3 n = hit.index < triangle_normals_.size() ? triangle_normals_[hit.index] : t.normal();
            return {snap_to_plane(p, t.p0, n), n, t.material, hit.kind, hit.index, n};
        }
        case ShapeKind::kMesh: {
            const Instance& inst = instances[hit.index];
            const TriangleMesh& m = meshes[inst.mesh];
            const std::uint32_t tri = hit.prim;
            const Transform place = inst.motion < 0 ? inst.transform : placement(hit.index, ray.time);
            // The vertices from the packet the traversal hit where it says (the same floats,
            // still in cache; through the index array they cost the bunny 4 % of its time),
            // else from the mesh.
            const auto [p0, p1, p2] = hit.vertices ? packet_triangle(hit.vertices) : m.vertices(tri);
            // The point from the barycentrics (on the triangle, whatever the ray's round-off),
            // in object space, then carried to the world: interpolate's arithmetic.
            const Point3 po = TriangleMesh::mix_xyz(p0, p1, p2, hit.b1, hit.b2);
            SurfaceInteraction si{place.point(po), Normal3{0, 0, 1},
                                  instance_material(hit.index, tri), hit.kind, hit.index};
            si.prim = tri;
            si.bary = {hit.b1, hit.b2};
            const Vector3 face = cross(p1 - p0, p2 - p0);
            Normal3 ng = normalize(place.normal(Normal3(face)));
            if (flip_mesh_normal(m, tri, face)) ng = -ng;
            si.n = ng;
            si.ns = ng;
            if (!m.normals.empty()) {
                const Normal3 ns = place.normal(m.interpolate(m.normals, tri, hit.b1, hit.b2));
                const Float len = length(ns);
                // The shading normal is used only where the viewer is on the same side of it as
                // of the true surface; elsewhere (grazing views of a coarse mesh) the geometric
                // normal shades, so that no light leaks through the surface.
                if (len > 0 && std::isfinite(len)) {
                    const Normal3 unit = ns * (1 / len);
                    if (dot(unit, ray.direction) * dot(ng, ray.direction) > 0) si.ns = unit;
                }
            }
            return si;
        }
    }
    return {p, Normal3{0, 1, 0}, 0, hit.kind, hit.index, Normal3{0, 1, 0}};  // unreachable: every kind is covered
}

Color Scene::vertex_color(const SurfaceInteraction& si) const {
    if (si.shape != ShapeKind::kMesh) return Color{1};
    const TriangleMesh& m = meshes[instances[si.shape_index].mesh];
    if (m.colors.empty()) return Color{1};
    return m.interpolate(m.colors, si.prim, si.bary.x, si.bary.y);
}

Color Scene::texture_general(TextureId id, const SurfaceInteraction& si) const {
    const std::uint8_t reads = texture_reads_[id];
    TextureContext ctx{si.p, reads & kReadsUv ? uv(si) : Point2{}};
    if (reads & kReadsVertexColor) {
        ctx.vertex_color = vertex_color(si);
        ctx.vertex_alpha = vertex_alpha(si);
    }
    const UvSetArg arg{this, &si};
    if (reads & kReadsMoreUvs) {
        ctx.uv_set = &Scene::uv_set_of;
        ctx.uv_set_arg = &arg;
    }
    // The path's own offset rays where it carries them, else the camera's model of a direct view.
    if ((reads & kReadsFootprint) && footprint &&
        ((si.differential && si.differential->at(si.p, si.n, ctx.dpdx, ctx.dpdy)) ||
         footprint->at(si.p, si.n, ctx.dpdx, ctx.dpdy))) {
        ctx.pyramids = &pyramids_;
        if (reads & kReadsUv) {
            const auto diff = [&](Vector3 dp) {
                const Point2 q = uv_near(si, si.p + dp);
                Point2 d{q.x - ctx.uv.x, q.y - ctx.uv.y};
                if (si.shape == ShapeKind::kSphere) d.x -= std::round(d.x);  // u wraps around
                return std::isfinite(d.x) && std::isfinite(d.y) ? d : Point2{};
            };
            ctx.duvdx = diff(ctx.dpdx);
            ctx.duvdy = diff(ctx.dpdy);
        }
    }
    return evaluate(textures, images, id, ctx);
}

Normal3 Scene::smooth_normal_at(const SurfaceInteraction& si, Point3 q) const {
    if (si.shape == ShapeKind::kSphere) {
        const Sphere& s = spheres[si.shape_index];
        if (const Motion* m = has_motion_ ? motion_of(si.shape, si.shape_index) : nullptr) {
            const Transform d = m->at(si.time);
            return normalize(d.normal(s.normal_at(d.to_object.apply(q))));
        }
        return normalize(s.normal_at(q));
    }
    if (si.shape != ShapeKind::kMesh) return si.n;  // flat
    const TriangleMesh& m = meshes[instances[si.shape_index].mesh];
    if (m.normals.empty()) return si.n;
    // At si.p itself, its own barycentrics (the same point, without the projection's round-off).
    const Point2 b = q == si.p ? si.bary : mesh_barycentrics(si.shape_index, si.prim, q, si.time);
    return normalize(placement(si.shape_index, si.time).normal(m.interpolate(m.normals, si.prim, b.x, b.y)));
}

Float Scene::vertex_alpha(const SurfaceInteraction& si) const {
    if (si.shape != ShapeKind::kMesh) return 1;
    const TriangleMesh& m = meshes[instances[si.shape_index].mesh];
    if (m.alphas.empty()) return 1;
    return m.interpolate(m.alphas, si.prim, si.bary.x, si.bary.y);
}

Point2 Scene::uv(const SurfaceInteraction& si, int set) const {
    if (set > 0 && si.shape == ShapeKind::kMesh) {
        const TriangleMesh& m = meshes[instances[si.shape_index].mesh];
        const auto k = static_cast<std::size_t>(set - 1);
        if (k < m.more_uvs.size() && !m.more_uvs[k].empty())
            return m.interpolate(m.more_uvs[k], si.prim, si.bary.x, si.bary.y);
    }
    return uv(si);
}

Point2 Scene::uv_near(const SurfaceInteraction& si, Point3 q) const {
    if (si.shape != ShapeKind::kMesh) {
        SurfaceInteraction moved = si;
        moved.p = q;
        return uv(moved);
    }
    const TriangleMesh& m = meshes[instances[si.shape_index].mesh];
    const Point2 b = mesh_barycentrics(si.shape_index, si.prim, q, si.time);
    return m.uvs.empty() ? b : m.interpolate(m.uvs, si.prim, b.x, b.y);
}

Point2 Scene::mesh_barycentrics(std::uint32_t inst, std::uint32_t prim, Point3 q, Float time) const {
    // In the mesh's own vertex order (world_triangle may rewind).
    const auto [p0, p1, p2] = meshes[instances[inst].mesh].vertices(prim);
    const Transform x = placement(inst, time);
    return Triangle{x.point(p0), x.point(p1), x.point(p2)}.uv_at(q);
}

Point2 Scene::uv(const SurfaceInteraction& si) const {
    if (has_motion_ && si.shape != ShapeKind::kMesh) {
        if (const Motion* m = motion_of(si.shape, si.shape_index)) {
            // Where the point is on the shape as stored: the texture moves with the shape.
            SurfaceInteraction stored = si;
            stored.p = m->at(si.time).to_object.apply(si.p);
            return uv_static(stored);
        }
    }
    return uv_static(si);
}

Point2 Scene::uv_static(const SurfaceInteraction& si) const {
    switch (si.shape) {
        case ShapeKind::kSphere: return spheres[si.shape_index].uv_at(si.p);
        case ShapeKind::kPlane: return planes[si.shape_index].uv_at(si.p);
        case ShapeKind::kQuad: return quads[si.shape_index].uv_at(si.p);
        case ShapeKind::kDisk: return disks[si.shape_index].uv_at(si.p);
        case ShapeKind::kTriangle: return triangles[si.shape_index].uv_at(si.p);
        case ShapeKind::kMesh: {
            const TriangleMesh& m = meshes[instances[si.shape_index].mesh];
            return m.uvs.empty() ? si.bary : m.interpolate(m.uvs, si.prim, si.bary.x, si.bary.y);
        }
    }
    return {};
}

}  // namespace glint
