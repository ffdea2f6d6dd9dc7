#include "glint/media/grid.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace glint {

namespace {
int bricks_for(int n) { return (n + VoxelGrid::kBrick - 1) >> VoxelGrid::kBrickLog2; }
}  // namespace

VoxelGrid::VoxelGrid(std::array<int, 3> lo, std::array<int, 3> size) : lo_(lo), size_(size) {
    for (int a = 0; a < 3; ++a) bricks_dim_[a] = bricks_for(std::max(size[a], 1));
    bricks_.assign(std::size_t(bricks_dim_[0]) * bricks_dim_[1] * bricks_dim_[2], kEmpty);
}

VoxelGrid VoxelGrid::from_function(std::array<int, 3> lo, std::array<int, 3> size,
                                   const std::function<float(int, int, int)>& f) {
    VoxelGrid g(lo, size);
    for (int k = 0; k < size[2]; ++k)
        for (int j = 0; j < size[1]; ++j)
            for (int i = 0; i < size[0]; ++i) {
                const float v = f(lo[0] + i, lo[1] + j, lo[2] + k);
                if (v != 0) g.set(lo[0] + i, lo[1] + j, lo[2] + k, v);
            }
    return g;
}

void VoxelGrid::set(int i, int j, int k, float v) {
    const int x = i - lo_[0], y = j - lo_[1], z = k - lo_[2];
    std::uint32_t& b = bricks_[brick_index(x >> kBrickLog2, y >> kBrickLog2, z >> kBrickLog2)];
    if (b == kEmpty) {
        b = static_cast<std::uint32_t>(data_.size() / kBrickVoxels);
        data_.resize(data_.size() + kBrickVoxels, 0.0f);
    }
    data_[std::size_t(b) * kBrickVoxels +
          std::size_t(((z & (kBrick - 1)) * kBrick + (y & (kBrick - 1))) * kBrick + (x & (kBrick - 1)))] = v;
}

float VoxelGrid::lookup(Point3 p) const {
    const float fx = std::floor(p.x), fy = std::floor(p.y), fz = std::floor(p.z);
    // Points far outside (or NaN) are 0 without converting a huge float to int.
    if (!(fx >= float(lo_[0] - 1) && fy >= float(lo_[1] - 1) && fz >= float(lo_[2] - 1) &&
          fx <= float(lo_[0] + size_[0]) && fy <= float(lo_[1] + size_[1]) && fz <= float(lo_[2] + size_[2])))
        return 0;
    const int i = int(fx), j = int(fy), k = int(fz);
    const float tx = p.x - fx, ty = p.y - fy, tz = p.z - fz;
    const auto lerp = [](float t, float a, float b) { return a + t * (b - a); };
    const float c00 = lerp(tx, voxel(i, j, k), voxel(i + 1, j, k));
    const float c10 = lerp(tx, voxel(i, j + 1, k), voxel(i + 1, j + 1, k));
    const float c01 = lerp(tx, voxel(i, j, k + 1), voxel(i + 1, j, k + 1));
    const float c11 = lerp(tx, voxel(i, j + 1, k + 1), voxel(i + 1, j + 1, k + 1));
    return lerp(tz, lerp(ty, c00, c10), lerp(ty, c01, c11));
}

Bounds3 VoxelGrid::support() const {
    Bounds3 b;
    if (empty()) return b;
    b.extend(Point3{float(lo_[0] - 1), float(lo_[1] - 1), float(lo_[2] - 1)});
    b.extend(Point3{float(lo_[0] + size_[0]), float(lo_[1] + size_[1]), float(lo_[2] + size_[2])});
    return b;
}

float VoxelGrid::max_value() const {
    float m = 0;
    for (float v : data_) m = std::max(m, v);
    return m;
}

float VoxelGrid::min_value() const {
    float m = 0;
    for (float v : data_) m = std::min(m, v);
    return m;
}

float VoxelGrid::max_over(Point3 a, Point3 b) const {
    // Voxel v contributes to lookup(p) for p in (v - 1, v + 1): the voxels floor(a) .. ceil(b).
    const int i0 = std::max(int(std::floor(a.x)), lo_[0]), i1 = std::min(int(std::ceil(b.x)), lo_[0] + size_[0] - 1);
    const int j0 = std::max(int(std::floor(a.y)), lo_[1]), j1 = std::min(int(std::ceil(b.y)), lo_[1] + size_[1] - 1);
    const int k0 = std::max(int(std::floor(a.z)), lo_[2]), k1 = std::min(int(std::ceil(b.z)), lo_[2] + size_[2] - 1);
    float m = 0;
    for (int k = k0; k <= k1; ++k)
        for (int j = j0; j <= j1; ++j) {
            for (int i = i0; i <= i1; ++i) {
                // Skip whole empty bricks along x.
                const int x = i - lo_[0], y = j - lo_[1], z = k - lo_[2];
                if (bricks_[brick_index(x >> kBrickLog2, y >> kBrickLog2, z >> kBrickLog2)] == kEmpty) {
                    i = lo_[0] + ((x >> kBrickLog2) + 1) * kBrick - 1;
                    continue;
                }
                m = std::max(m, voxel(i, j, k));
            }
        }
    return m;
}

