// Motion blur: the interpolation of motion keys against closed forms, moving shapes in both
// backends against the brute-force reference, the image of a moving sphere against the
// closed-form coverage of a moving disk, determinism across threads, and the readers' keys.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <sstream>

#include "glint/builder/build.h"
#include "glint/film/film.h"
#include "glint/formats/pbrt.h"
#include "glint/formats/scene_yaml.h"
#include "glint/math/motion.h"
#include "glint/render/render.h"
#include "test_paths.h"
#include "testing.h"

namespace glint {
namespace {

// Rotation by `degrees` about z: at the middle of a 0 -> 90 degree segment the slerp gives
// exactly 45 degrees, where blending the matrices would give a shrunken 45-degree matrix.
TEST(Motion, RotationTurnsAlongTheArcAndTranslationAlongTheLine) {
    const Motion m({Transform::translate({1, 2, 3}), Transform::translate({5, 2, -1}) * Transform::rotate(90, {0, 0, 1})});
    ASSERT_TRUE(m.moves());
    for (const double t : {0.0, 0.25, 0.5, 0.8, 1.0}) {
        const Transform x = m.at(Float(t));
        const double a = t * std::numbers::pi / 2;
        const Point3 p = x.point({1, 0, 0});
        EXPECT_NEAR(p.x, 1 + 4 * t + std::cos(a), 1e-5) << t;
        EXPECT_NEAR(p.y, 2 + std::sin(a), 1e-5) << t;
        EXPECT_NEAR(p.z, 3 - 4 * t, 1e-5) << t;
        // The inverse is the inverse.
        const Point3 back = x.to_object.apply(p);
        EXPECT_NEAR(back.x, 1, 1e-5);
        EXPECT_NEAR(back.y, 0, 1e-5);
    }
    // Clamped outside [0, 1]; one key (or equal keys) is still.
    EXPECT_EQ(m.at(-1).to_world, m.at(0).to_world);
    EXPECT_FALSE(Motion({Transform::translate({1, 0, 0}), Transform::translate({1, 0, 0})}).moves());
    // Scale blends linearly: half way from 1 to 3 is 2.
    const Motion s({Transform{}, Transform::scale({3, 3, 3})});
    EXPECT_NEAR(s.at(0.5f).point({1, 0, 0}).x, 2, 1e-5);
    EXPECT_THROW(Motion({Transform{}, Transform{Matrix34{{{{1, 0, 0, 0}, {0, 0, 0, 0}, {0, 0, 1, 0}}}}, {}}}),
                 std::invalid_argument);
}

// The swept box holds the box's corners at every time (dense brute force), for a translation
// (exact) and for a turn with a stretch (padded).
TEST(Motion, SweptBoundsHoldTheBoxAtEveryTime) {
    Bounds3 box;
    box.extend({-1, -0.5, 0});
    box.extend({2, 1, 3});
    for (const Motion& m : {Motion({Transform::translate({0, 0, 0}), Transform::translate({3, -1, 2})}),
                            Motion({Transform::rotate(10, {1, 1, 0}), Transform::rotate(170, {0, 1, 1}) * Transform::scale({1, 2, 1}),
                                    Transform::translate({4, 0, 0})})}) {
        const Bounds3 swept = m.swept_bounds(box);
        for (int i = 0; i <= 5000; ++i) {
            const Bounds3 b = m.at(Float(i) / 5000).bounds(box);
            for (int a = 0; a < 3; ++a) {
                EXPECT_LE(swept.lo[a], b.lo[a] + 1e-4f);
                EXPECT_GE(swept.hi[a], b.hi[a] - 1e-4f);
            }
        }
    }
}

// A scene of still and moving shapes and instances, for the backends to agree on.
Scene moving_scene(AccelKind accel) {
    Scene s;
    s.accel = accel;
    s.materials.push_back(ArticleMaterial{});
    s.spheres.push_back({{0, 0, 0}, 1});         // moving, object space
    s.spheres.push_back({{3, 0, 5}, 0.5f});      // still
    s.quads.push_back(Quad::make({-0.5f, -0.5f, 0}, {1, 0, 0}, {0, 1, 0}, 0));  // moving
    s.disks.push_back({{0, 0, 0}, Normal3{0, 0, 1}, 0.7f, 0});                    // moving
    s.triangles.push_back({{-1, 0, 0.4f}, {1, 0, 0.4f}, {0, 1, 0.4f}, 0});         // moving (behind the quad)
    s.motions.push_back(Motion({Transform::translate({-3, 0, 4}), Transform::translate({3, 1, 4})}));
    s.motions.push_back(Motion({Transform::translate({0, 2, 6}), Transform::translate({0, 2, 6}) * Transform::rotate(120, {0, 1, 0})}));
    s.motions.push_back(Motion({Transform::translate({1, -2, 3}) * Transform::scale({0.5f, 0.5f, 0.5f}),
                                Transform::translate({-1, -2, 3}) * Transform::rotate(80, {1, 0, 0})}));
    s.moving_shapes = {{ShapeKind::kSphere, 0, 0}, {ShapeKind::kQuad, 0, 1}, {ShapeKind::kDisk, 0, 2}, {ShapeKind::kTriangle, 0, 1}};
    TriangleMesh mesh;
    mesh.positions = {{-1, -1, -1}, {1, -1, -1}, {0, 1, -1}, {0, 0, 1}};
    mesh.indices = {0, 1, 2, 0, 1, 3, 1, 2, 3, 2, 0, 3};
    s.meshes.push_back(mesh);
    Instance still{0, Transform::translate({-3, 2, 5}), std::nullopt, -1};
    Instance moving{0, Transform::translate({2, -1, 7}), std::nullopt, -1};
    s.motions.push_back(Motion({Transform::translate({2, -1, 7}), Transform::translate({-2, 1, 8}) * Transform::rotate(200, {0, 0, 1})}));
    moving.motion = 3;
    s.instances = {still, moving};
    s.commit();
    return s;
}

void expect_agreement(const Scene& s, int allowed) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(0, 1);
    int differ = 0, hits = 0;
    for (int i = 0; i < testing::scaled(20000); ++i) {
        Ray r{{u(rng) * 2 - 1, u(rng) * 2 - 1, -4}, normalize(Vector3{u(rng) * 1.6f - 0.8f, u(rng) * 1.2f - 0.6f, 1})};
        r.time = u(rng);
        const auto a = s.intersect(r), b = s.intersect_brute_force(r);
        if (a.has_value() != b.has_value() || s.occluded(r) != b.has_value() ||
            (a && (a->kind != b->kind || a->index != b->index || std::abs(a->t - b->t) > 1e-4f * std::max(1.0f, b->t)))) {
            ++differ;
            continue;
        }
        hits += a.has_value();
        if (a) {  // the point is on the shape where it is at the ray's time
            const SurfaceInteraction si = s.interaction(r, *a);
            EXPECT_LT(length(si.p - r.at(a->t)), 1e-3f);
        }
    }
    EXPECT_GT(hits, testing::scaled(1000));
    EXPECT_LE(differ, allowed);
}

TEST(MotionScene, MovingShapesAndInstancesMatchTheBruteForceAtEveryTime) {
    const Scene s = moving_scene(AccelKind::kBvh);
    EXPECT_TRUE(s.has_motion());
    expect_agreement(s, 0);
    // The moving sphere is where its motion puts it: at time 0 on x = -3, at 1 on x = 3.
    Ray r{{-3, 0, 0}, {0, 0, 1}};
    r.time = 0;
    ASSERT_TRUE(s.intersect(r));
    EXPECT_NEAR(s.intersect(r)->t, 3, 1e-4f);
    r.time = 1;
    EXPECT_FALSE(s.intersect(r) && s.intersect(r)->kind == ShapeKind::kSphere && s.intersect(r)->index == 0);
}

#if GLINT_EMBREE
TEST(MotionScene, EmbreeMovesTheSameShapesAndInstances) {
    const Scene s = moving_scene(AccelKind::kEmbree);
    expect_agreement(s, 10);  // Embree's tests differ from glint's at grazing hits
}
#endif

// The sphere's silhouette, a disk of radius r, moves along x from a to b over the shutter under
// an orthographic camera; the flat integrator sees 1 on it, 0 beside. A point (x, y) is covered
// for the part of the shutter when |x - c(t)| <= sqrt(r^2 - (y - cy)^2): the closed form below,
// averaged over each pixel by a 64 x 64 quadrature, is the image the box filter must converge to.
TEST(MotionScene, AMovingSphereRendersTheClosedFormCoverageOfAMovingDisk) {
    const std::string yaml = R"(
camera: {type: look_at, from: [0, 0, -5], to: [0, 0, 0], projection: orthographic, height: 2, shutter: [0, 1]}
film: {width: 24, height: 24}
sampler: {spp: 1024}
integrator: {type: flat}
background: {type: constant, color: [0, 0, 0]}
materials: {white: {color: [1, 1, 1]}}
objects:
  - {type: sphere, center: {keyframes: [[0, [-0.6, 0.1, 0]], [1, [0.5, 0.1, 0]]]}, radius: 0.3, material: white}
)";
    auto sources = std::make_shared<SourceFiles>();
    const SceneDescription d = parse_scene_over_shutter(yaml, "moving.yaml", sources);
    ASSERT_EQ(d.objects.at(0).motion.size(), 5u);  // 4 segments over one frame
    const RenderJob job = build(d, Overrides{}, sources);
    Film film(24, 24);
    render(job.scene, job.camera, *job.integrator, job.options, film);
    const double r = 0.3, a = -0.6, b = 0.5, cy = 0.1;
    const auto covered = [&](double x, double y) {
        const double dy = y - cy;
        if (std::abs(dy) >= r) return 0.0;
        const double half = std::sqrt(r * r - dy * dy);
        const double t0 = (x - half - a) / (b - a), t1 = (x + half - a) / (b - a);
        return std::max(0.0, std::min(1.0, t1) - std::max(0.0, t0));
    };
    double total_error = 0, worst = 0;
    for (int row = 0; row < 24; ++row)
        for (int col = 0; col < 24; ++col) {
            double expected = 0;
            for (int j = 0; j < 64; ++j)
                for (int i = 0; i < 64; ++i) {
                    // Film x grows to the right, rows downward; the view is [-1, 1]^2.
                    const double x = -1 + 2 * (col + (i + 0.5) / 64) / 24, y = 1 - 2 * (row + (j + 0.5) / 64) / 24;
                    expected += covered(x, y);
                }
            expected /= 64 * 64;
            const double got = film.pixels()[static_cast<std::size_t>(row * 24 + col)].g;
            total_error += std::abs(got - expected);
            worst = std::max(worst, std::abs(got - expected));
        }
    // Per pixel the estimate of a fraction has standard deviation at most 0.5 / sqrt(1024).
    EXPECT_LT(worst, 4 * 0.5 / 32);
    EXPECT_LT(total_error / (24 * 24), 0.004);
}

