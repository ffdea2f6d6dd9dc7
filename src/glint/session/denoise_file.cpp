// `glint denoise`: an EXR's channels through the denoiser (denoise/denoise.h) and back out.
#include <fmt/core.h>

#include <algorithm>
#include <array>
#include <stdexcept>

#include "glint/base/errors.h"
#include "glint/base/limits.h"
#include "glint/denoise/denoise.h"
#include "glint/film/film.h"
#include "glint/image/image_io.h"
#include "glint/session/session.h"

namespace glint {

namespace {

// The channels read, in groups of three (Z alone): a group is used only when whole.
const std::vector<std::string> kChannels = {"R", "G", "B", "even.R", "even.G", "even.B", "odd.R", "odd.G",
                                            "odd.B", "albedo.R", "albedo.G", "albedo.B", "N.X", "N.Y", "N.Z", "Z",
                                            "albedo.even.R", "albedo.even.G", "albedo.even.B", "albedo.odd.R",
                                            "albedo.odd.G", "albedo.odd.B"};

}  // namespace

double denoise_file(const std::filesystem::path& in, const std::filesystem::path& out, int threads, int radius) {
    if (image_format_for(in) != ImageFormat::kExr)
        throw IoError(fmt::format("{}: glint denoise reads OpenEXR files (.exr) with the half images "
                                  "even.R/G/B and odd.R/G/B, as `glint render --aovs` writes them",
                                  in.string()));
    check_writable(out);
    std::error_code ec;
    if (std::filesystem::exists(out, ec) && std::filesystem::equivalent(in, out, ec))
        throw IoError(fmt::format("{}: the output would replace the input; name another file with -o", out.string()));
    ExrChannels c = read_exr_channels(in, kChannels, limit(Limit::kFilmPixels));
    for (std::size_t i = 0; i < 9; ++i) {
        if (c.planes[i].empty()) {
            throw IoError(fmt::format("{}: no channel {}: denoising needs R, G, B and the half images even.R/G/B "
                                      "and odd.R/G/B (`glint render --aovs` or `--denoise` writes them)",
                                      in.string(), kChannels[i]));
        }
    }
    const auto whole = [&](std::size_t first, std::size_t count) {
        for (std::size_t i = first; i < first + count; ++i)
            if (c.planes[i].empty()) return false;
        return true;
    };
    const bool albedo = whole(9, 3), normal = whole(12, 3), depth = whole(15, 1);
    const bool albedo_halves = albedo && whole(16, 6);
    const int w = c.width, h = c.height;
    Film film(w, h);
    film.enable_aovs();
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const std::size_t i = static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x);
            const auto rgb = [&](std::size_t first) {
                return Color{c.planes[first][i], c.planes[first + 1][i], c.planes[first + 2][i]};
            };
            film.at(x, y) = rgb(0);
            film.even(x, y) = rgb(3);
            film.odd(x, y) = rgb(6);
            if (albedo) film.albedo(x, y) = rgb(9);
            if (normal) film.normal(x, y) = Normal3{c.planes[12][i], c.planes[13][i], c.planes[14][i]};
            film.depth(x, y) = depth ? c.planes[15][i] : 0.0f;
            if (albedo_halves) film.even_albedo(x, y) = rgb(16), film.odd_albedo(x, y) = rgb(19);
        }
    }
    c = {};  // the film holds it now
    const DenoiseInput input{w,
                             h,
                             film.pixels().data(),
                             film.even().data(),
                             film.odd().data(),
                             albedo ? film.albedo().data() : nullptr,
                             normal ? film.normal().data() : nullptr,
                             depth ? film.depth().data() : nullptr,
                             albedo_halves ? film.even_albedo().data() : nullptr,
                             albedo_halves ? film.odd_albedo().data() : nullptr};
    DenoiseStats stats;
    std::vector<Color> result;
    try {
        result = denoise(input, {radius, threads}, &stats);
    } catch (const std::invalid_argument& e) {
        throw IoError(fmt::format("{}: {}", in.string(), e.what()));
    }
    BigVector<Color> noisy(film.pixels().begin(), film.pixels().end());
    std::copy(result.begin(), result.end(), film.pixels().begin());
    film.keep_noisy(std::move(noisy));
    write_image(out, film, DisplaySettings{}, {{"glint:denoised", "1"}, {"glint:denoised_from", in.filename().string()}});
    return stats.seconds;
}

}  // namespace glint
