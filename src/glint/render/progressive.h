#pragma once
// Progressive rendering: the film's running sums, filled by sample passes.
//
// A pixel's estimate is the filter-weighted sum of its samples divided by the sum of the weights,
// both accumulated in float in sample-index order. Sample i of a pixel is a pure function of
// (pixel, i), so continuing the sums pass after pass gives exactly the floats one pass would:
// any split of the samples into passes, on any thread count, interrupted and resumed from a
// checkpoint or not, yields the same bits.
//
// A pass is atomic: it reads the state of the previous pass and writes a second buffer, which
// becomes the state only when every pixel of the pass is done. A cancelled pass leaves the state
// as it was (the film of the completed passes).
//
// Adaptive sampling (noise_threshold > 0) follows Cycles: a second sum over the odd-numbered
// samples gives a per-pixel error estimate; a pixel stops when it falls below the threshold, and
// pixels next to one still noisy keep sampling. Decisions are taken at pass boundaries on a
// fixed schedule of passes, so they too are the same however the run was cut.
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "glint/cameras/camera.h"
#include "glint/film/film.h"
#include "glint/film/filter.h"
#include "glint/integrators/integrator.h"
#include "glint/render/progress.h"
#include "glint/render/render.h"
#include "glint/scene.h"

namespace glint {

/// Everything a checkpoint holds: the sums of every pixel after `spp_done` samples.
struct ProgressiveState {
    int width = 0, height = 0;
    int spp_target = 0;   ///< the samples a pixel gets at most (the sample pattern depends on it)
    int spp_done = 0;     ///< samples per pixel reached (the maximum, with adaptive sampling)
    int passes = 0;
    bool adaptive = false, aovs = false;
    double seconds = 0;   ///< rendering time spent on the completed passes
    std::uint64_t rays = 0;
    std::vector<Color> sum;
    std::vector<float> weight;
    // Adaptive sampling and AOVs (the denoiser's two half images): the odd-numbered samples.
    std::vector<Color> odd_sum;
    std::vector<float> odd_weight;
    // Adaptive sampling only.
    std::vector<std::uint32_t> samples;  ///< per pixel
    std::vector<std::uint8_t> active;    ///< 1: still sampling
    // AOVs only: filter-weighted albedo (all samples, and the odd-numbered ones: the denoiser's
    // estimate of how the albedo's noise goes with the colour's) and normal; depth over the
    // samples that hit.
    std::vector<Color> albedo, odd_albedo;
    std::vector<Vector3> normal;
    std::vector<float> depth, hit_weight;

    /// Whether the odd-numbered samples are summed apart (adaptive sampling's error estimate, the
    /// denoiser's noise estimate).
    bool halves() const { return adaptive || aovs; }
    std::size_t pixels() const {
        return static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    }
    /// Allocates every plane the flags call for, zeroed.
    void allocate();
    /// Throws std::runtime_error naming the first plane whose size does not match the flags.
    void check_shape() const;
};

/// The noise threshold Cycles uses internally for a user's `threshold` (it scales it by 5), and
/// the minimum samples it derives when none is given.
float adaptive_internal_threshold(float threshold);
int adaptive_default_min_spp(float threshold);

class ProgressiveRender {
public:
    ProgressiveRender(const Scene& scene, const Camera& camera, const Integrator& integrator,
                      const RenderOptions& options, int width, int height, bool aovs);

    /// Continues from a saved state (a checkpoint); throws std::runtime_error if it does not fit
    /// this render (size, spp, adaptive, AOVs).
    void restore(ProgressiveState state);
    const ProgressiveState& state() const { return state_; }

    int spp_target() const { return state_.spp_target; }
    int spp_done() const { return state_.spp_done; }
    int passes() const { return state_.passes; }
    bool adaptive() const { return state_.adaptive; }
    int min_spp() const { return min_spp_; }
    /// Every pixel has its samples, or (adaptive) every pixel has converged.
    bool finished() const;
    /// The share of pixels that stopped sampling (adaptive; 0 otherwise).
    double converged_fraction() const;
    /// Pixel samples taken so far, all pixels together.
    std::uint64_t samples_taken() const;
    /// Pixel samples still to take at most: pixels still sampling x samples they lack.
    std::uint64_t remaining_samples() const;

    /// The samples per pixel of the next pass. Adaptive sampling has a fixed schedule (doubling
    /// up to the minimum spp, then steps of 16); otherwise passes double while they are short,
    /// kept to about max(2 s, 10 % of the time so far). Given a time budget left, a pass predicted
    /// not to fit is shortened (uniform) or refused (adaptive, or not even one sample fits): 0.
    int next_pass_size(double seconds_left = -1) const;

    /// Runs `n` more samples for every pixel still sampling (adaptive: n must be
    /// next_pass_size()). Returns false, the state unchanged, if `cancel` became true before
    /// every tile had started.
    bool run_pass(int n, const std::atomic<bool>* cancel = nullptr, Progress* progress = nullptr);

    /// The image of the completed passes (and the AOVs and, if the film wants them, the per-pixel
    /// sample counts).
    void resolve(Film& film) const;

    // A pass in pieces, for spreading one over processes (distributed.h); run_pass is
    // begin_pass, render_tile for every tile, end_pass. Any split of the tiles gives the same state.

    /// The pass's tiles: tile_size squares in rows, the last row and column cut short.
    int tile_count() const;
    /// Starts a pass of n samples (cut to what the target leaves) and returns n; the state is
    /// unchanged until end_pass.
    int begin_pass(int n);
    /// Renders tile t of the pass begun (thread-safe for distinct tiles); returns the pixel
    /// samples taken.
    std::uint64_t render_tile(int t, RayCounter& counter);
    /// Tile t's planes, every plane's pixels one plane after another, appended to `out`: its
    /// result in the pass begun, or (`before`) the state the pass starts from. unpack_tile puts
    /// such bytes from another process in place: a result instead of rendering the tile, or the
    /// sums a tile's pass continues. Throws std::runtime_error on the wrong size.
    void pack_tile(int t, std::vector<std::uint8_t>& out, bool before = false) const;
    void unpack_tile(int t, const std::uint8_t* data, std::size_t size, bool before = false);
    std::size_t tile_bytes(int t) const;
    /// Makes the pass begun the state, with the time it took and what it traced.
    void end_pass(double seconds, std::uint64_t rays, std::uint64_t pixel_samples);
    /// What a pass starts from besides the tiles' sums (spp done, passes, time, rays), as bytes,
    /// and back. unpack_header throws std::runtime_error on bytes of another render (size, spp
    /// target, adaptive sampling or AOVs differ).
    std::vector<std::uint8_t> pack_header() const;
    void unpack_header(const std::uint8_t* data, std::size_t size);

private:
    struct TileRect {
        int x0, y0, x1, y1;
    };
    TileRect tile_rect(int t) const;
    int sample_pixel(std::size_t i, int col, int row, int n, RayCounter& counter);
    void update_convergence();

    const Scene& scene_;
    const Camera& camera_;
    /// Whether camera samples draw a time (something in the scene or the camera moves).
    bool moving_ = false;
    const Integrator& integrator_;
    RenderOptions options_;
    FilterSampler filter_;  ///< its tables are built once
    int min_spp_ = 0;
    float threshold_ = 0;  ///< Cycles' internal threshold
    ProgressiveState state_, next_;
    double seconds_per_sample_ = 0;  ///< measured: one pixel sample, the whole machine
    int pass_n_ = 0;                 ///< the samples of the pass begun
};

}  // namespace glint