TEST(MotionScene, MotionBlurredImagesAreTheSameForAnyThreadCount) {
    const std::string yaml = R"(
camera: {type: look_at, from: [0, 1, -5], to: [0, 0, 0], shutter: [-0.25, 0.25]}
film: {width: 32, height: 24}
sampler: {spp: 8}
integrator: {type: path, max_depth: 4}
lights: [{type: point, position: [2, 4, -3], intensity: [20, 20, 20]}]
materials: {lamp: {type: diffuse, albedo: [0, 0, 0], emission: [4, 4, 4]}}
objects:
  - {type: plane, point: [0, -1, 0], normal: [0, 1, 0]}
  - {type: sphere, center: {keyframes: [[-1, [-1, 0, 0]], [1, [1, 0, 0]]]}, radius: 0.5, material: lamp}
  - type: box
    min: [-0.3, -1, -0.3]
    max: [0.3, 0, 0.3]
    transform: [{rotate: {angle: {keyframes: [[-1, 0], [1, 90]]}, axis: [0, 1, 0]}}, {translate: [1.2, 0, 1]}]
)";
    auto sources = std::make_shared<SourceFiles>();
    const SceneDescription d = parse_scene_over_shutter(yaml, "moving.yaml", sources);
    std::vector<std::vector<Color>> images;
    for (const int threads : {1, 2}) {
        RenderJob job = build(d, Overrides{}, sources);
        EXPECT_TRUE(job.scene.has_motion());
        job.options.threads = threads;
        Film film(32, 24);
        render(job.scene, job.camera, *job.integrator, job.options, film);
        images.emplace_back(film.pixels().begin(), film.pixels().end());
    }
    ASSERT_EQ(images[0].size(), images[1].size());
    for (std::size_t i = 0; i < images[0].size(); ++i) EXPECT_EQ(images[0][i], images[1][i]) << i;
}

