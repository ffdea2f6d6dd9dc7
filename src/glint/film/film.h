#pragma once
// The film: float linear RGB per pixel, row 0 at the top. It knows nothing about scenes or
// files; the renderer fills it, image_io encodes and writes it.
#include <cstddef>
#include <vector>

#include "glint/math/color.h"

namespace glint {

class Film {
public:
    Film(int width, int height)
        : width_(width), height_(height),
          pixels_(static_cast<std::size_t>(width) * static_cast<std::size_t>(height)) {}
    int width() const { return width_; }
    int height() const { return height_; }
    Color& at(int col, int row) { return pixels_[index(col, row)]; }
    const Color& at(int col, int row) const { return pixels_[index(col, row)]; }
    const std::vector<Color>& pixels() const { return pixels_; }

private:
    std::size_t index(int col, int row) const {
        return static_cast<std::size_t>(row) * static_cast<std::size_t>(width_) +
               static_cast<std::size_t>(col);
    }
    int width_, height_;
    std::vector<Color> pixels_;
};

}  // namespace glint
