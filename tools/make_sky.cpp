// Writes a procedural HDR sky as a latitude-longitude EXR, for scenes/materials.yaml: a blue
// gradient from a pale horizon to the zenith, a dim ground below the horizon, and a sun of
// angular radius 3 degrees and radiance 200 at 35 degrees elevation, to the camera's left and
// behind it. The layout is glint's (background.h): top row straight up, centre column along +z.
//
//   glint_make_sky OUT.exr [WIDTH HEIGHT]      (default 128 x 64)
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <string>

#include "glint/background.h"
#include "glint/film/film.h"
#include "glint/image/image_io.h"

namespace {

glint::Color sky(glint::Vector3 d) {
    using glint::Color;
    constexpr float kPi = std::numbers::pi_v<float>;
    const float elevation = 35 * kPi / 180, azimuth = -130 * kPi / 180;  // atan2(x, z)
    const glint::Vector3 sun{std::cos(elevation) * std::sin(azimuth), std::sin(elevation),
                             std::cos(elevation) * std::cos(azimuth)};
    if (dot(d, sun) > std::cos(3 * kPi / 180)) return Color{200, 190, 170};
    if (d.y < 0) return Color{0.25f, 0.22f, 0.2f};
    const float t = std::sqrt(d.y);
    return Color{0.95f, 0.97f, 1.0f} * (1 - t) + Color{0.25f, 0.45f, 0.9f} * t;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 2 && argc != 4) {
        std::fprintf(stderr, "usage: %s OUT.exr [WIDTH HEIGHT]\n", argv[0]);
        return 2;
    }
    const int w = argc == 4 ? std::atoi(argv[2]) : 128, h = argc == 4 ? std::atoi(argv[3]) : 64;
    if (w < 2 || h < 2 || w > 16384 || h > 8192) {
        std::fprintf(stderr, "size must be within 2..16384 x 2..8192\n");
        return 2;
    }
    glint::Film film(w, h);
    // Each texel averages 4 x 4 directions, so the sun's edge is antialiased.
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            glint::Color sum{0};
            for (int j = 0; j < 4; ++j) {
                for (int i = 0; i < 4; ++i) {
                    const glint::Point2 uv{(static_cast<float>(x) + (static_cast<float>(i) + 0.5f) / 4) / static_cast<float>(w),
                                           (static_cast<float>(y) + (static_cast<float>(j) + 0.5f) / 4) / static_cast<float>(h)};
                    sum += sky(glint::EnvironmentMap::uv_to_direction(uv));
                }
            }
            film.at(x, y) = sum / 16;
        }
    }
    try {
        glint::write_image(argv[1], film, {});
    } catch (const std::exception& e) {
        std::fprintf(stderr, "glint_make_sky: %s\n", e.what());
        return 1;
    }
    return 0;
}
