// glint: the command line. The only place that prints diagnostics and chooses an exit status.
#include <sched.h>
#include <signal.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <fmt/core.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <mutex>
#include <memory>
#include <new>
#include <numbers>
#include <optional>
#include <string>
#include <thread>

#include "glint/demo_scene.h"
#include "glint/film/film.h"
#include "glint/builder/build.h"
#include "glint/base/limits.h"
#include "glint/session/checkpoint.h"
#include "glint/image/tev.h"
#include "glint/formats/pbrt.h"
#include "glint/image/image_io.h"
#include "glint/formats/scene_writer.h"
#include "glint/formats/scene_yaml.h"
#include "glint/render/distributed.h"
#include "glint/render/progressive.h"
#include "glint/render/ray_bench.h"
#include "glint/render/render.h"

namespace {

struct RenderArgs {
    std::string scene;
    std::string output;
    std::optional<long long> width, height, spp, threads, max_depth;
    std::optional<std::uint64_t> seed;
    bool quiet = false;
    bool aovs = false;
    bool strict = false;
    std::string accel;
    std::string camera;
    // Long renders.
    std::string time, checkpoint, checkpoint_every = "5m", resume, display;
    std::optional<double> noise_threshold;
    std::optional<long long> min_spp;
    // Distributed rendering (mpirun).
    double rank_timeout = 60;
    // Animation: --frames A:B and --fps; `frame` is the one being rendered, `animation` says a
    // frame of --frames is (an interrupted frame is then not written: it is rendered again).
    std::string frames;
    std::optional<double> fps;
    double frame = 0;
    bool animation = false;
    // Under mpirun, a frame this process renders whole, alone (an animation's frames handed out whole).
    bool local = false;
    std::string scene_label;  // the scene as the image's metadata names it, if not `scene` (a copy's)
};

// Exit status of a render stopped by SIGINT or SIGTERM (the image of the completed passes, if
// any, was written): distinct from success (0) and errors (1).
constexpr int kExitInterrupted = 3;

// Signals: the first SIGINT or SIGTERM only raises a flag the render loop polls between tiles;
// a second one removes the temporary files being written (if any) and exits at once. Nothing in
// the handler allocates, locks or throws.
std::atomic<bool> g_stop{false};
volatile std::sig_atomic_t g_signal = 0;
// An MPI job's messages (distributed.h), when mpirun started this process; g_ranks_stopped once
// rank 0 has told the other ranks to stop.
std::unique_ptr<glint::Transport> g_cluster;
bool g_ranks_stopped = false;
// Rank 0 of a distributed animation: the other ranks wait for the next frame between frames, and
// must be stopped there too.
bool g_animation_ranks = false;
// --restrict-paths was given (a rank loading a copy of rank 0's files restricts reads to it).
bool g_restrict_paths = false;
char g_temporary[2][4096];  // the image's and the checkpoint's temporary files, or empty
static_assert(std::atomic<bool>::is_always_lock_free);

extern "C" void on_signal(int sig) {
    if (g_signal != 0) {
        for (const char* path : g_temporary)
            if (path[0] != '\0') ::unlink(path);
        ::_exit(128 + sig);
    }
    g_signal = sig;
    g_stop.store(true, std::memory_order_relaxed);
}

void remember_temporary(int slot, const std::filesystem::path& target) {
    const std::string t = glint::temporary_path(target).string();
    if (t.size() < sizeof g_temporary[slot]) std::memcpy(g_temporary[slot], t.c_str(), t.size() + 1);
}

void install_signal_handlers() {
    struct sigaction sa {};
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = SA_RESTART;
    ::sigaction(SIGINT, &sa, nullptr);
    ::sigaction(SIGTERM, &sa, nullptr);
    // mpirun ends the job on SIGINT and SIGTERM but forwards SIGUSR1 to every rank: under MPI it
    // is the way to stop a distributed render cleanly (rank 0 acts on it, the others ignore it,
    // also while they render a whole frame of an animation through run_render).
    if (g_cluster && g_cluster->rank() == 0) ::sigaction(SIGUSR1, &sa, nullptr);
}

const char* signal_name(int sig) {
    return sig == SIGTERM ? "SIGTERM" : sig == SIGUSR1 ? "SIGUSR1" : "SIGINT";
}

std::optional<glint::AccelKind> parse_accel(const std::string& name) {
    if (name.empty()) return std::nullopt;
    if (name == "bvh") return glint::AccelKind::kBvh;
    if (name == "sbvh") return glint::AccelKind::kSbvh;
    if (name == "embree") return glint::AccelKind::kEmbree;
    throw glint::IoError(fmt::format("--accel: unknown backend '{}' (known: bvh, sbvh, embree)", name));
}

bool is_mesh_file(const std::string& path) { return glint::mesh_format(path).has_value(); }

// A mesh file rendered directly: the mesh under a sky, path traced, seen from the front
// (-z side) and a little above, framed by its bounds; the camera is placed after loading.
glint::SceneDescription mesh_file_scene(const std::string& path, const std::string& camera) {
    glint::SceneDescription d;
    d.path = path;
    d.integrator.kind = glint::IntegratorKind::kPath;
    d.background = glint::SkyBackground{};  // a default environment: the sky lights the model
    d.film.width.value = 800;
    d.film.height.value = 600;
    d.sampler.spp.value = 64;
    glint::ObjectDesc o;
    glint::MeshFileDesc f;
    f.file.value = std::filesystem::path(path).filename().string();
    f.file.loc = {"<command line>", 0, 0};
    f.camera = camera;
    o.shape = f;
    o.material_given = false;
    d.objects.push_back(o);
    return d;
}

// The automatic camera for a model without one: from the front (-z side), a little above and to
// the right, 40 degrees vertical, every corner of the model's bounds inside 90 % of the frame.
void frame_bounds(glint::RenderJob& job) {
    const glint::Bounds3 b = job.scene.bounds();
    if (b.empty()) return;
    job.camera = glint::frame_box(b, {0.35f, 0.35f, -1}, {0, 1, 0}, 40, job.width, job.height);
}

glint::RenderJob load_job(const RenderArgs& args) {
    auto sources = std::make_shared<glint::SourceFiles>();
    const bool mesh = !args.scene.empty() && is_mesh_file(args.scene);
    glint::SceneDescription description =
        args.scene.empty() ? glint::parse_scene(glint::kDemoScene, glint::kDemoSceneName, sources, args.frame)
        : mesh             ? mesh_file_scene(args.scene, args.camera)
        : glint::is_pbrt_file(args.scene) ? glint::load_pbrt_file(args.scene, sources, {args.strict})
                           : glint::load_scene_file(args.scene, sources, args.frame);
    description.frame = args.frame;
    if (args.fps) {
        if (!(*args.fps > 0) || !std::isfinite(*args.fps) || *args.fps > 1e6)
            throw glint::IoError(fmt::format("--fps {}: must be a number above 0", *args.fps));
        description.fps = *args.fps;
    }
    glint::Overrides overrides;
    overrides.width = args.width;
    overrides.height = args.height;
    overrides.spp = args.spp;
    overrides.max_depth = args.max_depth;
    overrides.threads = args.threads;
    overrides.seed = args.seed;
    overrides.aovs = args.aovs;
    overrides.accel = parse_accel(args.accel);
    glint::RenderJob job = glint::build(description, overrides, sources);
    if (mesh) {
        if (job.file_camera) {  // the file's own camera
            const glint::GltfCamera& c = *job.file_camera;
            if (c.orthographic) {
                job.camera = glint::Camera::orthographic(c.position, c.direction, c.up, 2 * c.ymag, job.width, job.height);
            } else {
                job.camera = glint::Camera::look_at(c.position, c.position + c.direction, c.up, c.yfov_degrees,
                                                    job.width, job.height);
            }
        } else {
            frame_bounds(job);
        }
    }
    if (!args.camera.empty() && !mesh)
        throw glint::IoError("--camera chooses a camera of a glTF file rendered directly; a scene file has its own");
    if (!args.quiet)
        for (const std::string& n : job.notes) fmt::print(stderr, "glint: note: {}\n", n);
    return job;
}

// Where the image goes: -o, else the scene's film.filename, else <scene stem>.png in the current
// folder (glint.png for the built-in demo).
std::filesystem::path output_path(const RenderArgs& args, const glint::RenderJob& job) {
    if (!args.output.empty()) return args.output;
    if (!job.filename.empty()) return job.filename;
    if (args.scene.empty()) return "glint.png";
    return std::filesystem::path(args.scene).stem().string() + ".png";
}

std::string bytes(std::uint64_t b) {
    if (b >= (1ull << 30)) return fmt::format("{:.2f} GiB", b / double(1ull << 30));
    if (b >= (1ull << 20)) return fmt::format("{:.2f} MiB", b / double(1ull << 20));
    if (b >= (1ull << 10)) return fmt::format("{:.1f} KiB", b / double(1ull << 10));
    return fmt::format("{} B", b);
}

// glint convert: the scene description written back as YAML, atomically (a temporary file,
// then a rename), after the scene has been checked by building it.
int run_convert(const RenderArgs& args, const std::string& out) {
    auto sources = std::make_shared<glint::SourceFiles>();
    const glint::SceneDescription d = glint::is_pbrt_file(args.scene)
                                          ? glint::load_pbrt_file(args.scene, sources, {args.strict})
                                          : glint::load_scene_file(args.scene, sources);
    (void)glint::build(d, {}, sources);  // every error of the source, before anything is written
    if (!args.quiet)
        for (const auto& w : d.warnings) fmt::print(stderr, "glint: note: {}", glint::format_warning(w, *sources));
    const glint::WrittenScene w = glint::write_scene_yaml(d, out);
    const std::filesystem::path target(out);
    const std::filesystem::path tmp = target.string() + ".tmp";
    {
        std::ofstream f(tmp, std::ios::binary);
        f << w.yaml;
        f.close();
        if (!f) throw glint::IoError(fmt::format("{}: cannot write", tmp.string()));
    }
    std::filesystem::rename(tmp, target);
    fmt::print("wrote {}{}\n", out, w.meshes.empty() ? "" : fmt::format(" and {} mesh or grid file{}", w.meshes.size(), w.meshes.size() == 1 ? "" : "s"));
    return 0;
}

int run_info(const RenderArgs& args) {
    glint::RenderJob job = load_job(args);
    const glint::SceneInfo i = glint::scene_info(job.scene);
    fmt::print("scene        {}\n", args.scene.empty() ? "(built-in demo)" : args.scene);
    fmt::print("triangles    {} rendered, {} stored\n", i.triangles, i.unique_triangles);
    fmt::print("meshes       {} ({} vertices), {} instances\n", i.meshes, i.vertices, i.instances);
    fmt::print("other shapes {}\n", i.analytic_shapes);
    fmt::print("lights       {} (area lights included)\n", job.scene.light_sampler().count());
    for (std::size_t k = 0; k < job.file_cameras.size(); ++k) {
        const glint::GltfCamera& c = job.file_cameras[k];
        const std::string kind = c.orthographic ? fmt::format("orthographic, {:.4g} high", 2 * c.ymag)
                                                : fmt::format("perspective, {:.3g} degrees", c.yfov_degrees);
        const auto& u = job.file_camera;  // the same camera: every field alike (unnamed ones too)
        const bool used = u && u->name == c.name && u->position == c.position && u->direction == c.direction &&
                          u->orthographic == c.orthographic && u->yfov_degrees == c.yfov_degrees && u->ymag == c.ymag;
        fmt::print("{}{} ({}) at [{:.4g}, {:.4g}, {:.4g}] looking [{:.3g}, {:.3g}, {:.3g}]{}\n",
                   k == 0 ? "cameras      " : "             ", c.name.empty() ? "(unnamed)" : c.name, kind,
                   c.position.x, c.position.y, c.position.z, c.direction.x, c.direction.y, c.direction.z,
                   used ? " (used)" : "");
    }
    if (!job.scene.media.empty()) {
        std::size_t grids = 0, voxel_bytes = 0, bricks = 0;
        for (const glint::Medium& m : job.scene.media) {
            if (const auto* g = std::get_if<glint::GridMedium>(&m)) {
                ++grids;
                voxel_bytes += g->density.memory_bytes() + g->emission.memory_bytes();
                bricks += g->density.brick_count() + g->emission.brick_count();
            }
        }
        fmt::print("media        {} ({} homogeneous, {} grid: {} bricks of 8^3 voxels, {})\n",
                   job.scene.media.size(), job.scene.media.size() - grids, grids, bricks, bytes(voxel_bytes));
    }
    if (!i.bounds.empty())
        fmt::print("bounds       [{:.4g}, {:.4g}, {:.4g}] .. [{:.4g}, {:.4g}, {:.4g}]\n", i.bounds.lo.x,
                   i.bounds.lo.y, i.bounds.lo.z, i.bounds.hi.x, i.bounds.hi.y, i.bounds.hi.z);
    fmt::print("memory       meshes {}, acceleration ({}) {}", bytes(i.mesh_bytes),
               glint::accel_name(job.scene.accel), bytes(i.accel_bytes));
    if (i.unique_triangles > 0)
        fmt::print(" = {:.1f} bytes per stored triangle", double(i.accel_bytes) / double(i.unique_triangles));
    fmt::print("\n");
    if (job.scene.accel != glint::AccelKind::kEmbree && i.meshes > 0)
        fmt::print("mesh bvh     {}-wide, {} kernel, depth {}, {} triangle references ({:.3f} per triangle)\n",
                   i.bvh_width, i.bvh_isa, i.bvh_depth, i.bvh_references,
                   i.unique_triangles ? double(i.bvh_references) / double(i.unique_triangles) : 0.0);
    return 0;
}

int run_bench(const RenderArgs& args, const std::string& set, int runs) {
    glint::RenderJob job = load_job(args);
    std::vector<glint::AccelKind> kinds{glint::AccelKind::kBvh};
    if (set == "all") kinds.push_back(glint::AccelKind::kSbvh);
    if (const auto one = set == "all" ? std::nullopt : parse_accel(set)) kinds = {*one};
    else if (GLINT_EMBREE) kinds.push_back(glint::AccelKind::kEmbree);
    const int threads = job.options.threads;
    const glint::SceneInfo info = glint::scene_info(job.scene);
    fmt::print("{}: {} triangles ({} stored), {}x{} primary rays, {} thread{}, median of {} runs (backends in turn)\n",
               args.scene.empty() ? "(built-in demo)" : args.scene, info.triangles, info.unique_triangles,
               job.width, job.height, threads > 0 ? fmt::format("{}", threads) : "all",
               threads == 1 ? "" : "s", runs);
    if (info.meshes > 0)
        fmt::print("mesh bvh: {}-wide nodes, {} kernel\n", info.bvh_width, info.bvh_isa);
    fmt::print("{:<8} {:>10} {:>12} {:>10} {:>16} {:>16}\n", "backend", "build (s)", "memory", "B/tri",
               "primary Mrays/s", "diffuse Mrays/s");
    // The rays, made once with the scene as load_job committed it, for every backend.
    const glint::BenchRays rays = glint::bench_rays(job.scene, job.camera, job.width, job.height);
    for (const glint::BenchResult& r : glint::bench_backends(job.scene, kinds, rays, threads, runs)) {
        fmt::print("{:<8} {:>10.3f} {:>12} {:>10.1f} {:>16.2f} {:>16.2f}   (hits: {} primary, {} diffuse)\n",
                   r.backend, r.build_seconds, bytes(r.accel_bytes),
                   info.unique_triangles ? double(r.accel_bytes) / double(info.unique_triangles) : 0.0,
                   r.primary_mrays, r.diffuse_mrays, r.primary_hits, r.diffuse_hits);
        std::fflush(stdout);
    }
    return 0;
}

// The options that change the image, as text: part of a checkpoint's fingerprint.
std::string image_settings(const RenderArgs& args, const glint::RenderJob& job) {
    const glint::RenderOptions& o = job.options;
    return fmt::format(
        "glint {}|film {}x{} of {}x{} at {},{}|spp {}|seed {}|sampler {}|filter {} {} {}|scale {}|"
        "noise {} min {}|aovs {}|max-depth {}|camera {}|{}",
        GLINT_VERSION, job.film_width, job.film_height, job.width, job.height, o.offset_x, o.offset_y, o.spp,
        o.seed, static_cast<int>(o.sampler), static_cast<int>(o.filter.type), o.filter.radius,
        o.filter.sigma, o.scale, o.noise_threshold, o.min_spp, job.aovs,
        args.max_depth ? *args.max_depth : -1, args.camera, args.scene.empty() ? "(demo)" : "");
}

// What the image header says about the render (EXR attributes, PNG text chunks).
glint::ImageMetadata metadata(const RenderArgs& args, int spp, int target, int passes, double seconds,
                              bool complete) {
    return {{"glint:spp", std::to_string(spp)},
            {"glint:spp_target", std::to_string(target)},
            {"glint:passes", std::to_string(passes)},
            {"glint:render_seconds", fmt::format("{:.3f}", seconds)},
            {"glint:complete", complete ? "yes" : "no"},
            {"glint:scene", args.scene_label.empty() ? args.scene : args.scene_label},
            {"Software", std::string("glint ") + GLINT_VERSION}};
}

std::string spp_text(const glint::ProgressiveRender& r) {
    if (!r.adaptive()) return fmt::format("{} spp", r.spp_done());
    const auto& s = r.state().samples;
    const double mean = static_cast<double>(r.samples_taken()) / static_cast<double>(std::max<std::size_t>(1, s.size()));
    return fmt::format("{:.1f} spp on average ({} to {} per pixel, {:.1f}% converged)", mean,
                       s.empty() ? 0 : *std::min_element(s.begin(), s.end()),
                       s.empty() ? 0 : *std::max_element(s.begin(), s.end()), 100 * r.converged_fraction());
}

// The scene and every option that changes the image: what each rank of a distributed render
// prepares alike.
glint::RenderJob prepare_job(const RenderArgs& args) {
    glint::RenderJob job = load_job(args);
    if (args.noise_threshold) {
        if (!(*args.noise_threshold > 0) || !std::isfinite(*args.noise_threshold))
            throw glint::IoError(fmt::format("--noise-threshold {}: must be a number above 0 (e.g. 0.01)",
                                             *args.noise_threshold));
        job.options.noise_threshold = static_cast<float>(*args.noise_threshold);
    }
    if (args.min_spp) {
        if (!args.noise_threshold && !(job.options.noise_threshold > 0))
            throw glint::IoError("--min-spp goes with --noise-threshold or the scene's sampler noise_threshold (adaptive sampling)");
        if (*args.min_spp < 1 || *args.min_spp > job.options.spp)
            throw glint::IoError(fmt::format("--min-spp {}: must be between 1 and the spp ({})", *args.min_spp,
                                             job.options.spp));
        job.options.min_spp = static_cast<int>(*args.min_spp);
    }
    if (g_cluster && g_cluster->size() > 1 && !args.threads) {
        // The cores this rank may use (mpirun may have bound it to some), shared with the other
        // ranks on this host unless it was bound.
        cpu_set_t set;
        int allowed = static_cast<int>(std::max(1U, std::thread::hardware_concurrency()));
        const int cores = allowed;
        if (sched_getaffinity(0, sizeof set, &set) == 0) allowed = std::max(1, CPU_COUNT(&set));
        job.options.threads = allowed < cores ? allowed : std::max(1, cores / glint::local_ranks());
    }
    return job;
}

// A private folder under $TMPDIR (or /tmp), removed with everything in it when done.
struct TempFolder {
    std::filesystem::path path;
    TempFolder() {
        const char* tmp = std::getenv("TMPDIR");
        std::string pattern = (std::filesystem::path(tmp && *tmp ? tmp : "/tmp") / "glint-rank-XXXXXX").string();
        if (!::mkdtemp(pattern.data()))
            throw glint::IoError(fmt::format("{}: cannot make a folder for rank 0's files: {}", pattern, std::strerror(errno)));
        path = pattern;
    }
    ~TempFolder() {
        std::error_code ec;
        std::filesystem::remove_all(path, ec);
    }
    TempFolder(const TempFolder&) = delete;
    TempFolder& operator=(const TempFolder&) = delete;
};

// Renders one image (defined below; `preloaded`: the job, already loaded).
int run_render(const RenderArgs& args, std::optional<glint::RenderJob> preloaded = std::nullopt);

// What every frame of an animation shares, for ranks rendering whole frames to compare: the
// options that change the image and the bytes of every file the last load read (files_read(),
// emptied before it), whatever their paths.
std::uint64_t files_fingerprint(const RenderArgs& args, const glint::RenderJob& job) {
    std::vector<std::uint64_t> files;
    for (const auto& path : glint::files_read()) {
        std::ifstream in(path, std::ios::binary);
        const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        files.push_back(glint::hash_bytes(bytes.data(), bytes.size()));
    }
    std::sort(files.begin(), files.end());
    const std::string settings = image_settings(args, job);
    std::uint64_t h = glint::hash_bytes(settings.data(), settings.size());
    return glint::hash_bytes(files.data(), files.size() * sizeof(files[0]), h);
}

// A rank whose own files failed it: asks rank 0 for the files it read, writes them into `copy`
// (made on first use) and loads `load(args)` from there: the scene as rank 0 named it, in the
// copy, and meshes found in rank 0's model folders, in the copy of them. `error` (this rank's
// own failure) gets the copy's failure added, with rank 0's paths rather than the copy's; it is
// cleared on success. False if rank 0 stopped the job first.
template <class Load>
bool load_from_rank0_copy(const RenderArgs& args, std::optional<TempFolder>& copy, std::optional<RenderArgs>& from_copy,
                          std::deque<glint::Message>& pending, std::string& error, const Load& load) {
    try {
        if (!copy) copy.emplace();
        const std::optional<glint::SceneFiles> files = glint::fetch_scene_files(*g_cluster, copy->path, pending);
        if (!files) return false;
        RenderArgs local = args;
        local.scene = (copy->path / (files->cwd / args.scene).lexically_normal().relative_path()).string();
        std::string folders;
        for (const auto& f : files->model_folders)
            folders += (folders.empty() ? "" : ":") + (copy->path / f.relative_path()).string();
        ::setenv("GLINT_MODEL_PATH", folders.c_str(), 1);
        if (g_restrict_paths) glint::restrict_reads_to({copy->path});
        from_copy = local;
        std::string again = load(local);
        if (again.empty()) {
            error.clear();
        } else {
            for (std::size_t at; (at = again.find(copy->path.string())) != std::string::npos;)
                again.erase(at, copy->path.string().size());
            error += "\nnor from the copy of the files rank 0 read: " + again;
        }
    } catch (const std::exception& e) {
        error += fmt::format("\nnor could it get rank 0's files: {}", e.what());
    }
    return true;
}

// One frame of an animation handed out by whole frames, rendered alone into a private folder:
// the image file's bytes, or nothing if the render was interrupted. (Ranks send the bytes to rank
// 0; rank 0 writes them only if no other rank's copy of the frame came first, so no two
// renders of a frame ever write its file.)
std::optional<std::vector<std::uint8_t>> render_frame_file(RenderArgs args, std::optional<glint::RenderJob> job) {
    TempFolder out;
    args.local = true;
    args.quiet = true;
    args.output = (out.path / ("frame" + std::filesystem::path(args.output).extension().string())).string();
    if (run_render(args, std::move(job)) != 0) return std::nullopt;
    std::ifstream in(args.output, std::ios::binary);
    std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (!in.good() && !in.eof()) throw glint::IoError(fmt::format("frame {}: cannot read back its image", args.frame));
    return bytes;
}

// A rank other than 0 of an animation handed out by whole frames: renders `args.frame` alone
// (from its own files, else rank 0's copy) into a private folder and sends the image file to
// rank 0. A failure goes to rank 0, which ends the job.
void run_rank_whole_frame(const RenderArgs& args, std::uint64_t expected, std::optional<TempFolder>& copy,
                          std::optional<RenderArgs>& from_copy) {
    std::optional<glint::RenderJob> job;
    RenderArgs used = args;
    const auto load = [&](const RenderArgs& a) {
        try {
            glint::forget_files_read();
            job.emplace(prepare_job(a));
            used = a;
            return std::string();
        } catch (const std::exception& e) {
            std::string what = e.what();
            while (!what.empty() && what.back() == '\n') what.pop_back();
            return what;
        }
    };
    std::string error = load(args);
    if (!job && from_copy) {
        RenderArgs a = *from_copy;
        a.frame = args.frame;
        if (load(a).empty()) error.clear();
    }
    if (!job && !args.scene.empty()) {
        std::deque<glint::Message> pending;  // rank 0 sends nothing else while a frame is out
        if (!load_from_rank0_copy(args, copy, from_copy, pending, error, load)) return;
    }
    if (!job) {
        glint::send_failure(*g_cluster, fmt::format("could not load the scene at frame {}:\n{}", args.frame, error));
        return;
    }
    if (files_fingerprint(args, *job) != expected) {
        glint::send_failure(*g_cluster, fmt::format("frame {}: the scene, its files or the options differ from rank 0's "
                                                    "(each rank loads the scene itself: give every node the same files)",
                                                    args.frame));
        return;
    }
    try {
        used.scene_label = args.scene;
        std::optional<std::vector<std::uint8_t>> bytes = render_frame_file(used, std::move(job));
        if (!bytes) throw glint::IoError(fmt::format("frame {} was interrupted", args.frame));
        glint::send_frame_image(*g_cluster, args.frame, *bytes);
    } catch (const std::exception& e) {
        glint::send_failure(*g_cluster, fmt::format("frame {}: {}", args.frame, e.what()));
    }
}

// A rank other than 0 of a distributed render: loads what rank 0 loads and renders the tiles it
// is given; what fails here is sent to rank 0, which reports it. A rank that cannot load the
// scene from its own files loads a copy of the files rank 0 read.
// `copy`: the folder of rank 0's files, kept from one frame of an animation to the next.
int run_rank_frame(const RenderArgs& args, std::optional<TempFolder>& copy, std::optional<RenderArgs>& from_copy) {
    std::optional<glint::RenderJob> job;
    std::unique_ptr<glint::ProgressiveRender> render;
    std::uint64_t fingerprint = 0;
    std::string error;
    const auto load = [&](const RenderArgs& a) {
        render.reset();  // before the scene it renders
        job.reset();
        try {
            job.emplace(prepare_job(a));
            render = std::make_unique<glint::ProgressiveRender>(job->scene, job->camera, *job->integrator,
                                                                job->options, job->film_width, job->film_height,
                                                                job->aovs);
            fingerprint = glint::render_fingerprint(*job, image_settings(a, *job));
            return std::string();
        } catch (const glint::SceneError& e) {
            std::string what = e.what();
            while (!what.empty() && what.back() == '\n') what.pop_back();
            render.reset();
            return fmt::format("could not load the scene:\n{}", what);
        } catch (const std::exception& e) {
            render.reset();
            return std::string(e.what());
        }
    };
    error = load(args);
    std::deque<glint::Message> pending;
    if (!error.empty() && from_copy) {  // an earlier frame needed rank 0's files: try the copy first
        RenderArgs local = *from_copy;
        local.frame = args.frame;
        if (load(local).empty()) error.clear();
    }
    if (!error.empty() && !args.scene.empty() &&
        !load_from_rank0_copy(args, copy, from_copy, pending, error, load))
        return 0;  // rank 0 stopped the job first
    return glint::serve(*g_cluster, render.get(), fingerprint, job ? job->options.threads : 1, error,
                        std::move(pending));
}

int run_rank(const RenderArgs& args) {
    std::optional<TempFolder> copy;  // removed when this rank is done
    std::optional<RenderArgs> from_copy;
    if (args.frames.empty()) return run_rank_frame(args, copy, from_copy);
    // An animation: one render per frame rank 0 announces, until it stops the job; a frame is
    // either shared by tiles or this rank's alone.
    while (const std::optional<glint::FrameOrder> order = glint::wait_frame(*g_cluster)) {
        RenderArgs a = args;
        a.frame = order->frame;
        a.animation = true;
        if (order->whole) {
            run_rank_whole_frame(a, order->fingerprint, copy, from_copy);
            continue;
        }
        if (const int status = run_rank_frame(a, copy, from_copy); status != 0) return status;
    }
    return 0;
}

int run_render(const RenderArgs& args, std::optional<glint::RenderJob> preloaded) {
    const bool distributed = !args.local && g_cluster && g_cluster->size() > 1;
    if (distributed && g_cluster->rank() > 0) return run_rank(args);
    glint::RenderJob job = preloaded ? std::move(*preloaded) : prepare_job(args);
    const std::filesystem::path out = output_path(args, job);
    glint::check_writable(out, job.film_width, job.film_height);  // fail before rendering, not after
    if (job.aovs && glint::image_format_for(out) != glint::ImageFormat::kExr) {
        throw glint::IoError(fmt::format(
            "{}: AOVs (albedo, normal, depth) are written as EXR channels; use an .exr output",
            out.string()));
    }
    const double budget = args.time.empty() ? -1 : glint::parse_duration(args.time, "--time");
    const double every = glint::parse_duration(args.checkpoint_every, "--checkpoint-every");
    // --resume FILE goes on writing FILE, unless --checkpoint names another.
    const std::filesystem::path checkpoint = !args.checkpoint.empty() ? args.checkpoint : args.resume;
    if (!checkpoint.empty()) {
        if (std::filesystem::weakly_canonical(checkpoint) == std::filesystem::weakly_canonical(out))
            throw glint::IoError(fmt::format("{}: the checkpoint and the image cannot be one file", out.string()));
        const auto dir = checkpoint.parent_path().empty() ? std::filesystem::path(".") : checkpoint.parent_path();
        if (!std::filesystem::is_directory(dir))
            throw glint::IoError(fmt::format("{}: cannot write: folder '{}' does not exist", checkpoint.string(), dir.string()));
    }

    const auto mode = args.quiet                 ? glint::ProgressMode::kQuiet
                      : ::isatty(::fileno(stderr)) ? glint::ProgressMode::kBar
                                                   : glint::ProgressMode::kSummary;
    const int w = job.film_width, h = job.film_height;
    const auto pixels = static_cast<std::uint64_t>(w) * static_cast<std::uint64_t>(h);
    glint::Progress progress(mode, stderr, pixels * static_cast<std::uint64_t>(std::max(1, job.options.spp)));
    remember_temporary(0, out);
    if (!checkpoint.empty()) remember_temporary(1, checkpoint);
    install_signal_handlers();
    const auto note = [&args](const std::string& text) {
        if (!args.quiet) fmt::print(stderr, "\nglint: note: {}\n", text);
    };
    const auto interrupted_status = [&args](const std::string& what) {
        if (!args.quiet)
            fmt::print(stderr, "glint: interrupted by {}: {}\n", signal_name(g_signal), what);
        return kExitInterrupted;
    };

    // The article's case (one sample, no AOVs, nothing to save or show): one sweep, no sums;
    // for PNG and PPM straight to 8-bit codes, with no float film (a 1080p film is 25 MB of
    // memory the kernel must clear and the encoder read back: docs/architecture.md).
    if (job.options.spp == 1 && !job.aovs && checkpoint.empty() && args.display.empty() && !distributed) {
        if (!glint::is_linear_format(glint::image_format_for(out))) {
            // PNG strips are encoded by the render's threads as their rows come in.
            glint::Image8Writer writer(out, w, h, job.display.encoding == glint::Encoding::kSrgb);
            const glint::RenderStats stats = glint::render_8bit(
                job.scene, job.camera, *job.integrator, job.options, job.display, w, h, writer.rgb(), &progress,
                &g_stop, [&writer](int y0, int y1) { writer.rows_ready(y0, y1); });
            if (!stats.complete) return interrupted_status(args.animation ? fmt::format("frame {} not written", args.frame) : "no pass completed; nothing written");
            writer.finish(metadata(args, 1, 1, 1, stats.seconds, true));
            progress.finish(stats, w, h, "1 spp");
            if (!args.quiet) fmt::print(stderr, "wrote {}\n", out.string());
            return 0;
        }
        glint::Film film(w, h);
        const glint::RenderStats stats =
            glint::render(job.scene, job.camera, *job.integrator, job.options, film, &progress, &g_stop);
        if (!stats.complete) return interrupted_status(args.animation ? fmt::format("frame {} not written", args.frame) : "no pass completed; nothing written");
        glint::write_image(out, film, job.display, metadata(args, 1, 1, 1, stats.seconds, true));
        progress.finish(stats, w, h, "1 spp");
        if (!args.quiet) fmt::print(stderr, "wrote {}\n", out.string());
        return 0;
    }
    glint::Film film(w, h);
    if (job.aovs) film.enable_aovs();

    glint::ProgressiveRender render(job.scene, job.camera, *job.integrator, job.options, w, h, job.aovs);
    if (render.adaptive() && glint::image_format_for(out) == glint::ImageFormat::kExr) film.enable_sample_counts();
    std::uint64_t fingerprint = 0;
    if (!checkpoint.empty() || distributed) {
        fingerprint = glint::render_fingerprint(job, image_settings(args, job));
    }
    std::optional<glint::Coordinator> cluster;
    if (distributed) {
        const int threads = job.options.threads > 0 ? job.options.threads
                                                    : static_cast<int>(std::max(1U, std::thread::hardware_concurrency()));
        // What a rank that cannot read the scene's files gets from this one.
        glint::SceneFiles files{std::filesystem::current_path(), glint::files_read(), {}};
        for (const auto& f : glint::model_folders(std::filesystem::path(args.scene).parent_path()))
            files.model_folders.push_back(std::filesystem::absolute(f).lexically_normal());
        cluster.emplace(*g_cluster, render, glint::ClusterOptions{args.rank_timeout, threads, std::move(files)},
                        fingerprint);
    }
    if (!args.resume.empty()) {
        glint::Checkpoint c = glint::read_checkpoint(args.resume);
        if (c.fingerprint != fingerprint)
            throw glint::IoError(fmt::format(
                "{}: a checkpoint of another scene or other options (the scene files, meshes, textures, "
                "camera, film, spp, seed, sampler, filter, adaptive settings and AOVs must all match); "
                "nothing rendered", args.resume));
        try {
            render.restore(std::move(c.state));
        } catch (const std::runtime_error& e) {
            throw glint::IoError(fmt::format("{}: does not fit this render: {}", args.resume, e.what()));
        }
        progress.set_done(render.samples_taken());
        if (!args.quiet)
            fmt::print(stderr, "glint: resuming {} at {} after {} pass{} ({:.1f} s)\n", args.resume,
                       spp_text(render), render.passes(), render.passes() == 1 ? "" : "es", render.state().seconds);
    }
    std::optional<glint::TevClient> display;
    if (!args.display.empty()) {
        display.emplace(args.display);
        if (!display->connected()) note(display->note());
    }
    const std::string view_name = args.scene.empty() ? "glint" : std::filesystem::path(args.scene).filename().string();

    using clock = std::chrono::steady_clock;
    const auto start = clock::now();
    auto last_checkpoint = start;
    const auto seconds_since = [](clock::time_point t) {
        return std::chrono::duration<double>(clock::now() - t).count();
    };
    const auto save = [&] {
        glint::write_checkpoint(checkpoint, fingerprint, render.state());
        last_checkpoint = clock::now();
    };
    bool interrupted = false, budget_hit = false;
    while (!render.finished()) {
        if (g_stop.load()) {
            interrupted = true;
            break;
        }
        const double left = budget >= 0 ? std::max(0.0, budget - seconds_since(start)) : -1;
        const int n = render.next_pass_size(left);
        if (n == 0) {
            budget_hit = true;
            break;
        }
        progress.pass_started({render.passes() + 1, render.spp_done(), render.spp_target(),
                               render.adaptive() ? render.converged_fraction() : -1, left,
                               render.remaining_samples()});
        const bool done = cluster ? cluster->run_pass(n, &g_stop, &progress) : render.run_pass(n, &g_stop, &progress);
        if (!done) {  // the pass in flight is abandoned
            interrupted = true;
            break;
        }
        if (display && display->connected()) {
            render.resolve(film);
            if (!display->send(view_name, film)) note(display->note());
        }
        if (!checkpoint.empty() && seconds_since(last_checkpoint) >= every && !render.finished()) save();
    }
    if (cluster) {
        g_ranks_stopped = true;  // by finish, even if it throws
        const std::vector<glint::RankReport> reports = cluster->finish();
        if (!args.quiet) fmt::print(stderr, "{}", glint::format_reports(reports));
    }
    if (interrupted && args.animation)
        return interrupted_status(fmt::format("frame {} not written; run the command again to go on from it", args.frame));
    if (render.passes() == 0) {
        if (interrupted) return interrupted_status("no pass completed; nothing written");
        if (budget_hit) throw glint::IoError("--time: the budget ended before the first pass; nothing written");
    }
    if (!checkpoint.empty()) save();
    render.resolve(film);
    const glint::ProgressiveState& state = render.state();
    glint::RenderStats stats;
    stats.complete = !interrupted;
    stats.seconds = state.seconds;
    stats.rays = state.rays;
    std::string what = spp_text(render);
    if (!render.finished()) what += fmt::format(" of {}", render.spp_target());
    if (budget_hit) what += " (time budget reached)";
    glint::write_image(out, film, job.display,
                       metadata(args, render.spp_done(), render.spp_target(), render.passes(), state.seconds,
                                render.finished()));
    progress.finish(stats, w, h, what);
    if (!args.quiet) {
        fmt::print(stderr, "wrote {}{}\n", out.string(),
                   checkpoint.empty() ? "" : fmt::format(" and checkpoint {}", checkpoint.string()));
    }
    if (interrupted) return interrupted_status(fmt::format("the image holds {} passes ({})", render.passes(), what));
    return 0;
}

// The file of frame `frame` from an output pattern: printf's %d, %0Nd or %Nd (N up to 9) once,
// %% for a percent sign. Throws IoError naming what is wrong with the pattern.
std::string frame_path(const std::string& pattern, long long frame, bool need_number) {
    std::string out;
    int numbers = 0;
    for (std::size_t i = 0; i < pattern.size(); ++i) {
        if (pattern[i] != '%') {
            out += pattern[i];
            continue;
        }
        if (i + 1 < pattern.size() && pattern[i + 1] == '%') {
            out += '%';
            ++i;
            continue;
        }
        std::size_t j = i + 1;
        const bool zero = j < pattern.size() && pattern[j] == '0';
        if (zero) ++j;
        int width = 0;
        if (j < pattern.size() && pattern[j] >= '1' && pattern[j] <= '9') width = pattern[j++] - '0';
        if (j >= pattern.size() || pattern[j] != 'd')
            throw glint::IoError(fmt::format("-o {}: '%' at character {} must be %d, %0Nd (N from 1 to 9) or %%",
                                             pattern, i + 1));
        std::string digits = std::to_string(frame);
        const std::size_t w = static_cast<std::size_t>(width);
        if (digits.size() < w) digits.insert(digits.front() == '-' && zero ? 1 : 0, w - digits.size(), zero ? '0' : ' ');
        out += digits;
        ++numbers;
        i = j;
    }
    if (numbers > 1) throw glint::IoError(fmt::format("-o {}: the frame number may appear once", pattern));
    if (numbers == 0 && need_number)
        throw glint::IoError(fmt::format("-o {}: several frames need the frame number in the name, e.g. frame_%04d.exr",
                                         pattern));
    return out;
}

// glint render SCENE --frames A:B -o out/frame_%04d.exr: each frame rendered in turn (across the
// ranks under mpirun), frames whose file exists skipped, so a killed job goes on where it stopped.
int run_frames(RenderArgs args) {
    const bool distributed = g_cluster && g_cluster->size() > 1;
    if (distributed && g_cluster->rank() > 0) return run_rank(args);
    long long first = 0, last = 0;
    {
        const std::string& f = args.frames;
        const std::size_t colon = f.find(':');
        const auto integer = [&](const std::string& text, long long& v) {
            if (text.empty() || text.size() > 9) return false;
            std::size_t used = 0;
            try {
                v = std::stoll(text, &used);
            } catch (const std::exception&) {
                return false;
            }
            return used == text.size();
        };
        const bool ok = colon == std::string::npos ? integer(f, first) && (last = first, true)
                                                   : integer(f.substr(0, colon), first) && integer(f.substr(colon + 1), last);
        if (!ok || first < 0 || last < first)
            throw glint::IoError(fmt::format("--frames {}: expected FIRST:LAST (whole numbers, 0 <= FIRST <= LAST) or one frame", f));
    }
    if (!args.checkpoint.empty() || !args.resume.empty())
        throw glint::IoError("--frames renders frame by frame and skips the frames already written (that is how an "
                             "animation resumes); --checkpoint and --resume are for one image");
    const std::string pattern = args.output;
    if (pattern.empty()) throw glint::IoError("--frames needs -o with the frame number in the name, e.g. -o out/frame_%04d.exr");
    frame_path(pattern, first, last > first);  // a bad pattern fails before anything renders
    args.animation = true;
    if (distributed) g_ranks_stopped = g_animation_ranks = true;  // the ranks wait for a frame
    long long rendered = 0, skipped = 0;
    std::vector<double> todo;
    for (long long f = first; f <= last; ++f) {
        const std::string out = frame_path(pattern, f, last > first);
        std::error_code ec;
        if (std::filesystem::exists(out, ec)) {  // written whole (images are renamed into place)
            ++skipped;
            if (!args.quiet) fmt::print(stderr, "glint: frame {}: {} exists; skipped\n", f, out);
        } else {
            todo.push_back(static_cast<double>(f));
        }
    }
    if (distributed && !todo.empty() && todo.size() >= static_cast<std::size_t>(g_cluster->size())) {
        // At least a frame per rank: frames go out whole. The first frame is loaded here first, so
        // its errors come before any rank starts and rank 0 knows its files for ranks that ask.
        RenderArgs a = args;
        a.frame = todo.front();
        glint::forget_files_read();
        const std::uint64_t fingerprint = files_fingerprint(a, prepare_job(a));
        glint::SceneFiles files{std::filesystem::current_path(), glint::files_read(), {}};
        for (const auto& f : glint::model_folders(std::filesystem::path(args.scene).parent_path()))
            files.model_folders.push_back(std::filesystem::absolute(f).lexically_normal());
        std::mutex print;
        const auto said = [&](double f, int rank) {
            if (args.quiet) return;
            std::lock_guard lock(print);
            fmt::print(stderr, "glint: frame {} written by rank {}: {}\n", f, rank,
                       frame_path(pattern, static_cast<long long>(f), last > first));
        };
        g_animation_ranks = false;  // dispatch_frames stops the ranks however it ends
        install_signal_handlers();
        const std::vector<glint::FrameReport> reports = glint::dispatch_frames(
            *g_cluster, todo, fingerprint, files,
            [&](double f) {
                RenderArgs one = args;
                one.frame = f;
                one.output = frame_path(pattern, static_cast<long long>(f), last > first);
                return render_frame_file(one, std::nullopt);
            },
            [&](double f, int rank, const std::vector<std::uint8_t>& bytes) {
                glint::write_file_atomically(frame_path(pattern, static_cast<long long>(f), last > first), bytes);
                said(f, rank);
            },
            &g_stop);
        for (const glint::FrameReport& r : reports) rendered += r.frames;
        if (!args.quiet) {
            fmt::print(stderr, "{}", glint::format_frame_reports(reports));
            fmt::print(stderr, "glint: {} frame{} rendered, {} skipped (already written)\n", rendered,
                       rendered == 1 ? "" : "s", skipped);
        }
        if (g_stop.load()) {
            if (!args.quiet) fmt::print(stderr, "glint: interrupted by {}: the frames in flight on rank 0 were not written\n", signal_name(g_signal));
            return kExitInterrupted;
        }
        return 0;
    }
    for (const double frame : todo) {
        const auto f = static_cast<long long>(frame);
        const std::string out = frame_path(pattern, f, last > first);
        if (!args.quiet) fmt::print(stderr, "glint: frame {} of {}:{}\n", f, first, last);
        RenderArgs a = args;
        a.output = out;
        a.frame = static_cast<double>(f);
        if (distributed) {
            glint::send_frame(*g_cluster, a.frame);
            g_ranks_stopped = false;  // until this frame's render stops them
        }
        if (const int status = run_render(a); status != 0) return status;
        ++rendered;
        if (g_stop.load()) break;  // a signal after the frame's last pass: the frame is whole
    }
    if (!args.quiet)
        fmt::print(stderr, "glint: {} frame{} rendered, {} skipped (already written)\n", rendered,
                   rendered == 1 ? "" : "s", skipped);
    return g_stop.load() ? kExitInterrupted : 0;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"glint: a ray tracer. Renders YAML or JSON scene files (the article's camera and "
                 "Whitted shading with shadows and reflections, or physically based path "
                 "tracing with area lights, metals, glass and HDR environments; spheres, planes, "
                 "quads, disks, triangles, polygons and boxes; image textures; depth of field) "
                 "to PNG, EXR, JPEG, HDR, PFM or PPM.",
                 "glint"};
    app.set_version_flag("--version", std::string("glint ") + GLINT_VERSION);
    app.require_subcommand(1);

