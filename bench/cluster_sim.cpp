// The distributed scheduler on N virtual ranks (docs/benchmarks.md, "Distributed rendering").
//
// 1. Measures: renders the scene for real on one thread, pass by pass, timing every tile; each
//    tile's cost per sample is its time over the samples it took.
// 2. Replays: for each N, rank 0's decisions are made by a real ProgressiveRender (pass sizes
//    from the simulated elapsed time, as on a cluster), and each pass is an event simulation of
//    the protocol of render/distributed.cpp with the same chunk policy (chunk_tiles): PASS to
//    every rank, requests, chunks carrying their tiles' sums, results carrying them back, rank 0
//    rendering on a thread of its own while its main thread serves messages one at a time.
//    Network: a latency per message and rank 0's link as one serial resource each way (every
//    chunk leaves and every result arrives through it); rank 0 spends a fixed overhead per message
//    plus the bytes at memory speed to pack or unpack them. `--whole-state` models the first
//    version of the protocol instead (the whole state sent to every rank with each PASS).
//
//   glint_cluster_sim SCENE [--width W] [--height H] [--spp S] [--ranks 1,2,8,64,512]
//                     [--latency-us L] [--bandwidth-gbs B] [--whole-state]
// Without a network option it reports three: InfiniBand-like, 10 GbE-like, and 10 GbE-like with
// the first protocol.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <queue>
#include <string>
#include <vector>

#include "glint/builder/build.h"
#include "glint/formats/scene_yaml.h"
#include "glint/render/distributed.h"
#include "glint/render/progressive.h"

