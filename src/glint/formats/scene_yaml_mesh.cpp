// Meshes given in the scene itself: `{type: mesh, positions: [...], indices: [...]}`, from YAML
// lists or from arrays handed over beside the text (the Python module's numpy arrays).
#include <fmt/core.h>
#include <yaml-cpp/yaml.h>

#include <charconv>
#include <cmath>
#include <stdexcept>

#include "glint/base/limits.h"
#include "glint/formats/scene_yaml_parser.h"

namespace glint::yaml_detail {

long long array_number(const std::string& s) {
    constexpr std::string_view head = "<array ";
    if (s.size() < head.size() + 2 || s.compare(0, head.size(), head) != 0 || s.back() != '>') return -1;
    long long n = -1;
    const char* first = s.data() + head.size();
    const char* last = s.data() + s.size() - 1;
    const auto [end, ec] = std::from_chars(first, last, n);
    return ec == std::errc{} && end == last ? n : -1;
}

bool SceneParser::check_mesh_size(const YAML::Node& node, const char* key, std::size_t rows, bool triangles) {
    const Limit l = triangles ? Limit::kTriangles : Limit::kVertices;
    if (static_cast<long long>(rows) > limit(l)) {
        r_.error(node, fmt::format("mesh: '{}': {}", key, over_limit(l, static_cast<long long>(rows))));
        return false;
    }
    // What the mesh will hold: about 12 bytes a vertex and a triangle for each array.
    const std::string e = charge_memory(static_cast<long long>(rows) * 12, "an inline mesh");
    if (!e.empty()) {
        r_.error(node, fmt::format("mesh: '{}': {}", key, e));
        return false;
    }
    return true;
}

const ArrayView* SceneParser::handed_array(const YAML::Node& node, const char* key, std::size_t columns, bool ints) {
    const long long n = array_number(node.Scalar());
    if (n < 0 || !arrays_ || n >= static_cast<long long>(arrays_->size())) {
        r_.error(node, fmt::format("mesh: '{}' must be a list of numbers{}", key,
                                   n >= 0 ? fmt::format(" (no array {} was given with the scene)", n) : ""));
        return nullptr;
    }
    const ArrayView& a = (*arrays_)[static_cast<std::size_t>(n)];
    if (a.columns != columns && !(a.columns == 1 && a.rows % columns == 0)) {
        r_.error(node, fmt::format("mesh: '{}' must have {} columns, not {}", key, columns, a.columns));
        return nullptr;
    }
    if (!check_mesh_size(node, key, a.rows * a.columns / columns, ints)) return nullptr;
    if (ints != (a.ints != nullptr)) {
        r_.error(node, fmt::format("mesh: '{}' must hold {}", key, ints ? "integers" : "numbers"));
        return nullptr;
    }
    return &a;
}

bool SceneParser::mesh_list(const YAML::Node& node, const char* key, std::size_t columns, bool ints,
                            std::vector<float>& floats, std::vector<std::uint32_t>& indices) {
    if (!node.IsSequence()) {
        r_.error(node, fmt::format("mesh: '{}' must be a list of numbers, got {}", key, describe(node)));
        return false;
    }
    // Flat ([x, y, z, x, y, z, ...]) or of rows ([[x, y, z], ...]).
    bool ok = true;
    const auto add = [&](const YAML::Node& v) {
        if (ints) {
            if (const auto i = r_.integer_in(v, key, 0, 0xffffffffLL)) indices.push_back(static_cast<std::uint32_t>(*i));
            else ok = false;
        } else {
            const auto x = r_.number(v);
            if (x && std::isfinite(static_cast<float>(*x))) {
                floats.push_back(static_cast<float>(*x));
            } else {
                if (x) r_.error(v, fmt::format("mesh: '{}' values must be finite floats", key));
                ok = false;
            }
        }
    };
    for (const YAML::Node& item : node) {
        if (!ok) break;
        if (item.IsSequence()) {
            if (item.size() != columns) {
                r_.error(item, fmt::format("mesh: each row of '{}' must have {} numbers, not {}", key, columns, item.size()));
                return false;
            }
            for (const YAML::Node& v : item) add(v);
        } else {
            add(item);
        }
    }
    const std::size_t count = ints ? indices.size() : floats.size();
    if (ok && !check_mesh_size(node, key, count / columns, ints)) return false;
    if (ok && count % columns != 0) {
        r_.error(node, fmt::format("mesh: '{}' holds {} numbers, not a multiple of {}", key, count, columns));
        return false;
    }
    return ok;
}

std::optional<std::span<const float>> SceneParser::mesh_floats(const YAML::Node& node, const char* key,
                                                               std::size_t columns, std::vector<float>& storage) {
    if (node.IsScalar()) {
        const ArrayView* a = handed_array(node, key, columns, false);
        if (!a) return std::nullopt;
        return std::span<const float>(a->floats, a->rows * a->columns);
    }
    std::vector<std::uint32_t> unused;
    if (!mesh_list(node, key, columns, false, storage, unused)) return std::nullopt;
    return std::span<const float>(storage);
}

std::shared_ptr<const TriangleMesh> SceneParser::inline_mesh(MapReader& m, const YAML::Node& item) {
    auto mesh = std::make_shared<TriangleMesh>();
    mesh->name = "inline mesh";
    std::vector<float> p_list, n_list, uv_list, c_list, unused;
    const auto positions = m.require("positions");
    const auto indices = m.require("indices");
    if (!positions || !indices) return nullptr;
    // Objects naming the same arrays share one mesh (and its BVH): instances, as a mesh file
    // named twice is read once.
    std::string key;
    for (const char* k : {"positions", "indices", "normals", "uvs", "colors"}) {
        const auto node = m.get(k);
        if (!node) {
            key += "-|";
        } else if (node->IsScalar() && array_number(node->Scalar()) >= 0) {
            key += node->Scalar() + "|";
        } else {
            key.clear();
            break;
        }
    }
    if (!key.empty())
        if (const auto it = shared_meshes_.find(key); it != shared_meshes_.end()) return it->second;
    // Each array is copied once, from the caller's memory or the list read, into the mesh.
    const auto read_p = mesh_floats(*positions, "positions", 3, p_list);
    if (!read_p) return nullptr;
    const std::span<const float> p = *read_p;
    if (indices->IsScalar()) {
        const ArrayView* a = handed_array(*indices, "indices", 3, true);
        if (!a) return nullptr;
        mesh->indices.assign(a->ints, a->ints + a->rows * a->columns);
    } else if (!mesh_list(*indices, "indices", 3, true, unused, mesh->indices)) {
        return nullptr;
    }
    const std::size_t vertices = p.size() / 3;
    if (vertices == 0 || mesh->indices.empty()) {
        r_.error(item, "mesh: 'positions' and 'indices' must not be empty");
        return nullptr;
    }
    // Each optional attribute: one row per position.
    bool ok = true;
    const auto optional = [&](const char* key, std::size_t columns, std::vector<float>& storage) {
        const auto node = m.get(key);
        if (!node || !ok) return std::span<const float>();
        const auto out = mesh_floats(*node, key, columns, storage);
        if (!out) {
            ok = false;
        } else if (out->size() / columns != vertices) {
            r_.error(*node, fmt::format("mesh: '{}' has {} rows for {} positions", key, out->size() / columns, vertices));
            ok = false;
        }
        return ok ? *out : std::span<const float>();
    };
    const std::span<const float> n = optional("normals", 3, n_list), uv = optional("uvs", 2, uv_list),
                                 c = optional("colors", 3, c_list);
    if (!ok) return nullptr;
    mesh->positions.resize(vertices);
    for (std::size_t i = 0; i < vertices; ++i) mesh->positions[i] = {p[3 * i], p[3 * i + 1], p[3 * i + 2]};
    if (!n.empty()) {
        mesh->normals.resize(vertices);
        for (std::size_t i = 0; i < vertices; ++i) mesh->normals[i] = Normal3{n[3 * i], n[3 * i + 1], n[3 * i + 2]};
    }
    if (!uv.empty()) {
        mesh->uvs.resize(vertices);
        for (std::size_t i = 0; i < vertices; ++i) mesh->uvs[i] = Point2{uv[2 * i], uv[2 * i + 1]};
    }
    if (!c.empty()) {
        mesh->colors.resize(vertices);
        for (std::size_t i = 0; i < vertices; ++i) mesh->colors[i] = Color{c[3 * i], c[3 * i + 1], c[3 * i + 2]};
    }
    try {
        const std::size_t dropped = validate_and_drop_degenerate(*mesh);
        if (mesh->indices.empty()) {
            r_.error(*indices, "mesh: every triangle has zero area or a non-finite corner; nothing would render");
            return nullptr;
        }
        if (dropped > 0)
            warnings_.push_back({r_.loc(item), fmt::format("mesh: dropped {} degenerate triangle{}", dropped,
                                                           dropped == 1 ? "" : "s")});
    } catch (const std::invalid_argument& e) {
        r_.error(*indices, fmt::format("mesh: {}", e.what()));
        return nullptr;
    }
    if (!key.empty()) shared_meshes_.emplace(key, mesh);
    return mesh;
}

}  // namespace glint::yaml_detail
