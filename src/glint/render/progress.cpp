#include "glint/render/progress.h"

#include <fmt/core.h>

#include <string>

namespace glint {

Progress::Progress(ProgressMode mode, std::FILE* out, std::uint64_t total_pixels)
    : mode_(mode), out_(out), total_(total_pixels), start_(std::chrono::steady_clock::now()) {}

void Progress::tile_done(std::uint64_t pixels, std::uint64_t rays) {
    const std::uint64_t p = pixels_.fetch_add(pixels, std::memory_order_relaxed) + pixels;
    const std::uint64_t r = rays_.fetch_add(rays, std::memory_order_relaxed) + rays;
    if (mode_ != ProgressMode::kBar) return;
    const auto now_ns = std::chrono::duration_cast<std::chrono::nanoseconds>(
                            std::chrono::steady_clock::now() - start_)
                            .count();
    if (now_ns - last_draw_ns_.load(std::memory_order_relaxed) < 200'000'000 && p < total_) return;
    if (drawing_.test_and_set(std::memory_order_acquire)) return;  // someone else is drawing
    last_draw_ns_.store(now_ns, std::memory_order_relaxed);
    draw(p, r, static_cast<double>(now_ns) * 1e-9);
    drawing_.clear(std::memory_order_release);
}

void Progress::draw(std::uint64_t pixels, std::uint64_t rays, double elapsed) {
    constexpr int kWidth = 30;
    const double fraction = total_ ? static_cast<double>(pixels) / static_cast<double>(total_) : 1;
    const int filled = static_cast<int>(fraction * kWidth);
    const double mrays = elapsed > 0 ? static_cast<double>(rays) / elapsed * 1e-6 : 0;
    const double eta = fraction > 0 ? elapsed * (1 - fraction) / fraction : 0;
    fmt::print(out_, "\r[{}{}] {:5.1f}%  {:7.2f} Mrays/s  ETA {:5.1f} s ",
               std::string(static_cast<std::size_t>(filled), '#'),
               std::string(static_cast<std::size_t>(kWidth - filled), '.'), fraction * 100, mrays,
               eta);
    std::fflush(out_);
}

void Progress::finish(const RenderStats& stats, int width, int height, int spp) {
    if (mode_ == ProgressMode::kQuiet) return;
    if (mode_ == ProgressMode::kBar) {
        draw(total_, stats.rays, stats.seconds);
        fmt::print(out_, "\n");
    }
    fmt::print(out_, "rendered {}x{} at {} spp in {:.3f} s: {} rays, {:.2f} Mrays/s\n", width,
               height, spp, stats.seconds, stats.rays, stats.mrays_per_second());
    std::fflush(out_);
}

}  // namespace glint
