#include "glint/io/vdb.h"

#include <fmt/core.h>
#include <openvdb/openvdb.h>

#include <cmath>
#include <mutex>

#include "glint/io/diagnostics.h"
#include "glint/io/image_io.h"
#include "glint/io/limits.h"

namespace glint {

namespace {

void init() {
    static std::once_flag once;
    std::call_once(once, [] { openvdb::initialize(); });
}

void open(const std::filesystem::path& path, openvdb::io::File& file) {
    if (!std::filesystem::exists(path)) throw IoError(fmt::format("{}: no such file", path.string()));
    if (const std::string why = why_not_readable(path); !why.empty())
        throw IoError(fmt::format("{}: cannot read: it {}", path.string(), why));
    try {
        file.open(false);  // no delayed loading: the file may change after we return
    } catch (const std::exception& e) {
        throw IoError(fmt::format("{}: not a readable OpenVDB file ({})", path.string(), e.what()));
    }
}

}  // namespace

std::vector<std::pair<std::string, std::string>> vdb_grids(const std::filesystem::path& path) {
    init();
    openvdb::io::File file(path.string());
    open(path, file);
    std::vector<std::pair<std::string, std::string>> out;
    try {
        for (auto it = file.beginName(); it != file.endName(); ++it) {
            const openvdb::GridBase::ConstPtr meta = file.readGridMetadata(it.gridName());
            out.emplace_back(it.gridName(), meta->valueType());
        }
    } catch (const std::exception& e) {
        throw IoError(fmt::format("{}: cannot read the grid list ({})", path.string(), e.what()));
    }
    file.close();
    return out;
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
    openvdb::io::File file(path.string());
    open(path, file);
    openvdb::FloatGrid::Ptr grid;
    try {
        grid = openvdb::gridPtrCast<openvdb::FloatGrid>(file.readGrid(name));
    } catch (const std::exception& e) {
        throw IoError(fmt::format("{}: cannot read grid '{}' ({})", path.string(), name, e.what()));
    }
    file.close();
    if (!grid) throw IoError(fmt::format("{}: grid '{}' is not a float grid", path.string(), name));

    VdbGrid out;
    const openvdb::math::Transform& xf = grid->transform();
    if (!xf.isLinear())
        throw IoError(fmt::format("{}: grid '{}' has a non-linear (frustum) transform, which glint does not "
                                  "support", path.string(), name));
    // OpenVDB multiplies row vectors: world = index * M, the translation in the 4th row.
    const openvdb::Mat4d m = xf.baseMap()->getAffineMap()->getMat4();
    Matrix34 to_world;
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) to_world.m[i][j] = static_cast<Float>(m(j, i));
        to_world.m[i][3] = static_cast<Float>(m(3, i));
    }
    const auto t = Transform::from(to_world);
    if (!t) throw IoError(fmt::format("{}: grid '{}' has a singular transform", path.string(), name));
    out.index_to_world = *t;

    const openvdb::CoordBBox box = grid->evalActiveVoxelBoundingBox();
    if (box.empty()) {
        out.grid = VoxelGrid({0, 0, 0}, {1, 1, 1});
        return out;
    }
    const openvdb::Coord lo = box.min(), dim = box.dim();
    const long long box_voxels = static_cast<long long>(dim.x()) * dim.y() * dim.z();
    if (box_voxels > kMaxGridBoxVoxels)
        throw IoError(fmt::format("{}: grid '{}' spans {} x {} x {} voxels, more than the limit of {}",
                                  path.string(), name, dim.x(), dim.y(), dim.z(), kMaxGridBoxVoxels));
    const auto active = static_cast<long long>(grid->activeVoxelCount());
    if (active > limit(Limit::kGridVoxels))
        throw IoError(fmt::format("{}: grid '{}': {}", path.string(), name, over_limit(Limit::kGridVoxels, active)));
    if (const std::string e = charge_memory(box_voxels / 64 + active * 4, fmt::format("{}: grid '{}'", path.string(), name));
        !e.empty())
        throw IoError(e);
    out.grid = VoxelGrid({lo.x(), lo.y(), lo.z()}, {dim.x(), dim.y(), dim.z()});
    for (auto it = grid->cbeginValueOn(); it; ++it) {
        const float v = *it;
        if (!std::isfinite(v) || v < 0) {
            const openvdb::Coord c = it.getCoord();
            throw IoError(fmt::format("{}: grid '{}' has the value {} at voxel ({}, {}, {}); densities must be "
                                      "finite and non-negative", path.string(), name, v, c.x(), c.y(), c.z()));
        }
        if (v == 0) continue;
        if (it.isVoxelValue()) {
            const openvdb::Coord c = it.getCoord();
            out.grid.set(c.x(), c.y(), c.z(), v);
        } else {  // an active tile: a constant block
            const openvdb::CoordBBox b = it.getBoundingBox();
            for (int z = b.min().z(); z <= b.max().z(); ++z)
                for (int y = b.min().y(); y <= b.max().y(); ++y)
                    for (int x = b.min().x(); x <= b.max().x(); ++x) out.grid.set(x, y, z, v);
        }
    }
    return out;
}

void write_vdb(const std::filesystem::path& path,
               const std::vector<std::pair<std::string, const VoxelGrid*>>& grids, float voxel_size) {
    init();
    openvdb::GridPtrVec out;
    for (const auto& [name, g] : grids) {
        openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(0.0f);
        grid->setName(name);
        grid->setGridClass(openvdb::GRID_FOG_VOLUME);
        grid->setTransform(openvdb::math::Transform::createLinearTransform(voxel_size));
        auto acc = grid->getAccessor();
        const auto lo = g->lo(), size = g->size();
        for (int z = lo[2]; z < lo[2] + size[2]; ++z)
            for (int y = lo[1]; y < lo[1] + size[1]; ++y)
                for (int x = lo[0]; x < lo[0] + size[0]; ++x)
                    if (const float v = g->voxel(x, y, z); v != 0) acc.setValue(openvdb::Coord(x, y, z), v);
        out.push_back(grid);
    }
    try {
        openvdb::io::File file(path.string());
        file.write(out);
        file.close();
    } catch (const std::exception& e) {
        throw IoError(fmt::format("{}: cannot write ({})", path.string(), e.what()));
    }
}

}  // namespace glint