// A moving emitter is sampled where it is at the path's time: the sampled point lies on the
// moved sphere and the density pdf_li gives for it is the one sample_li reported.
TEST(MotionScene, AMovingLightIsSampledWhereItIs) {
    Scene s;
    s.materials.push_back(DiffuseMaterial{});
    s.emission.push_back(Emission{Color{2}});
    s.spheres.push_back({{0, 0, 0}, 1, 0});
    s.motions.push_back(Motion({Transform::translate({-2, 0, 5}), Transform::translate({2, 0, 5}) * Transform::scale({0.5f, 0.5f, 0.5f})}));
    s.moving_shapes = {{ShapeKind::kSphere, 0, 0}};
    s.commit();
    const LightSampler& ls = s.light_sampler();
    ASSERT_GE(ls.count(), 1u);  // the sphere is light 0 (the default sky follows)
    for (const float t : {0.0f, 0.3f, 1.0f}) {
        const Transform x = s.motions[0].at(t);
        const Point3 centre = x.point({0, 0, 0});
        const Float radius = length(x.vector({1, 0, 0}));
        const auto sample = ls.sample_li(s, 0, {0, 0, 0}, {0.3f, 0.7f}, t);
        ASSERT_TRUE(sample);
        EXPECT_NEAR(length(sample->p_light - centre), radius, 1e-4f) << t;
        EXPECT_NEAR(ls.pdf_li(s, 0, {0, 0, 0}, sample->wi, sample->p_light, t), sample->pdf, 1e-3f * sample->pdf);
        // Seen from the origin, the sphere subtends the cone of its radius at its distance.
        const double sin2 = double(radius) * radius / dot(centre - Point3{0, 0, 0}, centre - Point3{0, 0, 0});
        EXPECT_NEAR(sample->pdf, 1 / (2 * std::numbers::pi * (1 - std::sqrt(1 - sin2))), 1e-3 * sample->pdf);
    }
}

