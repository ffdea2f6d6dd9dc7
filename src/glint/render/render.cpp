#include "glint/render/render.h"

#include <tbb/blocked_range2d.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <limits>

#include "glint/samplers/sampler.h"

namespace glint {

RenderStats render(const Scene& scene, const Camera& camera, const Integrator& integrator,
                   const RenderOptions& options, Film& film, Progress* progress) {
    const auto start = std::chrono::steady_clock::now();
    const int w = film.width(), h = film.height();
    const int spp = std::max(1, options.spp);
    const int tile = std::max(1, options.tile_size);
    const FilterSampler filter(options.filter);
    const bool aovs = film.has_aovs();
    std::atomic<std::uint64_t> total_rays{0};

    // The single-sample ray: the pixel centre, through the lens centre.
    // Film pixel (col, row) is pixel (col + ox, row + oy) of the camera's frame (a crop).
    const int ox = options.offset_x, oy = options.offset_y;
    const auto centre_ray = [&camera, ox, oy](int col, int row) {
        return camera.generate_ray(static_cast<float>(col + ox) + 0.5f,
                                   static_cast<float>(row + oy) + 0.5f, {0.5f, 0.5f});
    };

    auto render_tile = [&](const tbb::blocked_range2d<int>& r) {
        RayCounter counter;
        const auto seed_of = [&options, ox, oy](int col, int row) {
            return pixel_seed(options.seed, static_cast<std::uint32_t>(col + ox),
                              static_cast<std::uint32_t>(row + oy));
        };
        for (int row = r.rows().begin(); row < r.rows().end(); ++row) {
            for (int col = r.cols().begin(); col < r.cols().end(); ++col) {
                if (spp == 1 && !aovs) {  // the article's case, kept minimal
                    const PixelSampler sampler(options.sampler, 1, seed_of(col, row));
                    SampleStream samples(sampler, 0);
                    film.at(col, row) = integrator.li(scene, centre_ray(col, row), samples, counter);
                    if (options.scale != 1) film.at(col, row) = film.at(col, row) * options.scale;
                    continue;
                }
                Color sum{0};
                // AOVs, filter-weighted like the colour; depth averages the samples that hit.
                FirstHit first;
                FirstHit* const want = aovs ? &first : nullptr;
                Color albedo{0};
                Vector3 normal{0, 0, 0};
                float depth = 0, hit_weight = 0;
                auto add_aovs = [&](float weight) {
                    albedo += first.albedo * weight;
                    normal += to_vector(first.normal) * weight;
                    if (first.hit) depth += first.depth * weight, hit_weight += weight;
                };
                float weight_sum = 1;
                if (spp == 1) {
                    const PixelSampler sampler(options.sampler, 1, seed_of(col, row));
                    SampleStream samples(sampler, 0);
                    sum = integrator.li(scene, centre_ray(col, row), samples, counter, want);
                    if (aovs) add_aovs(1);
                } else {
                    // Dimension pair 0 places the sample in the pixel (through the filter), pair 1
                    // on the lens; later pairs are the integrator's.
                    const PixelSampler sampler(options.sampler, static_cast<std::uint32_t>(spp),
                                               seed_of(col, row));
                    weight_sum = 0;
                    for (int i = 0; i < spp; ++i) {
                        const auto index = static_cast<std::uint32_t>(i);
                        const FilterSampler::Sample f = filter.sample(sampler.get_2d(index, 0));
                        const Sample2 lens = sampler.get_2d(index, 1);
                        const Ray ray =
                            camera.generate_ray(static_cast<float>(col + ox) + 0.5f + f.dx,
                                                static_cast<float>(row + oy) + 0.5f + f.dy, lens);
                        SampleStream samples(sampler, index);
                        sum += integrator.li(scene, ray, samples, counter, want) * f.weight;
                        if (aovs) add_aovs(f.weight);
                        weight_sum += f.weight;
                    }
                    sum = weight_sum > 0 ? sum / weight_sum : Color{0};
                }
                film.at(col, row) = options.scale != 1 ? sum * options.scale : sum;
                if (aovs) {
                    const float inv = weight_sum > 0 ? 1 / weight_sum : 0;
                    film.albedo(col, row) = albedo * inv;
                    film.normal(col, row) = Normal3(normal * inv);
                    film.depth(col, row) = hit_weight > 0 ? depth / hit_weight
                                                          : std::numeric_limits<float>::infinity();
                }
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

    RenderStats stats;
    stats.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    stats.rays = total_rays.load();
    stats.samples = static_cast<std::uint64_t>(w) * static_cast<std::uint64_t>(h) *
                    static_cast<std::uint64_t>(spp);
    return stats;
}

}  // namespace glint
