// Motion blur for glint's YAML scenes: keyframes are read across the shutter, not only at the
// frame (docs/motion.md). The scene is read again at evenly spaced times over the shutter; what
// differs between those readings (an object's transform, a sphere's centre and radius, the
// camera) becomes motion keys, everything else is read at the frame.
#include <algorithm>
#include <cmath>

#include "glint/formats/scene_yaml.h"
#include "glint/math/motion.h"

namespace glint {

namespace {

// Where an object is: its transform, times a sphere's own centre and radius (the sphere is
// then the unit sphere at the origin, placed by the keys).
Transform placement(const ObjectDesc& o) {
    const Transform t = o.transform.value_or(Transform{});
    if (const auto* s = std::get_if<Sphere>(&o.shape))
        return t * Transform::translate(to_vector(s->center)) * Transform::scale({s->radius, s->radius, s->radius});
    return t;
}

bool same_camera(const CameraDesc& a, const CameraDesc& b) {
    if (a.index() != b.index()) return false;
    if (const auto* x = std::get_if<ArticleCameraDesc>(&a)) {
        const auto& y = std::get<ArticleCameraDesc>(b);
        return x->position == y.position && x->direction == y.direction && x->up == y.up;
    }
    const auto& x = std::get<LookAtCameraDesc>(a);
    const auto& y = std::get<LookAtCameraDesc>(b);
    return x.from == y.from && x.to == y.to && x.up == y.up;
}

}  // namespace

SceneDescription parse_scene_over_shutter(const std::string& text, const std::string& path,
                                          std::shared_ptr<SourceFiles> sources, double frame,
                                          const InlineArrays* arrays) {
    SceneDescription d = parse_scene(text, path, sources, frame, arrays);
    const double open = d.shutter[0], close = d.shutter[1];
    if (!d.animated || !(close > open)) return d;
    const int segments = shutter_segments(close - open);
    std::vector<SceneDescription> keys;
    for (int k = 0; k <= segments; ++k)
        keys.push_back(parse_scene(text, path, sources, frame + open + (close - open) * k / segments, arrays));
    // Keyframes cannot add or remove objects, so the readings match one to one.
    for (std::size_t i = 0; i < d.objects.size(); ++i) {
        ObjectDesc& o = d.objects[i];
        std::vector<Transform> motion;
        bool moves = false;
        for (const SceneDescription& key : keys) {
            motion.push_back(placement(key.objects[i]));
            moves = moves || !(motion.back().to_world == motion.front().to_world);
        }
        if (!moves) continue;
        if (auto* s = std::get_if<Sphere>(&o.shape)) {
            s->center = {0, 0, 0};
            s->radius = 1;
        } else {
            o.shape = keys.front().objects[i].shape;
        }
        o.transform = motion.front();
        o.motion = std::move(motion);
    }
    // Point and spot lights move by their positions, spot and directional lights turn by their
    // directions.
    for (std::size_t i = 0; i < d.lights.size(); ++i) {
        std::vector<Point3> route;
        std::vector<Vector3> turns;
        for (const SceneDescription& key : keys) {
            std::visit(
                [&](const auto& l) {
                    if constexpr (requires { l.position; }) route.push_back(l.position);
                    if constexpr (requires { l.direction; }) turns.push_back(l.direction);
                },
                key.lights[i]);
        }
        const auto still = [&](const auto& v) {
            return v.size() != keys.size() || std::all_of(v.begin(), v.end(), [&](const auto& q) { return q == v.front(); });
        };
        if (still(route)) route.clear();
        if (still(turns)) turns.clear();
        if (route.empty() && turns.empty()) continue;
        d.light_paths.resize(d.lights.size());
        d.light_turns.resize(d.lights.size());
        d.light_paths[i] = std::move(route);
        d.light_turns[i] = std::move(turns);
    }
    bool camera_moves = false;
    for (const SceneDescription& key : keys) camera_moves = camera_moves || !same_camera(key.camera, keys.front().camera);
    if (camera_moves) {
        d.camera = keys.front().camera;
        for (const SceneDescription& key : keys) d.camera_motion.push_back(key.camera);
    }
    return d;
}

}  // namespace glint