// A moving sphere kept as the unit sphere and placed at radius 2 is as strong a light as a
// still sphere of radius 2: the power sampler gives them the same share.
TEST(MotionScene, AMovingLightsPowerIsItsPlacedSize) {
    Scene s;
    s.background = ConstantBackground{Color{0}};
    s.light_sampling = LightSamplerKind::kPower;
    s.materials.push_back(DiffuseMaterial{});
    s.emission.push_back(Emission{Color{2}});
    s.spheres.push_back({{0, 0, 5}, 2, 0});
    s.spheres.push_back({{0, 0, 0}, 1, 0});
    s.motions.push_back(Motion({Transform::translate({5, 0, 5}) * Transform::scale({2, 2, 2}), Transform::translate({8, 0, 5}) * Transform::scale({2, 2, 2})}));
    s.moving_shapes = {{ShapeKind::kSphere, 1, 0}};
    s.commit();
    ASSERT_EQ(s.light_sampler().count(), 2u);
    EXPECT_NEAR(s.light_sampler().pmf(0), 0.5f, 1e-6f);
    EXPECT_NEAR(s.light_sampler().pmf(1), 0.5f, 1e-6f);
}

// A keyframed point light moves over the shutter: the path tracer's light sample and the
// article integrator's light both come from where it is at the time.
TEST(MotionScene, AKeyframedPointLightMovesOverTheShutter) {
    const std::string yaml = R"(
camera: {type: look_at, from: [0, 0, -5], to: [0, 0, 0], shutter: [0, 2]}
integrator: {type: path}
lights: [{type: point, position: {keyframes: [[0, [-4, 3, 0]], [2, [4, 3, 0]]]}, intensity: [10, 10, 10]}]
objects: [{type: sphere, center: [0, 0, 0], radius: 1}]
)";
    auto sources = std::make_shared<SourceFiles>();
    const SceneDescription d = parse_scene_over_shutter(yaml, "light.yaml", sources);
    const RenderJob job = build(d, Overrides{}, sources);
    const Scene& s = job.scene;
    ASSERT_TRUE(s.has_motion());
    for (const float t : {0.0f, 0.25f, 1.0f}) {
        const Light moved = s.light_at(0, t);
        ASSERT_TRUE(std::holds_alternative<PointLight>(moved));
        const Point3 expected{-4 + 8 * t, 3, 0};
        EXPECT_NEAR(std::get<PointLight>(moved).position.x, expected.x, 1e-5f) << t;
        const auto sample = s.light_sampler().sample_li(s, 0, {0, 0, 0}, {0.5f, 0.5f}, t);
        ASSERT_TRUE(sample);
        EXPECT_NEAR(sample->distance, length(expected - Point3{0, 0, 0}), 1e-4f) << t;
        EXPECT_NEAR(sample->wi.x, expected.x / length(expected - Point3{0, 0, 0}), 1e-5f) << t;
    }
}