    RenderArgs args;
    CLI::App* render = app.add_subcommand(
        "render", "Render a scene file (YAML, JSON or pbrt-v4); with no SCENE, the built-in demo "
                  "(the article's Figure 14) to glint.png");
    render->add_option("SCENE", args.scene, "Scene file (.yaml, .yml, .json or .pbrt)");
    const char* strict_help = "pbrt files: what glint cannot render is an error, not a warning";
    render->add_flag("--strict", args.strict, strict_help);
    render->add_option("-o,--output", args.output,
                       "Output image; the format comes from the extension: .png, .jpg, .ppm (8-bit), "
                       ".exr, .hdr, .pfm (linear)");
    render->add_option("--width", args.width, "Film width in pixels (overrides the scene)");
    render->add_option("--height", args.height, "Film height in pixels (overrides the scene)");
    render->add_option("--spp", args.spp,
                       "Samples per pixel: 1 samples the pixel centre, more are low-discrepancy "
                       "samples averaged over the pixel (anti-aliasing, and the path tracer's "
                       "noise falls as 1/sqrt(spp))");
    render->add_option("--threads", args.threads, "Worker threads (0 or absent: all cores)");
    render->add_option("--rank-timeout", args.rank_timeout,
                       "Under mpirun: seconds after which a rank's unanswered tiles are given to another "
                       "(default 60; at least four times the tiles' expected time)")
        ->check(CLI::PositiveNumber);
    render->add_option("--seed", args.seed, "Sampler seed (overrides the scene)");
    render->add_option("--max-depth", args.max_depth,
                       "Path length: whitted's reflection depth (the camera ray is depth 0), "
                       "path's scattering events (1 = direct light only)");
    render->add_flag("--aovs", args.aovs,
                     "Also write albedo, normal and depth (for denoisers) as EXR channels "
                     "albedo.R/G/B, N.X/Y/Z and Z; needs an .exr output");
    render->add_flag("-q,--quiet", args.quiet, "Print nothing but errors");
    const char* accel_help =
        "Acceleration structure: bvh (glint's own), sbvh (the same with spatial splits) or embree "
        "(Embree 3, when built in)";
    render->add_option("--accel", args.accel, accel_help);
    render->add_option("--time", args.time,
                       "Time budget for rendering (90s, 10m, 1h30m): stops after the last sample pass "
                       "that fits and writes the image with the spp reached");
    render->add_option("--checkpoint", args.checkpoint,
                       "Save the render's state to this file every --checkpoint-every, at the end, and "
                       "when interrupted, so --resume can continue it");
    render->add_option("--checkpoint-every", args.checkpoint_every, "How often to checkpoint (default 5m)");
    render->add_option("--resume", args.resume,
                       "Continue the render saved in this checkpoint (same scene and options); it goes on "
                       "being checkpointed there");
    render->add_option("--noise-threshold", args.noise_threshold,
                       "Adaptive sampling: a pixel stops when its relative error estimate falls below this "
                       "(Cycles' meaning; 0.01 is a good start); --spp is then the maximum");
    render->add_option("--min-spp", args.min_spp,
                       "Adaptive sampling: samples every pixel takes first (default: Cycles' rule, "
                       "16 / threshold^0.3)");
    render->add_option("--display", args.display,
                       "Show the image as it forms in a viewer speaking tev's protocol at HOST:PORT "
                       "(tev's default: 127.0.0.1:14158)");
    render->add_option("--frames", args.frames,
                       "Render an animation's frames FIRST:LAST (or one frame N), each to -o with the frame "
                       "number put in for %d or %04d; frames whose file exists are skipped");
    render->add_option("--fps", args.fps, "Frames per second of the animation (default: the scene's animation.fps, else 24)");
    render->add_option("--camera", args.camera,
                       "For a .gltf/.glb rendered directly: the camera to look through, by name "
                       "(default: the first one)");

