#pragma once
// Pixel reconstruction filters, by filter importance sampling (as in pbrt-v4): each pixel's
// sample offsets are drawn with a density close to the filter f, and weighted by f / pdf; the
// pixel is sum(w L) / sum(w). Every sample still belongs to exactly one pixel, so images stay
// bit-identical for any thread count (splatting to neighbours would break that).
//
// All filters here are separable, f(x, y) = f1(x) f1(y), and non-negative. Each axis is sampled
// from a piecewise-constant table of f1 over [-radius, radius] (kBins bins, inverted CDF), which
// keeps stratified inputs stratified.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "glint/samplers/stratified.h"

namespace glint {

enum class FilterType { kBox, kTent, kGaussian, kBlackmanHarris };

struct FilterDesc {
    FilterType type = FilterType::kBox;
    float radius = 0.5f;  ///< in pixels
    float sigma = 0.5f;   ///< Gaussian only
};

/// The 1D filter profile f1(x), zero outside [-radius, radius]:
///  box 1; tent 1 - |x|/r; Gaussian exp(-x^2/2s^2) - exp(-r^2/2s^2) (truncated to reach 0 at r);
///  Blackman-Harris a0 - a1 cos(2 pi t) + a2 cos(4 pi t) - a3 cos(6 pi t), t = (x + r)/2r,
///  with Harris's 4-term coefficients (0.35875, 0.48829, 0.14128, 0.01168).
float filter_profile(const FilterDesc& filter, float x);

class FilterSampler {
public:
    struct Sample {
        float dx, dy;  ///< offset from the pixel centre, in pixels
        float weight;  ///< f(dx, dy) / pdf(dx, dy)
    };

    explicit FilterSampler(const FilterDesc& filter);
    Sample sample(Sample2 u) const;
    /// The density of one axis' offsets (for tests).
    float pdf_1d(float x) const;
    static constexpr int kBins = 256;
    /// The table inverted (for tests): cdf()[k] = the probability of bins 0 .. k-1, k <= kBins.
    std::span<const float> cdf() const { return {cdf_.data(), kBins + 1}; }

private:
    float sample_1d(float u, float& pdf) const;

    FilterDesc filter_;
    std::array<float, kBins> pdf_{};      ///< per bin, normalised over [-r, r]
    /// cdf_[0] = 0, cdf_[kBins] = 1, then +inf: a search window may reach past the end.
    std::array<float, 2 * kBins + 2> cdf_{};
    /// guide_[j]: the last CDF entry <= j / kGuide, so that u's bin lies in [guide_[j],
    /// guide_[j + 1]] for j = floor(u kGuide): a search of `window_` entries, not of all.
    static constexpr int kGuide = 1024;
    std::array<std::uint16_t, kGuide + 1> guide_{};
    int window_ = 1;  ///< the most entries any guide interval holds
};

}  // namespace glint
