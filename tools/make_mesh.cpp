// Writes a large test mesh as binary little-endian PLY, for benchmarks (never committed): a
// sphere whose radius is displaced by a sum of sines, so that the surface has detail at many
// scales like a scanned or sculpted model. Two tessellations:
//   cube (default)  each face of a cube as an N x N grid of quads, projected onto the sphere:
//                   12 N^2 triangles of nearly equal size (N = 289: 1,002,252 triangles)
//   latlong         an N x 2N latitude-longitude grid, 4 N (N - 1) triangles, whose poles are
//                   fans of 2N slivers (N = 500: 998,000 triangles): the case spatial splits
//                   (SBVH) exist for
//
//   glint_make_mesh OUT.ply [N [cube|latlong]]      (default 289 cube)
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <numbers>
#include <string>
#include <vector>

int main(int argc, char** argv) {
    if (argc < 2 || argc > 4) {
        std::fprintf(stderr, "usage: glint_make_mesh OUT.ply [N [cube|latlong]]\n");
        return 2;
    }
    const long n = argc >= 3 ? std::strtol(argv[2], nullptr, 10) : 289;
    const std::string kind = argc == 4 ? argv[3] : "cube";
    if (kind != "cube" && kind != "latlong") {
        std::fprintf(stderr, "glint_make_mesh: unknown tessellation '%s' (known: cube, latlong)\n", kind.c_str());
        return 2;
    }
    if (n < 2 || n > 20000) {
        std::fprintf(stderr, "glint_make_mesh: N must be in [2, 20000]\n");
        return 2;
    }
    constexpr double kPi = std::numbers::pi;
    const long rows = n, cols = 2 * n;
    std::vector<float> v;
    // Poles are single vertices; rows 1..rows-1 are rings of `cols` vertices.
    const auto radius = [](double th, double ph) {
        return 1 + 0.08 * std::sin(7 * th) * std::sin(9 * ph) + 0.03 * std::sin(31 * th + 2) * std::sin(29 * ph) +
               0.01 * std::sin(97 * th) * std::sin(101 * ph + 1);
    };
    const auto push = [&](double th, double ph) {
        const double r = radius(th, ph);
        v.push_back(static_cast<float>(r * std::sin(th) * std::cos(ph)));
        v.push_back(static_cast<float>(r * std::cos(th)));
        v.push_back(static_cast<float>(r * std::sin(th) * std::sin(ph)));
    };
    std::vector<std::uint32_t> f;
    if (kind == "cube") {
        // Face k: the points c + s u + t w for s, t in [-1, 1], normalised, then displaced.
        const double frames[6][9] = {{1, 0, 0, 0, 0, 1, 0, 1, 0},  {-1, 0, 0, 0, 1, 0, 0, 0, 1},
                                     {0, 1, 0, 1, 0, 0, 0, 0, 1},  {0, -1, 0, 0, 0, 1, 1, 0, 0},
                                     {0, 0, 1, 0, 1, 0, 1, 0, 0},  {0, 0, -1, 1, 0, 0, 0, 1, 0}};
        for (const auto& fr : frames) {
            const std::uint32_t base = static_cast<std::uint32_t>(v.size() / 3);
            for (long i = 0; i <= n; ++i)
                for (long j = 0; j <= n; ++j) {
                    const double a = -1 + 2.0 * i / n, b = -1 + 2.0 * j / n;
                    double p[3];
                    for (int k = 0; k < 3; ++k) p[k] = fr[k] + a * fr[3 + k] + b * fr[6 + k];
                    const double len = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
                    const double th = std::acos(p[1] / len), ph = std::atan2(p[2], p[0]);
                    const double r = radius(th, ph) / len;
                    for (int k = 0; k < 3; ++k) v.push_back(static_cast<float>(p[k] * r));
                }
            const auto at = [&](long i, long j) { return static_cast<std::uint32_t>(base + i * (n + 1) + j); };
            for (long i = 0; i < n; ++i)
                for (long j = 0; j < n; ++j) {
                    f.insert(f.end(), {at(i, j), at(i + 1, j), at(i + 1, j + 1)});
                    f.insert(f.end(), {at(i, j), at(i + 1, j + 1), at(i, j + 1)});
                }
        }
    } else {
    push(0, 0);
    for (long i = 1; i < rows; ++i)
        for (long j = 0; j < cols; ++j) push(kPi * i / rows, 2 * kPi * j / cols);
    push(kPi, 0);
    const auto ring = [&](long i, long j) { return static_cast<std::uint32_t>(1 + (i - 1) * cols + (j % cols)); };
    const std::uint32_t south = static_cast<std::uint32_t>(v.size() / 3 - 1);
    for (long j = 0; j < cols; ++j) f.insert(f.end(), {0u, ring(1, j + 1), ring(1, j)});
    for (long i = 1; i + 1 < rows; ++i)
        for (long j = 0; j < cols; ++j) {
            f.insert(f.end(), {ring(i, j), ring(i, j + 1), ring(i + 1, j + 1)});
            f.insert(f.end(), {ring(i, j), ring(i + 1, j + 1), ring(i + 1, j)});
        }
    for (long j = 0; j < cols; ++j) f.insert(f.end(), {ring(rows - 1, j), ring(rows - 1, j + 1), south});
    }
    std::ofstream out(argv[1], std::ios::binary);
    out << "ply\nformat binary_little_endian 1.0\ncomment glint_make_mesh " << n << "\nelement vertex "
        << v.size() / 3 << "\nproperty float x\nproperty float y\nproperty float z\nelement face " << f.size() / 3
        << "\nproperty list uchar uint vertex_indices\nend_header\n";
    out.write(reinterpret_cast<const char*>(v.data()), static_cast<std::streamsize>(v.size() * sizeof(float)));
    for (std::size_t k = 0; k < f.size(); k += 3) {
        const unsigned char three = 3;
        out.write(reinterpret_cast<const char*>(&three), 1);
        out.write(reinterpret_cast<const char*>(&f[k]), 12);
    }
    if (!out) {
        std::fprintf(stderr, "glint_make_mesh: cannot write %s\n", argv[1]);
        return 1;
    }
    std::fprintf(stderr, "wrote %s: %zu vertices, %zu triangles\n", argv[1], v.size() / 3, f.size() / 3);
    return 0;
}
