// libglint_vdb.so: OpenVDB behind vdb_module.h.
#include "glint/assets/vdb_module.h"

#include <fmt/core.h>
#include <openvdb/openvdb.h>

#include <cmath>
#include <mutex>
#include <stdexcept>

namespace glint {

namespace {

void init() {
    static std::once_flag once;
    std::call_once(once, [] { openvdb::initialize(); });
}

void open(const std::string& path, openvdb::io::File& file) {
    try {
        file.open(false);  // no delayed loading: the file may change after we return
    } catch (const std::exception& e) {
        throw std::runtime_error(fmt::format("{}: not a readable OpenVDB file ({})", path, e.what()));
    }
}

VdbGridList grids(const std::string& path) {
    init();
    openvdb::io::File file(path);
    open(path, file);
    VdbGridList out;
    try {
        for (auto it = file.beginName(); it != file.endName(); ++it) {
            const openvdb::GridBase::ConstPtr meta = file.readGridMetadata(it.gridName());
            out.emplace_back(it.gridName(), meta->valueType());
        }
    } catch (const std::exception& e) {
        throw std::runtime_error(fmt::format("{}: cannot read the grid list ({})", path, e.what()));
    }
    file.close();
    return out;
}

void read(const std::string& path, const std::string& name, const VdbAdmit& admit, VoxelGrid& out,
          double to_world[3][4]) {
    init();
    openvdb::io::File file(path);
    open(path, file);
    openvdb::FloatGrid::Ptr grid;
    try {
        grid = openvdb::gridPtrCast<openvdb::FloatGrid>(file.readGrid(name));
    } catch (const std::exception& e) {
        throw std::runtime_error(fmt::format("{}: cannot read grid '{}' ({})", path, name, e.what()));
    }
    file.close();
    if (!grid) throw std::runtime_error(fmt::format("{}: grid '{}' is not a float grid", path, name));
    const openvdb::math::Transform& xf = grid->transform();
    if (!xf.isLinear())
        throw std::runtime_error(fmt::format("{}: grid '{}' has a non-linear (frustum) transform, which glint does "
                                             "not support", path, name));
    // OpenVDB multiplies row vectors: world = index * M, the translation in the 4th row.
    const openvdb::Mat4d m = xf.baseMap()->getAffineMap()->getMat4();
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) to_world[i][j] = m(j, i);
        to_world[i][3] = m(3, i);
    }
    const openvdb::CoordBBox box = grid->evalActiveVoxelBoundingBox();
    if (box.empty()) {
        out = VoxelGrid({0, 0, 0}, {1, 1, 1});
        return;
    }
    const openvdb::Coord lo = box.min(), dim = box.dim();
    admit(static_cast<long long>(dim.x()) * dim.y() * dim.z(), static_cast<long long>(grid->activeVoxelCount()));
    out = VoxelGrid({lo.x(), lo.y(), lo.z()}, {dim.x(), dim.y(), dim.z()});
    for (auto it = grid->cbeginValueOn(); it; ++it) {
        const float v = *it;
        if (!std::isfinite(v) || v < 0) {
            const openvdb::Coord c = it.getCoord();
            throw std::runtime_error(fmt::format("{}: grid '{}' has the value {} at voxel ({}, {}, {}); densities "
                                                 "must be finite and non-negative", path, name, v, c.x(), c.y(), c.z()));
        }
        if (v == 0) continue;
        if (it.isVoxelValue()) {
            const openvdb::Coord c = it.getCoord();
            out.set(c.x(), c.y(), c.z(), v);
        } else {  // an active tile: a constant block
            const openvdb::CoordBBox b = it.getBoundingBox();
            for (int z = b.min().z(); z <= b.max().z(); ++z)
                for (int y = b.min().y(); y <= b.max().y(); ++y)
                    for (int x = b.min().x(); x <= b.max().x(); ++x) out.set(x, y, z, v);
        }
    }
}

void write(const std::string& path, const std::vector<std::pair<std::string, const VoxelGrid*>>& grids,
           float voxel_size) {
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
        openvdb::io::File file(path);
        file.write(out);
        file.close();
    } catch (const std::exception& e) {
        throw std::runtime_error(fmt::format("{}: cannot write ({})", path, e.what()));
    }
}

const VdbModule kModule{kVdbModuleAbi, &grids, &read, &write};

}  // namespace

}  // namespace glint

extern "C" [[gnu::visibility("default")]] const glint::VdbModule* glint_vdb_module() { return &glint::kModule; }
