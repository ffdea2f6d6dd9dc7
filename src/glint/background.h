#pragma once
// What a ray that leaves the scene sees. Under the path tracer the background is also a light
// (the environment), sampled by lights/light_sampler.h.
#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <variant>

#include "glint/math/color.h"
#include "glint/math/transform.h"
#include "glint/math/vector.h"
#include "glint/samplers/distribution.h"
#include "glint/textures/texture.h"

namespace glint {

/// The article's sky: t = 0.5 (D.y + 1), colour = (1-t) horizon + t zenith, for unit D.
struct SkyBackground {
    Color horizon{1, 1, 1};
    Color zenith{0.5f, 0.7f, 1.0f};
    Color eval(Vector3 d) const {
        const float t = 0.5f * (d.y + 1);
        return horizon * (1 - t) + zenith * t;
    }
};

struct ConstantBackground {
    Color color;
    Color eval(Vector3) const { return color; }
    /// Spectral mode: the sky's spectrum (Y = 1; `color` is its colour at the sky's luminance), or
    /// null for the colour upsampled.
    std::shared_ptr<const Spectrum> spectrum;
};

/// pbrt-v4's equal-area octahedral mapping (Clarberg's) of a unit direction to the square
/// [0,1]^2: +z at the centre, -z at the corners, the +z hemisphere the inner diamond; u grows with
/// x, v with y (v = 0 is the image's top row, as pbrt stores images).
Point2 equal_area_sphere_to_square(Vector3 d);

/// An equal-area octahedral environment image (square) resampled to glint's latitude-longitude
/// layout (2n x n for an n x n source): each texel takes the bilinearly filtered source at the
/// direction world_to_light(d) (pbrt's light transform, inverted).
Image equal_area_to_latlong(const Image& square, const Matrix34& world_to_light);

/// The illuminance a surface facing `up` receives from a latitude-longitude radiance map:
/// the integral of luminance x cos over the hemisphere around `up` (a midpoint sum over texels).
double illuminance(const Image& latlong, Vector3 up);

/// An HDR environment in the latitude-longitude layout: the image's top row is straight up
/// (+y), its bottom row straight down, its centre column looks along +z (where the default
/// camera looks) and its right half towards +x. Radiance = scale x the bilinearly filtered texel.
/// make() builds the importance-sampling distribution: per texel, the largest luminance of the
/// texel and its eight neighbours (so every direction the filter can light has density) times
/// sin(theta) (the texel's solid angle).
struct EnvironmentMap {
    Image image;
    float scale = 1;
    Distribution2D distribution;

    static EnvironmentMap make(Image image, float scale);

    /// (u, v) in [0,1)^2 with v = 0 at the top row, and back.
    static Point2 direction_to_uv(Vector3 d) {
        const float phi = std::atan2(d.x, d.z);
        const float theta = std::acos(std::clamp(d.y, -1.0f, 1.0f));
        return {0.5f + phi * (0.5f * std::numbers::inv_pi_v<float>),
                theta * std::numbers::inv_pi_v<float>};
    }
    static Vector3 uv_to_direction(Point2 uv) {
        const float theta = uv.y * std::numbers::pi_v<float>;
        const float phi = (uv.x - 0.5f) * 2 * std::numbers::pi_v<float>;
        const float s = std::sin(theta);
        return {s * std::sin(phi), std::cos(theta), s * std::cos(phi)};
    }
    /// Bilinear between texel centres, wrapping around in longitude, clamped at the poles.
    Color eval(Vector3 d) const;
};

using Background = std::variant<SkyBackground, ConstantBackground, EnvironmentMap>;

inline Color evaluate(const Background& bg, Vector3 d) {
    return std::visit([d](const auto& b) { return b.eval(d); }, bg);
}

}  // namespace glint
