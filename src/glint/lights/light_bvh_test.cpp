// The light BVH against independent computations: the orientation measure against numerical
// integration, importance against the hand formula, cone unions against their members, the
// pmf summing to 1 (with the choices that find no light) and matching pick's frequencies (chi-square), and no light that can reach a
// point ever given probability 0 there.
#include "glint/lights/light_bvh.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "glint/math/frame.h"
#include "glint/samplers/hash.h"
#include "glint/scene.h"
#include "stats.h"
#include "testing.h"

namespace glint {
namespace {

constexpr double kPi = std::numbers::pi;

float rnd(std::uint32_t seed, std::uint32_t i) { return to_unit_float(hash_combine(seed, i)); }

Vector3 random_direction(std::uint32_t seed, std::uint32_t i) {
    const float z = 1 - 2 * rnd(seed, 2 * i), phi = 2 * std::numbers::pi_v<float> * rnd(seed, 2 * i + 1);
    const float r = std::sqrt(std::max(0.0f, 1 - z * z));
    return {r * std::cos(phi), r * std::sin(phi), z};
}

// M_Omega as its definition: the integral over the sphere of cos(theta - theta_o) where theta
// is beyond theta_o but within theta_o + theta_e, 1 inside theta_o (midpoint rule in theta).
double orientation_integral(double theta_o, double theta_e) {
    const int n = 200000;
    double sum = 0;
    for (int i = 0; i < n; ++i) {
        const double theta = (i + 0.5) * kPi / n;
        double f = 0;
        if (theta <= theta_o) f = 1;
        else if (theta <= std::min(theta_o + theta_e, kPi)) f = std::cos(theta - theta_o);
        sum += f * 2 * kPi * std::sin(theta) * kPi / n;
    }
    return sum;
}

TEST(LightBvh, OrientationMeasureMatchesItsIntegral) {
    for (const double theta_o : {0.0, 0.3, 1.0, 2.0, kPi}) {
        for (const double theta_e : {0.1, 0.7, kPi / 2}) {
            const float m = orientation_measure(static_cast<float>(std::cos(theta_o)), static_cast<float>(std::cos(theta_e)));
            EXPECT_NEAR(m, orientation_integral(theta_o, theta_e), 2e-3) << theta_o << " " << theta_e;
        }
    }
    // Two landmarks: a flat emitter's pi, a point light's 4 pi.
    EXPECT_NEAR(orientation_measure(1, 0), kPi, 1e-5);
    EXPECT_NEAR(orientation_measure(-1, 0), 4 * kPi, 1e-4);
}

TEST(LightBvh, ImportanceOfOneLightIsItsIrradianceBound) {
    LightBounds point;
    point.box.extend({1, 2, 3});
    point.phi = 5;
    point.cos_o = -1;
    // From (1, 2, 7): distance 4; in a medium (no normal), phi / d^2; on a surface, times the cosine.
    EXPECT_NEAR(importance(point, {1, 2, 7}, Normal3{0, 0, 0}), 5.0 / 16, 1e-6);
    EXPECT_NEAR(importance(point, {1, 2, 7}, normalize(Normal3{0, 1, 1})), 5.0 / 16 * std::sqrt(0.5), 1e-6);
    // A flat light facing +y, seen at 60 degrees off its normal: phi cos(60) / d^2.
    LightBounds flat;
    flat.box.extend({0, 0, 0});
    flat.phi = 2;
    flat.w = {0, 1, 0};
    const Point3 p{std::sin(60 * std::numbers::pi_v<float> / 180) * 3, std::cos(60 * std::numbers::pi_v<float> / 180) * 3, 0};
    EXPECT_NEAR(importance(flat, p, Normal3{0, 0, 0}), 2 * 0.5 / 9, 1e-6);
    // Behind it: nothing, unless two-sided.
    EXPECT_EQ(importance(flat, {0, -3, 0}, Normal3{0, 0, 0}), 0);
    flat.two_sided = true;
    EXPECT_NEAR(importance(flat, {0, -3, 0}, Normal3{0, 0, 0}), 2.0 / 9, 1e-6);
}

TEST(LightBvh, UnitedConesHoldBothCones) {
    for (std::uint32_t i = 0; i < 2000; ++i) {
        LightBounds a, b;
        a.phi = b.phi = 1;
        a.box.extend({0, 0, 0});
        b.box.extend({1, 1, 1});
        a.w = random_direction(1, i);
        b.w = random_direction(2, i);
        a.cos_o = std::cos(rnd(3, i) * 3.0f);
        b.cos_o = std::cos(rnd(4, i) * 3.0f);
        const LightBounds u = unite(a, b);
        // The edges of each cone, in 16 directions around its axis, lie in the union's cone.
        for (const LightBounds* c : {&a, &b}) {
            Vector3 t, s;
            orthonormal_basis(c->w, t, s);
            const float sin_o = std::sqrt(std::max(0.0f, 1 - c->cos_o * c->cos_o));
            for (int k = 0; k < 16; ++k) {
                const float phi = k * std::numbers::pi_v<float> / 8;
                const Vector3 d = c->w * c->cos_o + (t * std::cos(phi) + s * std::sin(phi)) * sin_o;
                EXPECT_GE(dot(d, u.w), u.cos_o - 2e-4f) << i;
            }
        }
    }
}

// Lights of every kind that has a place, scattered over a 20 x 20 area, with varied power, and
// distant ones: a sun and an environment.
Scene many_lights(int count, bool distant) {
    Scene s;
    s.materials = {DiffuseMaterial{0}, DiffuseMaterial{0}, DiffuseMaterial{0}};
    s.textures = {ConstantTexture{Color{0.5f}}};
    s.emission = {Emission{}, Emission{Color{2, 3, 4}, false, std::nullopt}, Emission{Color{1}, true, std::nullopt}};
    for (int i = 0; i < count; ++i) {
        const auto u = static_cast<std::uint32_t>(i);
        const Point3 c{20 * rnd(11, u) - 10, 4 * rnd(12, u), 20 * rnd(13, u) - 10};
        const float power = 0.1f + 10 * rnd(14, u) * rnd(15, u);
        switch (i % 5) {
            case 0: s.lights.push_back(PointLight{c, Color{power}}); break;
            case 1: {  // every other one hard-edged
                const float outer = i % 10 == 1 ? 0.3f : 0.5f;
                s.lights.push_back(SpotLight{c, random_direction(16, u), Color{power}, std::cos(0.3f), std::cos(outer)});
                break;
            }
            case 2: s.quads.push_back(Quad::make(c, random_direction(17, u) * 0.3f, random_direction(18, u) * 0.3f, 1)); break;
            case 3: s.triangles.push_back({c, c + random_direction(19, u) * 0.4f, c + random_direction(20, u) * 0.4f, 2}); break;
            default: s.spheres.push_back({c, 0.2f, 1}); break;
        }
    }
    if (distant) {
        s.lights.push_back(DirectionalLight{normalize(Vector3{0.3f, -1, 0.2f}), Color{3}});
        s.background = ConstantBackground{Color{0.3f}};
    } else {
        s.background = ConstantBackground{Color{0}};
    }
    s.commit();
    return s;
}

TEST(LightBvh, PmfSumsToOneWithTheChoicesThatFindNoLight) {
    for (const bool distant : {false, true}) {
        const Scene s = many_lights(200, distant);
        const LightSampler& ls = s.light_sampler();
        ASSERT_EQ(ls.kind(), LightSamplerKind::kBvh);
        ASSERT_FALSE(ls.bvh().empty());
        // Points are repetitions of one check: a fifth of them under the sanitizers.
        for (std::uint32_t k = 0; k < static_cast<std::uint32_t>(testing::scaled(50)); ++k) {
            const Point3 p{24 * rnd(30, k) - 12, 6 * rnd(31, k) - 1, 24 * rnd(32, k) - 12};
            const Normal3 n = k % 4 == 0 ? Normal3{0, 0, 0} : Normal3(random_direction(33, k));
            double sum = 0;
            for (std::uint32_t l = 0; l < ls.count(); ++l) sum += ls.pmf(p, n, l);
            // What is missing is the share of choices that end in a node none of whose lights
            // reaches p: the fraction of u in [0, 1) (stratified, so exact to a few 1/N) for
            // which pick finds no light.
            constexpr int kN = 100000;
            int none = 0;
            for (int i = 0; i < kN; ++i) {
                float pmf = 0;
                const std::uint32_t l = ls.pick(p, n, (i + 0.5f) / kN, &pmf);
                if (l == kNoLight) {
                    ++none;
                    EXPECT_EQ(pmf, 0);
                } else if (i % 97 == 0) {
                    EXPECT_EQ(pmf, ls.pmf(p, n, l));
                }
            }
            EXPECT_NEAR(sum + static_cast<double>(none) / kN, 1, 1e-3) << "point " << k;
            EXPECT_LT(none, kN / 2) << "point " << k;  // loose bounds waste some choices, not most
        }
    }
}

TEST(LightBvh, PickFrequenciesMatchThePmfChiSquare) {
    const Scene s = many_lights(60, true);
    const LightSampler& ls = s.light_sampler();
    for (std::uint32_t k = 0; k < 4; ++k) {
        const Point3 p{10 * rnd(40, k) - 5, 2, 10 * rnd(41, k) - 5};
        const Normal3 n(random_direction(42, k));
        // The last cell: choices that find no light.
        std::vector<double> observed(ls.count() + 1, 0), expected(ls.count() + 1, 0);
        constexpr int kN = 400000;
        for (int i = 0; i < kN; ++i) {
            float pmf = 0;
            const std::uint32_t l = ls.pick(p, n, rnd(43 + k, static_cast<std::uint32_t>(i)), &pmf);
            observed[std::min(l, ls.count())] += 1;
        }
        double rest = kN;
        for (std::uint32_t l = 0; l < ls.count(); ++l) {
            expected[l] = kN * static_cast<double>(ls.pmf(p, n, l));
            rest -= expected[l];
        }
        expected[ls.count()] = std::max(0.0, rest);
        // Cells expected below 5 are pooled (chi-square's rule), and must hold few observations.
        std::vector<double> obs, exp;
        double pool_o = 0, pool_e = 0;
        for (std::size_t l = 0; l < expected.size(); ++l) {
            if (expected[l] < 5) {
                pool_o += observed[l];
                pool_e += expected[l];
            } else {
                obs.push_back(observed[l]);
                exp.push_back(expected[l]);
            }
        }
        if (pool_e > 0) obs.push_back(pool_o), exp.push_back(pool_e);
        EXPECT_LT(testing::chi_square(obs, exp), testing::chi_square_critical_1e4(static_cast<double>(obs.size() - 1)))
            << "point " << k;
    }
}

// A light that sends something to p (a one-sided emitter facing it, a spot light whose cone
// holds it) must have a positive pmf there: the importance bounds may overestimate, never
// exclude.
TEST(LightBvh, NoLightThatReachesAPointIsExcluded) {
    const Scene s = many_lights(300, false);
    const LightSampler& ls = s.light_sampler();
    int reaching = 0;
    for (std::uint32_t k = 0; k < 400; ++k) {
        const Point3 p{24 * rnd(50, k) - 12, 6 * rnd(51, k) - 1, 24 * rnd(52, k) - 12};
        const Normal3 n = Normal3(random_direction(53, k));
        for (std::uint32_t l = 0; l < ls.count(); ++l) {
            bool reaches = false;
            for (std::uint32_t i = 0; i < 16 && !reaches; ++i) {
                const auto x = ls.sample_li(s, l, p, {rnd(54, i), rnd(55, i)});
                reaches = x && x->pdf > 0 && x->L.max_component() > 0 && dot(n, x->wi) != 0;
            }
            if (!reaches) continue;
            ++reaching;
            EXPECT_GT(ls.pmf(p, n, l), 0) << "light " << l << " at point " << k;
        }
    }
    EXPECT_GT(reaching, 10000);
}

// With one light, or every light the same, the BVH chooses as the power sampler does.
TEST(LightBvh, OneLightIsChosenAlways) {
    Scene s;
    s.lights.push_back(PointLight{{0, 5, 0}, Color{2}});
    s.background = ConstantBackground{Color{0}};
    s.commit();
    float pmf = 0;
    EXPECT_EQ(s.light_sampler().pick({0, 0, 0}, Normal3{0, 1, 0}, 0.7f, &pmf), 0u);
    EXPECT_EQ(pmf, 1);
}

}  // namespace
}  // namespace glint