// A sun keyframed from straight down to 60 degrees off over the shutter lights a white floor by
// the mean of its cosine over the turn, in closed form: the keys' direction is (0, -1, sqrt(3) t)
// normalised, whose cosine to the floor's normal is 1 / sqrt(1 + 3 t^2), with mean
// asinh(sqrt(3)) / sqrt(3) = 0.7603 over t in [0, 1] (the sun at the opening would give 1). A
// soft sun turns the same way for light sampling and for the BSDF samples that meet its disk (its
// irradiance on a tilted floor is the same, the disk being above the horizon). BSDF samples alone
// meet a 20-degree sun at 1024 spp a few thousand times: 4 % is about three standard deviations
// (the sun left where it is at the opening would be 30 % off).
TEST(MotionScene, AKeyframedSunTurnsOverTheShutter) {
    for (const char* diameter : {"0", "20"}) {
        for (const char* strategy : {"mis", "bsdf"}) {
            if (std::string(diameter) == "0" && std::string(strategy) == "bsdf") continue;  // a delta
            const bool bsdf = std::string(strategy) == "bsdf";
            const std::string yaml = std::string(R"(
camera: {type: look_at, from: [0, 5, 0], to: [0, 0, 0], up: [0, 0, 1], fov: 20, shutter: [0, 1]}
film: {width: 16, height: 16}
sampler: {spp: )") + (bsdf ? "1024" : "256") + R"(}
integrator: {type: path, max_depth: 1, strategy: )" + strategy + R"(}
background: {type: constant, color: [0, 0, 0]}
lights: [{type: directional, direction: {keyframes: [[0, [0, -1, 0]], [1, [0, -1, 1.7320508]]]},
          intensity: [3.14159265, 3.14159265, 3.14159265], angular_diameter: )" + diameter + R"(}]
materials: {white: {type: diffuse, albedo: [1, 1, 1]}}
objects: [{type: quad, corner: [-50, 0, -50], edge1: [0, 0, 100], edge2: [100, 0, 0], material: white}]
)";
            auto sources = std::make_shared<SourceFiles>();
            const RenderJob job = build(parse_scene_over_shutter(yaml, "sun.yaml", sources), Overrides{}, sources);
            ASSERT_TRUE(job.scene.has_motion());
            Film film(job.film_width, job.film_height);
            render(job.scene, job.camera, *job.integrator, job.options, film);
            double mean = 0;
            for (const Color& c : film.pixels()) mean += c.g;
            mean /= static_cast<double>(film.pixels().size());
            const double expected = std::asinh(std::sqrt(3.0)) / std::sqrt(3.0);
            EXPECT_NEAR(mean, expected, (bsdf ? 0.04 : 0.01) * expected) << diameter << " " << strategy;
        }
    }
}

