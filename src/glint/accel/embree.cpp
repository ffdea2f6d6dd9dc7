#include "glint/accel/embree.h"

#include <dlfcn.h>
#include <embree3/rtcore.h>

#include <atomic>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include <fmt/format.h>

#include "glint/scene.h"

namespace glint {

namespace {

// Embree is loaded with dlopen on the first use of --accel embree, not linked: its 44 MB stay out
// of every process that does not ask for it (the start-up measured in docs/benchmarks.md).
#define GLINT_EMBREE_FUNCTIONS(X) \
    X(rtcAttachGeometryByID) \
    X(rtcCommitGeometry) \
    X(rtcCommitScene) \
    X(rtcGetDeviceError) \
    X(rtcIntersect1) \
    X(rtcNewDevice) \
    X(rtcNewGeometry) \
    X(rtcNewScene) \
    X(rtcOccluded1) \
    X(rtcReleaseDevice) \
    X(rtcReleaseGeometry) \
    X(rtcReleaseScene) \
    X(rtcSetDeviceMemoryMonitorFunction) \
    X(rtcSetGeometryBoundsFunction) \
    X(rtcSetGeometryBuildQuality) \
    X(rtcSetGeometryInstancedScene) \
    X(rtcSetGeometryIntersectFilterFunction) \
    X(rtcSetGeometryIntersectFunction) \
    X(rtcSetGeometryOccludedFilterFunction) \
    X(rtcSetGeometryOccludedFunction) \
    X(rtcSetGeometryTimeStepCount) \
    X(rtcSetGeometryTransform) \
    X(rtcSetGeometryTransformQuaternion) \
    X(rtcSetGeometryUserData) \
    X(rtcSetGeometryUserPrimitiveCount) \
    X(rtcSetNewGeometryBuffer) \
    X(rtcSetSceneBuildQuality)

struct EmbreeLibrary {
#define GLINT_EMBREE_POINTER(f) decltype(&::f) f = nullptr;
    GLINT_EMBREE_FUNCTIONS(GLINT_EMBREE_POINTER)
#undef GLINT_EMBREE_POINTER
};

const EmbreeLibrary& embree() {
    static const EmbreeLibrary library = [] {
        EmbreeLibrary l;
#if GLINT_EMBREE_DLOPEN
        void* handle = dlopen("libembree3.so.3", RTLD_NOW | RTLD_LOCAL);
        if (!handle) throw std::runtime_error(fmt::format("cannot load Embree (libembree3.so.3): {}", dlerror()));
#define GLINT_EMBREE_LOOKUP(f)                                                                      \
    l.f = reinterpret_cast<decltype(&::f)>(dlsym(handle, #f));                                     \
    if (!l.f) throw std::runtime_error("cannot load Embree (libembree3.so.3): it has no " #f);
#else  // linked (the sanitizer build: LeakSanitizer's tracer crashes on a dlopen'ed Embree at exit)
#define GLINT_EMBREE_LOOKUP(f) l.f = &::f;
#endif
        GLINT_EMBREE_FUNCTIONS(GLINT_EMBREE_LOOKUP)
#undef GLINT_EMBREE_LOOKUP
        return l;
    }();
    return library;
}

// Top-level geometry ids: fixed slots for the shape arrays and the moving shapes, then one per
// instance.
constexpr unsigned kTrianglesId = 0, kSpheresId = 1, kQuadsId = 2, kDisksId = 3, kMovingId = 4, kFirstInstanceId = 5;

// A shape array, whose moving members (Scene::moving_shapes) the callbacks pass over: those are
// the moving geometry's.
template <typename Shape>
struct UserShapes {
    const std::vector<Shape>* shapes;
    const Scene* scene = nullptr;
    ShapeKind kind = ShapeKind::kSphere;
    bool still(unsigned i) const { return !scene->has_motion() || !scene->motion_of(kind, i); }
};

// The boxes glint's own BVH uses (padded for the shapes' rounding, math/bounds.h): spheres' and
// disks' balls (a disk lies in its ball), quads' corners.
template <typename Shape>
void shape_bounds(const RTCBoundsFunctionArguments* args) {
    const auto* u = static_cast<const UserShapes<Shape>*>(args->geometryUserPtr);
    const Shape& s = (*u->shapes)[args->primID];
    Bounds3 bb;
    if constexpr (std::is_same_v<Shape, Quad>) bb = padded_for_rounding(s.bounds());
    else bb = padded_for_rounding(ball_bounds(s.center, s.radius));
    RTCBounds* b = args->bounds_o;
    b->lower_x = bb.lo.x, b->lower_y = bb.lo.y, b->lower_z = bb.lo.z;
    b->upper_x = bb.hi.x, b->upper_y = bb.hi.y, b->upper_z = bb.hi.z;
}

// glint calls rtcIntersect1 / rtcOccluded1 only, so the callbacks see one ray (N == 1), laid out
// as RTCRayHit / RTCRay.
template <typename Shape>
void shape_intersect(const RTCIntersectFunctionNArguments* args) {
    if (args->N != 1 || !args->valid[0]) return;
    const auto* u = static_cast<const UserShapes<Shape>*>(args->geometryUserPtr);
    if (!u->still(args->primID)) return;
    auto* rh = reinterpret_cast<RTCRayHit*>(args->rayhit);
    const Ray ray{{rh->ray.org_x, rh->ray.org_y, rh->ray.org_z},
                  {rh->ray.dir_x, rh->ray.dir_y, rh->ray.dir_z},
                  rh->ray.tfar};
    if (const auto t = (*u->shapes)[args->primID].intersect(ray)) {
        rh->ray.tfar = *t;
        rh->hit.geomID = args->geomID;
        rh->hit.primID = args->primID;
        rh->hit.instID[0] = args->context->instID[0];
        rh->hit.u = rh->hit.v = 0;
    }
}

template <typename Shape>
void shape_occluded(const RTCOccludedFunctionNArguments* args) {
    if (args->N != 1 || !args->valid[0]) return;
    const auto* u = static_cast<const UserShapes<Shape>*>(args->geometryUserPtr);
    if (!u->still(args->primID)) return;
    auto* r = reinterpret_cast<RTCRay*>(args->ray);
    const Ray ray{{r->org_x, r->org_y, r->org_z}, {r->dir_x, r->dir_y, r->dir_z}, r->tfar};
    if ((*u->shapes)[args->primID].intersect(ray)) r->tfar = -std::numeric_limits<float>::infinity();
}

// The moving shapes: bounded over the shutter, tested at the ray's time by glint.
void moving_bounds(const RTCBoundsFunctionArguments* args) {
    const auto* scene = static_cast<const Scene*>(args->geometryUserPtr);
    const Bounds3 bb = scene->moving_bounds(args->primID);
    RTCBounds* b = args->bounds_o;
    b->lower_x = bb.lo.x, b->lower_y = bb.lo.y, b->lower_z = bb.lo.z;
    b->upper_x = bb.hi.x, b->upper_y = bb.hi.y, b->upper_z = bb.hi.z;
}

void moving_intersect(const RTCIntersectFunctionNArguments* args) {
    if (args->N != 1 || !args->valid[0]) return;
    const auto* scene = static_cast<const Scene*>(args->geometryUserPtr);
    auto* rh = reinterpret_cast<RTCRayHit*>(args->rayhit);
    Ray ray{{rh->ray.org_x, rh->ray.org_y, rh->ray.org_z}, {rh->ray.dir_x, rh->ray.dir_y, rh->ray.dir_z}, rh->ray.tfar,
            rh->ray.time};
    std::optional<Hit> hit;
    scene->closest_moving(args->primID, ray, hit);
    if (!hit) return;
    rh->ray.tfar = hit->t;
    rh->hit.geomID = args->geomID;
    rh->hit.primID = args->primID;
    rh->hit.instID[0] = args->context->instID[0];
    rh->hit.u = rh->hit.v = 0;
}

void moving_occluded(const RTCOccludedFunctionNArguments* args) {
    if (args->N != 1 || !args->valid[0]) return;
    const auto* scene = static_cast<const Scene*>(args->geometryUserPtr);
    auto* r = reinterpret_cast<RTCRay*>(args->ray);
    const Ray ray{{r->org_x, r->org_y, r->org_z}, {r->dir_x, r->dir_y, r->dir_z}, r->tfar, r->time};
    if (scene->any_moving(args->primID, ray)) r->tfar = -std::numeric_limits<float>::infinity();
}

std::string error_name(RTCError e) {
    switch (e) {
        case RTC_ERROR_NONE: return "no error";
        case RTC_ERROR_INVALID_ARGUMENT: return "invalid argument";
        case RTC_ERROR_INVALID_OPERATION: return "invalid operation";
        case RTC_ERROR_OUT_OF_MEMORY: return "out of memory";
        case RTC_ERROR_UNSUPPORTED_CPU: return "unsupported CPU";
        case RTC_ERROR_CANCELLED: return "cancelled";
        default: return "unknown error";
    }
}

}  // namespace

struct EmbreeAccel::Impl {
    RTCDevice device = nullptr;
    RTCScene top = nullptr;
    std::vector<RTCScene> mesh_scenes;
    std::atomic<long long> bytes{0};
    UserShapes<Sphere> spheres;
    UserShapes<Quad> quads;
    UserShapes<Disk> disks;
    std::vector<std::uint32_t> triangle_ids;  ///< per primitive of the lone triangles: its index

    void check(const char* what) const {
        // Reading the error clears it: read once.
        if (const RTCError e = embree().rtcGetDeviceError(device); e != RTC_ERROR_NONE)
            throw std::runtime_error(fmt::format("Embree: {} failed: {}", what, error_name(e)));
    }
    ~Impl() {
        for (RTCScene s : mesh_scenes)
            if (s) embree().rtcReleaseScene(s);
        if (top) embree().rtcReleaseScene(top);
        if (device) embree().rtcReleaseDevice(device);
    }
};

namespace {

// The intersect context glint passes: Embree's, then what the alpha filter needs.
struct AlphaIntersectContext {
    RTCIntersectContext context;  // first: Embree hands the filter a pointer to it
    const Scene* scene;
    Ray ray;  // world space, as the hash of a stochastic mask wants it
};

void alpha_filter(const RTCFilterFunctionNArguments* args) {
    const auto* c = reinterpret_cast<const AlphaIntersectContext*>(args->context);
    for (unsigned k = 0; k < args->N; ++k) {
        if (!args->valid[k]) continue;
        const unsigned inst = RTCHitN_instID(args->hit, args->N, k, 0);
        if (inst == RTC_INVALID_GEOMETRY_ID) continue;
        if (!c->scene->alpha_keeps(inst - kFirstInstanceId, RTCHitN_primID(args->hit, args->N, k),
                                   RTCHitN_u(args->hit, args->N, k), RTCHitN_v(args->hit, args->N, k), c->ray))
            args->valid[k] = 0;
    }
}

bool count_memory(void* user, ssize_t bytes, bool) {
    static_cast<std::atomic<long long>*>(user)->fetch_add(bytes);
    return true;
}

RTCGeometry triangle_geometry(RTCDevice device, const std::vector<Point3>& positions,
                              const std::vector<std::uint32_t>& indices) {
    RTCGeometry g = embree().rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    embree().rtcSetGeometryBuildQuality(g, RTC_BUILD_QUALITY_HIGH);
    // Copies (rtcSetNewGeometryBuffer pads the buffers as Embree's SIMD loads need).
    auto* v = static_cast<float*>(embree().rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                          3 * sizeof(float), positions.size()));
    for (std::size_t i = 0; i < positions.size(); ++i) {
        v[3 * i] = positions[i].x;
        v[3 * i + 1] = positions[i].y;
        v[3 * i + 2] = positions[i].z;
    }
    auto* ix = static_cast<unsigned*>(embree().rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                              3 * sizeof(unsigned), indices.size() / 3));
    std::memcpy(ix, indices.data(), indices.size() * sizeof(unsigned));
    embree().rtcCommitGeometry(g);
    return g;
}

// A moving instance's keys as Embree's time steps: each as its decomposition T R S, which
// Embree interpolates as glint does (slerp, lerp), where the stretch S has no shear; with shear
// (Embree wants it upper triangular, glint's is symmetric) as matrices, which Embree blends
// linearly (docs/motion.md).
void set_motion(RTCGeometry g, const Motion& motion) {
    const auto n = static_cast<unsigned>(motion.key_count());
    embree().rtcSetGeometryTimeStepCount(g, n);
    bool sheared = false;
    for (unsigned k = 0; k < n; ++k) {
        const auto s = motion.stretch(k);
        sheared = sheared || s[0][1] != 0 || s[0][2] != 0 || s[1][2] != 0 || s[1][0] != 0 || s[2][0] != 0 || s[2][1] != 0;
    }
    for (unsigned k = 0; k < n; ++k) {
        if (sheared) {
            float xfm[12];
            for (int r = 0; r < 3; ++r)
                for (int c = 0; c < 4; ++c) xfm[4 * r + c] = motion.key(k).to_world.m[r][c];
            embree().rtcSetGeometryTransform(g, k, RTC_FORMAT_FLOAT3X4_ROW_MAJOR, xfm);
            continue;
        }
        RTCQuaternionDecomposition q;
        rtcInitQuaternionDecomposition(&q);
        const auto s = motion.stretch(k);
        rtcQuaternionDecompositionSetScale(&q, float(s[0][0]), float(s[1][1]), float(s[2][2]));
        const auto r = motion.rotation(k);
        rtcQuaternionDecompositionSetQuaternion(&q, float(r[0]), float(r[1]), float(r[2]), float(r[3]));
        const Vector3 t = motion.translation(k);
        rtcQuaternionDecompositionSetTranslation(&q, t.x, t.y, t.z);
        embree().rtcSetGeometryTransformQuaternion(g, k, &q);
    }
}

template <typename Shape>
void attach_user(RTCDevice device, RTCScene scene, UserShapes<Shape>& user, unsigned id) {
    if (user.shapes->empty()) return;
    RTCGeometry g = embree().rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
    embree().rtcSetGeometryUserPrimitiveCount(g, static_cast<unsigned>(user.shapes->size()));
    embree().rtcSetGeometryUserData(g, &user);
    embree().rtcSetGeometryBoundsFunction(g, shape_bounds<Shape>, nullptr);
    embree().rtcSetGeometryIntersectFunction(g, shape_intersect<Shape>);
    embree().rtcSetGeometryOccludedFunction(g, shape_occluded<Shape>);
    embree().rtcCommitGeometry(g);
    embree().rtcAttachGeometryByID(scene, g, id);
    embree().rtcReleaseGeometry(g);
}

}  // namespace

EmbreeAccel::EmbreeAccel(const Scene& scene) : impl_(new Impl) {
    try {
        Impl& m = *impl_;
        m.device = embree().rtcNewDevice(nullptr);
        if (!m.device) throw std::runtime_error("Embree: could not create a device");
        embree().rtcSetDeviceMemoryMonitorFunction(m.device, count_memory, &m.bytes);
        std::vector<bool> masked(scene.meshes.size(), false);
        for (const Instance& inst : scene.instances)
            if (inst.alpha >= 0) masked[inst.mesh] = true;
        for (std::size_t k = 0; k < scene.meshes.size(); ++k) {
            const TriangleMesh& mesh = scene.meshes[k];
            RTCScene s = embree().rtcNewScene(m.device);
            m.mesh_scenes.push_back(s);
            embree().rtcSetSceneBuildQuality(s, RTC_BUILD_QUALITY_HIGH);
            if (mesh.indices.empty()) {
                embree().rtcCommitScene(s);
                continue;
            }
            RTCGeometry g = triangle_geometry(m.device, mesh.positions, mesh.indices);
            if (masked[k]) {  // the filter asks the instance, which may have no mask: then it keeps
                embree().rtcSetGeometryIntersectFilterFunction(g, alpha_filter);
                embree().rtcSetGeometryOccludedFilterFunction(g, alpha_filter);
                embree().rtcCommitGeometry(g);
            }
            embree().rtcAttachGeometryByID(s, g, 0);
            embree().rtcReleaseGeometry(g);
            embree().rtcCommitScene(s);
        }
        m.check("building the meshes");
        m.top = embree().rtcNewScene(m.device);
        for (std::uint32_t i = 0; i < scene.triangles.size(); ++i)
            if (!scene.has_motion() || !scene.motion_of(ShapeKind::kTriangle, i)) m.triangle_ids.push_back(i);
        if (!m.triangle_ids.empty()) {
            std::vector<Point3> p;
            std::vector<std::uint32_t> ix;
            for (const std::uint32_t i : m.triangle_ids) {
                const Triangle& t = scene.triangles[i];
                ix.insert(ix.end(), {static_cast<std::uint32_t>(p.size()), static_cast<std::uint32_t>(p.size() + 1),
                                     static_cast<std::uint32_t>(p.size() + 2)});
                p.insert(p.end(), {t.p0, t.p1, t.p2});
            }
            RTCGeometry g = triangle_geometry(m.device, p, ix);
            embree().rtcAttachGeometryByID(m.top, g, kTrianglesId);
            embree().rtcReleaseGeometry(g);
        }
        m.spheres = {&scene.spheres, &scene, ShapeKind::kSphere};
        m.quads = {&scene.quads, &scene, ShapeKind::kQuad};
        m.disks = {&scene.disks, &scene, ShapeKind::kDisk};
        attach_user(m.device, m.top, m.spheres, kSpheresId);
        attach_user(m.device, m.top, m.quads, kQuadsId);
        attach_user(m.device, m.top, m.disks, kDisksId);
        if (!scene.moving_shapes.empty()) {
            RTCGeometry g = embree().rtcNewGeometry(m.device, RTC_GEOMETRY_TYPE_USER);
            embree().rtcSetGeometryUserPrimitiveCount(g, static_cast<unsigned>(scene.moving_shapes.size()));
            embree().rtcSetGeometryUserData(g, const_cast<Scene*>(&scene));
            embree().rtcSetGeometryBoundsFunction(g, moving_bounds, nullptr);
            embree().rtcSetGeometryIntersectFunction(g, moving_intersect);
            embree().rtcSetGeometryOccludedFunction(g, moving_occluded);
            embree().rtcCommitGeometry(g);
            embree().rtcAttachGeometryByID(m.top, g, kMovingId);
            embree().rtcReleaseGeometry(g);
        }
        for (std::uint32_t i = 0; i < scene.instances.size(); ++i) {
            const Instance& inst = scene.instances[i];
            RTCGeometry g = embree().rtcNewGeometry(m.device, RTC_GEOMETRY_TYPE_INSTANCE);
            embree().rtcSetGeometryInstancedScene(g, m.mesh_scenes[inst.mesh]);
            if (const Motion* motion = scene.motion_of(ShapeKind::kMesh, i)) {
                set_motion(g, *motion);
            } else {
                float xfm[12];
                for (int r = 0; r < 3; ++r)
                    for (int c = 0; c < 4; ++c) xfm[4 * r + c] = inst.transform.to_world.m[r][c];
                embree().rtcSetGeometryTransform(g, 0, RTC_FORMAT_FLOAT3X4_ROW_MAJOR, xfm);
            }
            embree().rtcCommitGeometry(g);
            embree().rtcAttachGeometryByID(m.top, g, kFirstInstanceId + i);
            embree().rtcReleaseGeometry(g);
        }
        embree().rtcCommitScene(m.top);
        m.check("building the scene");
    } catch (...) {
        delete impl_;
        throw;
    }
}

EmbreeAccel::~EmbreeAccel() { delete impl_; }

std::size_t EmbreeAccel::memory_bytes() const {
    const long long b = impl_->bytes.load();
    return b > 0 ? static_cast<std::size_t>(b) : 0;
}

void EmbreeAccel::closest(const Scene& scene, Ray& ray, std::optional<Hit>& best) const {
    AlphaIntersectContext alpha{{}, &scene, ray};
    RTCIntersectContext& context = alpha.context;
    rtcInitIntersectContext(&context);
    RTCRayHit rh{};
    rh.ray.org_x = ray.origin.x, rh.ray.org_y = ray.origin.y, rh.ray.org_z = ray.origin.z;
    rh.ray.dir_x = ray.direction.x, rh.ray.dir_y = ray.direction.y, rh.ray.dir_z = ray.direction.z;
    rh.ray.tnear = kRayTMin;
    rh.ray.tfar = ray.t_max;
    rh.ray.time = ray.time;
    rh.ray.mask = 0xffffffffu;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    embree().rtcIntersect1(impl_->top, &context, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return;
    // Embree counts hits up to tfar inclusive; glint's convention excludes t_max.
    if (!(rh.ray.tfar < ray.t_max)) return;
    ray.t_max = rh.ray.tfar;
    if (rh.hit.instID[0] != RTC_INVALID_GEOMETRY_ID) {
        best = Hit{rh.ray.tfar, ShapeKind::kMesh, rh.hit.instID[0] - kFirstInstanceId, rh.hit.primID,
                   rh.hit.u, rh.hit.v};
        return;
    }
    switch (rh.hit.geomID) {
        case kTrianglesId: best = Hit{rh.ray.tfar, ShapeKind::kTriangle, impl_->triangle_ids[rh.hit.primID]}; break;
        case kMovingId: {
            const auto& moving = scene.moving_shapes[rh.hit.primID];
            best = Hit{rh.ray.tfar, moving.kind, moving.index};
            break;
        }
        case kSpheresId: best = Hit{rh.ray.tfar, ShapeKind::kSphere, rh.hit.primID}; break;
        case kQuadsId: best = Hit{rh.ray.tfar, ShapeKind::kQuad, rh.hit.primID}; break;
        case kDisksId: best = Hit{rh.ray.tfar, ShapeKind::kDisk, rh.hit.primID}; break;
        default: break;
    }
}

bool EmbreeAccel::occluded(const Scene& scene, const Ray& ray) const {
    AlphaIntersectContext alpha{{}, &scene, ray};
    RTCIntersectContext& context = alpha.context;
    rtcInitIntersectContext(&context);
    RTCRay r{};
    r.org_x = ray.origin.x, r.org_y = ray.origin.y, r.org_z = ray.origin.z;
    r.dir_x = ray.direction.x, r.dir_y = ray.direction.y, r.dir_z = ray.direction.z;
    r.tnear = kRayTMin;
    // Embree's interval is closed at tfar; glint's excludes t_max: shrink by one ulp.
    r.tfar = std::nextafter(ray.t_max, 0.0f);
    r.time = ray.time;
    r.mask = 0xffffffffu;
    embree().rtcOccluded1(impl_->top, &context, &r);
    return r.tfar < 0;
}

}  // namespace glint
