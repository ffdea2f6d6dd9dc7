#pragma once
// Textures: a closed set of plain structs in a std::variant (lajolla's model), evaluated at a
// surface point and its uv. Textures that combine others (scale, mix) refer to them by id; build
// adds children before parents, so the ids form a tree and evaluation always terminates.
#include <cmath>
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <variant>
#include <vector>

#include "glint/math/color.h"
#include "glint/math/vector.h"
#include "glint/spectra/spectrum.h"

namespace glint {

using TextureId = std::uint32_t;
using ImageId = std::uint32_t;
struct MipPyramid;  // textures/mipmap.h

struct TextureContext {
    Point3 p;
    Point2 uv;              ///< texture coordinate set 0
    Color vertex_color{1};  ///< interpolated per-vertex colour on meshes that have one; 1 elsewhere
    Float vertex_alpha = 1; ///< interpolated per-vertex alpha (glTF COLOR_0's fourth channel)
    /// Texture coordinate set `set` >= 1 (glTF TEXCOORD_1 and up), computed only when a texture
    /// asks for one; null or returning set 0's where the surface has no such set.
    Point2 (*uv_set)(const void* arg, int set) = nullptr;
    const void* uv_set_arg = nullptr;
    /// The pixel's footprint (cameras/camera.h, PixelFootprint): how p and uv (set 0) change from
    /// one pixel to the next; zero where textures are not filtered. `pyramids`: the MIP pyramid of
    /// each image (empty for images no filtered texture reads).
    Vector3 dpdx{}, dpdy{};
    Point2 duvdx{}, duvdy{};
    const std::vector<MipPyramid>* pyramids = nullptr;
};

/// Linear RGB texels, row 0 at the top of the image. Texture coordinates follow the OBJ, pbrt and
/// OpenGL convention: (u, v) = (0, 0) is the image's bottom-left corner, v grows upward.
struct Image {
    int width = 0, height = 0;
    std::vector<Color> texels;
    std::vector<float> alpha;  ///< empty (opaque), or one per texel: the image's alpha channel
    const Color& texel(int x, int y) const {
        return texels[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                      static_cast<std::size_t>(x)];
    }
};

enum class WrapMode { kRepeat, kClamp, kMirror };

/// How an image texture is read over a pixel's footprint: an elliptically weighted average (EWA,
/// the default), trilinear MIP mapping, or one bilinear lookup at the point (no filtering).
enum class TextureFilter { kEwa, kTrilinear, kBilinear };

/// Texel i of an axis of n texels, wrapped.
int wrap_index(int i, int n, WrapMode wrap);
/// u in texel coordinates of an axis of n texels (texel centres at integers): repeat and
/// mirror bring it into one period first, clamp limits it; non-finite u gives 0.
float to_texels(Float u, int n, WrapMode wrap);

/// Bilinear interpolation of the four texels around uv (texel centres at u = (i + 1/2)/width
/// and v = 1 - (j + 1/2)/height for column i, row j), with repeat or clamp addressing.
Color bilinear(const Image& image, Point2 uv, WrapMode wrap_u, WrapMode wrap_v);
inline Color bilinear(const Image& image, Point2 uv, WrapMode wrap) { return bilinear(image, uv, wrap, wrap); }
/// The same interpolation of the image's alpha channel (1 where it has none).
float bilinear_alpha(const Image& image, Point2 uv, WrapMode wrap_u, WrapMode wrap_v);

struct ConstantTexture {
    Color value;
    /// A reflectance spectrum (values in [0, 1]) that spectral mode reads instead of upsampling
    /// `value` (its colour under D65); null for a colour.
    std::shared_ptr<const Spectrum> spectrum;
};

/// A checkerboard. In space (the default): a 3D checkerboard of cubes of side `size`, `even` where
/// floor(x/s)+floor(y/s)+floor(z/s) is even, `odd` elsewhere; on a plane y = k this is a 2D
/// checkerboard whose parity is shifted by floor(k/s). On uv (`on_uv`, pbrt-v4's 2D
/// checkerboard): squares of side `size` over (s, t) = (u_scale u + u_offset, v_scale v + v_offset),
/// `even` where floor(s/size) + floor(t/size) is even.
struct CheckerTexture {
    Float size;
    Color even;
    Color odd;
    bool on_uv = false;
    Float u_scale = 1, v_scale = 1, u_offset = 0, v_offset = 0;

