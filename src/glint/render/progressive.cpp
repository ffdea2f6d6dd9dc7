#include "glint/render/progressive.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <tbb/task_group.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>

#include "glint/samplers/sampler.h"

namespace glint {

namespace {

constexpr int kAdaptiveStep = 16;  // Cycles' adaptive_step: passes of 16 samples after the minimum
constexpr double kMargin = 1.1;    // a pass must fit the time left with 10 % to spare

template <typename T>
void check_plane(const std::vector<T>& v, std::size_t want, const char* name) {
    if (v.size() != want)
        throw std::runtime_error(std::string("the ") + name + " plane holds " + std::to_string(v.size()) +
                                 " pixels, not " + std::to_string(want));
}

}  // namespace

void ProgressiveState::allocate() {
    const std::size_t n = pixels();
    sum.assign(n, Color{0});
    weight.assign(n, 0.0f);
    odd_sum.assign(halves() ? n : 0, Color{0});
    odd_weight.assign(halves() ? n : 0, 0.0f);
    samples.assign(adaptive ? n : 0, 0);
    active.assign(adaptive ? n : 0, 1);
    albedo.assign(aovs ? n : 0, Color{0});
    odd_albedo.assign(aovs ? n : 0, Color{0});
    normal.assign(aovs ? n : 0, Vector3{0, 0, 0});
    depth.assign(aovs ? n : 0, 0.0f);
    hit_weight.assign(aovs ? n : 0, 0.0f);
}

void ProgressiveState::check_shape() const {
    const std::size_t n = pixels(), a = adaptive ? n : 0, v = aovs ? n : 0, o = halves() ? n : 0;
    check_plane(sum, n, "sum");
    check_plane(weight, n, "weight");
    check_plane(odd_sum, o, "odd-sample sum");
    check_plane(odd_weight, o, "odd-sample weight");
    check_plane(samples, a, "sample count");
    check_plane(active, a, "active");
    check_plane(albedo, v, "albedo");
    check_plane(odd_albedo, v, "odd-sample albedo");
    check_plane(normal, v, "normal");
    check_plane(depth, v, "depth");
    check_plane(hit_weight, v, "depth weight");
}

float adaptive_internal_threshold(float threshold) { return threshold * 5.0f; }

int adaptive_default_min_spp(float threshold) {
    // Cycles: threshold 0.1 -> 32, 0.01 -> 64, 0.001 -> 128.
    return std::max(4, static_cast<int>(std::ceil(16.0f / std::pow(threshold, 0.3f))));
}

ProgressiveRender::ProgressiveRender(const Scene& scene, const Camera& camera,
                                     const Integrator& integrator, const RenderOptions& options,
                                     int width, int height, bool aovs)
    : scene_(scene), camera_(camera), moving_(scene.has_motion() || camera.moves()), integrator_(integrator),
      options_(options), filter_(options.filter) {
    state_.width = width;
    state_.height = height;
    state_.spp_target = std::max(1, options.spp);
    state_.adaptive = options.noise_threshold > 0 && state_.spp_target > 1;
    state_.aovs = aovs;
    if (state_.adaptive) {
        threshold_ = adaptive_internal_threshold(options.noise_threshold);
        min_spp_ = options.min_spp > 0 ? std::max(4, options.min_spp)
                                       : adaptive_default_min_spp(options.noise_threshold);
        min_spp_ = std::min(min_spp_, state_.spp_target);
    }
    state_.allocate();
}

void ProgressiveRender::restore(ProgressiveState state) {
    const auto mismatch = [](const char* what, long long have, long long want) {
        return std::runtime_error(std::string("its ") + what + " is " + std::to_string(have) +
                                  ", this render's is " + std::to_string(want));
    };
    if (state.width != state_.width) throw mismatch("width", state.width, state_.width);
    if (state.height != state_.height) throw mismatch("height", state.height, state_.height);
    if (state.spp_target != state_.spp_target)
        throw mismatch("target spp", state.spp_target, state_.spp_target);
    if (state.adaptive != state_.adaptive)
        throw std::runtime_error(state.adaptive ? "it was rendered with adaptive sampling, this render is not"
                                                : "this render uses adaptive sampling, it was rendered without");
    if (state.aovs != state_.aovs)
        throw std::runtime_error(state.aovs ? "it holds AOVs, this render has none"
                                            : "this render writes AOVs, it holds none");
    if (state.spp_done < 0 || state.spp_done > state.spp_target)
        throw mismatch("spp done", state.spp_done, state_.spp_target);
    state.check_shape();
    state_ = std::move(state);
    // The pace of the saved passes stands in for this machine's until a pass is measured.
    const auto taken = static_cast<double>(samples_taken());
    seconds_per_sample_ = taken > 0 ? state_.seconds / taken : 0;
}

bool ProgressiveRender::finished() const {
    if (state_.spp_done >= state_.spp_target) return true;
    if (!state_.adaptive || state_.spp_done < min_spp_) return false;
    return std::none_of(state_.active.begin(), state_.active.end(), [](std::uint8_t a) { return a != 0; });
}

double ProgressiveRender::converged_fraction() const {
    if (!state_.adaptive || state_.active.empty() || state_.spp_done < min_spp_) return 0;
    const auto still = std::count(state_.active.begin(), state_.active.end(), std::uint8_t{1});
    return 1.0 - static_cast<double>(still) / static_cast<double>(state_.active.size());
}

std::uint64_t ProgressiveRender::samples_taken() const {
    if (!state_.adaptive) return static_cast<std::uint64_t>(state_.pixels()) * static_cast<std::uint64_t>(state_.spp_done);
    std::uint64_t n = 0;
    for (std::uint32_t s : state_.samples) n += s;
    return n;
}

std::uint64_t ProgressiveRender::remaining_samples() const {
    if (!state_.adaptive)
        return static_cast<std::uint64_t>(state_.pixels()) * static_cast<std::uint64_t>(state_.spp_target - state_.spp_done);
    std::uint64_t r = 0;
    for (std::size_t i = 0; i < state_.pixels(); ++i)
        if (state_.active[i]) r += static_cast<std::uint64_t>(state_.spp_target) - state_.samples[i];
    return r;
}

int ProgressiveRender::next_pass_size(double seconds_left) const {
    const int done = state_.spp_done, target = state_.spp_target;
    if (finished()) return 0;
    const bool budget = seconds_left >= 0;
    if (budget && seconds_left <= 0) return 0;
    double active = static_cast<double>(state_.pixels());
    if (state_.adaptive) {
        active = static_cast<double>(std::count(state_.active.begin(), state_.active.end(), std::uint8_t{1}));
        // The fixed schedule: 1, 1, 2, 4, ... up to the minimum, then steps of 16.
        int n = done < min_spp_ ? std::min(std::max(done, 1), min_spp_ - done)
                                : std::min(kAdaptiveStep, target - done);
        if (budget && seconds_per_sample_ > 0 && kMargin * n * active * seconds_per_sample_ > seconds_left) return 0;
        return n;
    }
    int n = std::min(std::max(done, 1), target - done);  // cumulative 1, 2, 4, 8, ...
    if (seconds_per_sample_ > 0 && active > 0) {
        const double per_spp = seconds_per_sample_ * active;
        const double cap = std::max(2.0, 0.1 * state_.seconds);
        n = std::min(n, std::max(1, static_cast<int>(std::min(cap / per_spp, 1e9))));
        if (budget) {
            const double fit = std::floor(seconds_left / (kMargin * per_spp));
            if (fit < 1) return 0;
            n = std::min(n, static_cast<int>(std::min(fit, 1e9)));
        }
    }
    return n;
}

// Samples [c, c + n) of one pixel, c its count so far, continuing its sums from state_ into
// next_ (n = 0 copies the pixel over); returns the samples taken. The arithmetic is the one-pass
// loop's, term for term.
// Flattened: the sampler, filter and camera calls inline into the loop, as they did in the
// one-pass loop this replaced (7 % of a Whitted render went to the calls otherwise).
[[gnu::flatten]] int ProgressiveRender::sample_pixel(std::size_t i, int col, int row, int n, RayCounter& counter) {
    const ProgressiveState& in = state_;
    ProgressiveState& out = next_;
    const int spp = in.spp_target;
    const int ox = options_.offset_x, oy = options_.offset_y;
    const std::uint32_t seed = pixel_seed(options_.seed, static_cast<std::uint32_t>(col + ox),
                                          static_cast<std::uint32_t>(row + oy));
    const PixelSampler sampler(options_.sampler, static_cast<std::uint32_t>(spp), seed);
    const int first = in.adaptive ? static_cast<int>(in.samples[i]) : in.spp_done;
    const int last = std::min(spp, first + n);

    Color sum = in.sum[i], odd = in.halves() ? in.odd_sum[i] : Color{0};
    float weight = in.weight[i], odd_weight = in.halves() ? in.odd_weight[i] : 0.0f;
    Color albedo{0}, odd_albedo{0};
    Vector3 normal{0, 0, 0};
    float depth = 0, hit_weight = 0;
    if (in.aovs) albedo = in.albedo[i], odd_albedo = in.odd_albedo[i], normal = in.normal[i], depth = in.depth[i], hit_weight = in.hit_weight[i];
    const FilterSampler& filter = filter_;
    for (int s = first; s < last; ++s) {
        const auto index = static_cast<std::uint32_t>(s);
        FirstHit hit;
        FirstHit* const want = in.aovs ? &hit : nullptr;
        Color li;
        float w;
        if (spp == 1) {  // the pixel centre, through the lens centre
            const Ray ray = camera_.at_time(camera_.generate_ray(static_cast<float>(col + ox) + 0.5f,
                                                                 static_cast<float>(row + oy) + 0.5f, {0.5f, 0.5f}),
                                            0.5f);  // the shutter's middle
            SampleStream samples(sampler, 0);
            sum = integrator_.li(scene_, ray, samples, counter, want);
            w = 1;
            weight = 1;
            li = sum;
        } else {
            // Dimension pair 0 places the sample in the pixel (through the filter), pair 1 on the
            // lens; later pairs are the integrator's. The time, where something moves, is a pair
            // of its own far past them, so that still scenes draw exactly what they always drew.
            SampleStream samples(sampler, index, 0);
            const FilterSampler::Sample f = filter.sample(samples.next_2d());
            const Sample2 lens = samples.next_2d();
            Ray ray = camera_.generate_ray(static_cast<float>(col + ox) + 0.5f + f.dx,
                                           static_cast<float>(row + oy) + 0.5f + f.dy, lens);
            if (moving_) ray = camera_.at_time(ray, sampler.get_2d(index, kTimeDimension).x);
            li = integrator_.li(scene_, ray, samples, counter, want);
            w = f.weight;
            sum += li * w;
            weight += w;
            if (in.halves() && (s & 1)) odd += li * w, odd_weight += w;
        }
        if (in.aovs) {
            albedo += hit.albedo * w;
            if (s & 1) odd_albedo += hit.albedo * w;
            normal += to_vector(hit.normal) * w;
            if (hit.hit) depth += hit.depth * w, hit_weight += w;
        }
    }
    out.sum[i] = sum;
    out.weight[i] = weight;
    if (in.halves()) {
        out.odd_sum[i] = odd;
        out.odd_weight[i] = odd_weight;
    }
    if (in.adaptive) {
        out.samples[i] = static_cast<std::uint32_t>(std::max(first, last));
        out.active[i] = in.active[i];
    }
    if (in.aovs) {
        out.albedo[i] = albedo;
        out.odd_albedo[i] = odd_albedo;
        out.normal[i] = normal;
        out.depth[i] = depth;
        out.hit_weight[i] = hit_weight;
    }
    return std::max(0, last - first);
}

int ProgressiveRender::tile_count() const {
    const int tile = std::max(1, options_.tile_size);
    const int tx = (state_.width + tile - 1) / tile, ty = (state_.height + tile - 1) / tile;
    return tx * ty;
}

ProgressiveRender::TileRect ProgressiveRender::tile_rect(int t) const {
    const int tile = std::max(1, options_.tile_size);
    const int tx = (state_.width + tile - 1) / tile;
    const int x0 = (t % tx) * tile, y0 = (t / tx) * tile;
    return {x0, y0, std::min(state_.width, x0 + tile), std::min(state_.height, y0 + tile)};
}

int ProgressiveRender::begin_pass(int n) {
    n = std::max(0, std::min(n, state_.spp_target - state_.spp_done));
    if (next_.pixels() != state_.pixels() || next_.sum.size() != state_.sum.size()) {
        next_ = state_;  // same shape: the buffer the pass writes
    }
    pass_n_ = n;
    return n;
}

std::uint64_t ProgressiveRender::render_tile(int t, RayCounter& counter) {
    const TileRect r = tile_rect(t);
    const auto w = static_cast<std::size_t>(state_.width);
    std::uint64_t taken = 0;
    for (int row = r.y0; row < r.y1; ++row) {
        for (int col = r.x0; col < r.x1; ++col) {
            const std::size_t i = static_cast<std::size_t>(row) * w + static_cast<std::size_t>(col);
            // A converged pixel takes no samples: it is carried over as it is.
            const bool active = !state_.adaptive || state_.active[i];
            taken += static_cast<std::uint64_t>(sample_pixel(i, col, row, active ? pass_n_ : 0, counter));
        }
    }
    return taken;
}

namespace {

// Every plane the state's flags call for, in a fixed order, as f(vector&).
template <typename State, typename F>
void each_plane(State& s, F&& f) {
    f(s.sum);
    f(s.weight);
    if (s.halves()) {
        f(s.odd_sum);
        f(s.odd_weight);
    }
    if (s.adaptive) {
        f(s.samples);
        f(s.active);
    }
    if (s.aovs) {
        f(s.albedo);
        f(s.odd_albedo);
        f(s.normal);
        f(s.depth);
        f(s.hit_weight);
    }
}

template <typename T>
constexpr std::size_t element_size(const std::vector<T>&) {
    return sizeof(T);
}

}  // namespace

std::size_t ProgressiveRender::tile_bytes(int t) const {
    const TileRect r = tile_rect(t);
    const auto pixels = static_cast<std::size_t>(r.x1 - r.x0) * static_cast<std::size_t>(r.y1 - r.y0);
    std::size_t bytes = 0;
    each_plane(next_, [&](const auto& plane) { bytes += pixels * element_size(plane); });
    return bytes;
}

void ProgressiveRender::pack_tile(int t, std::vector<std::uint8_t>& out, bool before) const {
    const TileRect r = tile_rect(t);
    const auto w = static_cast<std::size_t>(state_.width);
    const auto cols = static_cast<std::size_t>(r.x1 - r.x0);
    out.reserve(out.size() + tile_bytes(t));
    each_plane(before ? state_ : next_, [&](const auto& plane) {
        const std::size_t size = element_size(plane);
        for (int row = r.y0; row < r.y1; ++row) {
            const auto* p = reinterpret_cast<const std::uint8_t*>(&plane[static_cast<std::size_t>(row) * w +
                                                                         static_cast<std::size_t>(r.x0)]);
            out.insert(out.end(), p, p + cols * size);
        }
    });
}

void ProgressiveRender::unpack_tile(int t, const std::uint8_t* data, std::size_t size, bool before) {
    if (size != tile_bytes(t))
        throw std::runtime_error("tile " + std::to_string(t) + ": " + std::to_string(size) + " bytes, not " +
                                 std::to_string(tile_bytes(t)));
    const TileRect r = tile_rect(t);
    const auto w = static_cast<std::size_t>(state_.width);
    const auto cols = static_cast<std::size_t>(r.x1 - r.x0);
    each_plane(before ? state_ : next_, [&](auto& plane) {
        const std::size_t bytes = cols * element_size(plane);
        for (int row = r.y0; row < r.y1; ++row) {
            std::memcpy(&plane[static_cast<std::size_t>(row) * w + static_cast<std::size_t>(r.x0)], data, bytes);
            data += bytes;
        }
    });
}

void ProgressiveRender::end_pass(double seconds, std::uint64_t rays, std::uint64_t pixel_samples) {
    std::swap(state_, next_);
    state_.spp_done = next_.spp_done + pass_n_;
    state_.passes = next_.passes + 1;
    state_.seconds = next_.seconds + seconds;
    state_.rays = next_.rays + rays;
    if (pixel_samples > 0) seconds_per_sample_ = seconds / static_cast<double>(pixel_samples);
    if (state_.adaptive && state_.spp_done >= min_spp_) update_convergence();
}

namespace {

struct StateHeader {
    std::int32_t width, height, spp_target, spp_done, passes, flags;
    double seconds;
    std::uint64_t rays;
};

}  // namespace

std::vector<std::uint8_t> ProgressiveRender::pack_header() const {
    const StateHeader h{state_.width, state_.height, state_.spp_target, state_.spp_done, state_.passes,
                        (state_.adaptive ? 1 : 0) | (state_.aovs ? 2 : 0), state_.seconds, state_.rays};
    std::vector<std::uint8_t> out(sizeof h);
    std::memcpy(out.data(), &h, sizeof h);
    return out;
}

void ProgressiveRender::unpack_header(const std::uint8_t* data, std::size_t size) {
    StateHeader h{};
    if (size != sizeof h) throw std::runtime_error("a render header of " + std::to_string(size) + " bytes");
    std::memcpy(&h, data, sizeof h);
    if (h.width != state_.width || h.height != state_.height || h.spp_target != state_.spp_target ||
        h.flags != ((state_.adaptive ? 1 : 0) | (state_.aovs ? 2 : 0)) || h.spp_done < 0 || h.spp_done > h.spp_target)
        throw std::runtime_error("a render header of another render (size, spp or flags differ)");
    state_.spp_done = h.spp_done;
    state_.passes = h.passes;
    state_.seconds = h.seconds;
    state_.rays = h.rays;
}

bool ProgressiveRender::run_pass(int n, const std::atomic<bool>* cancel, Progress* progress) {
    if (n <= 0 || finished()) return true;
    if (state_.adaptive && n != next_pass_size())
        throw std::invalid_argument("an adaptive render's passes follow its schedule");
    begin_pass(n);
    const auto start = std::chrono::steady_clock::now();
    std::atomic<bool> skipped{false};
    std::atomic<std::uint64_t> rays{0}, pixel_samples{0};

    const int threads = options_.threads > 0 ? options_.threads : tbb::this_task_arena::max_concurrency();
    tbb::task_arena arena(threads);
    arena.execute([&] {
        tbb::parallel_for(tbb::blocked_range<int>(0, tile_count(), 1), [&](const tbb::blocked_range<int>& r) {
            for (int t = r.begin(); t < r.end(); ++t) {
                if (cancel && cancel->load(std::memory_order_relaxed)) {
                    skipped.store(true, std::memory_order_relaxed);
                    return;
                }
                RayCounter counter;
                const std::uint64_t taken = render_tile(t, counter);
                rays.fetch_add(counter.rays, std::memory_order_relaxed);
                pixel_samples.fetch_add(taken, std::memory_order_relaxed);
                if (progress) progress->tile_done(taken, counter.rays);
            }
        }, tbb::simple_partitioner());
    });
    if (skipped.load()) return false;  // the state is still the previous pass's
    end_pass(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), rays.load(),
             pixel_samples.load());
    return true;
}

