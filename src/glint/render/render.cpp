#include "glint/render/render.h"

#include <tbb/blocked_range.h>
#include <tbb/blocked_range2d.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <functional>

#include "glint/render/progressive.h"
#include "glint/samplers/sampler.h"

namespace glint {

namespace {

// One sample through each pixel centre, over 16x16 tiles in parallel; store(col, row, colours, n)
// receives the colours of n pixels of a row from (col, row) on, scaled, each once.
// With rows_done, the work is split into bands of whole rows instead of tiles, and
// rows_done(y0, y1) is called once each band is stored.
template <typename Store>
RenderStats sweep(const Scene& scene, const Camera& camera, const Integrator& integrator,
                  const RenderOptions& options, int w, int h, Progress* progress,
                  const std::atomic<bool>* cancel, Store&& store,
                  const std::function<void(int, int)>& rows_done = {}) {
    const auto start = std::chrono::steady_clock::now();
    const int tile = std::max(1, options.tile_size);
    std::atomic<std::uint64_t> total_rays{0};
    std::atomic<bool> skipped{false};
    // Film pixel (col, row) is pixel (col + ox, row + oy) of the camera's frame (a crop).
    const int ox = options.offset_x, oy = options.offset_y;
    // (Packets trace still scenes only; with motion each ray goes alone, at the shutter's middle.)
    const bool packets = integrator.traces_packets() && options.packets && !scene.has_motion() && !camera.moves();
    auto render_tile = [&](const tbb::blocked_range2d<int>& r) {
        if (cancel && cancel->load(std::memory_order_relaxed)) {
            skipped.store(true, std::memory_order_relaxed);
            return;
        }
        RayCounter counter;
        Ray rays[Scene::kPacketSize];
        Color colors[Scene::kPacketSize];
        const int width = packets ? Scene::kPacketSize : 1;
        for (int row = r.rows().begin(); row < r.rows().end(); ++row) {
            for (int col0 = r.cols().begin(); col0 < r.cols().end(); col0 += width) {
                const int n = std::min(width, r.cols().end() - col0);
                if (packets) {
                    // Up to 16 pixels of a row as one packet: the camera rays, then each
                    // bounce's rays, go to the scene together (the colours are li's to the bit).
                    for (int k = 0; k < n; ++k)
                        rays[k] = camera.generate_ray(static_cast<float>(col0 + k + ox) + 0.5f,
                                                      static_cast<float>(row + oy) + 0.5f, {0.5f, 0.5f});
                    integrator.li_packet(scene, rays, n, colors, counter);
                } else {
                    const PixelSampler sampler(options.sampler, 1,
                                               pixel_seed(options.seed, static_cast<std::uint32_t>(col0 + ox),
                                                          static_cast<std::uint32_t>(row + oy)));
                    SampleStream samples(sampler, 0);
                    const Ray ray = camera.at_time(camera.generate_ray(static_cast<float>(col0 + ox) + 0.5f,
                                                                       static_cast<float>(row + oy) + 0.5f, {0.5f, 0.5f}),
                                                   0.5f);
                    colors[0] = integrator.li(scene, ray, samples, counter);
                }
                if (options.scale != 1)
                    for (int k = 0; k < n; ++k) colors[k] = colors[k] * options.scale;
                store(col0, row, colors, n);
            }
        }
        total_rays.fetch_add(counter.rays, std::memory_order_relaxed);
        if (progress) {
            progress->tile_done(static_cast<std::uint64_t>(r.rows().size()) * r.cols().size(),
                                counter.rays);
        }
    };

    const int threads = options.threads > 0 ? options.threads : tbb::this_task_arena::max_concurrency();
    tbb::task_arena arena(threads);
    arena.execute([&] {
        if (!rows_done) {
            tbb::parallel_for(tbb::blocked_range2d<int>(0, h, tile, 0, w, tile), render_tile,
                              tbb::simple_partitioner());
            return;
        }
        // Bands of about 64 tiles' pixels (at least one row), tiled across in the same way.
        const int band = std::clamp(tile * tile * 64 / std::max(1, w), 1, h);
        tbb::parallel_for(tbb::blocked_range<int>(0, h, band), [&](const tbb::blocked_range<int>& rows) {
            render_tile(tbb::blocked_range2d<int>(rows.begin(), rows.end(), band, 0, w, w));
            if (!(cancel && cancel->load(std::memory_order_relaxed))) rows_done(rows.begin(), rows.end());
        }, tbb::simple_partitioner());
    });

    RenderStats stats;
    stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    stats.rays = total_rays.load();
    stats.complete = !skipped.load();
    stats.samples = stats.complete ? static_cast<std::uint64_t>(w) * static_cast<std::uint64_t>(h) : 0;
    return stats;
}

}  // namespace

RenderStats render(const Scene& scene, const Camera& camera, const Integrator& integrator,
                   const RenderOptions& options, Film& film, Progress* progress,
                   const std::atomic<bool>* cancel) {
    const auto start = std::chrono::steady_clock::now();
    const int w = film.width(), h = film.height();
    const int spp = std::max(1, options.spp);
    RenderStats stats;
    if (spp > 1 || film.has_aovs()) {
        ProgressiveRender r(scene, camera, integrator, options, w, h, film.has_aovs());
        // Uniform: one pass (nothing to show or save between passes here, and any split gives
        // these bits); adaptive sampling keeps its schedule.
        while (stats.complete && !r.finished()) {
            const int n = r.adaptive() ? r.next_pass_size() : r.spp_target();
            if (!r.run_pass(n, cancel, progress)) stats.complete = false;
        }
        r.resolve(film);
        stats.rays = r.state().rays;
        stats.samples = r.samples_taken();
        stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        return stats;
    }

    // The article's case, one sample through each pixel centre, kept minimal: the film is
    // written directly, with no sums.
    return sweep(scene, camera, integrator, options, w, h, progress, cancel,
                 [&](int col, int row, const Color* colors, int n) {
                     std::copy_n(colors, n, &film.at(col, row));
                 });
}

RenderStats render_8bit(const Scene& scene, const Camera& camera, const Integrator& integrator,
                        const RenderOptions& options, const DisplaySettings& display, int width,
                        int height, std::uint8_t* rgb, Progress* progress, const std::atomic<bool>* cancel,
                        const std::function<void(int, int)>& rows_done) {
    static_assert(sizeof(Color) == 3 * sizeof(float));
    return sweep(scene, camera, integrator, options, width, height, progress, cancel,
                 [&](int col, int row, const Color* colors, int n) {
                     const std::size_t at = (static_cast<std::size_t>(row) * static_cast<std::size_t>(width) +
                                             static_cast<std::size_t>(col)) * 3;
                     encode_8bit(&colors->r, static_cast<std::size_t>(n) * 3, rgb + at, display);
                 },
                 rows_done);
}

}  // namespace glint