    Color eval(Point3 p) const {
        const std::int64_t sum = cell(p.x) + cell(p.y) + cell(p.z);
        return (sum & 1) == 0 ? even : odd;
    }
    Color eval_uv(Point2 uv) const {
        const std::int64_t sum = cell(u_scale * uv.x + u_offset) + cell(v_scale * uv.y + v_offset);
        return (sum & 1) == 0 ? even : odd;
    }
    /// The mean over the box around p that holds the pixel's footprint (half-widths
    /// (|dpdx| + |dpdy|) / 2 per axis), in closed form: the checker is (even + odd) / 2 +
    /// (even - odd) / 2 times a product of square waves, one per axis, and a box average of a
    /// product of one-axis functions is the product of their averages.
    Color eval_filtered(Point3 p, Vector3 dpdx, Vector3 dpdy) const;
    /// The same over uv's footprint (duvdx, duvdy), on_uv.
    Color eval_uv_filtered(Point2 uv, Point2 duvdx, Point2 duvdy) const;

private:
    std::int64_t cell(Float v) const {
        const Float f = std::floor(v * (1 / size));
        // Past 2^62 (or infinite or NaN, from an absurdly small size) the cell index is
        // meaningless and converting it would be undefined behaviour: use cell 0.
        return std::abs(f) < 0x1p62f ? static_cast<std::int64_t>(f) : std::int64_t{0};
    }
    /// (even + odd) / 2 + (even - odd) / 2 times the product over `n` axes of the square wave's
    /// mean over [x - h, x + h] (x in cells); none without a footprint or where a coordinate is
    /// out of range (the caller reads the point).
    std::optional<Color> box_mean(const double* x, const double* h, int n) const;
};

/// An image over uv, covering `size` x `size` units of uv space, after an optional affine map
/// of uv (glTF's KHR_texture_transform): uv' = (m0 u + m1 v + m2, m3 u + m4 v + m5).
struct ImageTexture {
    ImageId image;
    WrapMode wrap = WrapMode::kRepeat;  ///< along u (and v, unless wrap_v says otherwise)
    Float size = 1;
    WrapMode wrap_v = WrapMode::kRepeat;
    std::array<Float, 6> uv_transform{1, 0, 0, 0, 1, 0};
    std::uint8_t uv_set = 0;  ///< which texture coordinate set (glTF texCoord)
    bool alpha = false;       ///< the alpha channel (as grey) instead of the colour
    TextureFilter filter = TextureFilter::kEwa;  ///< over the footprint of set 0's uv; others: bilinear
    bool filtered() const { return filter != TextureFilter::kBilinear && uv_set == 0 && !alpha; }
};

/// texture * factor, per channel.
struct ScaleTexture {
    TextureId texture, factor;
};

/// (1 - amount) a + amount b, per channel.
struct MixTexture {
    TextureId a, b, amount;
};

/// The mesh's interpolated per-vertex colour (PLY red/green/blue); 1 on everything else.
/// `alpha`: the per-vertex alpha (as grey) instead.
struct VertexColorTexture {
    bool alpha = false;
};

using Texture = std::variant<ConstantTexture, CheckerTexture, ImageTexture, ScaleTexture, MixTexture,
                             VertexColorTexture>;

/// The colour of texture `id` at `ctx`.
Color evaluate(const std::vector<Texture>& textures, const std::vector<Image>& images, TextureId id,
               const TextureContext& ctx);

}  // namespace glint
