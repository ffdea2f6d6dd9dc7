// glint_rgb2spec: tabulates the sigmoid-polynomial coefficients of every RGB reflectance (see
// rgb_spectrum_model.h) and writes them as a binary file of floats, built into the library.
//
// For a target linear sRGB colour rho, the coefficients c minimise |rgb(c) - rho|^2, where rgb(c)
// is the colour of the reflectance s_c lit by D65 (the white of sRGB): the CIE 1931 integrals of
// s_c(lambda) D65(lambda) at 1 nm, over the integral of y-bar, through the XYZ-to-sRGB matrix.
// Levenberg-Marquardt with the exact Jacobian (the sigmoid's derivative is closed form). Each grid
// row is solved outwards from z = 0.2, every node starting from its neighbour's solution.
//
// usage: glint_rgb2spec OUTPUT.bin
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <thread>
#include <vector>

#include "glint/spectra/rgb_spectrum_model.h"
#include "glint/spectra/spectrum.h"

namespace {

using namespace glint;
using Vec3 = std::array<double, 3>;

struct Weights {
    std::vector<double> t;           // the mapped wavelength of each 1 nm sample
    std::vector<Vec3> w;             // its contribution to linear sRGB per unit reflectance
};

Weights make_weights() {
    Weights W;
    const double norm = 1.0 / cie_y_integral();
    for (int l = 360; l <= 830; ++l) {
        const Xyz c = cie_xyz(float(l));
        const double e = d65()(float(l)) * norm;
        const Color rgb = xyz_to_linear_srgb({float(c.x * e), float(c.y * e), float(c.z * e)});
        W.t.push_back(rgb_model::wavelength_t(float(l)));
        W.w.push_back({rgb.r, rgb.g, rgb.b});
    }
    return W;
}

// rgb(c) and its Jacobian d rgb / d c.
void eval(const Weights& W, const Vec3& c, Vec3& rgb, double J[3][3]) {
    rgb = {0, 0, 0};
    for (int a = 0; a < 3; ++a) for (int b = 0; b < 3; ++b) J[a][b] = 0;
    for (std::size_t s = 0; s < W.t.size(); ++s) {
        const double t = W.t[s];
        const double x = (c[0] * t + c[1]) * t + c[2];
        const double q = 1 + x * x;
        const double v = 0.5 + x / (2 * std::sqrt(q));
        const double dv = 0.5 / (q * std::sqrt(q));
        const double dc[3] = {dv * t * t, dv * t, dv};
        for (int a = 0; a < 3; ++a) {
            rgb[a] += v * W.w[s][a];
            for (int b = 0; b < 3; ++b) J[a][b] += dc[b] * W.w[s][a];
        }
    }
}

bool solve3(double A[3][3], const Vec3& b, Vec3& x) {
    const double det = A[0][0] * (A[1][1] * A[2][2] - A[1][2] * A[2][1]) -
                       A[0][1] * (A[1][0] * A[2][2] - A[1][2] * A[2][0]) +
                       A[0][2] * (A[1][0] * A[2][1] - A[1][1] * A[2][0]);
    if (!(std::abs(det) > 1e-300)) return false;
    for (int k = 0; k < 3; ++k) {
        double M[3][3];
        for (int r = 0; r < 3; ++r)
            for (int q = 0; q < 3; ++q) M[r][q] = q == k ? b[r] : A[r][q];
        x[k] = (M[0][0] * (M[1][1] * M[2][2] - M[1][2] * M[2][1]) - M[0][1] * (M[1][0] * M[2][2] - M[1][2] * M[2][0]) +
                M[0][2] * (M[1][0] * M[2][1] - M[1][1] * M[2][0])) / det;
    }
    return true;
}

double error2(const Vec3& rgb, const Vec3& target) {
    double e = 0;
    for (int a = 0; a < 3; ++a) e += (rgb[a] - target[a]) * (rgb[a] - target[a]);
    return e;
}

// Levenberg-Marquardt from c towards the target; c is updated in place.
void fit(const Weights& W, const Vec3& target, Vec3& c) {
    double lambda = 1e-3;
    Vec3 rgb;
    double J[3][3];
    eval(W, c, rgb, J);
    double e = error2(rgb, target);
    for (int it = 0; it < 100 && e > 1e-14; ++it) {
        // (J^T J + lambda diag) d = J^T r
        Vec3 r{target[0] - rgb[0], target[1] - rgb[1], target[2] - rgb[2]}, g{};
        double A[3][3];
        for (int a = 0; a < 3; ++a) {
            for (int b = 0; b < 3; ++b) {
                A[a][b] = 0;
                for (int k = 0; k < 3; ++k) A[a][b] += J[k][a] * J[k][b];
            }
            for (int k = 0; k < 3; ++k) g[a] += J[k][a] * r[k];
        }
        bool improved = false;
        for (int tries = 0; tries < 12 && !improved; ++tries) {
            double B[3][3];
            for (int a = 0; a < 3; ++a)
                for (int b = 0; b < 3; ++b) B[a][b] = A[a][b] + (a == b ? lambda * (A[a][a] + 1e-12) : 0);
            Vec3 d;
            if (!solve3(B, g, d)) { lambda *= 10; continue; }
            const Vec3 c2{c[0] + d[0], c[1] + d[1], c[2] + d[2]};
            Vec3 rgb2;
            double J2[3][3];
            eval(W, c2, rgb2, J2);
            const double e2 = error2(rgb2, target);
            if (e2 < e && std::isfinite(e2)) {
                c = c2, rgb = rgb2, e = e2;
                for (int a = 0; a < 3; ++a) for (int b = 0; b < 3; ++b) J[a][b] = J2[a][b];
                lambda = std::max(lambda / 10, 1e-9);
                improved = true;
            } else {
                lambda *= 10;
            }
        }
        if (!improved) break;
    }
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: glint_rgb2spec OUTPUT.bin\n");
        return 2;
    }
    using namespace glint::rgb_model;
    const Weights W = make_weights();
    std::vector<float> table(kTableFloats);
    const auto row = [&](int l, int j, int i) {
        const int start = kRes / 5;
        Vec3 c{0, 0, 0};
        const auto solve_at = [&](int k, Vec3& cc) {
            const double z = z_node(k), x = x_node(i), y = x_node(j);
            Vec3 target;
            target[l] = z, target[(l + 1) % 3] = x * z, target[(l + 2) % 3] = y * z;
            fit(W, target, cc);
            for (int a = 0; a < 3; ++a) table[node(l, k, j, i) + a] = float(cc[a]);
        };
        Vec3 up = c;
        for (int k = start; k < kRes; ++k) solve_at(k, up);
        Vec3 down = c;
        solve_at(start, down);
        for (int k = start - 1; k >= 0; --k) solve_at(k, down);
    };
    const unsigned threads = std::max(1u, std::min(8u, std::thread::hardware_concurrency()));
    std::vector<std::thread> pool;
    for (unsigned t = 0; t < threads; ++t) {
        pool.emplace_back([&, t] {
            for (int n = int(t); n < 3 * kRes * kRes; n += int(threads)) row(n / (kRes * kRes), (n / kRes) % kRes, n % kRes);
        });
    }
    for (auto& th : pool) th.join();
    std::FILE* f = std::fopen(argv[1], "wb");
    if (!f || std::fwrite(table.data(), sizeof(float), table.size(), f) != table.size() || std::fclose(f) != 0) {
        std::fprintf(stderr, "glint_rgb2spec: cannot write %s\n", argv[1]);
        return 1;
    }
    return 0;
}
