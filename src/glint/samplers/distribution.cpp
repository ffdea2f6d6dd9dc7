#include "glint/samplers/distribution.h"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace glint {

Distribution1D::Distribution1D(const std::vector<float>& weights) {
    assert(!weights.empty());
    const std::size_t n = weights.size();
    double sum = 0;
    for (float w : weights) sum += std::isfinite(w) && w > 0 ? w : 0;
    total_ = sum;
    pmf_.resize(n);
    cdf_.resize(n + 1);
    cdf_[0] = 0;
    for (std::size_t i = 0; i < n; ++i) {
        const double w = std::isfinite(weights[i]) && weights[i] > 0 ? weights[i] : 0;
        const double p = sum > 0 ? w / sum : 1.0 / static_cast<double>(n);
        pmf_[i] = static_cast<float>(p);
        cdf_[i + 1] = cdf_[i] + p;
    }
    cdf_[n] = 1;
}

std::uint32_t Distribution1D::sample(float u, float* remapped) const {
    // The last i with cdf_[i] <= u and a non-empty interval.
    const auto it = std::upper_bound(cdf_.begin(), cdf_.end(), static_cast<double>(u));
    std::size_t i = static_cast<std::size_t>(std::max<std::ptrdiff_t>(0, it - cdf_.begin() - 1));
    i = std::min(i, pmf_.size() - 1);
    while (pmf_[i] == 0 && i > 0) --i;  // only reachable through rounding at an interval's end
    if (remapped) {
        const double width = cdf_[i + 1] - cdf_[i];
        const double r = width > 0 ? (static_cast<double>(u) - cdf_[i]) / width : 0.5;
        *remapped = std::clamp(static_cast<float>(r), 0.0f, 0x1.fffffep-1f);
    }
    return static_cast<std::uint32_t>(i);
}

Distribution2D::Distribution2D(const std::vector<float>& weights, int width, int height)
    : width_(width), height_(height) {
    assert(width > 0 && height > 0 &&
           weights.size() == static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
    std::vector<float> row_sums(static_cast<std::size_t>(height));
    rows_.reserve(static_cast<std::size_t>(height));
    for (int y = 0; y < height; ++y) {
        const auto first = weights.begin() + static_cast<std::ptrdiff_t>(y) * width;
        rows_.emplace_back(std::vector<float>(first, first + width));
        row_sums[static_cast<std::size_t>(y)] = static_cast<float>(rows_.back().total());
    }
    marginal_ = Distribution1D(row_sums);
}

Point2 Distribution2D::sample(Sample2 u, float* pdf) const {
    float uy = 0, ux = 0;
    const std::uint32_t row = marginal_.sample(u.y, &uy);
    const std::uint32_t col = rows_[row].sample(u.x, &ux);
    if (pdf) *pdf = marginal_.pmf(row) * rows_[row].pmf(col) * static_cast<float>(width_ * height_);
    return {(static_cast<float>(col) + ux) / static_cast<float>(width_),
            (static_cast<float>(row) + uy) / static_cast<float>(height_)};
}

float Distribution2D::pdf(Point2 p) const {
    const int col = std::clamp(static_cast<int>(p.x * static_cast<float>(width_)), 0, width_ - 1);
    const int row = std::clamp(static_cast<int>(p.y * static_cast<float>(height_)), 0, height_ - 1);
    return marginal_.pmf(static_cast<std::uint32_t>(row)) *
           rows_[static_cast<std::size_t>(row)].pmf(static_cast<std::uint32_t>(col)) *
           static_cast<float>(width_ * height_);
}

}  // namespace glint
