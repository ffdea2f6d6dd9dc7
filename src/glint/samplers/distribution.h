#pragma once
// Piecewise-constant distributions, for choosing lights by power and environment-map texels by
// luminance: sample by inverting the CDF, with the exact probability of what was chosen.
#include <cstdint>
#include <vector>

#include "glint/math/vector.h"
#include "glint/samplers/stratified.h"

namespace glint {

/// A discrete distribution over n >= 1 non-negative weights (all zero: uniform).
class Distribution1D {
public:
    Distribution1D() = default;
    explicit Distribution1D(const std::vector<float>& weights);
    std::uint32_t size() const { return static_cast<std::uint32_t>(pmf_.size()); }
    /// The index whose CDF interval holds u in [0, 1), and u remapped to [0, 1) within it (so
    /// one random number can serve twice).
    std::uint32_t sample(float u, float* remapped = nullptr) const;
    float pmf(std::uint32_t i) const { return pmf_[i]; }
    /// Sum of the weights given to the constructor.
    double total() const { return total_; }

private:
    std::vector<float> pmf_;
    std::vector<double> cdf_;  ///< cdf_[i] = P(index < i); cdf_[n] = 1
    double total_ = 0;
};

/// A 2D piecewise-constant density on [0,1)^2 over a width x height grid of weights (row-major,
/// row 0 at v = 0): a marginal over rows, then a conditional over the columns of the row.
class Distribution2D {
public:
    Distribution2D() = default;
    Distribution2D(const std::vector<float>& weights, int width, int height);
    /// A point of [0,1)^2 and its density with respect to area on the unit square.
    Point2 sample(Sample2 u, float* pdf) const;
    float pdf(Point2 p) const;
    int width() const { return width_; }
    int height() const { return height_; }

private:
    int width_ = 0, height_ = 0;
    Distribution1D marginal_;
    std::vector<Distribution1D> rows_;
};

}  // namespace glint