MajorantGrid::MajorantGrid(const VoxelGrid& grid, int cell) {
    bounds_ = grid.support();
    if (bounds_.empty()) {
        bounds_ = Bounds3{};
        bounds_.extend({0, 0, 0});
        bounds_.extend({1, 1, 1});
        cells_.assign(1, 0.0f);
        return;
    }
    for (int a = 0; a < 3; ++a) {
        const float extent = bounds_.hi[a] - bounds_.lo[a];
        res_[a] = std::clamp(int(std::ceil(extent / float(cell))), 1, 64);
    }
    cells_.assign(std::size_t(res_[0]) * res_[1] * res_[2], 0.0f);
    const Vector3 extent = bounds_.hi - bounds_.lo;
    for (int z = 0; z < res_[2]; ++z)
        for (int y = 0; y < res_[1]; ++y)
            for (int x = 0; x < res_[0]; ++x) {
                const Point3 a{bounds_.lo.x + extent.x * float(x) / float(res_[0]),
                               bounds_.lo.y + extent.y * float(y) / float(res_[1]),
                               bounds_.lo.z + extent.z * float(z) / float(res_[2])};
                const Point3 b{bounds_.lo.x + extent.x * float(x + 1) / float(res_[0]),
                               bounds_.lo.y + extent.y * float(y + 1) / float(res_[1]),
                               bounds_.lo.z + extent.z * float(z + 1) / float(res_[2])};
                cells_[(std::size_t(z) * res_[1] + y) * res_[0] + x] = grid.max_over(a, b);
            }
}

float MajorantGrid::max_value() const {
    float m = 0;
    for (float v : cells_) m = std::max(m, v);
    return m;
}

MajorantWalk::MajorantWalk(const MajorantGrid& grid, Point3 o, Vector3 d, float t_min, float t_max)
    : grid_(&grid) {
    // To the grid's unit cube, then clip [t_min, t_max] to it (the slab test).
    const Bounds3& b = grid.bounds();
    const Vector3 extent = b.hi - b.lo;
    const Point3 og{(o.x - b.lo.x) / extent.x, (o.y - b.lo.y) / extent.y, (o.z - b.lo.z) / extent.z};
    const Vector3 dg{d.x / extent.x, d.y / extent.y, d.z / extent.z};
    float t0 = t_min, t1 = t_max;
    for (int a = 0; a < 3; ++a) {
        if (dg[a] == 0) {
            if (!(og[a] >= 0 && og[a] <= 1)) return;
            continue;
        }
        float tn = (0 - og[a]) / dg[a], tf = (1 - og[a]) / dg[a];
        if (tn > tf) std::swap(tn, tf);
        t0 = std::max(t0, tn);
        t1 = std::min(t1, tf);
    }
    if (!(t0 < t1)) return;
    t_ = t0;
    t_max_ = t1;
    done_ = false;
    const auto res = grid.res();
    for (int a = 0; a < 3; ++a) {
        const float start = og[a] + dg[a] * t0;
        cell_[a] = std::clamp(int(start * float(res[a])), 0, res[a] - 1);
        if (dg[a] == 0) {
            next_t_[a] = std::numeric_limits<float>::infinity();
            delta_t_[a] = 0;
            step_[a] = 0;
            stop_[a] = -2;
        } else if (dg[a] > 0) {
            next_t_[a] = t0 + (float(cell_[a] + 1) / float(res[a]) - start) / dg[a];
            delta_t_[a] = 1 / (dg[a] * float(res[a]));
            step_[a] = 1;
            stop_[a] = res[a];
        } else {
            next_t_[a] = t0 + (float(cell_[a]) / float(res[a]) - start) / dg[a];
            delta_t_[a] = -1 / (dg[a] * float(res[a]));
            step_[a] = -1;
            stop_[a] = -1;
        }
    }
}

bool MajorantWalk::next(MajorantSegment& s) {
    if (done_ || !(t_ < t_max_)) return false;
    const int a = next_t_[0] < next_t_[1] ? (next_t_[0] < next_t_[2] ? 0 : 2) : (next_t_[1] < next_t_[2] ? 1 : 2);
    const float exit = std::min(t_max_, next_t_[a]);
    s = {t_, exit, grid_->at(cell_[0], cell_[1], cell_[2])};
    t_ = exit;
    if (next_t_[a] >= t_max_) {
        done_ = true;
        return true;
    }
    cell_[a] += step_[a];
    if (cell_[a] == stop_[a]) done_ = true;
    next_t_[a] += delta_t_[a];
    return true;
}

}  // namespace glint
