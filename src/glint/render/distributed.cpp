#include "glint/render/distributed.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <filesystem>
#include <fstream>
#include <exception>
#include <map>
#include <mutex>
#include <set>
#include <optional>
#include <thread>

#include "glint/base/errors.h"
#include "glint/base/module.h"
#include "glint/render/mpi_module.h"

namespace glint {

namespace {

using Clock = std::chrono::steady_clock;

double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// Message tags.
enum : int {
    kPass = 1,    // rank 0 -> rank: PassHeader, then the render's header (spp done, ...)
    kTiles = 2,   // rank 0 -> rank: u32 pass, u32 count, then per tile i32 index and its sums before the pass
    kStop = 3,    // rank 0 -> rank: nothing
    kResult = 4,  // rank -> rank 0: ResultHeader, then per tile TileEntry and its bytes (0 tiles: a request)
    kBye = 5,     // rank -> rank 0: ByeHeader, then the host name
    kFail = 6,    // rank -> rank 0: what went wrong, as text
    kWantFiles = 7,  // rank -> rank 0: nothing (it cannot read the scene's files)
    kFile = 8,       // rank 0 -> rank: FileHeader, the path, then the piece's bytes
    kFilesEnd = 9,   // rank 0 -> rank: u32 ok; then the working folder and the model folders, one a line, or the error
    kFrame = 10,     // rank 0 -> rank: f64 the animation frame rendered next, by tiles
    kFrameWhole = 11,  // rank 0 -> rank: f64 an animation frame for this rank to render whole, u64 the files' fingerprint
    kFramePiece = 12,  // rank -> rank 0: FramePiece, then that piece of the frame's image file
};

struct FramePiece {
    double frame;
    std::uint64_t size, offset;
};

// A file goes in pieces of at most this many bytes (MPI counts are ints).
constexpr std::uint64_t kFilePiece = std::uint64_t{64} << 20;

struct FileHeader {
    std::uint64_t size, offset;
    std::uint32_t path_bytes, pad;
};

struct PassHeader {
    std::uint32_t pass;
    std::int32_t n;
    std::uint64_t fingerprint;
};
struct ResultHeader {
    std::uint32_t pass, count;
    std::int32_t threads;
    std::int32_t pad;
};
struct TileEntry {
    std::int32_t tile, pad;
    std::uint64_t rays, samples;
};
struct ByeHeader {
    std::int32_t threads, pad;
    std::uint64_t tiles, samples;
    double busy, wall;
};

template <typename T>
void put(std::vector<std::uint8_t>& out, const T& v) {
    const auto* p = reinterpret_cast<const std::uint8_t*>(&v);
    out.insert(out.end(), p, p + sizeof(T));
}

// Reads a T at `at`, or throws: a message is checked like any input.
template <typename T>
T get(const Message& m, std::size_t& at) {
    if (m.bytes.size() - std::min(at, m.bytes.size()) < sizeof(T))
        throw IoError(fmt::format("a message from rank {} ends early (tag {}, {} bytes)", m.source, m.tag, m.bytes.size()));
    T v;
    std::memcpy(&v, m.bytes.data() + at, sizeof(T));
    at += sizeof(T);
    return v;
}

std::string host_name() {
    char name[256] = {};
    if (::gethostname(name, sizeof name - 1) != 0) return "?";
    return name;
}

// Waits for one message, sleeping between polls so that a waiting rank leaves its core to the
// ranks that render (MPI's own blocking receive spins).
Message wait_message(Transport& t) {
    Message m;
    while (!t.receive(m)) std::this_thread::sleep_for(std::chrono::microseconds(100));
    return m;
}

// The test-only fault hook: GLINT_TEST_STALL=R:S makes rank R sleep S seconds before returning
// its first chunk, as a stalled node would.
double stall_seconds(int rank) {
    const char* v = std::getenv("GLINT_TEST_STALL");
    if (!v) return 0;
    int r = -1;
    double s = 0;
    if (std::sscanf(v, "%d:%lf", &r, &s) != 2 || r != rank) return 0;
    return s;
}

// Rank 0: every file of `files` to `rank`, then the folders; a file that cannot be read now ends
// the list with its error instead.
void send_files(Transport& t, int rank, const SceneFiles& files) {
    std::string error;
    for (const std::filesystem::path& path : files.files) {
        std::ifstream in(path, std::ios::binary);
        std::error_code ec;
        const std::uint64_t size = std::filesystem::file_size(path, ec);
        if (!in || ec) {
            error = fmt::format("{}: rank 0 cannot read it again to send it", path.string());
            break;
        }
        const std::string name = path.string();
        std::uint64_t offset = 0;
        do {
            const std::uint64_t piece = std::min(kFilePiece, size - offset);
            std::vector<std::uint8_t> bytes;
            bytes.reserve(sizeof(FileHeader) + name.size() + piece);
            put(bytes, FileHeader{size, offset, static_cast<std::uint32_t>(name.size()), 0});
            bytes.insert(bytes.end(), name.begin(), name.end());
            const std::size_t at = bytes.size();
            bytes.resize(at + piece);
            if (!in.read(reinterpret_cast<char*>(bytes.data() + at), static_cast<std::streamsize>(piece))) {
                error = fmt::format("{}: rank 0 cannot read it again to send it (it changed?)", name);
                break;
            }
            t.send(rank, kFile, std::move(bytes));
            offset += piece;
        } while (offset < size);
        if (!error.empty()) break;
    }
    std::vector<std::uint8_t> bytes;
    put(bytes, static_cast<std::uint32_t>(error.empty()));
    std::string text = error;
    if (error.empty()) {
        text = files.cwd.string();
        for (const auto& f : files.model_folders) text += "\n" + f.string();
    }
    bytes.insert(bytes.end(), text.begin(), text.end());
    t.send(rank, kFilesEnd, std::move(bytes));
}

// A rank's goodbye: what it did, for rank 0's report.
void send_bye(Transport& t, int threads, std::uint64_t tiles, std::uint64_t samples, double busy, double wall) {
    const std::string host = host_name();
    std::vector<std::uint8_t> bytes;
    put(bytes, ByeHeader{threads, 0, tiles, samples, busy, wall});
    bytes.insert(bytes.end(), host.begin(), host.end());
    t.send(0, kBye, std::move(bytes));
    t.flush();
}

}  // namespace

bool launched_by_mpi() {
    return std::getenv("OMPI_COMM_WORLD_SIZE") || std::getenv("PMIX_RANK") || std::getenv("PMI_SIZE");
}

int local_ranks() {
    for (const char* name : {"OMPI_COMM_WORLD_LOCAL_SIZE", "MPI_LOCALNRANKS"}) {
        if (const char* v = std::getenv(name)) {
            const int n = std::atoi(v);
            if (n > 0) return n;
        }
    }
    return 1;
}

std::unique_ptr<Transport> mpi_transport(int& argc, char**& argv) {
    void* entry;
    try {
        entry = module_entry("mpi");
    } catch (const IoError& e) {
        throw IoError(fmt::format("started by mpirun, but this glint cannot use MPI ({}); build it with "
                                  "Open MPI installed (libopenmpi-dev) and -DGLINT_MPI=ON",
                                  e.what()));
    }
    const auto* m = reinterpret_cast<const MpiModule* (*)()>(entry)();
    if (m->abi != kMpiModuleAbi) throw IoError("libglint_mpi.so is from another build of glint");
    try {
        return std::unique_ptr<Transport>(m->create(&argc, &argv));
    } catch (const std::exception& e) {
        throw IoError(e.what());
    }
}

int chunk_tiles(int left, int all_threads, int k) {
    all_threads = std::max(1, all_threads);
    k = std::max(1, k);
    return std::min(left, std::max(k, (left + 2 * all_threads - 1) / (2 * all_threads) * k));
}

std::string format_reports(const std::vector<RankReport>& reports) {
    std::uint64_t tiles = 0;
    for (const RankReport& r : reports) tiles += r.tiles;
    std::string s = "rank  host                  threads   tiles   share   busy (s)   idle (s)\n";
    for (const RankReport& r : reports) {
        s += fmt::format("{:>4}  {:<20.20}  {:>7}  {:>6}  {:>5.1f} %  {:>9.2f}  {:>9.2f}\n", r.rank, r.host,
                         r.threads, r.tiles, tiles ? 100.0 * static_cast<double>(r.tiles) / static_cast<double>(tiles) : 0.0,
                         r.busy, r.idle);
    }
    return s;
}

std::string format_frame_reports(const std::vector<FrameReport>& reports) {
    int frames = 0;
    for (const FrameReport& r : reports) frames += r.frames;
    std::string s = "rank  frames   share   busy (s)   idle (s)\n";
    for (const FrameReport& r : reports) {
        s += fmt::format("{:>4}  {:>6}  {:>5.1f} %  {:>9.2f}  {:>9.2f}\n", r.rank, r.frames,
                         frames ? 100.0 * r.frames / frames : 0.0, r.busy, std::max(0.0, r.wall - r.busy));
    }
    return s;
}

// ---- rank 0 ----

struct Coordinator::Impl {
    Transport& transport;
    ProgressiveRender& render;
    ClusterOptions options;
    std::uint64_t fingerprint;
    Clock::time_point start = Clock::now();
    std::uint32_t pass = 0;
    std::vector<RankReport> reports;
    std::vector<int> threads;  // each rank's, as it reported (1 until then)
    bool finished = false;

