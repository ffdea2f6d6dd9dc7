// Keyframed values in scene files and glTF animations: the values at a frame against the curves
// worked out by hand (linear, step, the smooth Hermite curve, slerp, glTF's CUBICSPLINE).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <numbers>
#include <string>
#include <vector>

#include "glint/builder/build.h"
#include "glint/assets/mesh_import.h"
#include "glint/formats/scene_yaml.h"
#include "testing.h"

namespace glint {
namespace {

SceneDescription at_frame(const std::string& yaml, double frame) {
    return parse_scene(yaml, "scene.yaml", std::make_shared<SourceFiles>(), frame);
}

Point3 sphere_center(const SceneDescription& d, std::size_t i = 0) { return std::get<Sphere>(d.objects.at(i).shape).center; }

std::string error_of(const std::string& yaml, double frame) {
    try {
        at_frame(yaml, frame);
    } catch (const SceneError& e) {
        return e.what();
    }
    return "(no error)";
}

TEST(Keyframes, LinearIsHeldOutsideItsKeysAndStraightBetween) {
    const std::string yaml =
        "objects:\n"
        "  - {type: sphere, center: {keyframes: [[10, [0, 1, 0]], [20, [4, 3, -2]]]}, radius: 1}\n";
    const auto c = [&](double f) { return sphere_center(at_frame(yaml, f)); };
    EXPECT_EQ(c(0), Point3(0, 1, 0));   // before the first key
    EXPECT_EQ(c(10), Point3(0, 1, 0));
    EXPECT_EQ(c(15), Point3(2, 2, -1));  // half way
    EXPECT_EQ(c(12.5), Point3(1, 1.5, -0.5));
    EXPECT_EQ(c(20), Point3(4, 3, -2));
    EXPECT_EQ(c(99), Point3(4, 3, -2));  // after the last
    EXPECT_TRUE(at_frame(yaml, 0).animated);
    EXPECT_FALSE(at_frame("objects: [{type: sphere, center: [0, 0, 0], radius: 1}]\n", 3).animated);
}

TEST(Keyframes, StepHoldsEachKeyUntilTheNext) {
    const std::string yaml =
        "objects:\n"
        "  - {type: sphere, center: [0, 0, 0], radius: {keyframes: [[0, 1], [4, 2], [8, 3]], interpolation: step}}\n";
    const auto r = [&](double f) { return std::get<Sphere>(at_frame(yaml, f).objects[0].shape).radius; };
    EXPECT_EQ(r(0), 1);
    EXPECT_EQ(r(3.99), 1);
    EXPECT_EQ(r(4), 2);
    EXPECT_EQ(r(7), 2);
    EXPECT_EQ(r(8), 3);
}

// Smooth: through every key, and with keys of a quadratic at equal spacing the central-difference
// slopes are its exact derivatives, so between the inner keys the cubic Hermite curve is the
// quadratic itself: r(f) = 1 + f^2 at f = 0, 1, 2, 3.
TEST(Keyframes, SmoothPassesThroughTheKeysAndFollowsAQuadraticExactly) {
    const std::string yaml =
        "objects:\n"
        "  - {type: sphere, center: [0, 0, 0], radius: {keyframes: [[0, 1], [1, 2], [2, 5], [3, 10]], interpolation: smooth}}\n";
    const auto r = [&](double f) { return double(std::get<Sphere>(at_frame(yaml, f).objects[0].shape).radius); };
    for (int k = 0; k <= 3; ++k) EXPECT_FLOAT_EQ(r(k), 1 + k * k);
    for (double f : {1.25, 1.5, 1.75}) EXPECT_NEAR(r(f), 1 + f * f, 1e-6) << f;
    // Linear would give 3.5 at 1.5; smooth gives 3.25.
    EXPECT_NEAR(r(1.5), 3.25, 1e-6);
}

TEST(Keyframes, CameraAndTransformStepsAnimate) {
    const std::string yaml =
        "camera: {type: look_at, from: {keyframes: [[0, [0, 1, -6]], [4, [4, 1, -2]]]}, to: [0, 0, 0],\n"
        "         fov: {keyframes: [[0, 30], [4, 50]]}}\n"
        "objects:\n"
        "  - {type: box, min: [0, 0, 0], max: [1, 1, 1],\n"
        "     transform: [{rotate: {angle: {keyframes: [[0, 0], [4, 180]]}, axis: [0, 1, 0]}}, {translate: [2, 0, 0]}]}\n";
    const SceneDescription d = at_frame(yaml, 2);
    const auto& cam = std::get<LookAtCameraDesc>(d.camera);
    EXPECT_EQ(cam.from, Point3(2, 1, -4));
    EXPECT_FLOAT_EQ(cam.fov, 40);
    // 90 degrees about +y then 2 along x: pbrt's Rotate takes (1, 0, 0) to (cos 90, 0, -sin 90).
    const Transform& t = *d.objects.at(0).transform;
    const Point3 p = t.point({1, 0, 0});
    EXPECT_NEAR(p.x, 2, 1e-6);
    EXPECT_NEAR(p.y, 0, 1e-6);
    EXPECT_NEAR(p.z, -1, 1e-6);
}

TEST(Keyframes, MistakesArePointedAt) {
    const auto err = [](const std::string& value) {
        return error_of("objects:\n  - {type: sphere, center: [0, 0, 0], radius: " + value + "}\n", 1);
    };
    EXPECT_NE(err("{keyframes: [[0, 1], [0, 2]]}").find("scene.yaml:2:69: error: keyframe at frame 0: frames must increase"),
              std::string::npos) << err("{keyframes: [[0, 1], [0, 2]]}");
    EXPECT_NE(err("{keyframes: [[0, 1], [5, [2]]]}").find("every key must have the shape of the first (a number)"),
              std::string::npos);
    EXPECT_NE(err("{keyframes: []}").find("keyframes: expected a list of [frame, value] pairs"), std::string::npos);
    EXPECT_NE(err("{keyframes: [[0, 1, 2]]}").find("keyframe: expected [frame, value]"), std::string::npos);
    EXPECT_NE(err("{keyframes: [[0, 1]], interpolation: cubic}").find("unknown interpolation 'cubic' (known: linear, step, smooth)"),
              std::string::npos);
    EXPECT_NE(err("{keyframes: [[0, 1]], speed: 2}").find("speed"), std::string::npos);
    // A value out of range at the frame rendered is reported at its keyframes.
    EXPECT_NE(err("{keyframes: [[0, 1], [2, -1]]}").find("scene.yaml:2:47: error: radius must be > 0, got 0"),
              std::string::npos)
        << err("{keyframes: [[0, 1], [2, -1]]}");
    EXPECT_NE(error_of("animation: {fps: 0}\n", 0).find("scene.yaml:1:18: error: fps must be in (0, 1000000], got 0"),
              std::string::npos);
}

// --- glTF animations ---

std::string base64(const std::vector<std::uint8_t>& b) {
    static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (std::size_t i = 0; i < b.size(); i += 3) {
        const std::uint32_t v = (std::uint32_t(b[i]) << 16) | (i + 1 < b.size() ? std::uint32_t(b[i + 1]) << 8 : 0) |
                                (i + 2 < b.size() ? b[i + 2] : 0);
        out += k[(v >> 18) & 63];
        out += k[(v >> 12) & 63];
        out += i + 1 < b.size() ? k[(v >> 6) & 63] : '=';
        out += i + 2 < b.size() ? k[v & 63] : '=';
    }
    return out;
}

// A triangle drawn by four nodes, each animated on one path, in one buffer:
//   node 0 translation LINEAR: t 0, 1, 2 -> (0,0,0), (2,0,0), (2,4,0)
//   node 1 rotation LINEAR (slerp): t 0, 2 -> identity, 90 degrees about +y
//   node 2 scale STEP: t 0, 1 -> 1, 3
//   node 3 translation CUBICSPLINE: t 0, 2, x(t) = t^3 (values 0, 8; slopes 0, 12)
class GltfAnimation : public ::testing::Test {
protected:
    void SetUp() override {
        std::vector<float> f;
        const auto add = [&](std::initializer_list<float> v) {
            const std::size_t at = f.size() * 4;
            f.insert(f.end(), v);
            return at;
        };
        struct View { std::size_t offset, count; const char* type; };
        std::vector<View> views;
        const auto view = [&](std::initializer_list<float> v, std::size_t count, const char* type) {
            views.push_back({add(v), count, type});
            return views.size() - 1;
        };
        const float s = std::sin(std::numbers::pi_v<float> / 4), c = std::cos(std::numbers::pi_v<float> / 4);
        view({0, 0, 0, 1, 0, 0, 0, 1, 0}, 3, "VEC3");                     // 0 positions
        view({0, 1, 2}, 3, "SCALAR");                                     // 1
        view({0, 0, 0, 2, 0, 0, 2, 4, 0}, 3, "VEC3");                     // 2
        view({0, 2}, 2, "SCALAR");                                        // 3
        view({0, 0, 0, 1, 0, s, 0, c}, 2, "VEC4");                        // 4
        view({0, 1}, 2, "SCALAR");                                        // 5
        view({1, 1, 1, 3, 3, 3}, 2, "VEC3");                              // 6
        view({0, 0, 0, 0, 0, 0, 0, 0, 0, 12, 0, 0, 8, 0, 0, 0, 0, 0}, 6, "VEC3");  // 7: in, value, out per key
        std::vector<std::uint8_t> bytes(f.size() * 4);
        std::memcpy(bytes.data(), f.data(), bytes.size());
        std::string accessors, buffer_views;
        for (std::size_t i = 0; i < views.size(); ++i) {
            const std::size_t n = std::string(views[i].type) == "SCALAR" ? 1 : std::string(views[i].type) == "VEC3" ? 3 : 4;
            buffer_views += std::string(i ? "," : "") + "{\"buffer\": 0, \"byteOffset\": " + std::to_string(views[i].offset) +
                            ", \"byteLength\": " + std::to_string(views[i].count * n * 4) + "}";
            accessors += std::string(i ? "," : "") + "{\"bufferView\": " + std::to_string(i) +
                         ", \"componentType\": 5126, \"count\": " + std::to_string(views[i].count) + ", \"type\": \"" +
                         views[i].type + "\"" + (i == 0 ? ", \"min\": [0, 0, 0], \"max\": [1, 1, 0]" : "") +
                         (std::string(views[i].type) == "SCALAR" ? ", \"min\": [0], \"max\": [2]" : "") + "}";
        }
        const std::string json =
            "{\"asset\": {\"version\": \"2.0\"},\n"
            " \"buffers\": [{\"byteLength\": " + std::to_string(bytes.size()) +
            ", \"uri\": \"data:application/octet-stream;base64," + base64(bytes) + "\"}],\n"
            " \"bufferViews\": [" + buffer_views + "],\n"
            " \"accessors\": [" + accessors + "],\n"
            " \"meshes\": [{\"primitives\": [{\"attributes\": {\"POSITION\": 0}}]}],\n"
            " \"nodes\": [{\"mesh\": 0}, {\"mesh\": 0}, {\"mesh\": 0}, {\"mesh\": 0}],\n"
            " \"scenes\": [{\"nodes\": [0, 1, 2, 3]}],\n"
            " \"animations\": [{\"samplers\": [\n"
            "   {\"input\": 1, \"output\": 2},\n"
            "   {\"input\": 3, \"output\": 4, \"interpolation\": \"LINEAR\"},\n"
            "   {\"input\": 5, \"output\": 6, \"interpolation\": \"STEP\"},\n"
            "   {\"input\": 3, \"output\": 7, \"interpolation\": \"CUBICSPLINE\"}],\n"
            "  \"channels\": [\n"
            "   {\"sampler\": 0, \"target\": {\"node\": 0, \"path\": \"translation\"}},\n"
            "   {\"sampler\": 1, \"target\": {\"node\": 1, \"path\": \"rotation\"}},\n"
            "   {\"sampler\": 2, \"target\": {\"node\": 2, \"path\": \"scale\"}},\n"
            "   {\"sampler\": 3, \"target\": {\"node\": 3, \"path\": \"translation\"}}]}]}\n";
        std::ofstream(dir_ / "anim.gltf") << json;
    }
    // Where node `n` puts the glTF point p at `time`, in glTF's frame (glint flips z).
    Point3 place(double time, int n, Point3 p) {
        const ImportedFile f = import_gltf(dir_ / "anim.gltf", "", time);
        const Point3 q = f.nodes.at(static_cast<std::size_t>(n)).transform.point({p.x, p.y, -p.z});
        return {q.x, q.y, -q.z};
    }
    testing::TempDir dir_;
};

void expect_near(Point3 a, Point3 b, const char* what) {
    EXPECT_NEAR(a.x, b.x, 1e-5) << what;
    EXPECT_NEAR(a.y, b.y, 1e-5) << what;
    EXPECT_NEAR(a.z, b.z, 1e-5) << what;
}

TEST_F(GltfAnimation, TranslationIsLinearAndHeldOutsideTheKeys) {
    expect_near(place(-1, 0, {0, 0, 0}), {0, 0, 0}, "before");
    expect_near(place(0.5, 0, {0, 0, 0}), {1, 0, 0}, "0.5 s");
    expect_near(place(1.5, 0, {0, 0, 0}), {2, 2, 0}, "1.5 s");
    expect_near(place(9, 0, {0, 0, 0}), {2, 4, 0}, "after");
}

// Slerp at a quarter of the way from 0 to 90 degrees about +y turns (1, 0, 0) by 22.5 degrees to
// (cos, 0, -sin) (a right-handed rotation); normalising a straight blend of the quaternions would
// turn it by 21.6.
TEST_F(GltfAnimation, RotationIsSlerp) {
    const auto a = static_cast<Float>(std::numbers::pi / 8);
    expect_near(place(0.5, 1, {1, 0, 0}), {std::cos(a), 0, -std::sin(a)}, "slerp");
    expect_near(place(2, 1, {1, 0, 0}), {0, 0, -1}, "end");
}

TEST_F(GltfAnimation, StepAndCubicSpline) {
    expect_near(place(0.99, 2, {1, 1, 0}), {1, 1, 0}, "step before");
    expect_near(place(1, 2, {1, 1, 0}), {3, 3, 0}, "step at the key");
    for (Float t : {0.5f, 1.0f, 1.5f}) expect_near(place(t, 3, {0, 0, 0}), {t * t * t, 0, 0}, "x = t^3");
}

// A scene file plays the animation at frame / fps seconds: at 0.5 s node 0 has moved the triangle
// to x in [1, 2], the others stay within x <= 1; at 0 s everything is within x <= 1.
TEST_F(GltfAnimation, ASceneFilePlaysItAtFrameOverFpsSeconds) {
    std::ofstream(dir_ / "s.yaml") << "animation: {fps: 10}\nobjects: [{type: mesh, file: anim.gltf}]\n";
    const auto right_edge = [&](double frame) {
        auto sources = std::make_shared<SourceFiles>();
        const RenderJob job = build(load_scene_file((dir_ / "s.yaml").string(), sources, frame), {}, sources);
        return job.scene.bounds().hi.x;
    };
    EXPECT_NEAR(right_edge(5), 2, 1e-5);
    EXPECT_NEAR(right_edge(0), 1, 1e-5);
    EXPECT_NEAR(right_edge(2.5), 1.5, 1e-5);
}

// With a shutter open over frames 0 to 5 at 10 fps, the nodes move over 0 to 0.5 s: the
// instances' placements at the shutter's ends are the animation's at 0 and 0.5 s (node 0's
// translation, node 1's slerp to 22.5 degrees, as above), and the top-level box holds the sweep.
TEST_F(GltfAnimation, AShutterBlursTheNodesAlongTheirAnimation) {
    std::ofstream(dir_ / "s.yaml") << "animation: {fps: 10}\ncamera: {shutter: [0, 5]}\nobjects: [{type: mesh, file: anim.gltf}]\n";
    auto sources = std::make_shared<SourceFiles>();
    const RenderJob job = build(load_scene_file((dir_ / "s.yaml").string(), sources, 0), {}, sources);
    const Scene& scene = job.scene;
    ASSERT_EQ(scene.instances.size(), 4u);
    EXPECT_TRUE(scene.has_motion());
    const auto at = [&](std::uint32_t i, Float t, Point3 p) {  // in glTF's frame
        const Point3 q = scene.placement(i, t).point({p.x, p.y, -p.z});
        return Point3{q.x, q.y, -q.z};
    };
    expect_near(at(0, 0, {0, 0, 0}), {0, 0, 0}, "node 0 at the opening");
    expect_near(at(0, 0.5f, {0, 0, 0}), {0.5f, 0, 0}, "node 0 half way");
    expect_near(at(0, 1, {0, 0, 0}), {1, 0, 0}, "node 0 at the close");
    const auto a = static_cast<Float>(std::numbers::pi / 8);
    expect_near(at(1, 1, {1, 0, 0}), {std::cos(a), 0, -std::sin(a)}, "node 1 at the close");
    EXPECT_GE(scene.bounds().hi.x, 2 - 1e-5f);
}

}  // namespace
}  // namespace glint