// A spot light keyframed to turn and move: Scene::light_at gives its position on the straight
// line between the keys and its direction along the arc (the keys are whole placements of a
// light at the origin, math/motion.h).
TEST(MotionScene, AKeyframedSpotLightTurnsAndMoves) {
    const std::string yaml = R"(
camera: {type: look_at, from: [0, 0, -5], to: [0, 0, 0], shutter: [0, 1]}
integrator: {type: path}
lights: [{type: spot, position: {keyframes: [[0, [10, 3, 0]], [1, [14, 3, 0]]]},
          direction: {keyframes: [[0, [0, -1, 0]], [1, [1, 0, 0]]]}, intensity: [10, 10, 10]},
         {type: spot, position: [-7, 2, 5], direction: {keyframes: [[0, [0, -1, 0]], [1, [1, 0, 0]]]}}]
objects: [{type: sphere, center: [0, 0, 0], radius: 1}]
)";
    auto sources = std::make_shared<SourceFiles>();
    const RenderJob job = build(parse_scene_over_shutter(yaml, "spot.yaml", sources), Overrides{}, sources);
    for (const float t : {0.0f, 0.25f, 0.5f, 0.9f, 1.0f}) {
        const SpotLight l = std::get<SpotLight>(job.scene.light_at(0, t));
        EXPECT_NEAR(l.position.x, 10 + 4 * t, 1e-4f) << t;
        EXPECT_NEAR(l.position.y, 3, 1e-5f) << t;
        // The keyframes lerp (0, -1, 0) to (1, 0, 0) and normalise: the angle from straight down is
        // atan(t / (1 - t)); glint's slerp between the four segments' keys stays within 1.5 degrees
        // of it (1.06 at t = 0.9, where the keyframes' turn is fastest).
        const double angle = std::atan2(l.direction.x, -l.direction.y);
        EXPECT_NEAR(angle, std::atan2(t, 1 - t), 0.026) << t;
        EXPECT_NEAR(length(l.direction), 1, 1e-5f);
        EXPECT_NEAR(l.direction.z, 0, 1e-5f);
        // The second turns where it stands.
        const SpotLight still = std::get<SpotLight>(job.scene.light_at(1, t));
        EXPECT_NEAR(length(still.position - Point3{-7, 2, 5}), 0, 1e-5f) << t;
        EXPECT_NEAR(dot(still.direction, l.direction), 1, 1e-5f) << t;
    }
}

std::string error_of(const std::string& yaml) {
    try {
        parse_scene_over_shutter(yaml, "scene.yaml", std::make_shared<SourceFiles>());
    } catch (const SceneError& e) {
        return e.what();
    }
    return "(no error)";
}

TEST(MotionScene, ShutterErrorsPointAtTheKey) {
    EXPECT_NE(error_of("camera: {type: look_at, from: [0, 0, -1], to: [0, 0, 0], shutter: [1, 0]}\n")
                  .find("scene.yaml:1:67: error: camera: 'shutter' must be [open, close]"),
              std::string::npos)
        << error_of("camera: {type: look_at, from: [0, 0, -1], to: [0, 0, 0], shutter: [1, 0]}\n");
    EXPECT_NE(error_of("camera: {shutter: [0, .nan]}\n").find("scene.yaml:1:"), std::string::npos);
    EXPECT_NE(error_of("camera: {shutter: 0.5}\n").find("'shutter' must be [open, close]"), std::string::npos);
    // A plane cannot move.
    const std::string plane =
        "camera: {shutter: [0, 1]}\nobjects:\n  - {type: plane, point: [0, 0, 0], normal: [0, 1, 0], "
        "transform: [{translate: [0, {keyframes: [[0, 0], [1, 1]]}, 0]}]}\n";
    auto sources = std::make_shared<SourceFiles>();
    const SceneDescription d = parse_scene_over_shutter(plane, "scene.yaml", sources);
    try {
        build(d, Overrides{}, sources);
        ADD_FAILURE() << "a moving plane was accepted";
    } catch (const SceneError& e) {
        EXPECT_NE(std::string(e.what()).find("a plane cannot move"), std::string::npos) << e.what();
    }
}