    // The pass under way.
    int n = 0, tiles = 0;
    std::unique_ptr<std::atomic<std::uint8_t>[]> owner;  // 1: a result is in (or rank 0 is rendering it)
    std::atomic<int> done{0};
    std::atomic<std::uint64_t> rays{0}, samples{0};
    std::mutex mutex;  // guards the queue, the chunks out and the waiting ranks
    std::deque<int> queue;
    struct Chunk {
        std::vector<int> tiles;
        Clock::time_point issued;
    };
    std::vector<std::optional<Chunk>> out;  // per rank
    std::vector<int> waiting;               // ranks that asked when nothing was left
    double seconds_per_tile_sample = 0;     // one thread; measured
    std::atomic<bool> stop_local{false};
    std::atomic<std::uint64_t> local_tiles{0};
    std::atomic<double> local_busy{0};

    Impl(Transport& t, ProgressiveRender& r, const ClusterOptions& o, std::uint64_t f)
        : transport(t), render(r), options(o), fingerprint(f), reports(static_cast<std::size_t>(t.size())),
          threads(static_cast<std::size_t>(t.size()), 1), out(static_cast<std::size_t>(t.size())) {
        threads[0] = std::max(1, o.threads);
        for (int i = 0; i < t.size(); ++i) reports[static_cast<std::size_t>(i)].rank = i;
    }

