#include "glint/render/progress.h"

#include <fmt/core.h>

#include <algorithm>
#include <string>

namespace glint {

Progress::Progress(ProgressMode mode, std::FILE* out, std::uint64_t total)
    : mode_(mode), out_(out), total_(total), start_(std::chrono::steady_clock::now()) {}

void Progress::pass_started(const PassInfo& info) {
    if (pass_.pass == 0) samples_at_start_ = samples_.load(std::memory_order_relaxed);
    pass_ = info;
    total_.store(samples_.load(std::memory_order_relaxed) + info.remaining, std::memory_order_relaxed);
    pass_start_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

void Progress::tile_done(std::uint64_t samples, std::uint64_t rays) {
    const std::uint64_t s = samples_.fetch_add(samples, std::memory_order_relaxed) + samples;
    const std::uint64_t r = rays_.fetch_add(rays, std::memory_order_relaxed) + rays;
    if (mode_ != ProgressMode::kBar) return;
    const auto now_ns = std::chrono::duration_cast<std::chrono::nanoseconds>(
                            std::chrono::steady_clock::now() - start_)
                            .count();
    if (now_ns - last_draw_ns_.load(std::memory_order_relaxed) < 200'000'000 &&
        s < total_.load(std::memory_order_relaxed))
        return;
    if (drawing_.test_and_set(std::memory_order_acquire)) return;  // someone else is drawing
    last_draw_ns_.store(now_ns, std::memory_order_relaxed);
    draw(s, r, static_cast<double>(now_ns) * 1e-9);
    drawing_.clear(std::memory_order_release);
}

namespace {
std::string clock(double seconds) {
    const long long s = seconds > 0 ? static_cast<long long>(seconds + 0.5) : 0;
    if (s >= 3600) return fmt::format("{}:{:02}:{:02}", s / 3600, s / 60 % 60, s % 60);
    return fmt::format("{}:{:02}", s / 60, s % 60);
}
}  // namespace

void Progress::draw(std::uint64_t samples, std::uint64_t rays, double elapsed) {
    constexpr int kWidth = 24;
    const std::uint64_t total = total_.load(std::memory_order_relaxed);
    const double fraction = total ? static_cast<double>(samples) / static_cast<double>(total) : 1;
    const int filled = static_cast<int>(std::min(1.0, fraction) * kWidth);
    const double mrays = elapsed > 0 ? static_cast<double>(rays) / elapsed * 1e-6 : 0;
    // The rate of this run (a resumed render's earlier samples took no time here).
    const double done_here = static_cast<double>(samples - std::min(samples, samples_at_start_));
    const double eta = done_here > 0 ? elapsed * static_cast<double>(total - std::min(total, samples)) / done_here : 0;
    std::string line = fmt::format("\r[{}{}] {:5.1f}%", std::string(static_cast<std::size_t>(filled), '#'),
                                   std::string(static_cast<std::size_t>(kWidth - filled), '.'), fraction * 100);
    if (pass_.pass > 0) line += fmt::format("  pass {}  {}/{} spp", pass_.pass, pass_.spp_done, pass_.spp_target);
    if (pass_.converged >= 0) line += fmt::format("  {:.0f}% converged", pass_.converged * 100);
    line += fmt::format("  {:.2f} Mrays/s  ETA {}", mrays, clock(eta));
    if (pass_.budget_left >= 0)
        line += fmt::format("  budget left {}", clock(pass_.budget_left - (elapsed - pass_start_)));
    fmt::print(out_, "{} ", line);
    std::fflush(out_);
}

void Progress::finish(const RenderStats& stats, int width, int height, const std::string& what) {
    if (mode_ == ProgressMode::kQuiet) return;
    if (mode_ == ProgressMode::kBar) {
        if (stats.complete) total_.store(samples_.load());  // converged or budget reached: done
        draw(samples_.load(), rays_.load(), stats.seconds);
        fmt::print(out_, "\n");
    }
    fmt::print(out_, "rendered {}x{} at {} in {:.3f} s: {} rays, {:.2f} Mrays/s\n", width, height, what,
               stats.seconds, stats.rays, stats.mrays_per_second());
    std::fflush(out_);
}

}  // namespace glint
