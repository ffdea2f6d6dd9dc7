#pragma once
// Voxel grids for heterogeneous media, in the grid's index space (OpenVDB's): voxel (i, j, k)
// has its centre at the point (i, j, k), values between centres are trilinear, and the value
// outside the stored voxels is 0. Storage is sparse: bricks of 8^3 voxels (OpenVDB's leaf
// size, so a .vdb file's leaves copy in whole), an index of bricks over the grid's bounding box,
// and no storage for empty bricks. Read-only once built; lookups are lock-free and allocate
// nothing.
#include <array>
#include <cstdint>
#include <functional>
#include <vector>

#include "glint/math/bounds.h"
#include "glint/math/vector.h"

namespace glint {

class VoxelGrid {
public:
    static constexpr int kBrickLog2 = 3, kBrick = 1 << kBrickLog2, kBrickVoxels = kBrick * kBrick * kBrick;
    static constexpr std::uint32_t kEmpty = 0xffffffffU;

    VoxelGrid() = default;
    /// An empty grid covering voxels [lo, lo + size) (size >= 1 on each axis).
    VoxelGrid(std::array<int, 3> lo, std::array<int, 3> size);
    /// A grid filled from f(i, j, k) over voxels [lo, lo + size); bricks that stay 0 are not stored.
    static VoxelGrid from_function(std::array<int, 3> lo, std::array<int, 3> size,
                                   const std::function<float(int, int, int)>& f);

    /// Sets voxel (i, j, k), which must lie inside the box; allocates its brick on first write.
    void set(int i, int j, int k, float v);
    float voxel(int i, int j, int k) const {
        const int x = i - lo_[0], y = j - lo_[1], z = k - lo_[2];
        if (x < 0 || y < 0 || z < 0 || x >= size_[0] || y >= size_[1] || z >= size_[2]) return 0;
        const std::uint32_t b = bricks_[brick_index(x >> kBrickLog2, y >> kBrickLog2, z >> kBrickLog2)];
        if (b == kEmpty) return 0;
        return data_[std::size_t(b) * kBrickVoxels +
                     std::size_t(((z & (kBrick - 1)) * kBrick + (y & (kBrick - 1))) * kBrick + (x & (kBrick - 1)))];
    }
    /// Trilinear value at an index-space point.
    float lookup(Point3 p) const;

    /// Where lookup() can be non-zero: the stored box widened by one voxel (trilinear support).
    Bounds3 support() const;
    std::array<int, 3> lo() const { return lo_; }
    std::array<int, 3> size() const { return size_; }
    bool empty() const { return data_.empty(); }
    float max_value() const;
    float min_value() const;  ///< over stored voxels (0 where bricks are absent)
    std::size_t memory_bytes() const { return bricks_.size() * 4 + data_.size() * 4; }
    std::size_t brick_count() const { return data_.size() / kBrickVoxels; }

    /// The largest value lookup() takes over the index-space box [a, b] (every voxel whose
    /// trilinear support meets the box); the majorant grid's cells.
    float max_over(Point3 a, Point3 b) const;

private:
    std::size_t brick_index(int bx, int by, int bz) const {
        return (std::size_t(bz) * std::size_t(bricks_dim_[1]) + std::size_t(by)) * std::size_t(bricks_dim_[0]) +
               std::size_t(bx);
    }
    std::array<int, 3> lo_{0, 0, 0}, size_{0, 0, 0}, bricks_dim_{0, 0, 0};
    std::vector<std::uint32_t> bricks_;  ///< per brick of the box: its slot in data_, or kEmpty
    std::vector<float> data_;            ///< kBrickVoxels floats per stored brick, x fastest
};

/// A coarse grid of upper bounds (majorants) of a density over a box: each cell holds the
/// largest density anywhere in it. Free-flight sampling walks the cells a ray crosses (a 3D DDA,
/// Amanatides and Woo) and samples each with its own bound, so empty space costs one step per
/// cell and thin regions are not sampled at the density of the thickest one.
class MajorantGrid {
public:
    MajorantGrid() = default;
    /// Cells of about `cell` voxels over the grid's support, at most 64 per axis.
    MajorantGrid(const VoxelGrid& grid, int cell = VoxelGrid::kBrick);
    const Bounds3& bounds() const { return bounds_; }
    std::array<int, 3> res() const { return res_; }
    float at(int x, int y, int z) const { return cells_[(std::size_t(z) * res_[1] + y) * res_[0] + x]; }
    float max_value() const;

private:
    Bounds3 bounds_;
    std::array<int, 3> res_{1, 1, 1};
    std::vector<float> cells_;
};

/// One piece of a ray inside a majorant cell: parameters [t0, t1) along the ray and the bound.
struct MajorantSegment {
    float t0, t1;
    float sigma;  ///< the cell's density bound (to be multiplied by the medium's sigma_t)
};

/// Walks the majorant cells along an index-space ray (origin o, direction d, not necessarily
/// unit; t measured in the same units as the caller's) over [t_min, t_max).
class MajorantWalk {
public:
    MajorantWalk(const MajorantGrid& grid, Point3 o, Vector3 d, float t_min, float t_max);
    /// The next segment; false when the ray has left the grid or reached t_max.
    bool next(MajorantSegment& s);

private:
    const MajorantGrid* grid_ = nullptr;
    float t_ = 0, t_max_ = 0;
    std::array<int, 3> cell_{}, step_{}, stop_{};
    std::array<float, 3> next_t_{}, delta_t_{};
    bool done_ = true;
};

}  // namespace glint
