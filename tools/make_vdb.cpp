// Writes a procedural cloud as an OpenVDB file (a float grid "density" and a float grid
// "temperature"), so that the volume scenes need no downloaded data:
//   glint_make_vdb OUT.vdb [resolution]
// The density is a ball of fractal noise (six octaves of gradient noise) eroded towards its
// rim and flattened at the bottom, as a cumulus; the temperature grid is hot (up to 1500 K /
// 1000, i.e. a temperature_scale of 1000 gives kelvin) in the core. Deterministic: the same
// arguments give the same file.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>

#include "glint/assets/vdb.h"
#include "glint/samplers/hash.h"

namespace {

using glint::mix32;

// Perlin-style gradient noise on the integer lattice, gradients from a hash.
float grad(int x, int y, int z, float fx, float fy, float fz) {
    const std::uint32_t h = mix32(static_cast<std::uint32_t>(x) * 73856093U ^ static_cast<std::uint32_t>(y) * 19349663U ^
                                  static_cast<std::uint32_t>(z) * 83492791U);
    const float gx = float(h & 1023) / 511.5f - 1, gy = float((h >> 10) & 1023) / 511.5f - 1,
                gz = float((h >> 20) & 1023) / 511.5f - 1;
    return gx * fx + gy * fy + gz * fz;
}

float fade(float t) { return t * t * t * (t * (t * 6 - 15) + 10); }

float noise(float x, float y, float z) {
    const int ix = int(std::floor(x)), iy = int(std::floor(y)), iz = int(std::floor(z));
    const float fx = x - float(ix), fy = y - float(iy), fz = z - float(iz);
    const float u = fade(fx), v = fade(fy), w = fade(fz);
    const auto lerp = [](float t, float a, float b) { return a + t * (b - a); };
    const float x00 = lerp(u, grad(ix, iy, iz, fx, fy, fz), grad(ix + 1, iy, iz, fx - 1, fy, fz));
    const float x10 = lerp(u, grad(ix, iy + 1, iz, fx, fy - 1, fz), grad(ix + 1, iy + 1, iz, fx - 1, fy - 1, fz));
    const float x01 = lerp(u, grad(ix, iy, iz + 1, fx, fy, fz - 1), grad(ix + 1, iy, iz + 1, fx - 1, fy, fz - 1));
    const float x11 = lerp(u, grad(ix, iy + 1, iz + 1, fx, fy - 1, fz - 1),
                           grad(ix + 1, iy + 1, iz + 1, fx - 1, fy - 1, fz - 1));
    return lerp(w, lerp(v, x00, x10), lerp(v, x01, x11));
}

float fbm(float x, float y, float z) {
    float sum = 0, amp = 0.5f, f = 1;
    for (int o = 0; o < 6; ++o) {
        sum += amp * noise(x * f, y * f, z * f);
        f *= 2.03f;
        amp *= 0.5f;
    }
    return sum;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2 || argc > 3) {
        std::fprintf(stderr, "usage: glint_make_vdb OUT.vdb [resolution (16..512, default 96)]\n");
        return 2;
    }
    const int n = argc == 3 ? std::atoi(argv[2]) : 96;
    if (n < 16 || n > 512) {
        std::fprintf(stderr, "glint_make_vdb: resolution must be in [16, 512]\n");
        return 2;
    }
    // Voxels over [-1, 1] x [-0.6, 0.6] x [-1, 1] in cloud units (voxel size 2 / n).
    const int ny = int(float(n) * 0.6f);
    const auto density = glint::VoxelGrid::from_function({0, 0, 0}, {n, ny, n}, [&](int i, int j, int k) {
        const float x = 2 * (float(i) + 0.5f) / float(n) - 1, y = 2 * (float(j) + 0.5f) / float(n) - 0.6f,
                    z = 2 * (float(k) + 0.5f) / float(n) - 1;
        // A few overlapping blobs make the cumulus shape; noise erodes their rim.
        const auto blob = [&](float cx, float cy, float cz, float r) {
            const float d = std::sqrt((x - cx) * (x - cx) + (y - cy) * (y - cy) + (z - cz) * (z - cz));
            return 1 - d / r;
        };
        float shape = std::max({blob(0, -0.05f, 0, 0.55f), blob(-0.35f, -0.15f, 0.1f, 0.4f),
                                blob(0.35f, -0.12f, -0.1f, 0.42f), blob(0.1f, 0.2f, 0.05f, 0.35f)});
        shape -= std::max(0.0f, -0.3f - y) * 4;  // flat base
        const float v = shape + 0.45f * fbm(3 * x + 7.1f, 3 * y + 1.3f, 3 * z - 4.2f);
        return v > 0 ? std::min(1.0f, 3 * v) : 0.0f;
    });
    const auto temperature = glint::VoxelGrid::from_function({0, 0, 0}, {n, ny, n}, [&](int i, int j, int k) {
        const float d = density.voxel(i, j, k);
        const float x = 2 * (float(i) + 0.5f) / float(n) - 1, y = 2 * (float(j) + 0.5f) / float(n) - 0.6f,
                    z = 2 * (float(k) + 0.5f) / float(n) - 1;
        const float r = std::sqrt(x * x + (y + 0.1f) * (y + 0.1f) + z * z);
        return d > 0 ? std::max(0.0f, 1.5f * (1 - r / 0.45f)) : 0.0f;
    });
    try {
        glint::write_vdb(argv[1], {{"density", &density}, {"temperature", &temperature}}, 2.0f / float(n));
    } catch (const std::exception& e) {
        std::fprintf(stderr, "glint_make_vdb: %s\n", e.what());
        return 1;
    }
    std::printf("wrote %s: %d x %d x %d voxels, %zu + %zu bricks\n", argv[1], n, ny, n, density.brick_count(),
                temperature.brick_count());
    return 0;
}
