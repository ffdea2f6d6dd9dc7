#include "glint/film/filter.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "glint/samplers/hash.h"
#include "stats.h"

namespace glint {
namespace {

const FilterDesc kFilters[] = {{FilterType::kBox, 0.5f, 0.5f},
                               {FilterType::kTent, 1.0f, 0.5f},
                               {FilterType::kGaussian, 1.5f, 0.5f},
                               {FilterType::kBlackmanHarris, 1.5f, 0.5f}};

Sample2 uniform(std::uint32_t i) {
    return {to_unit_float(mix32(2 * i + 991)), to_unit_float(mix32(2 * i + 992))};
}

TEST(Filter, ProfilesHandValues) {
    const FilterDesc tent{FilterType::kTent, 2, 0.5f};
    EXPECT_FLOAT_EQ(filter_profile(tent, 0), 1);
    EXPECT_FLOAT_EQ(filter_profile(tent, 1), 0.5f);
    EXPECT_FLOAT_EQ(filter_profile(tent, -2), 0);
    EXPECT_FLOAT_EQ(filter_profile(tent, 2.5f), 0);
    const FilterDesc gauss{FilterType::kGaussian, 1.5f, 0.5f};
    EXPECT_NEAR(filter_profile(gauss, 0), 1 - std::exp(-4.5), 1e-6);  // r^2 / 2s^2 = 4.5
    EXPECT_NEAR(filter_profile(gauss, 1.5f), 0, 1e-6);
    const FilterDesc bh{FilterType::kBlackmanHarris, 1.5f, 0.5f};
    EXPECT_NEAR(filter_profile(bh, 0), 0.35875 + 0.48829 + 0.14128 + 0.01168, 1e-6);  // = 1
    EXPECT_NEAR(filter_profile(bh, 1.5f), 0.35875 - 0.48829 + 0.14128 - 0.01168, 1e-6);
}

TEST(Filter, TheOffsetIsTheInvertedTableByALinearScan) {
    // The bin search against the plainest one: the last CDF entry not above u, found by scanning;
    // at every entry exactly, one float either side of it, and on a grid of u.
    for (const FilterDesc& f : kFilters) {
        if (f.type == FilterType::kBox) continue;  // sampled in closed form, no table
        const FilterSampler sampler(f);
        const auto& cdf = sampler.cdf();
        std::vector<float> us;
        for (const float c : cdf)
            for (const float u : {std::nextafter(c, 0.0f), c, std::nextafter(c, 1.0f)})
                if (u >= 0 && u < 1) us.push_back(u);
        for (int i = 0; i < 4096; ++i) us.push_back(static_cast<float>(i) / 4096);
        const float width = 2 * f.radius / FilterSampler::kBins;
        for (const float u : us) {
            int bin = 0;
            for (int k = 0; k <= FilterSampler::kBins; ++k)
                if (cdf[static_cast<std::size_t>(k)] <= u) bin = std::min(k, FilterSampler::kBins - 1);
            const auto b = static_cast<std::size_t>(bin);
            const float span = cdf[b + 1] - cdf[b];
            const float frac = span > 0 ? (u - cdf[b]) / span : 0.5f;
            const float want = -f.radius + (static_cast<float>(bin) + std::clamp(frac, 0.0f, 1.0f)) * width;
            ASSERT_EQ(sampler.sample({u, 0.5f}).dx, want) << static_cast<int>(f.type) << " u " << u;
        }
    }
}

TEST(Filter, OffsetsFollowTheTabulatedDensity) {
    // Chi-square of the sampled x offsets against the sampler's own pdf, 32 bins.
    for (const FilterDesc& f : kFilters) {
        const FilterSampler sampler(f);
        const int bins = 32, n = 100000;
        std::vector<double> observed(bins, 0), expected(bins, 0);
        for (int i = 0; i < n; ++i) {
            const float x = sampler.sample(uniform(static_cast<std::uint32_t>(i))).dx;
            ASSERT_LE(std::abs(x), f.radius);
            observed[static_cast<std::size_t>(std::clamp(static_cast<int>((x + f.radius) / (2 * f.radius) * bins), 0, bins - 1))] += 1;
        }
        const double width = 2.0 * f.radius / bins;
        for (int b = 0; b < bins; ++b) {  // integrate the pdf over the bin (fine midpoint rule)
            double p = 0;
            for (int j = 0; j < 64; ++j)
                p += sampler.pdf_1d(static_cast<float>(-f.radius + (b + (j + 0.5) / 64) * width));
            expected[static_cast<std::size_t>(b)] = p / 64 * width * n;
        }
        // Merge near-empty tail bins (Blackman-Harris reaches 6e-5) as chi-square requires.
        std::vector<double> obs, exp;
        double o_tail = 0, e_tail = 0;
        for (int b = 0; b < bins; ++b) {
            if (expected[static_cast<std::size_t>(b)] < 5) {
                o_tail += observed[static_cast<std::size_t>(b)];
                e_tail += expected[static_cast<std::size_t>(b)];
            } else {
                obs.push_back(observed[static_cast<std::size_t>(b)]);
                exp.push_back(expected[static_cast<std::size_t>(b)]);
            }
        }
        if (e_tail > 0) obs.push_back(o_tail), exp.push_back(e_tail);
        EXPECT_LT(testing::chi_square(obs, exp), testing::chi_square_critical_1e4(static_cast<double>(obs.size()) - 1))
            << static_cast<int>(f.type);
    }
}

TEST(Filter, WeightedSamplesReproduceTheFilter) {
    // The estimator sum(w g(x)) / sum(w) must converge to integral(f g) / integral(f): for g the
    // indicator of each of 12 bins, compare with the filter integrated independently (a fine
    // midpoint rule over filter_profile, not the sampler's table).
    for (const FilterDesc& f : kFilters) {
        const FilterSampler sampler(f);
        const int bins = 12, n = 200000;
        std::vector<double> weighted(bins, 0);
        double weight_sum = 0;
        for (int i = 0; i < n; ++i) {
            const FilterSampler::Sample s = sampler.sample(uniform(static_cast<std::uint32_t>(i)));
            ASSERT_GE(s.weight, 0);
            weighted[static_cast<std::size_t>(std::clamp(static_cast<int>((s.dx + f.radius) / (2 * f.radius) * bins), 0, bins - 1))] += s.weight;
            weight_sum += s.weight;
        }
        std::vector<double> truth(bins, 0);
        double total = 0;
        const int fine = 100000;
        for (int j = 0; j < fine; ++j) {
            const double x = -f.radius + (j + 0.5) * 2 * f.radius / fine;
            const double v = filter_profile(f, static_cast<float>(x));
            truth[static_cast<std::size_t>(std::min(bins - 1, j * bins / fine))] += v;
            total += v;
        }
        for (int b = 0; b < bins; ++b) {
            EXPECT_NEAR(weighted[static_cast<std::size_t>(b)] / weight_sum,
                        truth[static_cast<std::size_t>(b)] / total, 0.004)
                << static_cast<int>(f.type) << " bin " << b;
        }
    }
}

}  // namespace
}  // namespace glint
