#include "glint/textures/texture.h"

#include <algorithm>
#include <cstdint>

#include "glint/textures/mipmap.h"

namespace glint {

int wrap_index(int i, int n, WrapMode wrap) {
    if (wrap == WrapMode::kClamp) return std::clamp(i, 0, n - 1);
    if (wrap == WrapMode::kMirror) {  // ... 1 0 | 0 1 ... n-1 | n-1 ... 0 | 0 ...
        int m = i % (2 * n);
        if (m < 0) m += 2 * n;
        return m < n ? m : 2 * n - 1 - m;
    }
    const int m = i % n;
    return m < 0 ? m + n : m;
}

// Guards huge or non-finite u (repeat: only the fractional part matters; clamp: anything past
// the edge is the edge).
float to_texels(Float u, int n, WrapMode wrap) {
    if (!std::isfinite(u)) return 0;
    if (wrap == WrapMode::kRepeat) u -= std::floor(u);
    else if (wrap == WrapMode::kMirror) u -= 2 * std::floor(u / 2);  // one period of the mirror
    else u = std::clamp(u, Float(-1), Float(2));
    return u * static_cast<float>(n) - 0.5f;
}

std::optional<Color> CheckerTexture::box_mean(const double* x, const double* h, int n) const {
    // The square wave (-1)^floor(x) and its integral from 0, a triangle wave of period 2.
    const auto wave = [](double v) { return (static_cast<std::int64_t>(std::floor(v)) & 1) == 0 ? 1.0 : -1.0; };
    const auto integral = [](double v) { return 1 - std::abs(v - 2 * std::floor(v / 2) - 1); };
    double widest = 0;
    for (int a = 0; a < n; ++a) widest = std::max(widest, h[a]);
    if (!(widest > 0)) return std::nullopt;
    double product = 1;
    for (int a = 0; a < n; ++a) {
        if (!std::isfinite(x[a]) || !std::isfinite(h[a]) || std::abs(x[a]) > 0x1p52) return std::nullopt;
        // An axis the footprint hardly spans (a plane's normal axis, up to rounding) is read at the
        // point: a plane lying on a cell boundary would otherwise average both sides to grey.
        product *= h[a] > 1e-3 * widest ? (integral(x[a] + h[a]) - integral(x[a] - h[a])) / (2 * h[a]) : wave(x[a]);
    }
    const float k = static_cast<float>(product);
    return (even + odd) * 0.5f + (even - odd) * (0.5f * k);
}

Color CheckerTexture::eval_filtered(Point3 p, Vector3 dpdx, Vector3 dpdy) const {
    double x[3], h[3];
    for (int a = 0; a < 3; ++a) {
        x[a] = static_cast<double>(p[a]) / size;
        h[a] = 0.5 * (std::abs(dpdx[a]) + std::abs(dpdy[a])) / size;
    }
    const auto mean = box_mean(x, h, 3);
    return mean ? *mean : eval(p);
}

Color CheckerTexture::eval_uv_filtered(Point2 uv, Point2 duvdx, Point2 duvdy) const {
    const double su = static_cast<double>(u_scale) / size, sv = static_cast<double>(v_scale) / size;
    const double x[2] = {su * uv.x + static_cast<double>(u_offset) / size, sv * uv.y + static_cast<double>(v_offset) / size};
    const double h[2] = {0.5 * std::abs(su) * (std::abs(duvdx.x) + std::abs(duvdy.x)),
                         0.5 * std::abs(sv) * (std::abs(duvdx.y) + std::abs(duvdy.y))};
    const auto mean = box_mean(x, h, 2);
    return mean ? *mean : eval_uv(uv);
}

namespace {

template <typename... F>
struct Overloaded : F... {
    using F::operator()...;
};
template <typename... F>
Overloaded(F...) -> Overloaded<F...>;

// The four texels around uv and their weights, in the order (xa, ya), (xb, ya), (xa, yb), (xb, yb),
// given to `at(x, y)`.
template <typename At>
auto bilinear_at(const Image& image, Point2 uv, WrapMode wrap_u, WrapMode wrap_v, At at) {
    // v = 0 is the bottom row: flip before addressing rows.
    const float x = to_texels(uv.x, image.width, wrap_u), y = to_texels(1 - uv.y, image.height, wrap_v);
    const float fx0 = std::floor(x), fy0 = std::floor(y);
    const float tx = x - fx0, ty = y - fy0;
    const int x0 = static_cast<int>(fx0), y0 = static_cast<int>(fy0);
    const int xa = wrap_index(x0, image.width, wrap_u), xb = wrap_index(x0 + 1, image.width, wrap_u);
    const int ya = wrap_index(y0, image.height, wrap_v), yb = wrap_index(y0 + 1, image.height, wrap_v);
    return at(xa, ya) * ((1 - tx) * (1 - ty)) + at(xb, ya) * (tx * (1 - ty)) + at(xa, yb) * ((1 - tx) * ty) +
           at(xb, yb) * (tx * ty);
}

}  // namespace

Color bilinear(const Image& image, Point2 uv, WrapMode wrap_u, WrapMode wrap_v) {
    return bilinear_at(image, uv, wrap_u, wrap_v, [&](int x, int y) { return image.texel(x, y); });
}

float bilinear_alpha(const Image& image, Point2 uv, WrapMode wrap_u, WrapMode wrap_v) {
    if (image.alpha.empty()) return 1;
    return bilinear_at(image, uv, wrap_u, wrap_v, [&](int x, int y) {
        return image.alpha[static_cast<std::size_t>(y) * static_cast<std::size_t>(image.width) + static_cast<std::size_t>(x)];
    });
}

Color evaluate(const std::vector<Texture>& textures, const std::vector<Image>& images, TextureId id,
               const TextureContext& ctx) {
    // A missing alternative here is a compile error.
    return std::visit(
        Overloaded{
            [](const ConstantTexture& t) { return t.value; },
            [&](const VertexColorTexture& t) { return t.alpha ? Color{ctx.vertex_alpha} : ctx.vertex_color; },
            [&](const CheckerTexture& t) {
                if (t.on_uv) {
                    const bool footprint = ctx.duvdx.x != 0 || ctx.duvdx.y != 0 || ctx.duvdy.x != 0 || ctx.duvdy.y != 0;
                    return footprint ? t.eval_uv_filtered(ctx.uv, ctx.duvdx, ctx.duvdy) : t.eval_uv(ctx.uv);
                }
                const bool footprint = dot(ctx.dpdx, ctx.dpdx) > 0 || dot(ctx.dpdy, ctx.dpdy) > 0;
                return footprint ? t.eval_filtered(ctx.p, ctx.dpdx, ctx.dpdy) : t.eval(ctx.p);
            },
            [&](const ImageTexture& t) {
                const auto& m = t.uv_transform;
                const Point2 st = t.uv_set == 0 || !ctx.uv_set ? ctx.uv : ctx.uv_set(ctx.uv_set_arg, t.uv_set);
                const Point2 uv{m[0] * st.x + m[1] * st.y + m[2], m[3] * st.x + m[4] * st.y + m[5]};
                const Point2 at{uv.x / t.size, uv.y / t.size};
                if (t.alpha) return Color{bilinear_alpha(images[t.image], at, t.wrap, t.wrap_v)};
                const bool footprint = ctx.duvdx.x != 0 || ctx.duvdx.y != 0 || ctx.duvdy.x != 0 || ctx.duvdy.y != 0;
                if (footprint && t.filtered() && ctx.pyramids && t.image < ctx.pyramids->size() &&
                    !(*ctx.pyramids)[t.image].levels.empty()) {
                    // The differentials through the texture's own linear map.
                    const auto map = [&](Point2 d) {
                        return Point2{(m[0] * d.x + m[1] * d.y) / t.size, (m[3] * d.x + m[4] * d.y) / t.size};
                    };
                    const Point2 d0 = map(ctx.duvdx), d1 = map(ctx.duvdy);
                    const MipPyramid& pyramid = (*ctx.pyramids)[t.image];
                    if (t.filter == TextureFilter::kTrilinear) {
                        const float width = 2 * std::max({std::abs(d0.x), std::abs(d0.y), std::abs(d1.x), std::abs(d1.y)});
                        return trilinear(images[t.image], pyramid, at, width, t.wrap, t.wrap_v);
                    }
                    return ewa(images[t.image], pyramid, at, d0, d1, t.wrap, t.wrap_v);
                }
                return bilinear(images[t.image], at, t.wrap, t.wrap_v);
            },
            [&](const ScaleTexture& t) {
                return evaluate(textures, images, t.texture, ctx) *
                       evaluate(textures, images, t.factor, ctx);
            },
            [&](const MixTexture& t) {
                const Color k = evaluate(textures, images, t.amount, ctx);
                return evaluate(textures, images, t.a, ctx) * (Color{1} - k) +
                       evaluate(textures, images, t.b, ctx) * k;
            }},
        textures[id]);
}

}  // namespace glint