    CLI::App* info = app.add_subcommand(
        "info", "Print a scene's statistics: triangles, instances, bounds, memory");
    info->add_option("SCENE", args.scene, "Scene file (.yaml, .json, .pbrt) or mesh (.obj, .ply)")->required();
    info->add_option("--accel", args.accel, accel_help);
    info->add_flag("--strict", args.strict, strict_help);

    int runs = 3;
    CLI::App* bench = app.add_subcommand(
        "bench", "Measure the acceleration backends side by side: build time, memory, and Mrays/s "
                 "for primary rays and one-bounce diffuse rays (closest hit)");
    bench->add_option("SCENE", args.scene, "Scene file (.yaml, .json) or mesh (.obj, .ply)")->required();
    bench->add_option("--accel", args.accel, "bvh, sbvh, embree, both (bvh and embree: the default) or all");
    bench->add_option("--threads", args.threads, "Worker threads (0 or absent: all cores)");
    bench->add_option("--width", args.width, "Film width: the primary rays (overrides the scene)");
    bench->add_option("--height", args.height, "Film height (overrides the scene)");
    bench->add_option("--runs", runs, "Repetitions; medians are reported")->check(CLI::Range(1, 100));

    // What a scene may make glint read and allocate (docs/cli.md, "Untrusted scenes").
    std::vector<std::string> limits;
    bool restrict_paths = false;
    const std::string limit_help = "Raise or lower a limit on what the scene may ask for, NAME=N (" +
                                   glint::limit_names() + "; suffixes k, M, G, KiB, MiB, GiB); repeatable";
    const char* restrict_help =
        "Read files only under the scene's folder and the model search path ($GLINT_MODEL_PATH, the "
        "models folder): for services rendering scenes they did not write";
    for (CLI::App* sub : {render, info}) {
        sub->add_option("--limit", limits, limit_help);
        sub->add_flag("--restrict-paths", restrict_paths, restrict_help);
    }

