#pragma once
// Materials: a closed set (std::variant of plain structs). Today glint has the article's
// material; the path tracer's materials join the variant as new alternatives.
#include <variant>

#include "glint/textures/texture.h"

namespace glint {

/// The article's material: a colour K (from a texture) and a shininess s in [0,1] that blends
/// diffuse shading d with the reflected colour: (1-s) d + s (d * r).
struct ArticleMaterial {
    TextureId color;
    Float shininess = 0;
};

using Material = std::variant<ArticleMaterial>;

}  // namespace glint
