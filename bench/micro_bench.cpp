// Micro-benchmarks: the ray-shape tests, camera rays, and the Whitted integrator on Figure 14.
// Run: build/bench/glint_bench [--benchmark_repetitions=5 --benchmark_report_aggregates_only]
#include <benchmark/benchmark.h>

#include <bit>
#include <cstdio>
#include <vector>

#include "glint/builder/build.h"
#include "glint/formats/pbrt.h"
#include "glint/formats/scene_yaml.h"
#include "glint/render/render.h"
#include "glint/samplers/hash.h"
#include "glint/samplers/sampler.h"

namespace glint {
namespace {

std::vector<Ray> random_rays(std::size_t n, Point3 origin) {
    std::vector<Ray> rays;
    for (std::uint32_t i = 0; i < n; ++i) {
        const Vector3 d{to_unit_float(mix32(3 * i)) - 0.5f, to_unit_float(mix32(3 * i + 1)) - 0.5f,
                        1};
        rays.push_back(Ray{origin, normalize(d)});
    }
    return rays;
}

// The Sobol sampler's pairs, a new pixel each call (as a pixel's first call pays). Arg 0:
// get_2d_x8 (eight pairs); 1: get_2d_batch (sixteen where the CPU has AVX-512). Chained: each
// call's pixel depends on the last call's result, as a path's draws do, so a call's latency is
// measured; independent: each pixel known in advance, so that calls overlap: their throughput.
// ns per call, and pairs per call.
void sobol_pairs_per_pixel(benchmark::State& state, bool chained) {
    const bool batch = state.range(0) == 1;
    Sample2 out[16];
    std::uint32_t pixel = 1, index = 0;
    int pairs = 0;
    for (auto _ : state) {
        const PixelSampler s(SamplerType::kSobol, 64, pixel_seed(1, pixel, 7));
        pairs += batch ? s.get_2d_batch(index++ & 63, 2, out) : (s.get_2d_x8(index++ & 63, 2, out), 8);
        pixel = chained ? std::bit_cast<std::uint32_t>(out[7].y) & 1023u : (pixel + 1) & 1023u;
        benchmark::DoNotOptimize(out);
    }
    state.counters["pairs/call"] = static_cast<double>(pairs) / static_cast<double>(state.iterations());
}
void BM_SobolPairsChained(benchmark::State& state) { sobol_pairs_per_pixel(state, true); }
BENCHMARK(BM_SobolPairsChained)->Arg(0)->Arg(1);
void BM_SobolPairsIndependent(benchmark::State& state) { sobol_pairs_per_pixel(state, false); }
BENCHMARK(BM_SobolPairsIndependent)->Arg(0)->Arg(1);

// As a pixel's samples draw them: one sampler for all 64 samples of a pixel (with AVX-512 the
// pixel's kept keys serve its later samples). Arg 1: each call's sample chained to the last
// call's result (latency); 0: not (throughput). ns per 64 calls.
void BM_SobolPairsInPixel(benchmark::State& state) {
    const bool chained = state.range(0) == 1;
    Sample2 out[16];
    std::uint32_t chain = 1, pixel = 0;
    int pairs = 0;
    for (auto _ : state) {
        state.PauseTiming();
        const PixelSampler s(SamplerType::kSobol, 64, pixel_seed(1, pixel++ & 1023u, 7));
        state.ResumeTiming();
        for (std::uint32_t index = 0; index < 64; ++index) {
            pairs += s.get_2d_batch((index + chain) & 63, 2, out);
            if (chained) chain = std::bit_cast<std::uint32_t>(out[7].y) & 1u;
            benchmark::DoNotOptimize(out);
        }
    }
    state.counters["pairs/call"] = static_cast<double>(pairs) / static_cast<double>(state.iterations() * 64);
}
BENCHMARK(BM_SobolPairsInPixel)->Arg(1)->Arg(0);

void BM_SphereIntersect(benchmark::State& state) {
    const Sphere s{{0, 0, 4}, 1};
    const auto rays = random_rays(4096, {0, 0, 0});  // about a third hit
    std::size_t i = 0;
    for (auto _ : state) {
        benchmark::DoNotOptimize(s.intersect(rays[i++ & 4095]));
    }
    state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_SphereIntersect);

void BM_PlaneIntersect(benchmark::State& state) {
    const Plane p{{0, -1, 0}, {0, 1, 0}};
    const auto rays = random_rays(4096, {0, 0, 0});
    std::size_t i = 0;
    for (auto _ : state) {
        benchmark::DoNotOptimize(p.intersect(rays[i++ & 4095]));
    }
    state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_PlaneIntersect);

RenderJob fig14(int w, int h) {
    auto sources = std::make_shared<SourceFiles>();
    Overrides o;
    o.width = w;
    o.height = h;
    return build(load_scene_file(std::string(GLINT_SOURCE_DIR) +
                                     "/scenes/seed/fig14-reflections.yaml",
                                 sources),
                 o, sources);
}

void BM_CameraRay(benchmark::State& state) {
    const RenderJob job = fig14(1920, 1080);
    float x = 0;
    for (auto _ : state) {
        benchmark::DoNotOptimize(job.camera.generate_ray(x, 540.5f));
        x = x > 1919 ? 0 : x + 1;
    }
    state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_CameraRay);

void BM_SceneIntersectFig14(benchmark::State& state) {
    const RenderJob job = fig14(1920, 1080);
    std::vector<Ray> rays;
    for (int row = 0; row < 1080; row += 8)
        for (int col = 0; col < 1920; col += 8) rays.push_back(job.camera.generate_ray(col + 0.5f, row + 0.5f));
    std::size_t i = 0;
    for (auto _ : state) {
        benchmark::DoNotOptimize(job.scene.intersect(rays[i]));
        i = i + 1 == rays.size() ? 0 : i + 1;
    }
    state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_SceneIntersectFig14);

// The whole Whitted render of Figure 14 at 480x270, 1 spp, on one thread; counters give rays/s.
void BM_WhittedFig14(benchmark::State& state) {
    const RenderJob job = fig14(480, 270);
    Film film(job.width, job.height);
    RenderOptions o = job.options;
    o.threads = 1;
    std::uint64_t rays = 0;
    for (auto _ : state) {
        rays += render(job.scene, job.camera, *job.integrator, o, film).rays;
    }
    state.counters["rays/s"] = benchmark::Counter(static_cast<double>(rays), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_WhittedFig14)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace glint


// The pbrt-v4 parser on a generated trianglemesh of 2^17 triangles (a 513 x 129 vertex grid,
// coordinates with six digits, as exporters write them): parse only, no build. Reports MB/s.
void BM_PbrtParseTriangleMesh(benchmark::State& state) {
    std::string text = "WorldBegin\nShape \"trianglemesh\"\n  \"point3 P\" [\n";
    const int nx = 513, ny = 129;
    char buf[96];
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
            std::snprintf(buf, sizeof buf, "  %.6f %.6f %.6f\n", i * 0.013579, j * 0.024681, 0.001 * ((i * 7 + j * 13) % 97));
            text += buf;
        }
    text += "  ]\n  \"integer indices\" [\n";
    for (int j = 0; j + 1 < ny; ++j)
        for (int i = 0; i + 1 < nx; ++i) {
            const int a = j * nx + i, b = a + 1, c = a + nx, d = c + 1;
            std::snprintf(buf, sizeof buf, "  %d %d %d %d %d %d\n", a, b, d, a, d, c);
            text += buf;
        }
    text += "  ]\n";
    for (auto _ : state) {
        auto d = glint::parse_pbrt(text, "mesh.pbrt", std::make_shared<glint::SourceFiles>());
        benchmark::DoNotOptimize(d);
    }
    state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations()) * static_cast<std::int64_t>(text.size()));
    state.counters["MB"] = double(text.size()) / 1e6;
}
BENCHMARK(BM_PbrtParseTriangleMesh)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
