#pragma once
// Where a value sits in a JSON text, for error messages that point at a line: glTF's semantic
// errors (a node naming a mesh that does not exist) are found on the parsed model, which has no
// positions, so the text is walked again, only when an error is reported.
#include <optional>
#include <string_view>

namespace glint {

struct TextPosition {
    int line = 0;    ///< 1-based
    int column = 0;  ///< 1-based, in characters (UTF-8 continuation bytes not counted)
};

/// The start of the value that JSON pointer `pointer` (RFC 6901, e.g. "/nodes/0/mesh"; "" is the
/// whole document) names in `text`; nullopt if there is no such value or the text is not JSON
/// up to it. Walks only along the pointer's path (recursion as deep as the pointer is long), so
/// any input, however nested or malformed, ends in an answer.
std::optional<TextPosition> json_locate(std::string_view text, std::string_view pointer);

/// The first '[' or '{' of `text` that opens a level deeper than `max_depth`, found by a scan
/// that only counts brackets outside strings (no recursion, no allocation), so that a file nested
/// 40,000 deep is refused before any recursive JSON parser sees it; nullopt if none is.
std::optional<TextPosition> json_too_deep(std::string_view text, long long max_depth);

}  // namespace glint