// pbrt-v4's ActiveTransform: a shape whose start and end transforms differ moves between them
// over the camera's shutter; the keys are worked out by hand.
TEST(MotionScene, PbrtActiveTransformMovesShapesOverTheShutter) {
    auto sources = std::make_shared<SourceFiles>();
    const SceneDescription d = parse_pbrt(R"(Camera "perspective" "float shutteropen" 0 "float shutterclose" 0.5
WorldBegin
AttributeBegin
  Translate 1 0 0
  ActiveTransform EndTime
  Translate 0 4 0
  ActiveTransform All
  Shape "sphere" "float radius" 2
AttributeEnd
Shape "sphere"
)", "test.pbrt", sources, PbrtOptions{true});
    EXPECT_TRUE(d.warnings.empty());
    ASSERT_EQ(d.objects.size(), 2u);
    const auto& keys = d.objects[0].motion;
    ASSERT_EQ(keys.size(), 2u);
    // At time 0 the start transform; at 0.5, half way to the end's (1, 4, 0).
    EXPECT_NEAR(keys[0].point({0, 0, 0}).y, 0, 1e-6f);
    EXPECT_NEAR(keys[1].point({0, 0, 0}).x, 1, 1e-6f);
    EXPECT_NEAR(keys[1].point({0, 0, 0}).y, 2, 1e-6f);
    EXPECT_TRUE(d.objects[1].motion.empty());
    // Bad times and names are errors at their directive.
    const auto error = [](const std::string& text) -> std::string {
        try {
            parse_pbrt(text, "bad.pbrt", std::make_shared<SourceFiles>(), PbrtOptions{true});
        } catch (const SceneError& e) {
            return e.what();
        }
        return "(no error)";
    };
    EXPECT_NE(error("TransformTimes 2 1\n").find("bad.pbrt:1:1: error: TransformTimes: expected a start and an end time"),
              std::string::npos) << error("TransformTimes 2 1\n");
    EXPECT_NE(error("WorldBegin\nActiveTransform Sometimes\n").find("bad.pbrt:2:1: error: ActiveTransform: expected StartTime"),
              std::string::npos) << error("WorldBegin\nActiveTransform Sometimes\n");
}

// A pbrt camera whose end-time transform differs moves: pbrt's CTM is camera-from-world, so a
// Translate 1 0 0 at the end time puts the camera at x = -1 then (by hand).
TEST(MotionScene, PbrtMovingCameraMovesOverTheShutter) {
    auto sources = std::make_shared<SourceFiles>();
    const SceneDescription d = parse_pbrt(R"(LookAt 0 0 -5  0 0 0  0 1 0
ActiveTransform EndTime
Translate 1 0 0
ActiveTransform All
Camera "perspective" "float fov" 40
WorldBegin
Shape "sphere"
)", "test.pbrt", sources, PbrtOptions{true});
    EXPECT_TRUE(d.warnings.empty());
    ASSERT_EQ(d.camera_motion.size(), 2u);
    const auto& open = std::get<LookAtCameraDesc>(d.camera_motion[0]);
    const auto& close = std::get<LookAtCameraDesc>(d.camera_motion[1]);
    EXPECT_NEAR(open.from.x, 0, 1e-5f);
    EXPECT_NEAR(open.from.z, -5, 1e-5f);
    EXPECT_NEAR(close.from.x, -1, 1e-5f);
    EXPECT_NEAR(close.from.z, -5, 1e-5f);
    EXPECT_NEAR(close.to.x, -1, 1e-5f);  // it moves sideways, looking the same way
    Overrides o;
    o.width = 8;
    o.height = 8;
    const RenderJob job = build(d, o, sources);
    ASSERT_TRUE(job.camera.moves());
    // The centre ray at the close starts one unit to the left of the opening's.
    const Ray r0 = job.camera.at_time(job.camera.generate_ray(4, 4), 0), r1 = job.camera.at_time(job.camera.generate_ray(4, 4), 1);
    EXPECT_NEAR(r1.origin.x - r0.origin.x, -1, 1e-5f);
    EXPECT_NEAR(dot(r0.direction, r1.direction), 1, 1e-6f);
}

