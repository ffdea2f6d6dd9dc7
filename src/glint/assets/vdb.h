#pragma once
// OpenVDB files (.vdb): a float grid read into glint's own sparse voxel grid (media/grid.h),
// with the grid's index-to-world transform. OpenVDB is used only here, at load time; no ray ever
// touches an OpenVDB tree.
#include <filesystem>
#include <string>
#include <vector>

#include "glint/math/transform.h"
#include "glint/media/grid.h"

namespace glint {

struct VdbGrid {
    VoxelGrid grid;
    Transform index_to_world;  ///< the file's (linear) voxel-to-world transform
};

/// The names and value types of every grid in the file ("density: float", ...).
std::vector<std::pair<std::string, std::string>> vdb_grids(const std::filesystem::path& path);

/// Reads float grid `name`. Throws IoError naming the file and the reason: unreadable or not a
/// VDB, no grid of that name (listing the names there are), a grid of another type, a transform
/// that is not linear, a negative or non-finite value, or a grid beyond the size limits
/// (base/limits.h).
VdbGrid read_vdb_grid(const std::filesystem::path& path, const std::string& name);

/// Writes float grids to a .vdb (the tools' and tests' side): each (name, grid) with voxel size
/// `voxel_size` and the index origin at world (0, 0, 0).
void write_vdb(const std::filesystem::path& path, const std::vector<std::pair<std::string, const VoxelGrid*>>& grids,
               float voxel_size);

}  // namespace glint
