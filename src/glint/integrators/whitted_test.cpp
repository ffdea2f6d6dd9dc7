#include <gtest/gtest.h>

#include <cmath>

#include "glint/integrators/integrator.h"

namespace glint {
namespace {

void expect_color(Color a, Color b, float tol = 1e-6f) {
    EXPECT_NEAR(a.r, b.r, tol);
    EXPECT_NEAR(a.g, b.g, tol);
    EXPECT_NEAR(a.b, b.b, tol);
}

// A scene with a white floor at y = 0 and a unit sphere at (0,2,0) under a light shining
// straight down: the point (0,0,0) is in the sphere's shadow, (5,0,0) is not.
Scene shadow_scene(Light light) {
    Scene s;
    s.textures = {ConstantTexture{Color{1}}, ConstantTexture{Color{0.5f, 0.25f, 1}}};
    s.materials = {ArticleMaterial{0, 0}, ArticleMaterial{1, 0}};
    s.planes.push_back(Plane{{0, 0, 0}, {0, 1, 0}, 1});
    s.spheres.push_back(Sphere{{0, 2, 0}, 1, 0});
    s.lights.push_back(light);
    s.background = ConstantBackground{Color{0}};
    s.commit();
    return s;
}

TEST(Whitted, ReflectionVectorMirrorsAboutTheNormal) {
    // R = D - 2(N.D)N: (1,-1,0)/sqrt2 off a floor becomes (1,1,0)/sqrt2, whichever way N faces.
    const Vector3 d = normalize(Vector3{1, -1, 0});
    for (Normal3 n : {Normal3{0, 1, 0}, Normal3{0, -1, 0}}) {
        const Vector3 r = reflect(d, n);
        EXPECT_NEAR(r.x, 1 / std::sqrt(2.0f), 1e-6);
        EXPECT_NEAR(r.y, 1 / std::sqrt(2.0f), 1e-6);
        EXPECT_NEAR(r.z, 0, 1e-6);
    }
    // Head-on: straight back.
    const Vector3 back = reflect({0, 0, 1}, Normal3{0, 0, -1});
    EXPECT_FLOAT_EQ(back.z, -1);
}

TEST(Whitted, ShadowedPointGetsAmbientOnly) {
    const Scene scene = shadow_scene(DirectionalLight{{0, -1, 0}, Color{1}});
    const WhittedIntegrator w({0.1f, true, 5});
    RayCounter counter;
    const Color k{0.5f, 0.25f, 1};
    // K a = (0.05, 0.025, 0.1)
    expect_color(w.direct(scene, {0, 0, 0}, {0, 1, 0}, k, counter), k * 0.1f);
    EXPECT_EQ(counter.rays, 1u);  // one shadow ray
}

TEST(Whitted, LitPointGetsAmbientPlusDiffuse) {
    const Scene scene = shadow_scene(DirectionalLight{{0, -1, 0}, Color{1}});
    const WhittedIntegrator w({0.1f, true, 5});
    RayCounter counter;
    const Color k{0.5f, 0.25f, 1};
    // Unoccluded, -L.N = 1: K a + K I = 1.1 K.
    expect_color(w.direct(scene, {5, 0, 0}, {0, 1, 0}, k, counter), k * 1.1f);
    // A light at 60 degrees from the normal: cos = 0.5.
    const Scene tilted = shadow_scene(
        DirectionalLight{normalize(Vector3{-std::sqrt(3.0f), -1, 0}), Color{1}});
    expect_color(w.direct(tilted, {5, 0, 0}, {0, 1, 0}, k, counter), k * 0.6f);
}

TEST(Whitted, ShadowsOffIgnoresOccluders) {
    const Scene scene = shadow_scene(DirectionalLight{{0, -1, 0}, Color{1}});
    const WhittedIntegrator w({0.1f, false, 5});
    RayCounter counter;
    expect_color(w.direct(scene, {0, 0, 0}, {0, 1, 0}, Color{1}, counter), Color{1.1f});
    EXPECT_EQ(counter.rays, 0u);
}

TEST(Whitted, PointLightFallsOffWithInverseSquare) {
    // Intensity 8 at distance 2 straight above (5,0,0); the sphere at (0,2,0) is not in between.
    Scene scene = shadow_scene(PointLight{{5, 2, 0}, Color{8}});
    const WhittedIntegrator w({0, true, 5});
    RayCounter counter;
    expect_color(w.direct(scene, {5, 0, 0}, {0, 1, 0}, Color{1}, counter), Color{2});
    // At (7,0,0): distance sqrt(8), cos = 2/sqrt(8): 8/8 * 0.7071.
    expect_color(w.direct(scene, {7, 0, 0}, {0, 1, 0}, Color{1}, counter),
                 Color{1 / std::sqrt(2.0f)}, 1e-5f);
    // A point light below the occluding sphere's shadow: (0,0,0) under the sphere at (0,2,0)
    // with the light at (0,5,0) is shadowed; the shadow ray must stop at the light, so a light
    // *between* the sphere and the point (0,0.5,0) lights it.
    scene.lights = {PointLight{{0, 5, 0}, Color{1}}};
    expect_color(w.direct(scene, {0, 0, 0}, {0, 1, 0}, Color{1}, counter), Color{0});
    scene.lights = {PointLight{{0, 0.5f, 0}, Color{1}}};
    expect_color(w.direct(scene, {0, 0, 0}, {0, 1, 0}, Color{1}, counter), Color{4});
}

TEST(Whitted, AtTheDepthLimitReflectionSeesTheBackground) {
    // A mirror-ish sphere (s = 1) seen head-on with max_depth 0: colour = d * background(R).
    Scene s;
    s.textures = {ConstantTexture{Color{1, 0.5f, 0.25f}}};
    s.materials = {ArticleMaterial{0, 1}};
    s.spheres.push_back(Sphere{{0, 0, 5}, 1, 0});
    s.background = ConstantBackground{Color{0.5f}};
    s.commit();
    const WhittedIntegrator w({0.2f, true, 0});
    RayCounter counter;
    const PixelSampler sampler(SamplerType::kSobol, 1, 0);
    SampleStream samples(sampler, 0);
    // No lights: d = K a = (0.2, 0.1, 0.05); r = 0.5.
    expect_color(w.li(s, Ray{{0, 0, 0}, {0, 0, 1}}, samples, counter), Color{0.1f, 0.05f, 0.025f});
    EXPECT_EQ(counter.rays, 1u);
}

TEST(Whitted, ShininessBlendsDiffuseAndReflection) {
    // Two facing spheres: the camera ray hits sphere A (s = 0.5) whose reflection goes straight
    // back to the camera side where sphere B (s = 0, colour 0.4) sits behind the camera.
    Scene s;
    s.textures = {ConstantTexture{Color{1}}, ConstantTexture{Color{0.4f}}};
    s.materials = {ArticleMaterial{0, 0.5f}, ArticleMaterial{1, 0}};
    s.spheres.push_back(Sphere{{0, 0, 5}, 1, 0});
    s.spheres.push_back(Sphere{{0, 0, -5}, 1, 1});
    s.background = ConstantBackground{Color{0}};
    s.commit();
    const WhittedIntegrator w({0.5f, true, 5});
    RayCounter counter;
    const PixelSampler sampler(SamplerType::kSobol, 1, 0);
    SampleStream samples(sampler, 0);
    // d_A = 1 * 0.5 = 0.5; r = d_B = 0.4 * 0.5 = 0.2; colour = 0.5 * 0.5 + 0.5 * 0.5 * 0.2.
    expect_color(w.li(s, Ray{{0, 0, 0}, {0, 0, 1}}, samples, counter), Color{0.25f + 0.05f});
    EXPECT_EQ(counter.rays, 2u);
}

TEST(Whitted, FacingMirrorsStopAtMaxDepth) {
    Scene s;
    s.textures = {ConstantTexture{Color{1}}};
    s.materials = {ArticleMaterial{0, 1}};
    s.spheres.push_back(Sphere{{0, 0, 5}, 1, 0});
    s.spheres.push_back(Sphere{{0, 0, -5}, 1, 0});
    s.background = ConstantBackground{Color{1}};
    s.commit();
    for (int depth : {0, 1, 5, 100}) {
        const WhittedIntegrator w({0.5f, true, depth});
        RayCounter counter;
        const PixelSampler sampler(SamplerType::kSobol, 1, 0);
        SampleStream samples(sampler, 0);
        // Each bounce multiplies by d = 0.5; the last one sees the background (1).
        const Color c = w.li(s, Ray{{0, 0, 0}, {0, 0, 1}}, samples, counter);
        EXPECT_NEAR(c.r, std::pow(0.5, depth + 1), 1e-6) << depth;
        EXPECT_EQ(counter.rays, static_cast<std::uint64_t>(depth + 1));
    }
}

}  // namespace
}  // namespace glint
