#pragma once
// Typed, located reading of yaml-cpp nodes. Every accessor reports what is wrong with the node
// (with its line and column) into Diagnostics and returns nullopt, so that parsing goes on and
// all errors of a file surface in one run.
#include <yaml-cpp/yaml.h>

#include <array>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "glint/base/diagnostics.h"
#include "glint/math/color.h"
#include "glint/math/vector.h"

namespace glint {

class YamlReader {
public:
    YamlReader(Diagnostics& diagnostics, std::string file)
        : diagnostics_(diagnostics), file_(std::move(file)) {}
    /// The file being read (as given), which relative paths in it are relative to.
    const std::string& file() const { return file_; }

    SourceLoc loc(const YAML::Node& node) const;
    /// Errors about `node` (a value made by the parser, e.g. a keyframed value at one frame, which
    /// has no place in the file) are reported at `at`.
    void locate_as(const YAML::Node& node, SourceLoc at) { made_.emplace_back(node, std::move(at)); }
    void error(const YAML::Node& node, std::string message) { diagnostics_.error(loc(node), std::move(message)); }
    Diagnostics& diagnostics() { return diagnostics_; }

    std::optional<double> number(const YAML::Node& node);
    std::optional<long long> integer(const YAML::Node& node);
    std::optional<bool> boolean(const YAML::Node& node);
    std::optional<std::string> string(const YAML::Node& node);
    std::optional<std::array<double, 3>> triple(const YAML::Node& node);
    /// Two finite numbers [a, b]; `what` names them in errors.
    std::optional<std::array<double, 2>> pair(const YAML::Node& node, const char* what);
    /// Four finite numbers [x0, x1, y0, y1] with x0 < x1 and y0 < y1 (windows, crops).
    std::optional<std::array<double, 4>> bounds(const YAML::Node& node, const char* what);

    std::optional<Point3> point(const YAML::Node& node);
    /// A vector that must not be zero-length (directions, normals); `what` names it in errors.
    std::optional<Vector3> direction(const YAML::Node& node, const char* what);
    /// Three finite, non-negative numbers.
    std::optional<Color> color(const YAML::Node& node);

    /// A number in [lo, hi] (the ends excluded when lo_open, hi_open); `what` names it in errors.
    std::optional<double> number_in(const YAML::Node& node, const char* what, double lo, double hi,
                                    bool lo_open = false, bool hi_open = false);
    std::optional<long long> integer_in(const YAML::Node& node, const char* what, long long lo,
                                        long long hi);

private:
    Diagnostics& diagnostics_;
    std::string file_;
    std::vector<std::pair<YAML::Node, SourceLoc>> made_;
};

/// A YAML map whose keys are checked against a fixed set: unknown keys (with a did-you-mean),
/// duplicate keys and missing required keys are errors. `context` names the map in messages,
/// e.g. "sphere" or "camera".
class MapReader {
public:
    MapReader(YamlReader& reader, const YAML::Node& node, std::string context,
              std::vector<std::string> allowed);
    bool valid() const { return valid_; }
    bool has(const std::string& key) const;
    std::optional<YAML::Node> get(const std::string& key) const;
    /// get(), reporting an error at the map if the key is absent.
    std::optional<YAML::Node> require(const std::string& key);

private:
    YamlReader& reader_;
    YAML::Node node_;
    std::string context_;
    bool valid_ = false;
};

/// Walks `root` as the scene reader will, with aliases expanded, without recursion: an alias that
/// contains itself, nesting deeper than the nesting limit or more values in all than the nodes
/// limit (a "billion laughs") is reported at the node where it shows. Returns whether the tree is
/// safe to read recursively.
bool check_expanded_size(YamlReader& reader, const YAML::Node& root);

/// "a list", "a map", "'text'" or "nothing": how a node is described in "expected X, got Y".
std::string describe(const YAML::Node& node);

}  // namespace glint
