#pragma once
// The OpenVDB module's interface (libglint_vdb.so, loaded by module.h only when a scene names a
// .vdb file or one is written): OpenVDB and its libraries (Boost, Blosc, log4cplus, ~60,000
// relocations at start-up) stay out of every other process. Both sides are built from the same
// tree (kVdbModuleAbi guards against mixing builds), so C++ types cross the boundary; errors
// cross as std::runtime_error with the whole message.
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "glint/media/grid.h"

namespace glint {

inline constexpr int kVdbModuleAbi = 1;

using VdbGridList = std::vector<std::pair<std::string, std::string>>;
/// Called with the grid's bounding-box voxels and active voxels before anything is allocated for
/// it; throws to refuse (the host's limits and memory budget).
using VdbAdmit = std::function<void(long long box_voxels, long long active_voxels)>;

struct VdbModule {
    int abi;
    VdbGridList (*grids)(const std::string& path);
    /// Reads float grid `name` (already known to exist and hold floats) into `grid`, and its linear
    /// index-to-world matrix (rows of [R | t], world = R index + t) into `to_world`.
    void (*read)(const std::string& path, const std::string& name, const VdbAdmit& admit, VoxelGrid& grid,
                 double to_world[3][4]);
    void (*write)(const std::string& path, const std::vector<std::pair<std::string, const VoxelGrid*>>& grids,
                  float voxel_size);
};

}  // namespace glint

extern "C" const glint::VdbModule* glint_vdb_module();