// The collection's killeroo-moving.pbrt is killeroo-simple.pbrt with ActiveTransform blocks
// around the two killeroos; the same edits made here to the copy in ../shared/models: the first
// killeroo's start time is moved by (35, 35, 35) and the active transform stays the start time's
// for the rest of the block; the second, in an attribute block of its own, moves its start by a
// further (30, 0, 0), then both times by (-200, 0, 0). It reads with no warning (strict) and the
// killeroos' start-to-end shifts are those offsets carried by the Scale and Rotate above them,
// 0.5 R(-60 degrees about z) (35, 35, 35) and (65, 35, 35), by hand.
TEST(MotionScene, KillerooMovingReadsWithoutWarnings) {
    const std::filesystem::path dir = std::filesystem::path(GLINT_TEST_MODEL_DIR) / "pbrt-v4-scenes" / "killeroos";
    if (!std::filesystem::exists(dir / "killeroo-simple.pbrt")) GTEST_SKIP() << "no " << dir.string();
    std::string text = testing::read_file(dir / "killeroo-simple.pbrt");
    const std::string include = "    Include \"geometry/killeroo.pbrt\"\n";
    const std::string absolute = "    Include \"" + (dir / "geometry" / "killeroo.pbrt").string() + "\"\n";
    const std::size_t first = text.find(include);
    ASSERT_NE(first, std::string::npos);
    text.replace(first, include.size(),
                 "    ActiveTransform StartTime\n    Translate 35 35 35\n    AttributeBegin\n" + absolute + "    AttributeEnd\n");
    const std::string second_block = "    Translate -200 0 0\n" + include;
    const std::size_t second = text.find(second_block);
    ASSERT_NE(second, std::string::npos);
    text.replace(second, second_block.size(),
                 "    AttributeBegin\n    ActiveTransform StartTime\n    Translate 30 0 0\n    ActiveTransform All\n"
                 "    Translate -200 0 0\n" + absolute + "    AttributeEnd\n");
    auto sources = std::make_shared<SourceFiles>();
    const SceneDescription d = parse_pbrt(text, (dir / "killeroo-moving-test.pbrt").string(), sources, PbrtOptions{true});
    EXPECT_TRUE(d.warnings.empty());
    int moving = 0;
    for (const ObjectDesc& o : d.objects) {
        if (o.motion.empty()) continue;
        const Vector3 shift = o.motion[0].point({0, 0, 0}) - o.motion[1].point({0, 0, 0});
        const double c = std::cos(-std::numbers::pi / 3), s = std::sin(-std::numbers::pi / 3);
        const double ox = moving == 0 ? 35 : 65;  // the objects come in the file's order
        EXPECT_NEAR(shift.x, 0.5 * (ox * c - 35 * s), 1e-3) << moving;
        EXPECT_NEAR(shift.y, 0.5 * (ox * s + 35 * c), 1e-3) << moving;
        EXPECT_NEAR(shift.z, 0.5 * 35, 1e-3) << moving;
        ++moving;
    }
    EXPECT_EQ(moving, 2);
    Overrides o;
    o.width = 24;
    o.height = 24;
    o.spp = 2;
    const RenderJob job = build(d, o, sources);
    EXPECT_TRUE(job.scene.has_motion());
    Film film(job.film_width, job.film_height);
    render(job.scene, job.camera, *job.integrator, job.options, film);
    for (const Color& c : film.pixels()) ASSERT_TRUE(std::isfinite(c.r) && std::isfinite(c.g) && std::isfinite(c.b));
}

}  // namespace
}  // namespace glint