    std::string convert_out;
    CLI::App* convert = app.add_subcommand(
        "convert", "Write a scene (a pbrt-v4 file, or YAML) as a glint YAML scene; meshes given inline "
                   "become PLY files beside it");
    convert->add_option("SCENE", args.scene, "Scene file (.pbrt, .yaml, .json)")->required();
    convert->add_option("-o,--output", convert_out, "The YAML file to write")->required();
    convert->add_flag("--strict", args.strict, strict_help);
    convert->add_flag("-q,--quiet", args.quiet, "Print nothing but errors");
    convert->add_option("--limit", limits, limit_help);
    convert->add_flag("--restrict-paths", restrict_paths, restrict_help);

    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e);
    }

    // Under mpirun, rank 0 stops the other ranks however it leaves (a render, an error), and
    // every rank ends MPI before it exits.
    struct EndCluster {
        ~EndCluster() {
            if (!g_cluster) return;
            if (g_cluster->rank() == 0 && !g_ranks_stopped) glint::stop_ranks(*g_cluster);  // a frame's render
            if (g_cluster->rank() == 0 && g_animation_ranks) glint::stop_ranks(*g_cluster);  // waiting for a frame
            g_cluster.reset();
        }
    } end_cluster;
    try {
        if (render->parsed() && glint::launched_by_mpi()) {
            std::signal(SIGUSR1, SIG_IGN);  // mpirun forwards it to every rank; rank 0 acts on it
            g_cluster = glint::mpi_transport(argc, argv);
            // One voice: the other ranks' failures reach rank 0 as messages and are printed there.
            if (g_cluster->rank() > 0 && !std::getenv("GLINT_RANK_STDERR")) {
                if (std::FILE* null = std::fopen("/dev/null", "w")) ::dup2(::fileno(null), STDERR_FILENO);
            }
        }
        for (const std::string& l : limits) glint::set_limit_from_text(l);
        if (restrict_paths) {
            g_restrict_paths = true;
            const std::filesystem::path dir = std::filesystem::path(args.scene).parent_path();
            glint::restrict_reads_to(glint::model_folders(dir));
        }
        if (info->parsed()) return run_info(args);
        if (convert->parsed()) return run_convert(args, convert_out);
        if (bench->parsed()) {
            // The backends to compare; the scene itself is loaded with the default one.
            const std::string set = args.accel == "both" ? "" : args.accel;
            if (!set.empty() && set != "all") parse_accel(set);  // an unknown name fails first
            args.accel.clear();
            return run_bench(args, set, runs);
        }
        return args.frames.empty() ? run_render(args) : run_frames(args);
    } catch (const glint::SceneError& e) {
        std::fputs(e.what(), stderr);
        const std::size_t n = e.diagnostics().size();
        fmt::print(stderr, "glint: {} error{}; no image written\n", n, n == 1 ? "" : "s");
    } catch (const glint::IoError& e) {
        fmt::print(stderr, "glint: error: {}\n", e.what());
    } catch (const std::bad_alloc&) {
        fmt::print(stderr, "glint: error: out of memory\n");
    } catch (const std::exception& e) {
        fmt::print(stderr, "glint: error: {}\n", e.what());
    }
    return 1;
}
