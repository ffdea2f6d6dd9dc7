#pragma once
// The scene format's vocabulary, in one place: for each closed set of the YAML/JSON scene format
// (materials, textures, lights, objects, media, samplers, filters, integrators, tone curves, ...)
// the names of its types and, per type, every key the reader accepts. The YAML reader takes its
// type lists and allowed keys from here (formats/scene_yaml*.cpp), the writer its names
// (formats/scene_writer.cpp), and a test checks every name and key against docs/scene-format.md
// (description/vocabulary_test.cpp): a key read but not documented fails it, and the writer's
// output is read back by the reader, which refuses keys not listed here.
// Adding a type or a key: docs/architecture.md, "Adding a material".
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "glint/film/filter.h"
#include "glint/film/tonemap.h"
#include "glint/integrators/integrator.h"
#include "glint/samplers/sampler.h"

namespace glint {

struct VocabularyEntry {
    std::string_view kind;  ///< "material", "texture", "light", "object", ...: a closed set
    std::string_view type;  ///< its `type` value (or, for plain value sets, the value); "" for a kind's only map
    std::vector<std::string_view> keys;  ///< every key the reader accepts there ("type" included)
};

/// Every entry, kinds in the order docs/scene-format.md describes them.
std::span<const VocabularyEntry> vocabulary();

/// The names of a kind's types (or values), in the table's order (the reader's messages list them so).
std::vector<std::string> vocabulary_types(std::string_view kind);

/// The keys of `kind`'s `type` (`type` "" for a kind without types). A pair not in the table is a
/// programming error: std::logic_error.
std::vector<std::string> vocabulary_keys(std::string_view kind, std::string_view type = "");

/// The names the scene format gives to enumerations the writer writes back.
std::string_view vocabulary_name(SamplerType t);
std::string_view vocabulary_name(FilterType t);
std::string_view vocabulary_name(ToneCurve t);
std::string_view vocabulary_name(Encoding e);
std::string_view vocabulary_name(LightStrategy s);
std::string_view vocabulary_name(LightSamplerKind k);
std::string_view vocabulary_name(TextureFilter f);

}  // namespace glint
