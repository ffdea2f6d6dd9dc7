#pragma once
// Progress reporting for a render. On a terminal: a bar with percent, Mrays/s and ETA, redrawn at
// most a few times a second by whichever worker finishes a tile (a try-lock, never a wait).
// Otherwise: one summary line at the end. Quiet: nothing.
#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdio>

namespace glint {

enum class ProgressMode { kBar, kSummary, kQuiet };

struct RenderStats {
    double seconds = 0;
    std::uint64_t rays = 0;
    std::uint64_t samples = 0;
    double mrays_per_second() const { return seconds > 0 ? rays / seconds * 1e-6 : 0; }
};

class Progress {
public:
    Progress(ProgressMode mode, std::FILE* out, std::uint64_t total_pixels);
    /// Called by workers as tiles finish.
    void tile_done(std::uint64_t pixels, std::uint64_t rays);
    /// Called once, on the calling thread, after the render.
    void finish(const RenderStats& stats, int width, int height, int spp);

private:
    void draw(std::uint64_t pixels, std::uint64_t rays, double elapsed);
    ProgressMode mode_;
    std::FILE* out_;
    std::uint64_t total_;
    std::chrono::steady_clock::time_point start_;
    std::atomic<std::uint64_t> pixels_{0};
    std::atomic<std::uint64_t> rays_{0};
    std::atomic<std::int64_t> last_draw_ns_{0};
    std::atomic_flag drawing_ = ATOMIC_FLAG_INIT;
};

}  // namespace glint
