#include "glint/textures/mipmap.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace glint {

namespace {

// Output texel i of n_out covers [i s, (i + 1) s) of the n_in input texels, s = n_in / n_out:
// the input texels it overlaps and the overlaps' shares (summing to 1).
struct Tap {
    int first = 0, count = 0;
    float weight[3] = {0, 0, 0};  // s <= 2: at most three texels overlap
};

std::vector<Tap> box_taps(int n_in, int n_out) {
    std::vector<Tap> taps(static_cast<std::size_t>(n_out));
    const double s = static_cast<double>(n_in) / n_out;
    for (int i = 0; i < n_out; ++i) {
        const double a = i * s, b = (i + 1) * s;
        Tap& t = taps[static_cast<std::size_t>(i)];
        t.first = static_cast<int>(std::floor(a));
        for (int j = t.first; j < n_in && j < b && t.count < 3; ++j) {
            const double overlap = std::min(b, j + 1.0) - std::max(a, double(j));
            t.weight[t.count++] = static_cast<float>(overlap / s);
        }
    }
    return taps;
}

Image downsample(const Image& in) {
    Image out;
    out.width = std::max(1, (in.width + 1) / 2);
    out.height = std::max(1, (in.height + 1) / 2);
    const std::vector<Tap> tx = box_taps(in.width, out.width), ty = box_taps(in.height, out.height);
    // Rows first, then columns.
    std::vector<Color> rows(static_cast<std::size_t>(out.width) * static_cast<std::size_t>(in.height));
    std::vector<float> alpha_rows(in.alpha.empty() ? 0 : rows.size());
    for (int y = 0; y < in.height; ++y) {
        for (int x = 0; x < out.width; ++x) {
            const Tap& t = tx[static_cast<std::size_t>(x)];
            Color c{0};
            float a = 0;
            for (int k = 0; k < t.count; ++k) {
                const std::size_t at = static_cast<std::size_t>(y) * static_cast<std::size_t>(in.width) +
                                       static_cast<std::size_t>(t.first + k);
                c += in.texels[at] * t.weight[k];
                if (!in.alpha.empty()) a += in.alpha[at] * t.weight[k];
            }
            const std::size_t o = static_cast<std::size_t>(y) * static_cast<std::size_t>(out.width) + static_cast<std::size_t>(x);
            rows[o] = c;
            if (!alpha_rows.empty()) alpha_rows[o] = a;
        }
    }
    out.texels.assign(static_cast<std::size_t>(out.width) * static_cast<std::size_t>(out.height), Color{0});
    if (!in.alpha.empty()) out.alpha.assign(out.texels.size(), 0);
    for (int y = 0; y < out.height; ++y) {
        const Tap& t = ty[static_cast<std::size_t>(y)];
        for (int x = 0; x < out.width; ++x) {
            Color c{0};
            float a = 0;
            for (int k = 0; k < t.count; ++k) {
                const std::size_t at = static_cast<std::size_t>(t.first + k) * static_cast<std::size_t>(out.width) +
                                       static_cast<std::size_t>(x);
                c += rows[at] * t.weight[k];
                if (!alpha_rows.empty()) a += alpha_rows[at] * t.weight[k];
            }
            const std::size_t o = static_cast<std::size_t>(y) * static_cast<std::size_t>(out.width) + static_cast<std::size_t>(x);
            out.texels[o] = c;
            if (!out.alpha.empty()) out.alpha[o] = a;
        }
    }
    return out;
}

// The fractional level for a footprint `texels` level-0 texels wide, and the lookup between the
// two levels around it (`at(level, image)`).
template <typename At>
Color between_levels(const Image& base, const MipPyramid& pyramid, float texels, At at) {
    const float level = texels > 1 ? std::log2(texels) : 0.0f;
    const int top = pyramid.count() - 1;
    if (!(level > 0)) return at(0, base);
    if (level >= static_cast<float>(top)) return at(top, pyramid.level(base, top));
    const int k = static_cast<int>(level);
    const float f = level - static_cast<float>(k);
    return at(k, pyramid.level(base, k)) * (1 - f) + at(k + 1, pyramid.level(base, k + 1)) * f;
}

}  // namespace

