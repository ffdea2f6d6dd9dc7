#include "glint/render/ray_bench.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <chrono>

#include "glint/math/frame.h"
#include "glint/samplers/hash.h"
#include "glint/samplers/warp.h"

namespace glint {

SceneInfo scene_info(const Scene& s) {
    SceneInfo i;
    i.meshes = s.meshes.size();
    i.instances = s.instances.size();
    i.analytic_shapes = s.spheres.size() + s.planes.size() + s.quads.size() + s.disks.size() + s.triangles.size();
    for (const TriangleMesh& m : s.meshes) {
        i.unique_triangles += m.triangle_count();
        i.vertices += m.positions.size();
        i.mesh_bytes += m.memory_bytes();
    }
    for (const Instance& inst : s.instances) i.triangles += s.meshes[inst.mesh].triangle_count();
    i.triangles += s.triangles.size();
    i.accel_bytes = s.accel_memory_bytes();
    for (const MeshBvh& b : s.mesh_bvhs()) {
        i.bvh_depth = std::max(i.bvh_depth, b.depth());
        i.bvh_references += b.references();
        i.bvh_width = b.width();
        i.bvh_isa = simd_isa_name(b.isa());
    }
    i.bounds = s.bounds();
    return i;
}

namespace {

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const std::size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

BenchRays bench_rays(const Scene& scene, const Camera& camera, int width, int height) {
    BenchRays rays;
    rays.primary.reserve(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) rays.primary.push_back(camera.generate_ray(x + 0.5f, y + 0.5f));
    for (std::size_t i = 0; i < rays.primary.size(); ++i) {
        const Ray& r = rays.primary[i];
        const auto hit = scene.intersect(r);
        if (!hit) continue;
        const SurfaceInteraction si = scene.interaction(r, *hit);
        const Normal3 nf = face_forward(si.n, r.direction);
        Vector3 t, b;
        orthonormal_basis(to_vector(nf), t, b);
        const Sample2 u{to_unit_float(hash_combine(17, 2 * i)), to_unit_float(hash_combine(17, 2 * i + 1))};
        const Vector3 l = sample_cosine_hemisphere(u);
        rays.diffuse.push_back(spawn_ray(si.p, nf, t * l.x + b * l.y + to_vector(nf) * l.z));
    }
    return rays;
}

std::vector<BenchResult> bench_backends(Scene& scene, const std::vector<AccelKind>& accels, const BenchRays& rays,
                                        int threads, int runs) {
    runs = std::max(1, runs);
    tbb::task_arena arena(threads > 0 ? threads : tbb::this_task_arena::max_concurrency());
    const std::size_t n = accels.size();
    std::vector<BenchResult> results(n);
    std::vector<std::vector<double>> build(n), primary(n), diffuse(n);

    const auto trace = [&](const std::vector<Ray>& batch) {
        std::atomic<std::uint64_t> hits{0};
        const auto t0 = std::chrono::steady_clock::now();
        arena.execute([&] {
            tbb::parallel_for(tbb::blocked_range<std::size_t>(0, batch.size(), 1024),
                              [&](const tbb::blocked_range<std::size_t>& range) {
                                  std::uint64_t h = 0;
                                  for (std::size_t i = range.begin(); i < range.end(); ++i)
                                      h += scene.intersect(batch[i]).has_value();
                                  hits += h;
                              });
        });
        return std::pair{static_cast<double>(batch.size()) / seconds_since(t0) * 1e-6, hits.load()};
    };
    for (int k = 0; k < runs; ++k) {
        for (std::size_t j = 0; j < n; ++j) {
            const std::size_t b = k % 2 == 0 ? j : n - 1 - j;
            BenchResult& r = results[b];
            scene.accel = accels[b];
            const auto t0 = std::chrono::steady_clock::now();
            arena.execute([&] { scene.commit(); });
            build[b].push_back(seconds_since(t0));
            const auto [mp, hp] = trace(rays.primary);
            const auto [md, hd] = trace(rays.diffuse);
            primary[b].push_back(mp);
            diffuse[b].push_back(md);
            r.backend = accel_name(accels[b]);
            r.accel_bytes = scene.accel_memory_bytes();
            r.primary_rays = rays.primary.size();
            r.diffuse_rays = rays.diffuse.size();
            r.primary_hits = hp;
            r.diffuse_hits = hd;
        }
    }
    for (std::size_t b = 0; b < n; ++b) {
        results[b].build_seconds = median(build[b]);
        results[b].primary_mrays = median(primary[b]);
        results[b].diffuse_mrays = median(diffuse[b]);
    }
    return results;
}

}  // namespace glint
