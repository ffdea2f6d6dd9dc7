#include "glint/background.h"

#include <cmath>

namespace glint {

namespace {
int wrap_column(int x, int width) { return ((x % width) + width) % width; }
}  // namespace

EnvironmentMap EnvironmentMap::make(Image image, float scale) {
    EnvironmentMap env;
    const int w = image.width, h = image.height;
    std::vector<float> weights(static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
    for (int y = 0; y < h; ++y) {
        const float sin_theta =
            std::sin((static_cast<float>(y) + 0.5f) / static_cast<float>(h) * std::numbers::pi_v<float>);
        for (int x = 0; x < w; ++x) {
            float m = 0;
            for (int dy = -1; dy <= 1; ++dy) {
                const int yy = std::clamp(y + dy, 0, h - 1);
                for (int dx = -1; dx <= 1; ++dx)
                    m = std::max(m, luminance(image.texel(wrap_column(x + dx, w), yy)));
            }
            weights[static_cast<std::size_t>(y) * static_cast<std::size_t>(w) +
                    static_cast<std::size_t>(x)] = m * sin_theta;
        }
    }
    env.distribution = Distribution2D(weights, w, h);
    env.image = std::move(image);
    env.scale = scale;
    return env;
}

Color EnvironmentMap::eval(Vector3 d) const {
    const Point2 uv = direction_to_uv(d);
    if (!(std::isfinite(uv.x) && std::isfinite(uv.y))) return Color{0};
    const float x = uv.x * static_cast<float>(image.width) - 0.5f;
    const float y = std::clamp(uv.y * static_cast<float>(image.height) - 0.5f, 0.0f,
                               static_cast<float>(image.height - 1));
    const float fx = std::floor(x), fy = std::floor(y);
    const float tx = x - fx, ty = y - fy;
    const int x0 = wrap_column(static_cast<int>(fx), image.width);
    const int x1 = wrap_column(static_cast<int>(fx) + 1, image.width);
    const int y0 = static_cast<int>(fy), y1 = std::min(y0 + 1, image.height - 1);
    const Color c = image.texel(x0, y0) * ((1 - tx) * (1 - ty)) + image.texel(x1, y0) * (tx * (1 - ty)) +
                    image.texel(x0, y1) * ((1 - tx) * ty) + image.texel(x1, y1) * (tx * ty);
    return c * scale;
}

Point2 equal_area_sphere_to_square(Vector3 d) {
    const float x = std::abs(d.x), y = std::abs(d.y), z = std::abs(d.z);
    const float r = std::sqrt(std::max(0.0f, 1 - z));
    const float a = std::max(x, y), b = a == 0 ? 0 : std::min(x, y) / a;
    float phi = std::atan(b) * 2 * std::numbers::inv_pi_v<float>;
    if (x < y) phi = 1 - phi;
    float v = phi * r;
    float u = r - v;
    if (d.z < 0) {
        std::swap(u, v);
        u = 1 - u;
        v = 1 - v;
    }
    u = std::copysign(u, d.x);
    v = std::copysign(v, d.y);
    return {0.5f * (u + 1), 0.5f * (v + 1)};
}

Image equal_area_to_latlong(const Image& square, const Matrix34& world_to_light) {
    const int n = square.width;
    Image out;
    out.width = 2 * n;
    out.height = n;
    out.texels.resize(static_cast<std::size_t>(out.width) * static_cast<std::size_t>(out.height));
    const auto texel = [&](int x, int y) {
        return square.texel(std::clamp(x, 0, n - 1), std::clamp(y, 0, square.height - 1));
    };
    for (int j = 0; j < out.height; ++j)
        for (int i = 0; i < out.width; ++i) {
            const Vector3 d = EnvironmentMap::uv_to_direction({(i + 0.5f) / float(out.width), (j + 0.5f) / float(out.height)});
            const Point2 st = equal_area_sphere_to_square(normalize(world_to_light.apply(d)));
            // Bilinear between texel centres (pbrt's image rows run down from v = 0).
            const float fx = st.x * float(n) - 0.5f, fy = st.y * float(square.height) - 0.5f;
            const int x0 = int(std::floor(fx)), y0 = int(std::floor(fy));
            const float tx = fx - float(x0), ty = fy - float(y0);
            const Color c = texel(x0, y0) * ((1 - tx) * (1 - ty)) + texel(x0 + 1, y0) * (tx * (1 - ty)) +
                            texel(x0, y0 + 1) * ((1 - tx) * ty) + texel(x0 + 1, y0 + 1) * (tx * ty);
            out.texels[static_cast<std::size_t>(j) * static_cast<std::size_t>(out.width) + static_cast<std::size_t>(i)] = c;
        }
    return out;
}

double illuminance(const Image& latlong, Vector3 up) {
    const int w = latlong.width, h = latlong.height;
    const double d_phi = 2 * std::numbers::pi / w, d_theta = std::numbers::pi / h;
    double e = 0;
    for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i) {
            const Point2 uv{(float(i) + 0.5f) / float(w), (float(j) + 0.5f) / float(h)};
            const Vector3 d = EnvironmentMap::uv_to_direction(uv);
            const double c = dot(d, up);
            if (c <= 0) continue;
            const double sin_theta = std::sin((j + 0.5) * d_theta);
            e += double(luminance(latlong.texel(i, j))) * c * sin_theta * d_phi * d_theta;
        }
    return e;
}

}  // namespace glint
