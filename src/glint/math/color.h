#pragma once
// Colour: linear RGB with sRGB/Rec.709 primaries. All arithmetic inside the renderer is on
// linear values; encoding for display (sRGB curve, or the article's "raw" clamp) happens only
// when an image is written (film/tonemap.h).
#include <cmath>

namespace glint {

struct Color {
    float r = 0, g = 0, b = 0;
    constexpr Color() = default;
    constexpr Color(float r_, float g_, float b_) : r(r_), g(g_), b(b_) {}
    constexpr explicit Color(float v) : r(v), g(v), b(v) {}
    constexpr Color operator+(Color o) const { return {r + o.r, g + o.g, b + o.b}; }
    constexpr Color operator-(Color o) const { return {r - o.r, g - o.g, b - o.b}; }
    /// Component-wise (Hadamard) product, the article's K I and d r.
    constexpr Color operator*(Color o) const { return {r * o.r, g * o.g, b * o.b}; }
    constexpr Color operator*(float s) const { return {r * s, g * s, b * s}; }
    constexpr Color operator/(float s) const { return {r / s, g / s, b / s}; }
    constexpr Color& operator+=(Color o) { return *this = *this + o; }
    constexpr Color& operator*=(Color o) { return *this = *this * o; }
    constexpr bool operator==(const Color&) const = default;
    constexpr float operator[](int i) const { return i == 0 ? r : (i == 1 ? g : b); }
    constexpr bool is_black() const { return r == 0 && g == 0 && b == 0; }
    constexpr float max_component() const { return r > g ? (r > b ? r : b) : (g > b ? g : b); }
};
constexpr Color operator*(float s, Color c) { return c * s; }

inline bool is_finite(Color c) {
    return std::isfinite(c.r) && std::isfinite(c.g) && std::isfinite(c.b);
}

/// Luminance (Y) of a linear sRGB / Rec.709 colour.
constexpr float luminance(Color c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; }

/// The mean of the three channels (hero-channel MIS weights, a texture read as a number).
constexpr float average(Color c) { return (c.r + c.g + c.b) / 3; }

}  // namespace glint
