#pragma once
// Progress reporting for a render. On a terminal: a bar with percent, the pass, the spp reached,
// the share of converged pixels (adaptive sampling), Mrays/s, the ETA and the time budget left,
// redrawn at most a few times a second by whichever worker finishes a tile (a try-lock, never a
// wait). Otherwise: one summary line at the end. Quiet: nothing.
#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <string>

namespace glint {

enum class ProgressMode { kBar, kSummary, kQuiet };

struct RenderStats {
    double seconds = 0;
    std::uint64_t rays = 0;
    std::uint64_t samples = 0;
    bool complete = true;  ///< false: cancelled before the last sample
    double mrays_per_second() const { return seconds > 0 ? rays / seconds * 1e-6 : 0; }
};

/// What the bar says about the pass under way.
struct PassInfo {
    int pass = 0;             ///< 1-based
    int spp_done = 0;         ///< before this pass
    int spp_target = 0;
    double converged = -1;    ///< share of pixels converged; < 0: not adaptive
    double budget_left = -1;  ///< seconds of the time budget left; < 0: no budget
    /// Pixel samples still to take at most (adaptive: pixels still sampling x spp left); the bar's
    /// 100 % becomes the samples so far plus these.
    std::uint64_t remaining = 0;
};

class Progress {
public:
    /// `total` counts pixel samples: pixels x spp.
    Progress(ProgressMode mode, std::FILE* out, std::uint64_t total);
    /// Pixel samples already done when the render starts (a resumed render).
    void set_done(std::uint64_t samples) { samples_.store(samples, std::memory_order_relaxed); }
    /// Called on the calling thread before each pass.
    void pass_started(const PassInfo& info);
    /// Called by workers as tiles finish.
    void tile_done(std::uint64_t samples, std::uint64_t rays);
    /// Called once, on the calling thread, after the render: `what` says what was rendered
    /// ("64 spp", "32 of 64 spp (time budget reached)").
    void finish(const RenderStats& stats, int width, int height, const std::string& what);

private:
    void draw(std::uint64_t samples, std::uint64_t rays, double elapsed);
    ProgressMode mode_;
    std::FILE* out_;
    std::atomic<std::uint64_t> total_;
    std::chrono::steady_clock::time_point start_;
    std::atomic<std::uint64_t> samples_{0};
    std::atomic<std::uint64_t> rays_{0};
    std::atomic<std::int64_t> last_draw_ns_{0};
    std::atomic_flag drawing_ = ATOMIC_FLAG_INIT;
    std::uint64_t samples_at_start_ = 0;
    PassInfo pass_;        // written between passes only, read by the drawing worker
    double pass_start_ = 0;
};

}  // namespace glint