namespace {

using namespace glint;

struct Model {
    double latency = 2e-6;           // seconds per message, one way
    double bandwidth = 12.5e9;       // bytes per second through rank 0's link, each way
    double overhead = 2e-6;          // rank 0's main thread per message
    double memory = 5e9;             // bytes per second packing and unpacking
    bool whole_state = false;
};

struct Costs {
    std::vector<double> per_sample;  // per tile, one thread
    std::vector<std::size_t> bytes;  // per tile, its planes
    std::size_t state_bytes = 0;
};

// One pass of n samples on N ranks of one thread; returns its length in seconds.
double simulate_pass(const Costs& c, int n, int ranks, const Model& m) {
    const int tiles = static_cast<int>(c.per_sample.size());
    if (ranks == 1) {
        double t = 0;
        for (double s : c.per_sample) t += s * n;
        return t;
    }
    struct Event {
        double time;
        int kind;  // 0: a message is at rank 0 (request or result), 1: rank 0's thread wants work,
                   // 2: a result reaches rank 0's link
        int rank;
        std::vector<int> chunk;  // a result's tiles
        bool operator>(const Event& o) const { return time > o.time; }
    };
    std::priority_queue<Event, std::vector<Event>, std::greater<>> events;
    int next = 0;  // the queue is 0..tiles-1 in order; next is its head
    double main_free = 0, out_free = 0, in_free = 0;  // rank 0's main thread and link, each way
    int done = 0;
    double end = 0;
    std::vector<int> waiting;
    const auto chunk_for = [&](int k) {
        const int size = chunk_tiles(tiles - next, ranks, k);
        std::vector<int> chunk;
        for (int i = 0; i < size; ++i) chunk.push_back(next++);
        return chunk;
    };
    const auto cost = [&](const std::vector<int>& chunk) {
        double s = 0;
        for (int t : chunk) s += c.per_sample[static_cast<std::size_t>(t)] * n;
        return s;
    };
    const auto bytes = [&](const std::vector<int>& chunk) {
        std::size_t b = 0;
        for (int t : chunk) b += c.bytes[static_cast<std::size_t>(t)] + 28;
        return static_cast<double>(b);
    };
    // Sends a chunk to rank r from rank 0's main thread at `now`; schedules its result.
    const auto send_chunk = [&](int r, double now) {
        std::vector<int> chunk = chunk_for(1);
        const double payload = m.whole_state ? 8.0 * chunk.size() + 16 : bytes(chunk);
        main_free = std::max(main_free, now) + m.overhead + (m.whole_state ? 0 : payload / m.memory);
        out_free = std::max(out_free, main_free) + payload / m.bandwidth;
        const double arrives = out_free + m.latency;
        const double rendered = arrives + cost(chunk);
        // The result crosses back: it reaches rank 0's link a latency later and takes its turn
        // there (the rank's own link is not the limit; rank 0's is).
        events.push({rendered + m.latency, 2, r, std::move(chunk)});
    };
    // PASS to every rank (with the whole state, in the first version), then each one's request.
    const double pass_bytes = 64 + (m.whole_state ? static_cast<double>(c.state_bytes) : 0);
    for (int r = 1; r < ranks; ++r) {
        main_free += m.overhead + (m.whole_state ? 0 : 0);
        out_free = std::max(out_free, main_free) + pass_bytes / m.bandwidth;
        const double request = out_free + m.latency + (m.whole_state ? pass_bytes / m.memory : 0) + m.latency;
        events.push({request, 0, r, {}});
    }
    events.push({0, 1, 0, {}});
    while (!events.empty()) {
        Event e = events.top();
        events.pop();
        end = std::max(end, e.time);
        if (e.kind == 2) {  // a result reaches rank 0's link: in order of arrival, one at a time
            in_free = std::max(in_free, e.time) + bytes(e.chunk) / m.bandwidth;
            events.push({in_free, 0, e.rank, std::move(e.chunk)});
            continue;
        }
        if (e.kind == 1) {  // rank 0's render thread: takes a chunk (a lock, no message)
            if (next >= tiles) continue;
            std::vector<int> chunk = chunk_for(1);
            const double finished = e.time + cost(chunk);
            done += static_cast<int>(chunk.size());
            end = std::max(end, finished);
            events.push({finished, 1, 0, {}});
            continue;
        }
        // A message at rank 0: unpack the result's tiles, then serve the request.
        main_free = std::max(main_free, e.time) + m.overhead + bytes(e.chunk) / m.memory;
        done += static_cast<int>(e.chunk.size());
        end = std::max(end, main_free);
        if (next < tiles) send_chunk(e.rank, main_free);
    }
    if (done != tiles) std::fprintf(stderr, "simulation lost tiles: %d of %d\n", done, tiles);
    return end;
}

std::vector<int> parse_list(const char* s) {
    std::vector<int> v;
    for (const char* p = s; *p;) {
        v.push_back(std::atoi(p));
        p = std::strchr(p, ',');
        if (!p) break;
        ++p;
    }
    return v;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: %s SCENE [--width W] [--height H] [--spp S] [--ranks 1,2,8,64,512] "
                             "[--latency-us L] [--bandwidth-gbs B] [--whole-state]\n", argv[0]);
        return 2;
    }
    Overrides o;
    Model m;
    std::vector<int> ranks = {1, 2, 8, 64, 512};
    bool explicit_model = false;
    for (int i = 2; i < argc; ++i) {
        const std::string a = argv[i];
        const char* v = i + 1 < argc ? argv[i + 1] : "0";
        if (a == "--width") o.width = std::atoll(v), ++i;
        else if (a == "--height") o.height = std::atoll(v), ++i;
        else if (a == "--spp") o.spp = std::atoll(v), ++i;
        else if (a == "--ranks") ranks = parse_list(v), ++i;
        else if (a == "--latency-us") m.latency = std::atof(v) * 1e-6, ++i, explicit_model = true;
        else if (a == "--bandwidth-gbs") m.bandwidth = std::atof(v) * 1e9, ++i, explicit_model = true;
        else if (a == "--whole-state") m.whole_state = true, explicit_model = true;
        else {
            std::fprintf(stderr, "unknown option %s\n", a.c_str());
            return 2;
        }
    }
    o.threads = 1;
    auto sources = std::make_shared<SourceFiles>();
    RenderJob job = build(load_scene_file(argv[1], sources), o, sources);
    job.options.threads = 1;

    // 1. The real render, one thread, every tile timed.
    ProgressiveRender render(job.scene, job.camera, *job.integrator, job.options, job.film_width, job.film_height, false);
    const int tiles = render.tile_count();
    Costs c;
    c.per_sample.assign(static_cast<std::size_t>(tiles), 0);
    for (int t = 0; t < tiles; ++t) c.bytes.push_back(render.tile_bytes(t));
    for (std::size_t b : c.bytes) c.state_bytes += b;
    double total = 0;
    int passes = 0;
    while (!render.finished()) {
        render.begin_pass(render.next_pass_size());
        double pass = 0;
        std::uint64_t samples = 0;
        for (int t = 0; t < tiles; ++t) {
            RayCounter counter;
            const auto a = std::chrono::steady_clock::now();
            samples += render.render_tile(t, counter);
            const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - a).count();
            c.per_sample[static_cast<std::size_t>(t)] += s;
            pass += s;
        }
        render.end_pass(pass, 0, samples);
        total += pass;
        ++passes;
    }
    for (double& s : c.per_sample) s /= render.spp_done();
    std::printf("measured: %dx%d, %d spp, %d tiles, %d passes, %.2f s on one thread\n", job.film_width,
                job.film_height, render.spp_done(), tiles, passes, total);
    // 2. The replay: rank 0's pass decisions from the simulated clock, on the given network and
    // on two reference ones (an InfiniBand-like and a 10 GbE-like link), and the first protocol.
    struct Named {
        const char* name;
        Model model;
    };
    std::vector<Named> models = {{"as given", m}};
    if (!explicit_model) {
        Model infiniband;  // the defaults
        Model ethernet;
        ethernet.latency = 30e-6;
        ethernet.bandwidth = 1.25e9;
        Model first = ethernet;
        first.whole_state = true;
        models = {{"InfiniBand-like: 2 us, 12.5 GB/s", infiniband},
                  {"10 GbE-like: 30 us, 1.25 GB/s", ethernet},
                  {"10 GbE-like, the first protocol (whole state to every rank each pass)", first}};
    }
    for (const Named& nm : models) {
        const Model& model = nm.model;
        std::printf("\nnetwork: %s (latency %.1f us, rank 0's link %.2f GB/s each way)\n\n", nm.name,
                    model.latency * 1e6, model.bandwidth * 1e-9);
        std::printf("| ranks | passes | predicted (s) | speed-up | efficiency |\n|---|---|---|---|---|\n");
        double one = 0;
        for (const int n_ranks : ranks) {
            ProgressiveRender decide(job.scene, job.camera, *job.integrator, job.options, job.film_width,
                                     job.film_height, false);
            double t = 0;
            int p = 0;
            while (!decide.finished()) {
                const int n = decide.begin_pass(decide.next_pass_size());
                const double pass = simulate_pass(c, n, n_ranks, model);
                decide.end_pass(pass, 0, static_cast<std::uint64_t>(job.film_width) * job.film_height * n);
                t += pass;
                ++p;
            }
            if (n_ranks == 1) one = t;
            const double speedup = one > 0 ? one / t : 0;
            std::printf("| %d | %d | %.3f | %.2fx | %.2f |\n", n_ranks, p, t, speedup, speedup / n_ranks);
        }
    }
    return 0;
}
