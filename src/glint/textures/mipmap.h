#pragma once
// MIP maps for filtered texture lookups (issue 34): an image's pyramid, each level a box
// downsample of the one before, and lookups over a footprint in uv: trilinear (isotropic,
// Williams 1983) and EWA (an elliptical Gaussian, Heckbert 1989, with pbrt's anisotropy clamp).
// A lookup whose footprint is below a texel reads level 0 bilinearly, as an unfiltered one does.
#include <algorithm>
#include <cmath>
#include <vector>

#include "glint/textures/texture.h"

namespace glint {

/// Levels 1, 2, ... of an image's pyramid; level 0 is the image itself, not copied. Level k + 1
/// is ceil(w / 2) x ceil(h / 2) of level k's w x h, down to 1 x 1; each of its texels is the
/// area-weighted mean of the level-k texels its square covers (odd sizes: fractions of texels),
/// so every level keeps the image's mean. The levels add at most a third of the texels, and a
/// few rows for odd sizes.
struct MipPyramid {
    std::vector<Image> levels;
    static MipPyramid build(const Image& image);
    /// Level k (0: the image).
    const Image& level(const Image& base, int k) const { return k == 0 ? base : levels[static_cast<std::size_t>(k - 1)]; }
    int count() const { return static_cast<int>(levels.size()) + 1; }
    std::size_t texels() const;  ///< in levels 1 and up
};

/// The mean of the texels within a square footprint `width` (in uv) wide around uv: level
/// log2(width x the larger side) of the pyramid, between two levels linearly, each read
/// bilinearly.
Color trilinear(const Image& base, const MipPyramid& pyramid, Point2 uv, Float width, WrapMode wrap_u,
                WrapMode wrap_v);

/// The elliptically weighted average over the footprint spanned by the uv differentials d0 and
/// d1 (the change of uv from one pixel to the next in x and in y): a Gaussian over the ellipse,
/// on the level where its minor axis spans about a texel (the major axis clamped to 8x the minor,
/// pbrt's choice, so that a lookup reads a bounded number of texels), between two levels.
Color ewa(const Image& base, const MipPyramid& pyramid, Point2 uv, Point2 d0, Point2 d1, WrapMode wrap_u,
          WrapMode wrap_v);

/// exp(-2 r^2) - exp(-2) for r^2 in [0, 1), from a table of 64 entries (pbrt's Gaussian for EWA).
float ewa_gaussian(double r2);

/// The elliptical filter's weights at one level: for texel coordinates (s, t) (texel centres at
/// integers) and the texel-space differentials d0, d1, calls `each(x, y, w)` for every texel
/// inside the ellipse they span (widened by a texel, so that it always holds one) with its weight
/// ewa_gaussian(r^2), r^2 the texel's squared radius in the ellipse; returns their sum. The
/// ellipse is cut to 32 texels either side of the centre (a lookup on its proper level never
/// reaches that).
template <typename Each>
double ewa_weights(Float s, Float t, Point2 d0, Point2 d1, Each each) {
    double a = double(d0.y) * d0.y + double(d1.y) * d1.y + 1;
    double b = -2 * (double(d0.x) * d0.y + double(d1.x) * d1.y);
    double c = double(d0.x) * d0.x + double(d1.x) * d1.x + 1;
    const double inv_f = 1 / (a * c - b * b * 0.25);
    a *= inv_f, b *= inv_f, c *= inv_f;
    const double det = 4 * a * c - b * b;
    const double half_s = std::min(2 * std::sqrt(det * c) / det, 32.0), half_t = std::min(2 * std::sqrt(a * det) / det, 32.0);
    if (!(half_s >= 0 && half_t >= 0)) return 0;
    const int s0 = static_cast<int>(std::ceil(s - half_s)), s1 = static_cast<int>(std::floor(s + half_s));
    const int t0 = static_cast<int>(std::ceil(t - half_t)), t1 = static_cast<int>(std::floor(t + half_t));
    double sum = 0;
    for (int y = t0; y <= t1; ++y) {
        const double dt = y - double(t);
        for (int x = s0; x <= s1; ++x) {
            const double ds = x - double(s);
            const double r2 = a * ds * ds + b * ds * dt + c * dt * dt;
            if (r2 >= 1) continue;
            const double w = ewa_gaussian(r2);
            sum += w;
            each(x, y, w);
        }
    }
    return sum;
}

}  // namespace glint