    // A chunk for a rank of `k` threads: guided, so that chunks shrink as the queue does and the
    // pass ends together on every rank; at least one tile per thread. Caller holds the mutex.
    std::vector<int> take(int k) {
        int all = 0;
        for (int t : threads) all += t;
        const int size = chunk_tiles(static_cast<int>(queue.size()), all, k);
        std::vector<int> chunk(queue.begin(), queue.begin() + size);
        queue.erase(queue.begin(), queue.begin() + size);
        return chunk;
    }

    void send_chunk(int rank, std::vector<int> chunk) {
        std::vector<std::uint8_t> bytes;
        put(bytes, pass);
        put(bytes, static_cast<std::uint32_t>(chunk.size()));
        for (int t : chunk) {
            put(bytes, static_cast<std::int32_t>(t));
            render.pack_tile(t, bytes, /*before=*/true);
        }
        out[static_cast<std::size_t>(rank)] = Chunk{std::move(chunk), Clock::now()};
        transport.send(rank, kTiles, std::move(bytes));
    }

    // Hands the tiles of chunks out too long back to the queue (their late results still count
    // if they come first), then serves the ranks waiting for work. Caller holds the mutex.
    void reissue_and_serve() {
        for (std::size_t r = 1; r < out.size(); ++r) {
            if (!out[r]) continue;
            const Chunk& c = *out[r];
            const double expected = static_cast<double>(c.tiles.size()) * n * seconds_per_tile_sample /
                                    std::max(1, threads[r]);
            if (since(c.issued) <= std::max(options.timeout, 4 * expected)) continue;
            for (int t : c.tiles)
                if (!owner[static_cast<std::size_t>(t)].load()) queue.push_back(t);
            out[r].reset();
        }
        while (!waiting.empty() && !queue.empty()) {
            const int r = waiting.back();
            waiting.pop_back();
            send_chunk(r, take(threads[static_cast<std::size_t>(r)]));
        }
    }

