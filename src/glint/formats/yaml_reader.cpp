#include "glint/formats/yaml_reader.h"

#include "glint/base/limits.h"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <set>
#include <unordered_map>
#include <unordered_set>

namespace glint {

std::string describe(const YAML::Node& node) {
    switch (node.Type()) {
        case YAML::NodeType::Sequence: return "a list";
        case YAML::NodeType::Map: return "a map";
        case YAML::NodeType::Scalar: return fmt::format("'{}'", node.Scalar());
        default: return "nothing";
    }
}

SourceLoc YamlReader::loc(const YAML::Node& node) const {
    const YAML::Mark m = node.Mark();
    if (m.is_null()) {
        for (const auto& [made, at] : made_)
            if (made.is(node)) return at;
        return {file_, 0, 0};
    }
    return {file_, m.line + 1, m.column + 1};
}

std::optional<double> YamlReader::number(const YAML::Node& node) {
    double v = 0;
    if (!node.IsScalar() || !YAML::convert<double>::decode(node, v)) {
        error(node, fmt::format("expected a number, got {}", describe(node)));
        return std::nullopt;
    }
    if (!std::isfinite(v)) {
        error(node, fmt::format("expected a finite number, got {}", describe(node)));
        return std::nullopt;
    }
    // glint computes in float: a larger magnitude would silently become infinity.
    if (std::abs(v) > std::numeric_limits<float>::max()) {
        error(node, fmt::format("number {} is out of range (largest magnitude: {:.3g})",
                                describe(node), std::numeric_limits<float>::max()));
        return std::nullopt;
    }
    return v;
}

std::optional<long long> YamlReader::integer(const YAML::Node& node) {
    long long v = 0;
    if (!node.IsScalar() || !YAML::convert<long long>::decode(node, v)) {
        error(node, fmt::format("expected an integer, got {}", describe(node)));
        return std::nullopt;
    }
    return v;
}

std::optional<bool> YamlReader::boolean(const YAML::Node& node) {
    bool v = false;
    if (!node.IsScalar() || !YAML::convert<bool>::decode(node, v)) {
        error(node, fmt::format("expected true or false, got {}", describe(node)));
        return std::nullopt;
    }
    return v;
}

std::optional<std::string> YamlReader::string(const YAML::Node& node) {
    if (!node.IsScalar()) {
        error(node, fmt::format("expected a name, got {}", describe(node)));
        return std::nullopt;
    }
    return node.Scalar();
}

namespace {

// A list of exactly N numbers; `form` shows the expected shape in the message ("[x, y, z]").
template <std::size_t N>
std::optional<std::array<double, N>> fixed_list(YamlReader& r, const YAML::Node& node, const std::string& prefix,
                                                const char* form) {
    if (!node.IsSequence() || node.size() != N) {
        r.error(node, fmt::format("{}expected a list of {} numbers {}, got {}", prefix, N, form,
                                  node.IsSequence() ? fmt::format("a list of {}", node.size()) : describe(node)));
        return std::nullopt;
    }
    std::array<double, N> out{};
    bool ok = true;
    for (std::size_t i = 0; i < N; ++i) {
        const auto v = r.number(node[i]);
        if (v) out[i] = *v;
        ok = ok && v.has_value();
    }
    if (!ok) return std::nullopt;
    return out;
}

}  // namespace

std::optional<std::array<double, 3>> YamlReader::triple(const YAML::Node& node) {
    return fixed_list<3>(*this, node, "", "[x, y, z]");
}

std::optional<std::array<double, 2>> YamlReader::pair(const YAML::Node& node, const char* what) {
    return fixed_list<2>(*this, node, fmt::format("{}: ", what), "[u, v]");
}

std::optional<std::array<double, 4>> YamlReader::bounds(const YAML::Node& node, const char* what) {
    const auto b = fixed_list<4>(*this, node, fmt::format("{}: ", what), "[x0, x1, y0, y1]");
    if (!b) return std::nullopt;
    const auto& out = *b;
    if (!(out[1] > out[0] && out[3] > out[2])) {
        error(node, fmt::format("{}: needs x0 < x1 and y0 < y1", what));
        return std::nullopt;
    }
    return out;
}

std::optional<Point3> YamlReader::point(const YAML::Node& node) {
    const auto t = triple(node);
    if (!t) return std::nullopt;
    return Point3{static_cast<Float>((*t)[0]), static_cast<Float>((*t)[1]),
                  static_cast<Float>((*t)[2])};
}

std::optional<Vector3> YamlReader::direction(const YAML::Node& node, const char* what) {
    const auto t = triple(node);
    if (!t) return std::nullopt;
    const Vector3 v{static_cast<Float>((*t)[0]), static_cast<Float>((*t)[1]),
                    static_cast<Float>((*t)[2])};
    // In double, so that a long vector is not mistaken for a zero one (float's length overflows).
    const double len = std::sqrt((*t)[0] * (*t)[0] + (*t)[1] * (*t)[1] + (*t)[2] * (*t)[2]);
    if (len > 0 && !std::isfinite(length(v))) {
        error(node, fmt::format("{} is too long for float arithmetic: length {:g}, at most about 1.8e19 (its square must "
                                "be a float)", what, len));
        return std::nullopt;
    }
    if (!(length(v) > 0) || !std::isfinite(length(v))) {
        error(node, fmt::format("{} must not be zero-length", what));
        return std::nullopt;
    }
    return v;
}

std::optional<Color> YamlReader::color(const YAML::Node& node) {
    const auto t = triple(node);
    if (!t) return std::nullopt;
    if ((*t)[0] < 0 || (*t)[1] < 0 || (*t)[2] < 0) {
        error(node, "colour components must be >= 0");
        return std::nullopt;
    }
    return Color{static_cast<float>((*t)[0]), static_cast<float>((*t)[1]),
                 static_cast<float>((*t)[2])};
}

std::optional<double> YamlReader::number_in(const YAML::Node& node, const char* what, double lo,
                                            double hi, bool lo_open, bool hi_open) {
    const auto v = number(node);
    if (!v) return std::nullopt;
    const bool below = lo_open ? !(*v > lo) : *v < lo;
    const bool above = hi_open ? !(*v < hi) : *v > hi;
    if (below || above) {
        std::string range;
        if (std::isinf(hi)) {
            range = fmt::format("{} {}", lo_open ? ">" : ">=", lo);
        } else {
            range = fmt::format("in {}{}, {}{}", lo_open ? "(" : "[", lo, hi, hi_open ? ")" : "]");
        }
        error(node, fmt::format("{} must be {}, got {}", what, range, node.Scalar()));
        return std::nullopt;
    }
    return v;
}

std::optional<long long> YamlReader::integer_in(const YAML::Node& node, const char* what,
                                                long long lo, long long hi) {
    const auto v = integer(node);
    if (!v) return std::nullopt;
    if (*v < lo || *v > hi) {
        error(node, fmt::format("{} must be in [{}, {}], got {}", what, lo, hi, *v));
        return std::nullopt;
    }
    return v;
}

MapReader::MapReader(YamlReader& reader, const YAML::Node& node, std::string context,
                     std::vector<std::string> allowed)
    : reader_(reader), node_(node), context_(std::move(context)) {
    if (!node.IsMap()) {
        reader_.error(node, fmt::format("{}: expected a map of keys, got {}", context_,
                                        describe(node)));
        return;
    }
    valid_ = true;
    std::set<std::string> seen;
    for (auto it = node.begin(); it != node.end(); ++it) {
        const YAML::Node key = it->first;
        const std::string name = key.IsScalar() ? key.Scalar() : std::string();
        if (!key.IsScalar()) {
            reader_.error(key, fmt::format("{}: keys must be names", context_));
            continue;
        }
        if (!seen.insert(name).second) {
            reader_.error(key, fmt::format("{}: duplicate key '{}'", context_, name));
            continue;
        }
        if (std::find(allowed.begin(), allowed.end(), name) == allowed.end()) {
            std::string known;
            for (const auto& a : allowed) known += (known.empty() ? "" : ", ") + a;
            const std::string guess = closest_match(name, allowed);
            reader_.error(key, fmt::format("{}: unknown key '{}'{} (known: {})", context_, name,
                                           guess.empty() ? "" : fmt::format("; did you mean '{}'?", guess),
                                           known));
        }
    }
}

bool MapReader::has(const std::string& key) const {
    if (!valid_) return false;
    const YAML::Node& map = node_;
    return map[key].IsDefined();
}

std::optional<YAML::Node> MapReader::get(const std::string& key) const {
    if (!has(key)) return std::nullopt;
    const YAML::Node& map = node_;
    return map[key];
}

std::optional<YAML::Node> MapReader::require(const std::string& key) {
    if (!has(key)) {
        if (valid_) reader_.error(node_, fmt::format("{}: missing required key '{}'", context_, key));
        return std::nullopt;
    }
    return get(key);
}

bool check_expanded_size(YamlReader& reader, const YAML::Node& root) {
    // Post-order, with an explicit stack, over the graph yaml-cpp built (an alias is the anchored
    // node itself, shared): each collection's expanded size and depth are computed once and
    // remembered by where it starts in the text (a node's identity; yaml-cpp offers no other), so
    // a "billion laughs" costs what its text costs. A collection met again while it is still open
    // is an alias inside its own anchor.
    struct Measure {
        long long size = 1, depth = 0;  // values; collections nested (a leaf: none, as the flow pre-scan counts)
    };
    struct Frame {
        YAML::Node node;
        std::vector<YAML::Node> children;
        std::size_t next = 0;
        Measure m;
    };
    const long long max_values = limit(Limit::kNodes), max_depth = limit(Limit::kNesting);
    std::unordered_map<int, Measure> done;
    std::unordered_set<int> open;
    std::vector<Frame> stack;
    // Opens a collection (true), or gives a leaf's or a known collection's measure in `m` (false).
    const auto open_node = [&](const YAML::Node& node, Measure& m) -> std::optional<bool> {
        m = Measure{};
        if (!node.IsSequence() && !node.IsMap()) return false;
        const int pos = node.Mark().pos;
        if (const auto it = done.find(pos); it != done.end()) {
            m = it->second;
            return false;
        }
        if (open.count(pos)) {
            reader.error(node, "an alias (*name) inside the anchor (&name) it refers to: the value would contain itself");
            return std::nullopt;
        }
        Frame f{node, {}, 0, Measure{1, 1}};
        if (node.IsSequence()) {
            for (const YAML::Node& child : node) f.children.push_back(child);
        } else {
            for (const auto& kv : node) {
                f.children.push_back(kv.first);
                f.children.push_back(kv.second);
            }
        }
        open.insert(pos);
        stack.push_back(std::move(f));
        return true;
    };
    Measure m;
    if (!open_node(root, m).has_value()) return false;  // (not reached: nothing is open yet)
    while (!stack.empty()) {
        Frame& top = stack.back();
        if (top.next < top.children.size()) {
            const YAML::Node child = top.children[top.next++];
            const auto opened = open_node(child, m);
            if (!opened) return false;
            if (*opened) continue;
        } else {  // a collection is complete
            m = top.m;
            const YAML::Node node = top.node;
            open.erase(node.Mark().pos);
            done[node.Mark().pos] = m;
            stack.pop_back();
            if (stack.empty()) return true;
        }
        // Add the child's measure to its parent's, with the limits checked as the sums grow.
        Frame& parent = stack.back();
        parent.m.size = std::min(max_values + 1, parent.m.size + m.size);
        parent.m.depth = std::max(parent.m.depth, m.depth + 1);
        if (parent.m.size > max_values) {
            reader.error(parent.node, fmt::format("this value, with its aliases (*name) expanded, holds more than {} "
                                                  "values, the limit (raise it with --limit nodes=N)", max_values));
            return false;
        }
        if (parent.m.depth > max_depth) {
            reader.error(parent.node, "this value, with its aliases (*name) expanded: " +
                                          over_limit(Limit::kNesting, parent.m.depth));
            return false;
        }
    }
    return true;
}

}  // namespace glint
