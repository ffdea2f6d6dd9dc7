// glint's command line: flags (CLI11), printing and exit status, and nothing else. What a
// command does is the library's: a render is a RenderSession (session/session.h), a scene is read
// through the format table (session/formats.h).
#include <signal.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <fmt/core.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <atomic>
#include <charconv>
#include <cstdint>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <memory>
#include <new>
#include <optional>
#include <string>
#include <vector>

#include "glint/base/diagnostics.h"
#include "glint/base/limits.h"
#include "glint/formats/scene_writer.h"
#include "glint/image/image_io.h"
#include "glint/render/distributed.h"
#include "glint/render/ray_bench.h"
#include "glint/session/formats.h"
#include "glint/session/session.h"

namespace {

// Signals: the first SIGINT or SIGTERM only raises a flag the render loop polls between tiles;
// a second one removes the temporary files being written (if any) and exits at once. Nothing in
// the handler allocates, locks or throws.
std::atomic<bool> g_stop{false};
volatile std::sig_atomic_t g_signal = 0;
bool g_rank0_of_job = false;  // rank 0 of an MPI job: SIGUSR1 stops the render too
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
    // also while they render a whole frame of an animation).
    if (g_rank0_of_job) ::sigaction(SIGUSR1, &sa, nullptr);
}

const char* signal_name(int sig) {
    return sig == SIGTERM ? "SIGTERM" : sig == SIGUSR1 ? "SIGUSR1" : "SIGINT";
}

void print_notes(const glint::RenderJob& job, bool quiet) {
    if (!quiet)
        for (const std::string& n : job.notes) fmt::print(stderr, "glint: note: {}\n", n);
}

std::string bytes(std::uint64_t b) {
    if (b >= (1ull << 30)) return fmt::format("{:.2f} GiB", b / double(1ull << 30));
    if (b >= (1ull << 20)) return fmt::format("{:.2f} MiB", b / double(1ull << 20));
    if (b >= (1ull << 10)) return fmt::format("{:.1f} KiB", b / double(1ull << 10));
    return fmt::format("{} B", b);
}

// glint render --list-formats: the format tables (session/formats.h, image/image_io.h).
void print_formats() {
    fmt::print("Scene and mesh files (glint render, glint info; glint convert reads the scene files):\n");
    for (const glint::SceneFileFormat& f : glint::scene_file_formats())
        fmt::print("  {:<6} {:<16} {:<6} {}\n", f.name, fmt::format("{}", fmt::join(f.extensions, " ")),
                   f.mesh ? "mesh" : "scene", f.description);
    fmt::print("  (another extension: a binary glTF or a PLY is known by its first bytes; anything else is read "
               "as YAML)\n");
    fmt::print("Images written (-o, chosen by the extension):\n");
    for (const glint::ImageFormatInfo& f : glint::image_formats())
        fmt::print("  {:<16} {}\n", fmt::format("{}", fmt::join(f.extensions, " ")), f.description);
    fmt::print("Images read (textures, environment maps): the formats above by glint's own readers, and any other "
               "that OpenImageIO reads\n");
}

// glint convert: the scene written back as YAML (session.h's convert_scene).
int run_convert(const glint::SessionOptions& args, const std::string& out) {
    const glint::WrittenScene w = glint::convert_scene(args.scene, out, args.strict, [&](const std::string& n) {
        if (!args.quiet) fmt::print(stderr, "glint: note: {}", n);
    });
    fmt::print("wrote {}{}\n", out, w.meshes.empty() ? "" : fmt::format(" and {} mesh or grid file{}", w.meshes.size(), w.meshes.size() == 1 ? "" : "s"));
    return 0;
}