    void handle(const Message& m) {
        const auto r = static_cast<std::size_t>(m.source);
        if (m.source <= 0 || m.source >= transport.size()) return;
        if (m.tag == kFail) {
            throw IoError(fmt::format("rank {}: {}", m.source, std::string(m.bytes.begin(), m.bytes.end())));
        }
        if (m.tag == kWantFiles) {
            send_files(transport, m.source, options.files);
            return;
        }
        if (m.tag != kResult) return;  // a rank's bye comes only after a stop
        std::lock_guard lock(mutex);
        std::size_t at = 0;
        const auto h = get<ResultHeader>(m, at);
        threads[r] = std::max(1, static_cast<int>(h.threads));
        if (h.pass != pass) return;  // a stalled rank's result of a pass already over
        std::uint64_t accepted = 0;
        for (std::uint32_t i = 0; i < h.count; ++i) {
            const auto e = get<TileEntry>(m, at);
            if (e.tile < 0 || e.tile >= tiles) throw IoError(fmt::format("rank {} sent tile {}", m.source, e.tile));
            const std::size_t size = render.tile_bytes(e.tile);
            if (m.bytes.size() - at < size) throw IoError(fmt::format("rank {}: tile {} cut short", m.source, e.tile));
            std::uint8_t expected = 0;
            if (owner[static_cast<std::size_t>(e.tile)].compare_exchange_strong(expected, 1)) {
                render.unpack_tile(e.tile, m.bytes.data() + at, size);
                rays += e.rays;
                samples += e.samples;
                ++accepted;
                RankReport& report = reports[r];
                report.tiles += 1;
                report.samples += e.samples;
                done.fetch_add(1);
                if (progress) progress->tile_done(e.samples, e.rays);
            }
            at += size;
        }
        if (out[r] && h.count > 0) out[r].reset();
        if (queue.empty()) {
            waiting.push_back(m.source);
        } else {
            send_chunk(m.source, take(threads[r]));
        }
    }

    Progress* progress = nullptr;

