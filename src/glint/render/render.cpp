#include "glint/render/render.h"

#include <tbb/blocked_range2d.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>

#include "glint/render/progressive.h"
#include "glint/samplers/sampler.h"

namespace glint {

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
    const int tile = std::max(1, options.tile_size);
    std::atomic<std::uint64_t> total_rays{0};
    std::atomic<bool> skipped{false};
    // Film pixel (col, row) is pixel (col + ox, row + oy) of the camera's frame (a crop).
    const int ox = options.offset_x, oy = options.offset_y;
    auto render_tile = [&](const tbb::blocked_range2d<int>& r) {
        if (cancel && cancel->load(std::memory_order_relaxed)) {
            skipped.store(true, std::memory_order_relaxed);
            return;
        }
        RayCounter counter;
        for (int row = r.rows().begin(); row < r.rows().end(); ++row) {
            for (int col = r.cols().begin(); col < r.cols().end(); ++col) {
                const PixelSampler sampler(options.sampler, 1,
                                           pixel_seed(options.seed, static_cast<std::uint32_t>(col + ox),
                                                      static_cast<std::uint32_t>(row + oy)));
                SampleStream samples(sampler, 0);
                const Ray ray = camera.generate_ray(static_cast<float>(col + ox) + 0.5f,
                                                    static_cast<float>(row + oy) + 0.5f, {0.5f, 0.5f});
                film.at(col, row) = integrator.li(scene, ray, samples, counter);
                if (options.scale != 1) film.at(col, row) = film.at(col, row) * options.scale;
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
        tbb::parallel_for(tbb::blocked_range2d<int>(0, h, tile, 0, w, tile), render_tile,
                          tbb::simple_partitioner());
    });

    stats.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    stats.rays = total_rays.load();
    stats.complete = !skipped.load();
    stats.samples = stats.complete ? static_cast<std::uint64_t>(w) * static_cast<std::uint64_t>(h) : 0;
    return stats;
}

}  // namespace glint