int run_info(const glint::SessionOptions& args) {
    glint::RenderJob job = glint::load_job(args);
    print_notes(job, args.quiet);
    const glint::SceneInfo i = glint::scene_info(job.scene);
    fmt::print("scene        {}\n", args.scene.empty() ? "(built-in demo)" : args.scene);
    fmt::print("triangles    {} rendered, {} stored\n", i.triangles, i.unique_triangles);
    fmt::print("meshes       {} ({} vertices), {} instances\n", i.meshes, i.vertices, i.instances);
    fmt::print("other shapes {}\n", i.analytic_shapes);
    const glint::LightSampler& ls = job.scene.light_sampler();
    fmt::print("lights       {} (area lights included)", ls.count());
    if (ls.kind() == glint::LightSamplerKind::kBvh && !ls.bvh().empty())
        fmt::print(", chosen by a light BVH of {} nodes", ls.bvh().node_count());
    fmt::print("\n");
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

int run_bench(const glint::SessionOptions& args, const std::string& set, int runs) {
    glint::RenderJob job = glint::load_job(args);
    print_notes(job, args.quiet);
    std::vector<glint::AccelKind> kinds{glint::AccelKind::kBvh};
    if (set == "all") kinds.push_back(glint::AccelKind::kSbvh);
    if (const auto one = set == "all" ? std::nullopt : glint::parse_accel(set)) kinds = {*one};
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

    glint::SessionOptions args;
    CLI::App* render = app.add_subcommand(
        "render", "Render a scene file (YAML, JSON or pbrt-v4); with no SCENE, the built-in demo "
                  "(the article's Figure 14) to glint.png");
    render->add_option("SCENE", args.scene, "Scene file (.yaml, .yml, .json or .pbrt) or mesh file (--list-formats)");
    bool list_formats = false;
    render->add_flag("--list-formats", list_formats, "Print the scene, mesh and image formats glint reads and writes");
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
    std::string seed_text;
    render->add_option("--seed", seed_text, "Sampler seed, 0 to 18446744073709551615 (overrides the scene)");
    render->add_option("--max-depth", args.max_depth,
                       "Path length: whitted's reflection depth (the camera ray is depth 0), "
                       "path's scattering events (1 = direct light only)");
    render->add_flag("--aovs", args.aovs,
                     "Also write albedo, normal and depth (for denoisers) as EXR channels "
                     "albedo.R/G/B, N.X/Y/Z and Z, and the half images even.R/G/B, odd.R/G/B; "
                     "needs an .exr output");
    render->add_flag("--denoise", args.denoise,
                     "Write the image denoised by glint's feature-guided filter (needs 2 spp or more); "
                     "an .exr also keeps the image before (noisy.R/G/B), the features and the half images");
    render->add_flag("-q,--quiet", args.quiet, "Print nothing but errors");
    const char* accel_help =
        "Acceleration structure: bvh (glint's own), sbvh (the same with spatial splits) or embree "
        "(Embree 3, when built in)";
    render->add_option("--accel", args.accel, accel_help);
    render->add_option("--light-sampler", args.light_sampler,
                       "How the path tracer chooses a light to sample: bvh (by what each light can send to the "
                       "shaded point; the default) or power (in proportion to power)");
    render->add_option("--texture-filter", args.texture_filter,
                       "How the path tracer reads textures over a pixel's footprint: ewa (the default), "
                       "trilinear, or none (one point per sample, as before filtering)");
    auto* spectral = render->add_flag_function(
        "--spectral", [&args](std::int64_t) { args.spectral = true; },
        "Trace light by wavelength (the path tracer; the default for pbrt-v4 files): RGB values become "
        "spectra, metals and glasses given by their measured spectra, glass disperses");
    render->add_flag_function("--rgb", [&args](std::int64_t) { args.spectral = false; },
                              "Trace light in RGB even where the scene asks for spectral rendering")
        ->excludes(spectral);
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

    std::string denoise_in, denoise_out;
    CLI::App* denoise = app.add_subcommand(
        "denoise", "Denoise an EXR written by `glint render --aovs` (or any EXR with R, G, B and the half "
                   "images even.R/G/B, odd.R/G/B; albedo.R/G/B, N.X/Y/Z and Z guide the filter when present)");
    denoise->add_option("IMAGE", denoise_in, "The .exr to denoise")->required();
    denoise->add_option("-o,--output", denoise_out,
                        "The image to write: .exr keeps the input's channels and the image before as "
                        "noisy.R/G/B; .png, .jpg ... the denoised image alone")->required();
    denoise->add_option("--threads", args.threads, "Worker threads (0 or absent: all cores)");
    int denoise_radius = glint::DenoiseOptions{}.radius;
    denoise->add_option("--radius", denoise_radius, "The filter window's half size in pixels (default 5: 11 x 11)")
        ->check(CLI::Range(1, 20));
    denoise->add_flag("-q,--quiet", args.quiet, "Print nothing but errors");

    // A first word that is no command and no flag: name it and the nearest command, before CLI11
    // says only that a subcommand is required.
    if (argc > 1 && argv[1][0] != '-') {
        std::vector<std::string> commands;
        for (const CLI::App* sub : app.get_subcommands({})) commands.push_back(sub->get_name());
        const std::string word = argv[1];
        if (std::find(commands.begin(), commands.end(), word) == commands.end()) {
            const std::string guess = glint::closest_match(word, commands);
            std::error_code ec;
            const std::string hint = std::filesystem::exists(word, ec)
                                         ? fmt::format("; to render that file: glint render {}", word)
                                     : guess.empty() ? std::string()
                                                     : fmt::format("; did you mean '{}'?", guess);
            fmt::print(stderr, "glint: error: unknown command '{}'{} (commands: {}; see glint --help)\n", word, hint,
                       fmt::join(commands, ", "));
            return static_cast<int>(CLI::ExitCodes::RequiredError);  // 106, as for no command
        }
    }
    try {
        app.parse(argc, argv);
        // An empty argument is a mistake (an unset shell variable), never a request for a default:
        // `render ""` is not the demo and `-o ""` is not scene.png.
        for (const CLI::App* sub : app.get_subcommands())
            for (const CLI::Option* opt : sub->get_options())
                for (const std::string& r : opt->results())
                    if (r.empty())
                        throw CLI::ValidationError(opt->get_name(), "an empty argument (give a value, or leave the option out)");
        if (!seed_text.empty()) {
            std::uint64_t seed = 0;
            const char* end = seed_text.data() + seed_text.size();
            const auto [ptr, ec] = std::from_chars(seed_text.data(), end, seed);
            if (ec == std::errc::result_out_of_range)
                throw CLI::ValidationError("--seed", fmt::format("{} is out of range (0 to {})", seed_text, UINT64_MAX));
            if (ec != std::errc{} || ptr != end)
                throw CLI::ValidationError("--seed", fmt::format("'{}' is not a whole number from 0 to {}", seed_text, UINT64_MAX));
            args.seed = seed;
        }
    } catch (const CLI::ParseError& e) {
        return app.exit(e);
    }

    if (render->parsed() && list_formats) {
        print_formats();
        return 0;
    }

    // Under mpirun every rank ends MPI before it exits (the cluster outlives the session, whose
    // end on rank 0 stops the other ranks however it leaves: a render, an error).
    std::unique_ptr<glint::Transport> cluster;
    try {
        if (render->parsed() && glint::launched_by_mpi()) {
            std::signal(SIGUSR1, SIG_IGN);  // mpirun forwards it to every rank; rank 0 acts on it
            cluster = glint::mpi_transport(argc, argv);
            g_rank0_of_job = cluster->rank() == 0;
            // One voice: the other ranks' failures reach rank 0 as messages and are printed there.
            if (cluster->rank() > 0 && !std::getenv("GLINT_RANK_STDERR")) {
                if (std::FILE* null = std::fopen("/dev/null", "w")) ::dup2(::fileno(null), STDERR_FILENO);
            }
        }
        args.restrict_paths = restrict_paths;
        args.progress = ::isatty(::fileno(stderr)) ? glint::ProgressMode::kBar : glint::ProgressMode::kSummary;
        glint::SessionHooks hooks;
        hooks.print = [](const std::string& text) { std::fputs(text.c_str(), stderr); };
        hooks.cancel = &g_stop;
        hooks.cancel_reason = [] { return std::string(signal_name(g_signal)); };
        hooks.arm = install_signal_handlers;
        hooks.writing = remember_temporary;
        std::optional<glint::RenderSession> session;
        if (render->parsed()) session.emplace(args, hooks, cluster.get());
        for (const std::string& l : limits) glint::set_limit_from_text(l);
        if (restrict_paths) {
            const std::filesystem::path dir = std::filesystem::path(args.scene).parent_path();
            glint::restrict_reads_to(glint::model_folders(dir));
        }
        if (info->parsed()) return run_info(args);
        if (convert->parsed()) return run_convert(args, convert_out);
        if (denoise->parsed()) {
            const double seconds = glint::denoise_file(denoise_in, denoise_out, static_cast<int>(args.threads.value_or(0)),
                                                       denoise_radius);
            if (!args.quiet) fmt::print(stderr, "denoised in {:.2f} s\nwrote {}\n", seconds, denoise_out);
            return 0;
        }
        if (bench->parsed()) {
            // The backends to compare; the scene itself is loaded with the default one.
            const std::string set = args.accel == "both" ? "" : args.accel;
            if (!set.empty() && set != "all") glint::parse_accel(set);  // an unknown name fails first
            args.accel.clear();
            return run_bench(args, set, runs);
        }
        return static_cast<int>(session->run());
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
