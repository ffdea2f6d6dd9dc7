#pragma once
// The parallel render loop: oneTBB over 16x16 tiles. Each pixel is computed entirely by one task
// from its own deterministic samples and summed in a fixed order, so the image is bit-identical
// for any thread count and any tile schedule.
#include <atomic>
#include <cstdint>
#include <functional>

#include "glint/cameras/camera.h"
#include "glint/film/film.h"
#include "glint/film/filter.h"
#include "glint/film/tonemap.h"
#include "glint/integrators/integrator.h"
#include "glint/render/progress.h"
#include "glint/samplers/sampler.h"
#include "glint/scene.h"

namespace glint {

struct RenderOptions {
    int threads = 0;  ///< 0: all cores
    int spp = 1;      ///< 1: the pixel centre; >1: stratified samples drawn through `filter`
    FilterDesc filter;
    SamplerType sampler = SamplerType::kSobol;
    std::uint64_t seed = 0;
    int tile_size = 16;
    /// A crop: the film is the part of the camera's frame whose top-left pixel is
    /// (offset_x, offset_y); each pixel gets exactly the rays and samples of the whole frame's.
    int offset_x = 0, offset_y = 0;
    /// Multiplies every pixel's radiance (pbrt's imaging ratio: exposure time x ISO / 100).
    float scale = 1;
    /// Adaptive sampling (progressive.h): a pixel stops when its relative error estimate falls
    /// below this (Cycles' noise threshold); 0: every pixel gets `spp` samples.
    float noise_threshold = 0;
    int min_spp = 0;  ///< adaptive: samples every pixel gets first (0: Cycles' default for the threshold)
    /// One sample per pixel with an integrator that draws no samples (Whitted): trace up to 16
    /// pixels of a row as one packet. The image is the same either way (tests compare the two).
    bool packets = true;
};

/// Renders every sample (passes of progressive.h, or one sweep for one sample without AOVs).
/// If `cancel` becomes true the render stops early: stats.complete is false and the film holds
/// nothing of use.
RenderStats render(const Scene& scene, const Camera& camera, const Integrator& integrator,
                   const RenderOptions& options, Film& film, Progress* progress = nullptr,
                   const std::atomic<bool>* cancel = nullptr);

/// The one-sample sweep of render() (spp 1, no AOVs) straight to 8-bit display codes, for PNG
/// and PPM output: rgb (width x height x 3 bytes, rows top first) receives encode_8bit of what
/// render() would put in the film, with no float film written and read in between. With
/// rows_done, the image is rendered in bands of whole rows, and rows_done(y0, y1) is called
/// (on the thread that rendered them) as each band is complete: for encoding while rendering.
RenderStats render_8bit(const Scene& scene, const Camera& camera, const Integrator& integrator,
                        const RenderOptions& options, const DisplaySettings& display, int width,
                        int height, std::uint8_t* rgb, Progress* progress = nullptr,
                        const std::atomic<bool>* cancel = nullptr,
                        const std::function<void(int, int)>& rows_done = {});

}  // namespace glint
