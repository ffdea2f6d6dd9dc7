#pragma once
// Textures: a closed set of plain structs in a std::variant (lajolla's model). Each alternative
// provides `Color eval(Point3 p) const`; the concept documents that, and a missing overload in
// evaluate() is a compile error.
#include <cmath>
#include <concepts>
#include <cstdint>
#include <variant>

#include "glint/math/color.h"
#include "glint/math/vector.h"

namespace glint {

using TextureId = std::uint32_t;

template <typename T>
concept TextureLike = requires(const T& t, Point3 p) {
    { t.eval(p) } -> std::same_as<Color>;
};

struct ConstantTexture {
    Color value;
    Color eval(Point3) const { return value; }
};

/// A 3D checkerboard of cubes of side `size`: `even` where floor(x/s)+floor(y/s)+floor(z/s) is
/// even, `odd` elsewhere. On a plane y = k this is a 2D checkerboard whose parity is shifted by
/// floor(k/s).
struct CheckerTexture {
    Float size;
    Color even;
    Color odd;
    Color eval(Point3 p) const {
        const Float inv = 1 / size;
        const auto cell = [inv](Float v) {
            const Float f = std::floor(v * inv);
            // Past 2^62 (or infinite or NaN, from an absurdly small size) the cell index is
            // meaningless and converting it would be undefined behaviour: use cell 0.
            return std::abs(f) < 0x1p62f ? static_cast<std::int64_t>(f) : std::int64_t{0};
        };
        const std::int64_t sum = cell(p.x) + cell(p.y) + cell(p.z);
        return (sum & 1) == 0 ? even : odd;
    }
};

using Texture = std::variant<ConstantTexture, CheckerTexture>;
static_assert(TextureLike<ConstantTexture> && TextureLike<CheckerTexture>);

inline Color evaluate(const Texture& texture, Point3 p) {
    return std::visit([p](const auto& t) { return t.eval(p); }, texture);
}

}  // namespace glint
