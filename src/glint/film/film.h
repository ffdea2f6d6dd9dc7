#pragma once
// The film: float linear RGB per pixel, row 0 at the top, and optionally the AOVs denoisers
// consume (albedo, normal, depth) and each pixel's sample count. It knows nothing about scenes or files; the renderer fills
// it, image_io encodes and writes it.
#include <cstddef>
#include <utility>
#include <vector>

#include "glint/film/big_buffer.h"
#include "glint/math/color.h"
#include "glint/math/vector.h"

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
    const BigVector<Color>& pixels() const { return pixels_; }

    /// Allocates the AOV planes (albedo, normal, depth, and the two half images of the colour and
    /// of the albedo: the means of the even- and of the odd-numbered samples), before rendering.
    void enable_aovs() {
        albedo_.assign(pixels_.size(), Color{0});
        normal_.assign(pixels_.size(), Normal3{0, 0, 0});
        depth_.assign(pixels_.size(), 0);
        even_.assign(pixels_.size(), Color{0});
        odd_.assign(pixels_.size(), Color{0});
        even_albedo_.assign(pixels_.size(), Color{0});
        odd_albedo_.assign(pixels_.size(), Color{0});
    }
    bool has_aovs() const { return !albedo_.empty(); }
    Color& albedo(int col, int row) { return albedo_[index(col, row)]; }
    Normal3& normal(int col, int row) { return normal_[index(col, row)]; }
    float& depth(int col, int row) { return depth_[index(col, row)]; }
    const BigVector<Color>& albedo() const { return albedo_; }
    const BigVector<Normal3>& normal() const { return normal_; }
    const BigVector<float>& depth() const { return depth_; }
    Color& even(int col, int row) { return even_[index(col, row)]; }
    Color& odd(int col, int row) { return odd_[index(col, row)]; }
    const BigVector<Color>& even() const { return even_; }
    const BigVector<Color>& odd() const { return odd_; }
    Color& even_albedo(int col, int row) { return even_albedo_[index(col, row)]; }
    Color& odd_albedo(int col, int row) { return odd_albedo_[index(col, row)]; }
    const BigVector<Color>& even_albedo() const { return even_albedo_; }
    const BigVector<Color>& odd_albedo() const { return odd_albedo_; }

    /// The image before denoising, kept beside the denoised one (written as EXR channels).
    void keep_noisy(BigVector<Color> noisy) { noisy_ = std::move(noisy); }
    bool has_noisy() const { return !noisy_.empty(); }
    const BigVector<Color>& noisy() const { return noisy_; }
    BigVector<Color>& pixels() { return pixels_; }

    /// Allocates the per-pixel sample-count plane (adaptive sampling writes it).
    void enable_sample_counts() { samples_.assign(pixels_.size(), 0); }
    bool has_sample_counts() const { return !samples_.empty(); }
    float& sample_count(int col, int row) { return samples_[index(col, row)]; }
    const BigVector<float>& sample_counts() const { return samples_; }

private:
    std::size_t index(int col, int row) const {
        return static_cast<std::size_t>(row) * static_cast<std::size_t>(width_) +
               static_cast<std::size_t>(col);
    }
    int width_, height_;
    BigVector<Color> pixels_;
    BigVector<Color> albedo_;
    BigVector<Normal3> normal_;
    BigVector<float> depth_;
    BigVector<Color> even_, odd_, even_albedo_, odd_albedo_, noisy_;
    BigVector<float> samples_;
};

}  // namespace glint