// Cycles' test: the mean of all samples I against the mean of the odd ones A,
// error = sum |I - A| / (1e-4 + n(I_r + I_g + I_b)), n(x) = sqrt(x) below 1, x above; converged
// below the threshold. Then every pixel within one pixel (x, then y) of a noisy one samples on.
void ProgressiveRender::update_convergence() {
    const int w = state_.width, h = state_.height;
    std::vector<std::uint8_t> noisy(state_.pixels(), 0);
    for (std::size_t i = 0; i < noisy.size(); ++i) {
        if (!state_.active[i]) continue;
        if (state_.weight[i] <= 0 || state_.odd_weight[i] <= 0) {
            noisy[i] = 1;
            continue;
        }
        const Color mean = state_.sum[i] / state_.weight[i] * options_.scale;
        const Color odd = state_.odd_sum[i] / state_.odd_weight[i] * options_.scale;
        const float difference = std::abs(mean.r - odd.r) + std::abs(mean.g - odd.g) + std::abs(mean.b - odd.b);
        const float intensity = std::max(0.0f, mean.r + mean.g + mean.b);
        const float normalize = intensity < 1 ? std::sqrt(intensity) : intensity;
        const float error = difference / (1e-4f + normalize);
        noisy[i] = !(error < threshold_);  // a NaN error is noisy
    }
    std::vector<std::uint8_t> wide(noisy.size(), 0);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const std::size_t i = static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x);
            wide[i] = noisy[i] || (x > 0 && noisy[i - 1]) || (x + 1 < w && noisy[i + 1]);
        }
    }
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const std::size_t i = static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x);
            const auto W = static_cast<std::size_t>(w);
            const bool on = wide[i] || (y > 0 && wide[i - W]) || (y + 1 < h && wide[i + W]);
            state_.active[i] = on && state_.samples[i] < static_cast<std::uint32_t>(state_.spp_target);
        }
    }
}

