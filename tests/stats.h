#pragma once
// Statistical helpers for the sampling tests.
#include <cmath>
#include <vector>

namespace glint::testing {

/// Pearson's chi-square statistic of observed counts against expected counts (same length).
inline double chi_square(const std::vector<double>& observed, const std::vector<double>& expected) {
    double x2 = 0;
    for (std::size_t i = 0; i < observed.size(); ++i) {
        const double d = observed[i] - expected[i];
        x2 += d * d / expected[i];
    }
    return x2;
}

/// The chi-square value exceeded with probability about 1e-4 for `dof` degrees of freedom
/// (Wilson-Hilferty: chi2/k is close to normal after a cube root; z = 3.719 for 1e-4).
inline double chi_square_critical_1e4(double dof) {
    const double z = 3.719;
    const double c = 2 / (9 * dof);
    return dof * std::pow(1 - c + z * std::sqrt(c), 3);
}

}  // namespace glint::testing
