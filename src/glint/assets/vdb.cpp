#include "glint/assets/vdb.h"

#include <fmt/core.h>

#include "glint/base/diagnostics.h"
#include "glint/image/image_io.h"
#include "glint/base/limits.h"
#include "glint/base/module.h"
#include "glint/assets/vdb_module.h"

namespace glint {

namespace {

// OpenVDB itself lives in libglint_vdb.so (vdb_module.h), loaded on the first call here.
const VdbModule& vdb() {
    const auto* m = reinterpret_cast<const VdbModule* (*)()>(module_entry("vdb"))();
    if (m->abi != kVdbModuleAbi) throw IoError("glint's module libglint_vdb.so is from another build of glint");
    return *m;
}

void check_readable(const std::filesystem::path& path) {
    if (const std::string why = why_not_readable(path); !why.empty())
        throw IoError(fmt::format("{}: cannot read: it {}", path.string(), why));
    if (std::error_code ec; !std::filesystem::exists(path, ec)) throw IoError(fmt::format("{}: no such file", path.string()));
}

// Runs a module call, turning its errors (std::runtime_error with the whole message) into IoError.
template <typename F>
auto call(F&& f) {
    try {
        return f();
    } catch (const IoError&) {
        throw;
    } catch (const std::exception& e) {
        throw IoError(e.what());
    }
}

}  // namespace

std::vector<std::pair<std::string, std::string>> vdb_grids(const std::filesystem::path& path) {
    check_readable(path);
    return call([&] { return vdb().grids(path.string()); });
}

VdbGrid read_vdb_grid(const std::filesystem::path& path, const std::string& name) {
    const auto grids = vdb_grids(path);
    std::string known;
    const std::pair<std::string, std::string>* found = nullptr;
    for (const auto& g : grids) {
        known += fmt::format("{}{} ({})", known.empty() ? "" : ", ", g.first, g.second);
        if (g.first == name) found = &g;
    }
    if (!found)
        throw IoError(fmt::format("{}: no grid named '{}' (grids in the file: {})", path.string(), name,
                                  known.empty() ? "none" : known));
    if (found->second != "float")
        throw IoError(fmt::format("{}: grid '{}' holds {} values; glint reads float grids", path.string(),
                                  name, found->second));
    const VdbAdmit admit = [&](long long box_voxels, long long active) {
        if (box_voxels > kMaxGridBoxVoxels)
            throw IoError(fmt::format("{}: grid '{}' spans {} voxels in its bounding box, more than the limit of {}",
                                      path.string(), name, box_voxels, kMaxGridBoxVoxels));
        if (active > limit(Limit::kGridVoxels))
            throw IoError(fmt::format("{}: grid '{}': {}", path.string(), name, over_limit(Limit::kGridVoxels, active)));
        if (const std::string e = charge_memory(box_voxels / 64 + active * 4, fmt::format("{}: grid '{}'", path.string(), name));
            !e.empty())
            throw IoError(e);
    };
    VdbGrid out;
    double m[3][4] = {};
    call([&] {
        vdb().read(path.string(), name, admit, out.grid, m);
        return 0;
    });
    Matrix34 to_world;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 4; ++j) to_world.m[i][j] = static_cast<Float>(m[i][j]);
    const auto t = Transform::from(to_world);
    if (!t) throw IoError(fmt::format("{}: grid '{}' has a singular transform", path.string(), name));
    out.index_to_world = *t;
    return out;
}

void write_vdb(const std::filesystem::path& path,
               const std::vector<std::pair<std::string, const VoxelGrid*>>& grids, float voxel_size) {
    call([&] {
        vdb().write(path.string(), grids, voxel_size);
        return 0;
    });
}

}  // namespace glint
