#pragma once
// The glTF 2.0 specification's rules on the JSON itself, checked before tinygltf reads it: the
// version, and every property's JSON type and range (tinygltf reads a string where a number
// belongs as the default, silently). Each error names the JSON pointer of the value; the caller
// turns it into a line and column. A map of the Khronos glTF-Validator's type checks.
#include <optional>
#include <string>
#include <string_view>

namespace glint {

struct GltfRuleError {
    std::string pointer;  ///< "/accessors/0/count"
    std::string message;  ///< "accessors[0].count: -5 is not an integer of at least 1"
};

/// The first rule `json` (a glTF's JSON text, nesting already bounded) breaks, if any; nullopt
/// also when the text is not JSON (tinygltf reports that, located).
std::optional<GltfRuleError> gltf_rule_error(std::string_view json);

}  // namespace glint
