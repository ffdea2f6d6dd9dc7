// Images and voxel grids given in the scene itself: an image texture's `pixels` and a grid
// medium's `voxels`, as nested YAML lists or as arrays handed over beside the text (the Python
// module's numpy arrays). docs/scene-format.md, "Pixels and voxels in the scene itself".
#include <fmt/core.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <functional>

#include "glint/base/limits.h"
#include "glint/formats/scene_yaml_parser.h"
#include "glint/image/image_io.h"

namespace glint::yaml_detail {

namespace {

std::string shape_text(const std::array<std::size_t, 3>& shape, int dims) {
    std::string s;
    for (int i = 0; i < dims; ++i) s += fmt::format("{}{}", i ? " x " : "", shape[static_cast<std::size_t>(i)]);
    return s;
}

}  // namespace

std::optional<SceneParser::NumberBlock> SceneParser::number_block(const YAML::Node& node, const std::string& what,
                                                                  int min_dims, int max_dims, long long max_values) {
    NumberBlock b;
    if (node.IsScalar()) {  // "<array N>"
        const long long n = array_number(node.Scalar());
        if (n < 0 || !arrays_ || n >= static_cast<long long>(arrays_->size())) {
            r_.error(node, fmt::format("{} must be a list of numbers{}", what,
                                       n >= 0 ? fmt::format(" (no array {} was given with the scene)", n) : ""));
            return std::nullopt;
        }
        const ArrayView& a = (*arrays_)[static_cast<std::size_t>(n)];
        b.dims = a.dims > 0 ? a.dims : 2;
        b.shape = a.dims > 0 ? a.shape : std::array<std::size_t, 3>{a.rows, a.columns, 0};
        if (!a.floats) {
            r_.error(node, fmt::format("{} must hold numbers (float32), not integers", what));
            return std::nullopt;
        }
        if (b.dims < min_dims || b.dims > max_dims) {
            r_.error(node, fmt::format("{} must have {} dimensions, not {} ({})", what,
                                       min_dims == max_dims ? fmt::format("{}", min_dims)
                                                            : fmt::format("{} to {}", min_dims, max_dims),
                                       b.dims, shape_text(b.shape, b.dims)));
            return std::nullopt;
        }
        double count = 1;
        for (int i = 0; i < b.dims; ++i) count *= double(b.shape[static_cast<std::size_t>(i)]);
        if (count > double(max_values)) {
            r_.error(node, fmt::format("{} holds {} numbers ({}), more than {}", what, count, shape_text(b.shape, b.dims),
                                       max_values));
            return std::nullopt;
        }
        b.values = std::span<const float>(a.floats, static_cast<std::size_t>(count));
        return b;
    }
    if (!node.IsSequence()) {
        r_.error(node, fmt::format("{} must be a list of numbers, got {}", what, describe(node)));
        return std::nullopt;
    }
    // The shape from the first element of each level; then every row must match it. The depth is
    // at most max_dims (3): the recursion below is bounded by the format, not by the input.
    YAML::Node first;
    first.reset(node);  // reset(), not =: assigning a node writes into the tree it refers to
    while (first.IsSequence() && b.dims < 3) {
        b.shape[static_cast<std::size_t>(b.dims++)] = first.size();
        if (first.size() == 0) break;
        first.reset(first[0]);
    }
    if (first.IsSequence() || b.dims < min_dims || b.dims > max_dims) {
        r_.error(node, fmt::format("{} must be a list nested {} deep", what,
                                   min_dims == max_dims ? fmt::format("{}", min_dims)
                                                        : fmt::format("{} to {}", min_dims, max_dims)));
        return std::nullopt;
    }
    double count = 1;
    for (int i = 0; i < b.dims; ++i) count *= double(b.shape[static_cast<std::size_t>(i)]);
    if (count == 0 || count > double(max_values)) {
        r_.error(node, fmt::format("{} holds {} numbers ({}){}", what, count, shape_text(b.shape, b.dims),
                                   count == 0 ? "" : fmt::format(", more than {}", max_values)));
        return std::nullopt;
    }
    b.storage.reserve(static_cast<std::size_t>(count));
    bool ok = true;
    const std::function<void(const YAML::Node&, int)> read = [&](const YAML::Node& n, int level) {
        if (level == b.dims) {
            if (n.IsSequence()) {
                r_.error(n, fmt::format("{}: expected a number here, got a list (rows nested {} deep)", what, b.dims));
                ok = false;
            } else if (const auto v = r_.number(n)) {
                b.storage.push_back(static_cast<float>(*v));
            } else {
                ok = false;
            }
            return;
        }
        const std::size_t want = b.shape[static_cast<std::size_t>(level)];
        if (!n.IsSequence() || n.size() != want) {
            r_.error(n, fmt::format("{}: expected a list of {} here (the shape is {}), got {}", what, want,
                                    shape_text(b.shape, b.dims), n.IsSequence() ? fmt::format("{}", n.size()) : describe(n)));
            ok = false;
            return;
        }
        for (const YAML::Node& item : n) {
            if (!ok) return;
            read(item, level + 1);
        }
    };
    read(node, 0);
    if (!ok) return std::nullopt;
    b.values = std::span<const float>(b.storage);
    return b;
}

bool SceneParser::check_values(const YAML::Node& node, const std::string& what, std::span<const float> values) {
    for (std::size_t i = 0; i < values.size(); ++i) {
        if (!(std::isfinite(values[i]) && values[i] >= 0)) {
            r_.error(node, fmt::format("{}: every value must be finite and non-negative; number {} (counting from 0) is {}",
                                       what, i, values[i]));
            return false;
        }
    }
    return true;
}

std::shared_ptr<const Image> SceneParser::inline_image(const YAML::Node& node, ImageEncoding encoding) {
    const auto b = number_block(node, "image texture: 'pixels'", 2, 3, limit(Limit::kTexturePixels) * 4);
    if (!b) return nullptr;
    const std::size_t height = b->shape[0], width = b->shape[1], channels = b->dims == 3 ? b->shape[2] : 1;
    if (channels != 1 && channels != 3 && channels != 4) {
        r_.error(node, fmt::format("image texture: 'pixels' must have 1, 3 or 4 channels (grey, RGB, RGBA), not {}", channels));
        return nullptr;
    }
    const long long count = static_cast<long long>(width * height);
    if (count > limit(Limit::kTexturePixels)) {
        r_.error(node, fmt::format("image texture: 'pixels': {}", over_limit(Limit::kTexturePixels, count)));
        return nullptr;
    }
    if (const std::string e = charge_memory(count * (channels == 4 ? 16 : 12), "an image given as pixels"); !e.empty()) {
        r_.error(node, fmt::format("image texture: 'pixels': {}", e));
        return nullptr;
    }
    if (!check_values(node, "image texture: 'pixels'", b->values)) return nullptr;
    auto image = std::make_shared<Image>();
    image->width = static_cast<int>(width);
    image->height = static_cast<int>(height);
    image->texels.resize(static_cast<std::size_t>(count));
    if (channels == 4) image->alpha.resize(static_cast<std::size_t>(count));
    // Given values are linear unless the texture says `encoding: srgb`; alpha is always linear.
    const bool srgb = encoding == ImageEncoding::kSrgb;
    const auto channel = [&](float v) { return srgb ? srgb_decode(v) : v; };
    for (std::size_t i = 0; i < static_cast<std::size_t>(count); ++i) {
        const float* p = b->values.data() + i * channels;
        image->texels[i] = channels == 1 ? Color{channel(p[0])} : Color{channel(p[0]), channel(p[1]), channel(p[2])};
        if (channels == 4) image->alpha[i] = std::min(p[3], 1.0f);
    }
    return image;
}

void SceneParser::inline_voxels(MapReader& m, const YAML::Node& node, MediumDesc& d) {
    const auto b = number_block(node, "grid medium: 'voxels'", 3, 3, limit(Limit::kGridVoxels));
    if (!b) return;
    const std::size_t nz = b->shape[0], ny = b->shape[1], nx = b->shape[2];
    if (const std::string e = charge_memory(static_cast<long long>(b->values.size()) * 4, "a grid given as voxels");
        !e.empty()) {
        r_.error(node, fmt::format("grid medium: 'voxels': {}", e));
        return;
    }
    if (!check_values(node, "grid medium: 'voxels'", b->values)) return;
    // The box the voxels fill: `min` to `max` (default the unit cube), voxel centres half a voxel in.
    Point3 lo{0, 0, 0}, hi{1, 1, 1};
    assign(m.get("min"), lo, point());
    assign(m.get("max"), hi, point());
    if (!(hi.x > lo.x && hi.y > lo.y && hi.z > lo.z)) {
        r_.error(m.has("max") ? *m.get("max") : node, "grid medium: 'max' must exceed 'min' on every axis");
        return;
    }
    const float* v = b->values.data();
    d.inline_density = std::make_shared<const VoxelGrid>(VoxelGrid::from_function(
        {0, 0, 0}, {static_cast<int>(nx), static_cast<int>(ny), static_cast<int>(nz)},
        [&](int i, int j, int k) { return v[(std::size_t(k) * ny + std::size_t(j)) * nx + std::size_t(i)]; }));
    const Vector3 step{(hi.x - lo.x) / Float(nx), (hi.y - lo.y) / Float(ny), (hi.z - lo.z) / Float(nz)};
    const Transform box = Transform::translate(Vector3{lo.x, lo.y, lo.z} + step * Float(0.5)) * Transform::scale(step);
    d.transform = d.transform ? *d.transform * box : box;
}

}  // namespace glint::yaml_detail