void ProgressiveRender::resolve(Film& film) const {
    const int w = state_.width, h = state_.height;
    for (int row = 0; row < h; ++row) {
        for (int col = 0; col < w; ++col) {
            const std::size_t i = static_cast<std::size_t>(row) * static_cast<std::size_t>(w) +
                                  static_cast<std::size_t>(col);
            const float weight = state_.weight[i];
            const Color c = weight > 0 ? state_.sum[i] / weight : Color{0};
            film.at(col, row) = options_.scale != 1 ? c * options_.scale : c;
            if (film.has_aovs() && state_.aovs) {
                const float inv = weight > 0 ? 1 / weight : 0;
                film.albedo(col, row) = state_.albedo[i] * inv;
                film.normal(col, row) = Normal3(state_.normal[i] * inv);
                film.depth(col, row) = state_.hit_weight[i] > 0 ? state_.depth[i] / state_.hit_weight[i]
                                                                 : std::numeric_limits<float>::infinity();
                // The halves: the odd-numbered samples and the rest (each 0 before it has any).
                const float ow = state_.odd_weight[i], ew = weight - ow;
                const Color odd = ow > 0 ? state_.odd_sum[i] / ow : Color{0};
                const Color even = ew > 0 ? (state_.sum[i] - state_.odd_sum[i]) / ew : Color{0};
                film.even(col, row) = options_.scale != 1 ? even * options_.scale : even;
                film.odd(col, row) = options_.scale != 1 ? odd * options_.scale : odd;
                film.odd_albedo(col, row) = ow > 0 ? state_.odd_albedo[i] / ow : Color{0};
                film.even_albedo(col, row) = ew > 0 ? (state_.albedo[i] - state_.odd_albedo[i]) / ew : Color{0};
            }
            if (film.has_sample_counts()) {
                film.sample_count(col, row) = static_cast<float>(
                    state_.adaptive ? state_.samples[i] : static_cast<std::uint32_t>(state_.spp_done));
            }
        }
    }
}

}  // namespace glint