float ewa_gaussian(double r2) {
    constexpr int kEntries = 64;
    static const auto table = [] {
        std::array<float, kEntries> t{};
        for (int i = 0; i < kEntries; ++i) {
            const double r = static_cast<double>(i) / (kEntries - 1);
            t[static_cast<std::size_t>(i)] = static_cast<float>(std::exp(-2 * r) - std::exp(-2.0));
        }
        return t;
    }();
    const int i = std::clamp(static_cast<int>(r2 * (kEntries - 1)), 0, kEntries - 1);
    return table[static_cast<std::size_t>(i)];
}

MipPyramid MipPyramid::build(const Image& image) {
    MipPyramid p;
    if (image.width <= 0 || image.height <= 0) return p;
    const Image* prev = &image;
    while (prev->width > 1 || prev->height > 1) {
        p.levels.push_back(downsample(*prev));
        prev = &p.levels.back();
    }
    return p;
}

std::size_t MipPyramid::texels() const {
    std::size_t n = 0;
    for (const Image& l : levels) n += l.texels.size();
    return n;
}

Color trilinear(const Image& base, const MipPyramid& pyramid, Point2 uv, Float width, WrapMode wrap_u,
                WrapMode wrap_v) {
    const float texels = std::isfinite(width) ? std::abs(width) * static_cast<float>(std::max(base.width, base.height)) : 0.0f;
    return between_levels(base, pyramid, texels,
                          [&](int, const Image& image) { return bilinear(image, uv, wrap_u, wrap_v); });
}

Color ewa(const Image& base, const MipPyramid& pyramid, Point2 uv, Point2 d0, Point2 d1, WrapMode wrap_u,
          WrapMode wrap_v) {
    const auto len2 = [](Point2 d) { return d.x * d.x + d.y * d.y; };
    if (!(std::isfinite(len2(d0)) && std::isfinite(len2(d1))) || !std::isfinite(uv.x) || !std::isfinite(uv.y))
        return bilinear(base, uv, wrap_u, wrap_v);
    if (len2(d0) < len2(d1)) std::swap(d0, d1);
    const float longer = std::sqrt(len2(d0));
    float shorter = std::sqrt(len2(d1));
    // An ellipse more eccentric than 8:1 is widened along its minor axis: it then reads at most a
    // bounded number of texels, at the cost of some blur.
    constexpr float kMaxAnisotropy = 8;
    if (shorter * kMaxAnisotropy < longer && shorter > 0) {
        const float scale = longer / (shorter * kMaxAnisotropy);
        d1 = {d1.x * scale, d1.y * scale};
        shorter *= scale;
    }
    if (!(shorter > 0)) return bilinear(base, uv, wrap_u, wrap_v);
    const float texels = shorter * static_cast<float>(std::max(base.width, base.height));
    return between_levels(base, pyramid, texels, [&](int, const Image& image) {
        if (image.width == 1 && image.height == 1) return image.texel(0, 0);
        // Texel space of this level: v = 0 is the bottom row, so the t axis runs against v.
        const float s = to_texels(uv.x, image.width, wrap_u), t = to_texels(1 - uv.y, image.height, wrap_v);
        const float w = static_cast<float>(image.width), h = static_cast<float>(image.height);
        const Point2 e0{d0.x * w, -d0.y * h}, e1{d1.x * w, -d1.y * h};
        Color sum{0};
        const double total = ewa_weights(s, t, e0, e1, [&](int x, int y, double weight) {
            sum += image.texel(wrap_index(x, image.width, wrap_u), wrap_index(y, image.height, wrap_v)) *
                   static_cast<float>(weight);
        });
        return total > 0 ? sum / static_cast<float>(total) : bilinear(image, uv, wrap_u, wrap_v);
    });
}

}  // namespace glint
