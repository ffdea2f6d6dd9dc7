#pragma once
// What a ray that leaves the scene sees.
#include <variant>

#include "glint/math/color.h"
#include "glint/math/vector.h"

namespace glint {

/// The article's sky: t = 0.5 (D.y + 1), colour = (1-t) horizon + t zenith, for unit D.
struct SkyBackground {
    Color horizon{1, 1, 1};
    Color zenith{0.5f, 0.7f, 1.0f};
    Color eval(Vector3 d) const {
        const float t = 0.5f * (d.y + 1);
        return horizon * (1 - t) + zenith * t;
    }
};

struct ConstantBackground {
    Color color;
    Color eval(Vector3) const { return color; }
};

using Background = std::variant<SkyBackground, ConstantBackground>;

inline Color evaluate(const Background& bg, Vector3 d) {
    return std::visit([d](const auto& b) { return b.eval(d); }, bg);
}

}  // namespace glint
