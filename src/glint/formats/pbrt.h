#pragma once
// pbrt-v4 scene files (.pbrt) read into the same SceneDescription the YAML reader makes, so that
// one builder (builder/build.h) turns both into a Scene. The format, what is mapped and what is
// approximated: docs/scene-format.md, "pbrt-v4 scenes".
//
// Every token carries file:line:col. Errors (a malformed file, an unknown directive or
// parameter, a wrong parameter type, a missing Include) are collected and thrown as one
// SceneError; constructs glint cannot render are located warnings in
// SceneDescription::warnings saying what was done instead, or errors when `strict`.
#include <memory>
#include <string>

#include "glint/base/diagnostics.h"
#include "glint/description/scene_description.h"

namespace glint {

struct PbrtOptions {
    bool strict = false;  ///< warnings are errors
};

/// Reads a .pbrt file (and what it includes). `sources` receives every file's text.
SceneDescription load_pbrt_file(const std::string& path, std::shared_ptr<SourceFiles> sources,
                                const PbrtOptions& options = {});

/// Parses pbrt text; `path` names it in messages and anchors Include and mesh file names.
SceneDescription parse_pbrt(const std::string& text, const std::string& path,
                            std::shared_ptr<SourceFiles> sources, const PbrtOptions& options = {});

/// Whether `path` names a pbrt scene (.pbrt, any case).
bool is_pbrt_file(const std::string& path);

}  // namespace glint