    // Rank 0's own rendering, on a thread of its own.
    void render_locally(const std::atomic<bool>* cancel) {
        tbb::task_arena arena(threads[0]);
        for (;;) {
            std::vector<int> chunk;
            {
                std::lock_guard lock(mutex);
                chunk = take(threads[0]);
            }
            if (chunk.empty()) {
                if (stop_local.load() || done.load() == tiles) return;
                std::this_thread::sleep_for(std::chrono::milliseconds(1));
                continue;
            }
            const auto t0 = Clock::now();
            arena.execute([&] {
                tbb::parallel_for(std::size_t{0}, chunk.size(), std::size_t{1}, [&](std::size_t i) {
                    if (stop_local.load(std::memory_order_relaxed) || (cancel && cancel->load(std::memory_order_relaxed)))
                        return;
                    const int t = chunk[i];
                    std::uint8_t expected = 0;
                    if (!owner[static_cast<std::size_t>(t)].compare_exchange_strong(expected, 1)) return;
                    RayCounter counter;
                    const std::uint64_t taken = render.render_tile(t, counter);
                    rays += counter.rays;
                    samples += taken;
                    local_tiles.fetch_add(1);
                    done.fetch_add(1);
                    if (progress) progress->tile_done(taken, counter.rays);
                });
            });
            local_busy.store(local_busy.load() + since(t0));
        }
    }
};

Coordinator::Coordinator(Transport& transport, ProgressiveRender& render, const ClusterOptions& options,
                         std::uint64_t fingerprint)
    : impl_(std::make_unique<Impl>(transport, render, options, fingerprint)) {}

Coordinator::~Coordinator() = default;

bool Coordinator::run_pass(int n, const std::atomic<bool>* cancel, Progress* progress) {
    Impl& s = *impl_;
    s.n = s.render.begin_pass(n);
    if (s.n <= 0) return true;
    s.tiles = s.render.tile_count();
    ++s.pass;
    s.owner = std::make_unique<std::atomic<std::uint8_t>[]>(static_cast<std::size_t>(s.tiles));
    for (int t = 0; t < s.tiles; ++t) s.owner[static_cast<std::size_t>(t)].store(0);
    s.done = 0;
    s.rays = 0;
    s.samples = 0;
    s.progress = progress;
    s.stop_local = false;
    {
        std::lock_guard lock(s.mutex);
        s.queue.clear();
        for (int t = 0; t < s.tiles; ++t) s.queue.push_back(t);
        for (auto& c : s.out) c.reset();
        s.waiting.clear();
    }
    const auto start = Clock::now();
    // The pass to every rank; they ask for tiles when they have it. Each chunk then carries its
    // tiles' sums, so the state crosses the network once a pass, not once per rank.
    std::vector<std::uint8_t> bytes;
    put(bytes, PassHeader{s.pass, s.n, s.fingerprint});
    const std::vector<std::uint8_t> header = s.render.pack_header();
    bytes.insert(bytes.end(), header.begin(), header.end());
    for (int r = 1; r < s.transport.size(); ++r) s.transport.send(r, kPass, bytes);

    std::thread local([&s, cancel] { s.render_locally(cancel); });
    struct Join {
        Impl& s;
        std::thread& t;
        ~Join() {
            s.stop_local = true;
            if (t.joinable()) t.join();
        }
    } join{s, local};

    bool cancelled = false;
    // Polling backs off while nothing comes (to 2 ms: a probe of Open MPI costs the render thread
    // on the same core) and starts again at 50 us after each message.
    int idle_us = 50;
    while (s.done.load() < s.tiles) {
        if (cancel && cancel->load()) {
            cancelled = true;
            break;
        }
        bool any = false;
        Message m;
        while (s.transport.receive(m)) {
            any = true;
            s.handle(m);
        }
        {
            std::lock_guard lock(s.mutex);
            s.reissue_and_serve();
        }
        if (any) {
            idle_us = 50;
        } else {
            std::this_thread::sleep_for(std::chrono::microseconds(idle_us));
            idle_us = std::min(2000, idle_us * 2);
        }
    }
    s.stop_local = true;
    local.join();
    if (cancelled) return false;
    const double seconds = since(start);
    std::uint64_t sampled = s.samples.load();
    if (sampled > 0) {
        double threads = 0;
        for (int t : s.threads) threads += t;
        s.seconds_per_tile_sample = seconds * threads / (static_cast<double>(s.tiles) * s.n);
    }
    s.render.end_pass(seconds, s.rays.load(), sampled);
    return true;
}

std::vector<RankReport> Coordinator::finish() {
    Impl& s = *impl_;
    s.finished = true;
    for (int r = 1; r < s.transport.size(); ++r) s.transport.send(r, kStop, {});
    int left = s.transport.size() - 1;
    std::string failure;
    while (left > 0) {
        const Message m = wait_message(s.transport);
        if (m.source <= 0 || m.source >= s.transport.size()) continue;
        if (m.tag == kFail && failure.empty())
            failure = fmt::format("rank {}: {}", m.source, std::string(m.bytes.begin(), m.bytes.end()));
        if (m.tag != kBye) continue;
        std::size_t at = 0;
        const auto h = get<ByeHeader>(m, at);
        RankReport& r = s.reports[static_cast<std::size_t>(m.source)];
        r.host = std::string(m.bytes.begin() + static_cast<std::ptrdiff_t>(at), m.bytes.end());
        r.threads = h.threads;
        r.busy = h.busy;
        r.idle = std::max(0.0, h.wall - h.busy);
        --left;
    }
    s.transport.flush();
    RankReport& me = s.reports[0];
    me.host = host_name();
    me.threads = s.threads[0];
    me.tiles = s.local_tiles.load();
    me.busy = s.local_busy.load();
    me.idle = std::max(0.0, since(s.start) - me.busy);
    if (!failure.empty()) throw IoError(failure);
    return s.reports;
}

void stop_ranks(Transport& transport) noexcept {
    try {
        for (int r = 1; r < transport.size(); ++r) transport.send(r, kStop, {});
        int left = transport.size() - 1;
        while (left > 0)
            if (wait_message(transport).tag == kBye) --left;
        transport.flush();
    } catch (...) {
    }
}

// A stall of the test-only fault hook, for a rank rendering whole frames.
void stall_once(int rank) {
    static bool done = false;
    if (done) return;
    done = true;
    if (const double s = stall_seconds(rank); s > 0) std::this_thread::sleep_for(std::chrono::duration<double>(s));
}

std::vector<FrameReport> dispatch_frames(Transport& transport, const std::vector<double>& frames,
                                         std::uint64_t fingerprint, const SceneFiles& files,
                                         const std::function<std::optional<std::vector<std::uint8_t>>(double)>& render_here,
                                         const std::function<void(double, int, const std::vector<std::uint8_t>&)>& write,
                                         const std::atomic<bool>* cancel) {
    const int size = transport.size();
    std::vector<FrameReport> reports(static_cast<std::size_t>(size));
    for (int r = 0; r < size; ++r) reports[static_cast<std::size_t>(r)].rank = r;
    std::mutex mutex;
    std::deque<double> queue(frames.begin(), frames.end());
    std::set<double> done;
    std::map<double, std::set<int>> working;  // frame -> the ranks rendering it (duplicates: stragglers)
    std::vector<Clock::time_point> given_at(static_cast<std::size_t>(size));  // when rank r got its frame
    std::map<std::pair<int, double>, std::vector<std::uint8_t>> incoming;
    std::exception_ptr local_error;
    std::atomic<bool> local_done{false};
    const auto start = Clock::now();

    // The next frame for rank r: one nobody has, else a duplicate of the frame rendered by the
    // fewest ranks (a straggler's), else none.
    const auto next = [&](int r) -> std::optional<double> {
        std::lock_guard lock(mutex);
        if (!queue.empty()) {
            const double f = queue.front();
            queue.pop_front();
            working[f].insert(r);
            return f;
        }
        std::optional<double> best;
        for (const auto& [f, ranks] : working)
            if (!done.count(f) && !ranks.count(r) && ranks.size() < 2 && (!best || f < *best)) best = f;
        if (best) working[*best].insert(r);
        return best;
    };
    const auto finished = [&](double f, int r) {  // true if f was not done before
        std::lock_guard lock(mutex);
        working[f].erase(r);
        return done.insert(f).second;
    };
    const auto give = [&](int r) {
        const std::optional<double> f = next(r);
        given_at[static_cast<std::size_t>(r)] = Clock::now();
        if (f) {
            std::vector<std::uint8_t> bytes;
            put(bytes, *f);
            put(bytes, fingerprint);
            transport.send(r, kFrameWhole, std::move(bytes));
        }
    };

    // Rank 0 renders frames too, on a thread of its own; this thread serves the messages.
    std::thread local([&] {
        try {
            while (!(cancel && cancel->load())) {
                const std::optional<double> f = next(0);
                if (!f) break;
                const auto t0 = Clock::now();
                const std::optional<std::vector<std::uint8_t>> image = render_here(*f);
                reports[0].busy += since(t0);
                if (!image) break;  // interrupted: the frame is not written
                if (finished(*f, 0)) {  // unless another rank's copy came first
                    write(*f, 0, *image);
                    std::lock_guard lock(mutex);
                    ++reports[0].frames;
                }
            }
        } catch (...) {
            local_error = std::current_exception();
        }
        local_done = true;
    });
    // A piece of a rank's image file; true when it completes the file, which is written unless
    // another rank's copy of the frame came first.
    const auto take_piece = [&](const Message& m) {
        std::size_t at = 0;
        const auto h = get<FramePiece>(m, at);
        const std::size_t piece = m.bytes.size() - at;
        if (h.size > (std::uint64_t{1} << 40) || h.offset > h.size || piece > h.size - h.offset)
            throw IoError(fmt::format("rank {} sent a piece of frame {} out of place", m.source, h.frame));
        auto& buffer = incoming[{m.source, h.frame}];
        if (buffer.size() != h.size) buffer.assign(h.size, 0);
        std::copy(m.bytes.begin() + static_cast<std::ptrdiff_t>(at), m.bytes.end(),
                  buffer.begin() + static_cast<std::ptrdiff_t>(h.offset));
        if (h.offset + piece < h.size) return false;
        const std::vector<std::uint8_t> image = std::move(buffer);
        incoming.erase({m.source, h.frame});
        // Busy from the hand-out to the image's arrival (loading, rendering, sending), a
        // discarded duplicate's too.
        reports[static_cast<std::size_t>(m.source)].busy += since(given_at[static_cast<std::size_t>(m.source)]);
        if (finished(h.frame, m.source)) {
            write(h.frame, m.source, image);
            ++reports[static_cast<std::size_t>(m.source)].frames;
        }
        return true;
    };
    // Every rank but 0 waits for STOP and says goodbye; their frames in flight are written if
    // they arrive first (nothing finished is lost).
    const auto stop_and_collect = [&](bool write_late) {
        for (int r = 1; r < size; ++r) transport.send(r, kStop, {});
        int left = size - 1;
        while (left > 0) {
            Message m = wait_message(transport);
            if (m.tag == kBye) {
                --left;
            } else if (m.tag == kFramePiece && write_late) {
                try {
                    take_piece(m);
                } catch (const IoError&) {  // a piece out of place is dropped; the goodbyes are still awaited
                }
            }
        }
        transport.flush();
    };
    try {
        for (int r = 1; r < size; ++r) give(r);
        auto sleep = std::chrono::microseconds(50);
        for (;;) {
            {
                std::lock_guard lock(mutex);
                if (done.size() == frames.size()) break;
            }
            if (cancel && cancel->load()) break;
            if (local_done && local_error) std::rethrow_exception(local_error);
            Message m;
            if (!transport.receive(m)) {
                std::this_thread::sleep_for(sleep);
                sleep = std::min(sleep * 2, std::chrono::microseconds(2000));
                continue;
            }
            sleep = std::chrono::microseconds(50);
            if (m.source <= 0 || m.source >= size) continue;
            if (m.tag == kFail)
                throw IoError(fmt::format("rank {}: {}", m.source, std::string(m.bytes.begin(), m.bytes.end())));
            if (m.tag == kWantFiles) {
                send_files(transport, m.source, files);
                continue;
            }
            if (m.tag == kFramePiece && take_piece(m)) give(m.source);
        }
    } catch (...) {
        {  // rank 0's thread stops after its frame in flight
            std::lock_guard lock(mutex);
            queue.clear();
        }
        local.join();
        try {
            stop_and_collect(false);
        } catch (...) {
        }
        throw;
    }
    {
        std::lock_guard lock(mutex);
        queue.clear();
    }
    local.join();
    stop_and_collect(true);
    if (local_error) std::rethrow_exception(local_error);
    const double wall = since(start);
    for (FrameReport& r : reports) r.wall = wall;
    return reports;
}

void send_frame_image(Transport& transport, double frame, const std::vector<std::uint8_t>& image) {
    stall_once(transport.rank());
    std::uint64_t offset = 0;
    do {
        const std::uint64_t piece = std::min<std::uint64_t>(kFilePiece, image.size() - offset);
        std::vector<std::uint8_t> bytes;
        put(bytes, FramePiece{frame, image.size(), offset});
        bytes.insert(bytes.end(), image.begin() + static_cast<std::ptrdiff_t>(offset),
                     image.begin() + static_cast<std::ptrdiff_t>(offset + piece));
        transport.send(0, kFramePiece, std::move(bytes));
        offset += piece;
    } while (offset < image.size());
}

void send_failure(Transport& transport, const std::string& text) {
    transport.send(0, kFail, std::vector<std::uint8_t>(text.begin(), text.end()));
}

void send_frame(Transport& transport, double frame) {
    for (int r = 1; r < transport.size(); ++r) {
        std::vector<std::uint8_t> bytes;
        put(bytes, frame);
        transport.send(r, kFrame, std::move(bytes));
    }
}

// ---- the other ranks ----

std::optional<FrameOrder> wait_frame(Transport& transport) {
    const auto start = Clock::now();
    for (;;) {
        Message m = wait_message(transport);
        if (m.source != 0) continue;
        if (m.tag == kStop) {
            send_bye(transport, 0, 0, 0, 0, since(start));
            return std::nullopt;
        }
        if (m.tag == kFrame || m.tag == kFrameWhole) {
            std::size_t at = 0;
            FrameOrder order{get<double>(m, at), m.tag == kFrameWhole, 0};
            if (order.whole) order.fingerprint = get<std::uint64_t>(m, at);
            return order;
        }
    }
}

std::optional<SceneFiles> fetch_scene_files(Transport& transport, const std::filesystem::path& folder,
                                            std::deque<Message>& pending) {
    namespace fs = std::filesystem;
    const auto start = Clock::now();
    transport.send(0, kWantFiles, {});
    std::ofstream out;
    fs::path current;
    for (;;) {
        Message m = wait_message(transport);
        if (m.source != 0) continue;
        if (m.tag == kStop) {
            send_bye(transport, 0, 0, 0, 0, since(start));
            return std::nullopt;
        }
        if (m.tag == kFile) {
            std::size_t at = 0;
            const auto h = get<FileHeader>(m, at);
            if (m.bytes.size() - at < h.path_bytes) throw IoError("rank 0 sent a file message cut short");
            const fs::path path(std::string(m.bytes.begin() + static_cast<std::ptrdiff_t>(at),
                                            m.bytes.begin() + static_cast<std::ptrdiff_t>(at + h.path_bytes)));
            at += h.path_bytes;
            // Rank 0's paths are absolute and normal; anything else could write outside the copy.
            const bool safe = path.is_absolute() && path == path.lexically_normal() &&
                              std::none_of(path.begin(), path.end(), [](const fs::path& c) { return c == ".."; });
            if (!safe) throw IoError(fmt::format("rank 0 sent a file named {}", path.string()));
            const fs::path copy = folder / path.relative_path();
            if (h.offset == 0) {
                out.close();
                fs::create_directories(copy.parent_path());
                out.open(copy, std::ios::binary | std::ios::trunc);
                current = copy;
            } else if (copy != current) {
                throw IoError(fmt::format("rank 0 sent a piece of {} out of order", path.string()));
            }
            out.write(reinterpret_cast<const char*>(m.bytes.data() + at), static_cast<std::streamsize>(m.bytes.size() - at));
            if (!out) throw IoError(fmt::format("{}: cannot write the copy of rank 0's file", copy.string()));
            continue;
        }
        if (m.tag == kFilesEnd) {
            out.close();
            if (!out) throw IoError(fmt::format("{}: cannot write the copy of rank 0's file", current.string()));
            std::size_t at = 0;
            const auto ok = get<std::uint32_t>(m, at);
            const std::string text(m.bytes.begin() + static_cast<std::ptrdiff_t>(at), m.bytes.end());
            if (!ok) throw IoError(text);
            SceneFiles files;
            for (std::size_t from = 0, line = 0; from <= text.size(); ++line) {
                const std::size_t end = std::min(text.find('\n', from), text.size());
                const fs::path p = text.substr(from, end - from);
                if (line == 0) files.cwd = p;
                else files.model_folders.push_back(p);
                from = end + 1;
            }
            return files;
        }
        pending.push_back(std::move(m));  // a pass: for serve
    }
}

int serve(Transport& transport, ProgressiveRender* render, std::uint64_t fingerprint, int threads,
          const std::string& error, std::deque<Message> pending) {
    const auto start = Clock::now();
    const int rank = transport.rank();
    const std::string host = host_name();
    bool failed = !error.empty() || !render;
    if (failed) {
        const std::string text = error.empty() ? std::string("could not load the scene") : error;
        transport.send(0, kFail, std::vector<std::uint8_t>(text.begin(), text.end()));
    }
    threads = std::max(1, threads);
    tbb::task_arena arena(threads);
    double stall = stall_seconds(rank);
    std::uint32_t pass = 0;
    std::uint64_t tiles_done = 0, samples_done = 0;
    double busy = 0;
    const auto request = [&](std::vector<std::uint8_t> bytes) { transport.send(0, kResult, std::move(bytes)); };
    const auto header = [&](std::uint32_t count) {
        std::vector<std::uint8_t> bytes;
        put(bytes, ResultHeader{pass, count, threads, 0});
        return bytes;
    };
    for (;;) {
        Message m;
        if (!pending.empty()) {
            m = std::move(pending.front());
            pending.pop_front();
        } else {
            m = wait_message(transport);
        }
        if (m.source != 0) continue;
        if (m.tag == kStop) {
            send_bye(transport, threads, tiles_done, samples_done, busy, since(start));
            return 0;
        }
        if (failed) continue;
        try {
            if (m.tag == kPass) {
                std::size_t at = 0;
                const auto h = get<PassHeader>(m, at);
                if (h.fingerprint != fingerprint) {
                    throw IoError(fmt::format(
                        "on {} the scene, its files or the options differ from rank 0's (each rank loads the "
                        "scene itself: give every node the same files)", host));
                }
                render->unpack_header(m.bytes.data() + at, m.bytes.size() - at);
                render->begin_pass(h.n);
                pass = h.pass;
                request(header(0));
            } else if (m.tag == kTiles) {
                std::size_t at = 0;
                const auto p = get<std::uint32_t>(m, at);
                const auto count = get<std::uint32_t>(m, at);
                if (p != pass) continue;  // for a pass already over
                std::vector<int> chunk(count);
                for (auto& t : chunk) {
                    t = get<std::int32_t>(m, at);
                    if (t < 0 || t >= render->tile_count()) throw IoError(fmt::format("rank 0 sent tile {}", t));
                    const std::size_t size = render->tile_bytes(t);
                    if (m.bytes.size() - at < size) throw IoError(fmt::format("rank 0: tile {} cut short", t));
                    render->unpack_tile(t, m.bytes.data() + at, size, /*before=*/true);
                    at += size;
                }
                std::vector<TileEntry> entries(count);
                const auto t0 = Clock::now();
                arena.execute([&] {
                    tbb::parallel_for(std::size_t{0}, chunk.size(), std::size_t{1}, [&](std::size_t i) {
                        RayCounter counter;
                        const std::uint64_t taken = render->render_tile(chunk[i], counter);
                        entries[i] = TileEntry{chunk[i], 0, counter.rays, taken};
                    });
                });
                std::vector<std::uint8_t> bytes = header(count);
                for (const TileEntry& e : entries) {
                    put(bytes, e);
                    render->pack_tile(e.tile, bytes);
                    samples_done += e.samples;
                }
                tiles_done += count;
                busy += since(t0);
                if (stall > 0) {
                    std::this_thread::sleep_for(std::chrono::duration<double>(stall));
                    stall = 0;
                }
                request(std::move(bytes));
            }
        } catch (const std::exception& e) {
            failed = true;
            const std::string text = e.what();
            transport.send(0, kFail, std::vector<std::uint8_t>(text.begin(), text.end()));
        }
    }
}

}  // namespace glint
