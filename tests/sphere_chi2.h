#pragma once
// Goodness of fit of a direction sampler against its claimed density over the unit sphere
// (pbrt-v4's and Mitsuba's test): histogram the samples in cells of equal theta x phi extent
// (small cells at the poles, where narrow lobes peak), integrate the density over each cell
// numerically (midpoint rule with the sin(theta) measure), add one cell for what the density does not
// cover (delta samples, failures), pool cells with expected counts below 5, and compare with a
// chi-square test at significance 1e-4.
#include <cmath>
#include <functional>
#include <limits>
#include <algorithm>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "glint/math/vector.h"
#include "stats.h"

namespace glint::testing {

struct SphereFit {
    double chi2 = 0, critical = 0;
    double pdf_integral = 0;   ///< the density's integral over the sphere
    double other_fraction = 0; ///< samples outside the density (delta or failed)
    bool ok() const { return chi2 < critical; }
    std::string report() const {
        return "chi2 " + std::to_string(chi2) + " vs critical " + std::to_string(critical) +
               ", integral of pdf " + std::to_string(pdf_integral) + ", other " +
               std::to_string(other_fraction);
    }
};

/// `sample` returns a unit direction covered by the density, or nullopt for anything else.
inline SphereFit fit_sphere(const std::function<std::optional<Vector3>(int)>& sample,
                            const std::function<double(Vector3)>& pdf, int n_samples,
                            int n_theta = 20, int n_phi = 40, int sub = 12) {
    const double pi = std::numbers::pi;
    const auto cell_of = [&](Vector3 w) {
        const double theta = std::acos(std::clamp<double>(w.z, -1, 1));
        int t = static_cast<int>(theta / pi * n_theta);
        t = std::clamp(t, 0, n_theta - 1);
        double phi = std::atan2(w.y, w.x);
        if (phi < 0) phi += 2 * pi;
        int p = std::clamp(static_cast<int>(phi / (2 * pi) * n_phi), 0, n_phi - 1);
        return t * n_phi + p;
    };
    const int cells = n_theta * n_phi;
    std::vector<double> observed(static_cast<std::size_t>(cells) + 1, 0);
    for (int i = 0; i < n_samples; ++i) {
        const auto w = sample(i);
        if (w) observed[static_cast<std::size_t>(cell_of(*w))] += 1;
        else observed.back() += 1;
    }
    std::vector<double> expected(observed.size(), 0);
    double integral = 0;
    const double dtheta = pi / n_theta, dphi = 2 * pi / n_phi;
    // Midpoint rule on a sub x sub grid; cells the density's support only partly covers (a
    // light's edge, total internal reflection) are integrated again on a 256 x 256 grid, since a
    // step is where the midpoint rule is least accurate.  Refining where samples landed only
    // makes the integral more accurate; it cannot hide a sample the density does not allow.
    const auto integrate_cell = [&](int t, int p, int n, bool* mixed) {
        double sum = 0;
        bool any_zero = false, any_positive = false;
        for (int a = 0; a < n; ++a) {
            for (int b = 0; b < n; ++b) {
                const double theta = (t + (a + 0.5) / n) * dtheta;
                const double phi = (p + (b + 0.5) / n) * dphi;
                const double r = std::sin(theta);
                const double v = pdf(Vector3{static_cast<float>(r * std::cos(phi)),
                                             static_cast<float>(r * std::sin(phi)),
                                             static_cast<float>(std::cos(theta))});
                (v > 0 ? any_positive : any_zero) = true;
                sum += r * v;
            }
        }
        if (mixed) *mixed = any_zero && any_positive;
        return sum / (n * n);
    };
    for (int t = 0; t < n_theta; ++t) {
        for (int p = 0; p < n_phi; ++p) {
            bool mixed = false;
            double sum = integrate_cell(t, p, sub, &mixed);
            // Also where the coarse grid saw no support but samples landed (a sliver of an edge).
            const bool sampled = observed[static_cast<std::size_t>(t * n_phi + p)] > 0;
            if (mixed || (sum == 0 && sampled)) sum = integrate_cell(t, p, 256, nullptr);
            const double mass = sum * dtheta * dphi;
            integral += mass;
            expected[static_cast<std::size_t>(t * n_phi + p)] = mass * n_samples;
        }
    }
    expected.back() = std::max(0.0, 1 - integral) * n_samples;
    // Pool the small cells.
    std::vector<double> obs, exp;
    double pool_o = 0, pool_e = 0;
    for (std::size_t i = 0; i < observed.size(); ++i) {
        if (expected[i] < 5) {
            pool_o += observed[i];
            pool_e += expected[i];
        } else {
            obs.push_back(observed[i]);
            exp.push_back(expected[i]);
        }
    }
    if (pool_e > 0) {
        obs.push_back(pool_o);
        exp.push_back(pool_e);
    } else if (pool_o > 0) {
        obs.push_back(pool_o);  // samples where the density says none can be
        exp.push_back(1e-3);
    }
    SphereFit fit;
    fit.pdf_integral = integral;
    fit.other_fraction = observed.back() / n_samples;
    if (obs.size() < 2) {  // everything in one cell (a pure delta): nothing to test here
        fit.critical = std::numeric_limits<double>::infinity();
        return fit;
    }
    fit.chi2 = chi_square(obs, exp);
    fit.critical = chi_square_critical_1e4(static_cast<double>(obs.size() - 1));
    fit.pdf_integral = integral;
    fit.other_fraction = observed.back() / n_samples;
    return fit;
}

}  // namespace glint::testing
