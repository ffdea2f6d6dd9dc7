#pragma once
// The denoiser: a feature-guided filter of a rendered image, run on any CPU from what the
// renderer keeps beside the image (no trained weights). docs/denoising.md says why this design.
//
//  - Noise: each pixel's variance is estimated from two half images (the mean of the even- and
//    of the odd-numbered samples): E[(even - odd)^2] / 4 is the variance of the full mean. The
//    single-pixel estimate is smoothed over 5 x 5 pixels.
//  - Features (first non-specular hit: albedo, normal, depth) are prefiltered: each is averaged
//    over 3 x 3 pixels with weights from its own differences, so that a feature that varies per
//    sample (depth of field, edges) weighs less noisily.
//  - Weights over a (2r+1)^2 window: each neighbour weighs the least of a colour weight (non-local
//    means on 3 x 3 patches, distances normalised by the variance, Rousselle et al. 2012/2013) and
//    the feature weights; two sets, strict colour (k = 1) and loose colour (k = 2).
//  - Candidates: the strict weights' mean, and a plane in the image's coordinates fitted by
//    weighted least squares to each set's neighbours (first-order regression, as in Bitterli et
//    al. 2016, on the pixel position alone), evaluated at the pixel: where the features cut the
//    window to one side of the pixel (an edge, a corner), a mean is pulled towards that side's
//    gradient; the plane is not.
//  - Shading candidates (with the albedo's half images): the loose weights' mean and plane fit of
//    the shading s = c / (albedo + 0.01), times the pixel's own albedo, so that a texture finer
//    than the albedo feature's bandwidth is not averaged away. Their SURE gains
//    2 cov(a, c) (f - df s_p) per channel, the covariance of the albedo's and the colour's noise
//    from the halves: where the albedo's noise is the colour's (a texture's antialiasing) the
//    shading passes it through untouched, and the estimate must see it. Not considered where the
//    albedo's variance exceeds a quarter of its square (the first-order estimate fails there).
//  - Selection: per pixel, the candidate with the least estimated error, by Stein's unbiased
//    risk estimate (SURE, as Li et al. 2012 use it for rendering): |F(c) - c|^2 + sigma^2
//    (2 dF/dc - 1) per channel, with dF_p/dc_p the pixel's own weight in the candidate (w_pp /
//    sum w for the mean, the corner of the inverse moment matrix for a plane). The error maps are
//    smoothed over 7 x 7 pixels and the choice over 5 x 5, so that neighbouring pixels blend.
//
// Every pixel's sums are accumulated in a fixed order of offsets, so the result has the same bits
// for any number of threads. The image is filtered in strips of rows, each with the rows around
// it that it depends on, so the memory is bounded and the bits are those of the whole image.
#include <string>
#include <vector>

#include "glint/math/color.h"
#include "glint/math/vector.h"

namespace glint {

/// The planes the denoiser reads, row 0 at the top, `width * height` entries each.
struct DenoiseInput {
    int width = 0, height = 0;
    const Color* color = nullptr;   ///< the image (mean of all samples)
    const Color* even = nullptr;    ///< mean of the even-numbered samples
    const Color* odd = nullptr;     ///< mean of the odd-numbered samples
    const Color* albedo = nullptr;  ///< features; each may be null (then not used)
    const Normal3* normal = nullptr;
    const float* depth = nullptr;   ///< +inf where nothing was hit
    /// The albedo's half images (means of the even- and odd-numbered samples), optional: with
    /// them the filter also tries filtering the shading (colour / albedo), whose error estimate
    /// needs to know how the albedo's noise goes with the colour's.
    const Color* even_albedo = nullptr;
    const Color* odd_albedo = nullptr;
};

struct DenoiseOptions {
    int radius = 5;    ///< the window is (2 radius + 1)^2 pixels
    int threads = 0;   ///< 0: every core
    /// The image is filtered in strips of this many rows (each with the rows around it it
    /// depends on), which bounds the memory; 0: as many as fit 256 MB. The bits do not depend on it.
    int strip_rows = 0;
};

/// What the filter found, for tests and reports.
struct DenoiseStats {
    double seconds = 0;
    double chosen[5] = {0, 0, 0, 0, 0};  ///< the share of pixels each candidate won
};

/// The denoised image. Throws std::invalid_argument naming the first bad input: missing planes,
/// a size that is not positive, a value that is not finite (its pixel and plane).
std::vector<Color> denoise(const DenoiseInput& in, const DenoiseOptions& options = {},
                           DenoiseStats* stats = nullptr);

/// The per-pixel variance of the image's mean the filter uses (smoothed), per channel.
std::vector<Color> denoise_variance(const DenoiseInput& in);

}  // namespace glint
