#include "glint/film/filter.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace glint {

float filter_profile(const FilterDesc& f, float x) {
    const float r = f.radius;
    if (std::abs(x) > r) return 0;
    switch (f.type) {
        case FilterType::kBox: return 1;
        case FilterType::kTent: return 1 - std::abs(x) / r;
        case FilterType::kGaussian: {
            const float k = 1 / (2 * f.sigma * f.sigma);
            return std::max(0.0f, std::exp(-x * x * k) - std::exp(-r * r * k));
        }
        case FilterType::kBlackmanHarris: {
            constexpr float a0 = 0.35875f, a1 = 0.48829f, a2 = 0.14128f, a3 = 0.01168f;
            const float t = 2 * std::numbers::pi_v<float> * (x + r) / (2 * r);
            return a0 - a1 * std::cos(t) + a2 * std::cos(2 * t) - a3 * std::cos(3 * t);
        }
    }
    return 0;
}

FilterSampler::FilterSampler(const FilterDesc& filter) : filter_(filter) {
    // Tabulate the mean of f1 over each bin (8 midpoint samples per bin).
    const float r = filter.radius, width = 2 * r / kBins;
    double total = 0;
    std::array<double, kBins> mass{};
    for (int i = 0; i < kBins; ++i) {
        double m = 0;
        for (int j = 0; j < 8; ++j) m += filter_profile(filter, -r + (i + (j + 0.5f) / 8) * width);
        mass[static_cast<std::size_t>(i)] = m / 8 * width;
        total += mass[static_cast<std::size_t>(i)];
    }
    double running = 0;
    for (int i = 0; i < kBins; ++i) {
        const auto k = static_cast<std::size_t>(i);
        pdf_[k] = static_cast<float>(mass[k] / total / width);
        running += mass[k] / total;
        cdf_[k + 1] = static_cast<float>(running);
    }
    cdf_[kBins] = 1;
    std::fill(cdf_.begin() + kBins + 1, cdf_.end(), std::numeric_limits<float>::infinity());
    for (int j = 0, b = 0; j <= kGuide; ++j) {
        const float u = static_cast<float>(j) / kGuide;
        while (b < kBins && cdf_[static_cast<std::size_t>(b) + 1] <= u) ++b;
        guide_[static_cast<std::size_t>(j)] = static_cast<std::uint16_t>(b);
        if (j > 0) window_ = std::max(window_, b - guide_[static_cast<std::size_t>(j) - 1] + 1);
    }
}

float FilterSampler::sample_1d(float u, float& pdf) const {
    // The bin whose CDF interval holds u: the last CDF entry <= u (the filter test checks it
    // against a scan of the whole table), then linearly inside it. Searched in the guide's
    // window for u, by halving steps that select rather than branch: std::upper_bound over the
    // whole table mispredicted its way to 20 % of a Whitted render with a Gaussian filter
    // (docs/performance.md). Entries past the window are > u (or +inf past the table's end).
    const auto j = static_cast<std::size_t>(std::clamp(u * kGuide, 0.0f, static_cast<float>(kGuide)));
    const float* base = cdf_.data() + guide_[j];
    for (int n = window_; n > 1;) {
        const int half = n / 2;
        base = base[half] <= u ? base + half : base;
        n -= half;
    }
    const int bin = std::clamp(static_cast<int>(base - cdf_.data()), 0, kBins - 1);
    const auto k = static_cast<std::size_t>(bin);
    const float span = cdf_[k + 1] - cdf_[k];
    const float frac = span > 0 ? (u - cdf_[k]) / span : 0.5f;
    const float width = 2 * filter_.radius / kBins;
    pdf = pdf_[k];
    return -filter_.radius + (static_cast<float>(bin) + std::clamp(frac, 0.0f, 1.0f)) * width;
}

float FilterSampler::pdf_1d(float x) const {
    if (std::abs(x) >= filter_.radius) return 0;
    const float width = 2 * filter_.radius / kBins;
    const int bin = std::clamp(static_cast<int>((x + filter_.radius) / width), 0, kBins - 1);
    return pdf_[static_cast<std::size_t>(bin)];
}

FilterSampler::Sample FilterSampler::sample(Sample2 u) const {
    if (filter_.type == FilterType::kBox) {  // exact and cheap: uniform over the square
        return {(2 * u.x - 1) * filter_.radius, (2 * u.y - 1) * filter_.radius, 1};
    }
    float px = 0, py = 0;
    const float dx = sample_1d(u.x, px), dy = sample_1d(u.y, py);
    const float f = filter_profile(filter_, dx) * filter_profile(filter_, dy);
    return {dx, dy, px * py > 0 ? f / (px * py) : 0};
}

}  // namespace glint
