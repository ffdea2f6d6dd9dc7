#include "glint/session/session.h"

#include <sched.h>
#include <unistd.h>

#include <fmt/core.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <thread>

#include "glint/demo_scene.h"
#include "glint/denoise/denoise.h"
#include "glint/film/film.h"
#include "glint/formats/scene_yaml.h"
#include "glint/image/image_io.h"
#include "glint/image/tev.h"
#include "glint/render/progressive.h"
#include "glint/session/checkpoint.h"
#include "glint/session/formats.h"

namespace glint {

namespace {

// The automatic camera for a model without one: from the front (-z side), a little above and to
// the right, 40 degrees vertical, every corner of the model's bounds inside 90 % of the frame.
void frame_bounds(RenderJob& job) {
    const Bounds3 b = job.scene.bounds();
    if (b.empty()) return;
    job.camera = frame_box(b, {0.35f, 0.35f, -1}, {0, 1, 0}, 40, job.width, job.height);
}

// Where the image goes: the output, else the scene's film.filename, else <scene stem>.png in the
// current folder (glint.png for the built-in demo).
std::filesystem::path output_path(const SessionOptions& args, const RenderJob& job) {
    if (!args.output.empty()) return args.output;
    if (!job.filename.empty()) return job.filename;
    if (args.scene.empty()) return "glint.png";
    return std::filesystem::path(args.scene).stem().string() + ".png";
}

// What the image header says about the render (EXR attributes, PNG text chunks).
ImageMetadata metadata(const SessionOptions& args, int spp, int target, int passes, double seconds, bool complete) {
    return {{"glint:spp", std::to_string(spp)},
            {"glint:spp_target", std::to_string(target)},
            {"glint:passes", std::to_string(passes)},
            {"glint:render_seconds", fmt::format("{:.3f}", seconds)},
            {"glint:complete", complete ? "yes" : "no"},
            {"glint:scene", args.scene_label.empty() ? args.scene : args.scene_label},
            {"Software", std::string("glint ") + GLINT_VERSION}};
}

std::string spp_text(const ProgressiveRender& r) {
    if (!r.adaptive()) return fmt::format("{} spp", r.spp_done());
    const auto& s = r.state().samples;
    const double mean = static_cast<double>(r.samples_taken()) / static_cast<double>(std::max<std::size_t>(1, s.size()));
    return fmt::format("{:.1f} spp on average ({} to {} per pixel, {:.1f}% converged)", mean,
                       s.empty() ? 0 : *std::min_element(s.begin(), s.end()),
                       s.empty() ? 0 : *std::max_element(s.begin(), s.end()), 100 * r.converged_fraction());
}

}  // namespace

std::optional<AccelKind> parse_accel(const std::string& name) {
    if (name.empty()) return std::nullopt;
    if (name == "bvh") return AccelKind::kBvh;
    if (name == "sbvh") return AccelKind::kSbvh;
    if (name == "embree") return AccelKind::kEmbree;
    throw IoError(fmt::format("--accel: unknown backend '{}' (known: bvh, sbvh, embree)", name));
}

std::optional<LightSamplerKind> parse_light_sampler(const std::string& name) {
    if (name.empty()) return std::nullopt;
    if (name == "bvh") return LightSamplerKind::kBvh;
    if (name == "power") return LightSamplerKind::kPower;
    throw IoError(fmt::format("--light-sampler: unknown light sampler '{}' (known: bvh, power)", name));
}

std::optional<TextureFilter> parse_texture_filter(const std::string& name) {
    if (name.empty()) return std::nullopt;
    if (name == "ewa") return TextureFilter::kEwa;
    if (name == "trilinear") return TextureFilter::kTrilinear;
    if (name == "none") return TextureFilter::kBilinear;
    throw IoError(fmt::format("--texture-filter: unknown texture filter '{}' (known: ewa, trilinear, none)", name));
}

LoadedScene read_scene(const SessionOptions& args) {
    LoadedScene s;
    s.sources = std::make_shared<SourceFiles>();
    s.mesh = !args.scene.empty() && scene_file_format(args.scene).mesh;
    s.description = args.scene.empty() ? parse_scene(kDemoScene, kDemoSceneName, s.sources, args.frame)
                                       : read_scene_file(args.scene, s.sources, {args.strict, args.frame, args.camera});
    s.description.frame = args.frame;
    return s;
}

RenderJob load_job(const SessionOptions& args) {
    std::optional<LoadedScene> read;
    if (!args.loaded) read = read_scene(args);
    const LoadedScene& loaded = args.loaded ? *args.loaded : *read;
    const bool mesh = loaded.mesh;
    // Each build its own copy of the texts: building adds the files it reads (and a loaded scene
    // may be built by two threads at once).
    auto sources = args.loaded ? std::make_shared<SourceFiles>(*loaded.sources) : loaded.sources;
    SceneDescription description = args.loaded ? loaded.description : std::move(read->description);
    if (args.fps) {
        if (!(*args.fps > 0) || !std::isfinite(*args.fps) || *args.fps > 1e6)
            throw IoError(fmt::format("--fps {}: must be a number above 0", *args.fps));
        description.fps = *args.fps;
    }
    Overrides overrides;
    overrides.width = args.width;
    overrides.height = args.height;
    overrides.spp = args.spp;
    overrides.max_depth = args.max_depth;
    overrides.threads = args.threads;
    overrides.seed = args.seed;
    overrides.aovs = args.aovs;
    overrides.denoise = args.denoise;
    overrides.accel = parse_accel(args.accel);
    overrides.light_sampler = parse_light_sampler(args.light_sampler);
    overrides.texture_filter = parse_texture_filter(args.texture_filter);
    overrides.spectral = args.spectral;
    RenderJob job = build(description, overrides, sources);
    if (mesh) {
        if (job.file_camera) {  // the file's own camera
            const GltfCamera& c = *job.file_camera;
            if (c.orthographic) {
                job.camera = Camera::orthographic(c.position, c.direction, c.up, 2 * c.ymag, job.width, job.height);
            } else {
                job.camera = Camera::look_at(c.position, c.position + c.direction, c.up, c.yfov_degrees, job.width,
                                             job.height);
            }
        } else {
            frame_bounds(job);
        }
        set_texture_footprint(job);  // the camera changed
    }
    if (!args.camera.empty() && !mesh)
        throw IoError("--camera chooses a camera of a glTF file rendered directly; a scene file has its own");
    return job;
}

WrittenScene convert_scene(const std::string& scene, const std::filesystem::path& out, bool strict,
                           const std::function<void(const std::string&)>& note) {
    const SceneFileFormat& format = scene_file_format(scene);
    if (!format.convert)
        throw IoError(fmt::format("{}: a {} file is a mesh; convert reads scene files (render the mesh directly, or "
                                  "name it in a scene's mesh object)",
                                  scene, format.name));
    auto sources = std::make_shared<SourceFiles>();
    const SceneDescription d = read_scene_file(scene, sources, {strict, 0, ""});
    (void)build(d, {}, sources);  // every error of the source, before anything is written
    if (note)
        for (const auto& w : d.warnings) note(format_warning(w, *sources));
    WrittenScene w = write_scene_yaml(d, out);
    write_file_atomically(out, std::span(reinterpret_cast<const std::uint8_t*>(w.yaml.data()), w.yaml.size()),
                          "the scene");
    return w;
}

std::string image_settings(const SessionOptions& args, const RenderJob& job) {
    const RenderOptions& o = job.options;
    return fmt::format(
        "glint {}|film {}x{} of {}x{} at {},{}|spp {}|seed {}|sampler {}|filter {} {} {}|scale {}|"
        "noise {} min {}|aovs {}|max-depth {}|camera {}|{}",
        GLINT_VERSION, job.film_width, job.film_height, job.width, job.height, o.offset_x, o.offset_y, o.spp,
        o.seed, static_cast<int>(o.sampler), static_cast<int>(o.filter.type), o.filter.radius,
        o.filter.sigma, o.scale, o.noise_threshold, o.min_spp, job.features(),
        args.max_depth ? *args.max_depth : -1, args.camera, args.scene.empty() ? "(demo)" : "");
}

RenderSession::RenderSession(SessionOptions options, SessionHooks hooks, Transport* cluster)
    : options_(std::move(options)), hooks_(std::move(hooks)), cluster_(cluster) {}

RenderSession::~RenderSession() {
    if (!cluster_ || cluster_->rank() != 0) return;
    try {
        if (!ranks_stopped_) stop_ranks(*cluster_);    // a frame's render
        if (animation_ranks_) stop_ranks(*cluster_);   // waiting for a frame
    } catch (...) {  // a destructor does not throw; the job ends anyway
    }
}

void RenderSession::say(const std::string& text) const {
    if (hooks_.print) hooks_.print(text);
}

void RenderSession::note(const SessionOptions& args, const std::string& text) const {
    if (!args.quiet) say(fmt::format("\nglint: note: {}\n", text));
}

SessionResult RenderSession::interrupted(const SessionOptions& args, const std::string& what) {
    if (!args.quiet)
        say(fmt::format("glint: interrupted by {}: {}\n", hooks_.cancel_reason ? hooks_.cancel_reason() : "a cancellation",
                        what));
    return SessionResult::kInterrupted;
}

SessionResult RenderSession::run() {
    return options_.frames.empty() ? render(options_) : frames(options_);
}

// The scene and every option that changes the image: what each rank of a distributed render
// prepares alike.
RenderJob RenderSession::prepare_job(const SessionOptions& args) {
    RenderJob job = load_job(args);
    if (!args.quiet)
        for (const std::string& n : job.notes) say(fmt::format("glint: note: {}\n", n));
    if (args.noise_threshold) {
        if (!(*args.noise_threshold > 0) || !std::isfinite(*args.noise_threshold))
            throw IoError(fmt::format("--noise-threshold {}: must be a number above 0 (e.g. 0.01)", *args.noise_threshold));
        job.options.noise_threshold = static_cast<float>(*args.noise_threshold);
    }
    if (args.min_spp) {
        if (!args.noise_threshold && !(job.options.noise_threshold > 0))
            throw IoError("--min-spp goes with --noise-threshold or the scene's sampler noise_threshold (adaptive sampling)");
        if (*args.min_spp < 1 || *args.min_spp > job.options.spp)
            throw IoError(fmt::format("--min-spp {}: must be between 1 and the spp ({})", *args.min_spp, job.options.spp));
        job.options.min_spp = static_cast<int>(*args.min_spp);
    }
    if (cluster_ && cluster_->size() > 1 && !args.threads) {
        // The cores this rank may use (mpirun may have bound it to some), shared with the other
        // ranks on this host unless it was bound.
        cpu_set_t set;
        int allowed = static_cast<int>(std::max(1U, std::thread::hardware_concurrency()));
        const int cores = allowed;
        if (sched_getaffinity(0, sizeof set, &set) == 0) allowed = std::max(1, CPU_COUNT(&set));
        job.options.threads = allowed < cores ? allowed : std::max(1, cores / local_ranks());
    }
    return job;
}

namespace {

// The film's image denoised in place, the image before kept beside it (an EXR writes both); the
// seconds it took.
double denoise_film(Film& film, int threads) {
    const DenoiseInput in{film.width(),         film.height(),        film.pixels().data(),
                          film.even().data(),   film.odd().data(),    film.albedo().data(),
                          film.normal().data(), film.depth().data(),  film.even_albedo().data(),
                          film.odd_albedo().data()};
    DenoiseStats stats;
    DenoiseOptions options;
    options.threads = threads;
    std::vector<Color> out = denoise(in, options, &stats);
    BigVector<Color> noisy(film.pixels().begin(), film.pixels().end());
    std::copy(out.begin(), out.end(), film.pixels().begin());
    film.keep_noisy(std::move(noisy));
    return stats.seconds;
}

}  // namespace

SessionResult RenderSession::render(const SessionOptions& args, std::optional<RenderJob> preloaded) {
    const bool distributed = !args.local && cluster_ && cluster_->size() > 1;
    if (distributed && cluster_->rank() > 0) return run_rank(args) == 0 ? SessionResult::kComplete : SessionResult::kInterrupted;
    RenderJob job = preloaded ? std::move(*preloaded) : prepare_job(args);
    const bool in_memory = static_cast<bool>(hooks_.image);
    const std::filesystem::path out = in_memory ? std::filesystem::path() : output_path(args, job);
    if (!in_memory) check_writable(out, job.film_width, job.film_height);  // fail before rendering, not after
    if (job.aovs && !in_memory && image_format_for(out) != ImageFormat::kExr) {
        throw IoError(fmt::format(
            "{}: AOVs (albedo, normal, depth) are written as EXR channels; use an .exr output",
            out.string()));
    }
    if (job.denoise && job.options.spp < 2)
        throw IoError(fmt::format("--denoise: the render has {} sample per pixel; the denoiser estimates the noise "
                                  "from two halves of the samples, so it needs at least 2",
                                  job.options.spp));
    const auto spp = static_cast<unsigned>(job.options.spp);
    if (job.denoise && job.options.sampler == SamplerType::kSobol && (spp & (spp - 1)) != 0) {
        note(args, fmt::format("--denoise: {} samples per pixel is not a power of two, so the half images are not "
                               "stratified and the noise is overestimated (more smoothing); 64, 128 or 256 denoise best",
                               spp));
    }
    const double budget = args.time.empty() ? -1 : parse_duration(args.time, "--time");
    const double every = parse_duration(args.checkpoint_every, "--checkpoint-every");
    // --resume FILE goes on writing FILE, unless --checkpoint names another.
    const std::filesystem::path checkpoint = !args.checkpoint.empty() ? args.checkpoint : args.resume;
    if (!checkpoint.empty()) {
        std::error_code ec, ec2;
        if (!in_memory && std::filesystem::weakly_canonical(checkpoint, ec) == std::filesystem::weakly_canonical(out, ec2) && !ec && !ec2)
            throw IoError(fmt::format("{}: the checkpoint and the image cannot be one file", out.string()));
        const auto dir = checkpoint.parent_path().empty() ? std::filesystem::path(".") : checkpoint.parent_path();
        if (!std::filesystem::is_directory(dir, ec))
            throw IoError(fmt::format("{}: cannot write: folder '{}' does not exist", checkpoint.string(), dir.string()));
    }

    const ProgressMode mode = args.quiet ? ProgressMode::kQuiet : args.progress;
    const int w = job.film_width, h = job.film_height;
    const auto pixels = static_cast<std::uint64_t>(w) * static_cast<std::uint64_t>(h);
    Progress progress(mode, hooks_.progress_stream, pixels * static_cast<std::uint64_t>(std::max(1, job.options.spp)));
    if (hooks_.writing) {
        if (!in_memory) hooks_.writing(0, out);
        if (!checkpoint.empty()) hooks_.writing(1, checkpoint);
    }
    if (hooks_.arm) hooks_.arm();
    const auto interrupted_status = [&](const std::string& what) { return interrupted(args, what); };
    // The image to its file, or (in memory) to the front end.
    const auto deliver = [&](const Film& film, const ImageMetadata& meta) {
        if (in_memory) {
            hooks_.image(film, job.display, meta);
            return;
        }
        write_image(out, film, job.display, meta);
    };

    // The article's case (one sample, no AOVs, nothing to save or show): one sweep, no sums;
    // for PNG and PPM straight to 8-bit codes, with no float film (a 1080p film is 25 MB of
    // memory the kernel must clear and the encoder read back: docs/architecture.md).
    if (job.options.spp == 1 && !job.features() && checkpoint.empty() && args.display.empty() && !distributed) {
        if (!in_memory && !is_linear_format(image_format_for(out))) {
            // PNG strips are encoded by the render's threads as their rows come in.
            Image8Writer writer(out, w, h, job.display.encoding == Encoding::kSrgb);
            const RenderStats stats = render_8bit(
                job.scene, job.camera, *job.integrator, job.options, job.display, w, h, writer.rgb(), &progress,
                hooks_.cancel, [&writer](int y0, int y1) { writer.rows_ready(y0, y1); });
            if (!stats.complete) return interrupted_status(args.animation ? fmt::format("frame {} not written", args.frame) : "no pass completed; nothing written");
            writer.finish(metadata(args, 1, 1, 1, stats.seconds, true));
            progress.finish(stats, w, h, "1 spp");
            if (!args.quiet) say(fmt::format("wrote {}\n", out.string()));
            return SessionResult::kComplete;
        }
        Film film(w, h);
        const RenderStats stats =
            glint::render(job.scene, job.camera, *job.integrator, job.options, film, &progress, hooks_.cancel);
        if (!stats.complete) return interrupted_status(args.animation ? fmt::format("frame {} not written", args.frame) : "no pass completed; nothing written");
        deliver(film, metadata(args, 1, 1, 1, stats.seconds, true));
        progress.finish(stats, w, h, "1 spp");
        if (!args.quiet && !in_memory) say(fmt::format("wrote {}\n", out.string()));
        return SessionResult::kComplete;
    }
    Film film(w, h);
    if (job.features()) film.enable_aovs();

    ProgressiveRender render(job.scene, job.camera, *job.integrator, job.options, w, h, job.features());
    if (render.adaptive() && (in_memory || image_format_for(out) == ImageFormat::kExr)) film.enable_sample_counts();
    std::uint64_t fingerprint = 0;
    if (!checkpoint.empty() || distributed) {
        fingerprint = render_fingerprint(job, image_settings(args, job));
    }
    std::optional<Coordinator> cluster;
    if (distributed) {
        const int threads = job.options.threads > 0 ? job.options.threads
                                                    : static_cast<int>(std::max(1U, std::thread::hardware_concurrency()));
        // What a rank that cannot read the scene's files gets from this one.
        SceneFiles files{std::filesystem::current_path(), files_read(), {}};
        for (const auto& f : model_folders(std::filesystem::path(args.scene).parent_path()))
            files.model_folders.push_back(std::filesystem::absolute(f).lexically_normal());
        cluster.emplace(*cluster_, render, ClusterOptions{args.rank_timeout, threads, std::move(files)},
                        fingerprint);
    }
    if (!args.resume.empty()) {
        Checkpoint c = read_checkpoint(args.resume);
        if (c.fingerprint != fingerprint)
            throw IoError(fmt::format(
                "{}: a checkpoint of another scene or other options (the scene files, meshes, textures, "
                "camera, film, spp, seed, sampler, filter, adaptive settings and AOVs must all match); "
                "nothing rendered", args.resume));
        try {
            render.restore(std::move(c.state));
        } catch (const std::runtime_error& e) {
            throw IoError(fmt::format("{}: does not fit this render: {}", args.resume, e.what()));
        }
        progress.set_done(render.samples_taken());
        if (!args.quiet)
            say(fmt::format("glint: resuming {} at {} after {} pass{} ({:.1f} s)\n", args.resume, spp_text(render),
                            render.passes(), render.passes() == 1 ? "" : "es", render.state().seconds));
    }
    std::optional<TevClient> display;
    if (!args.display.empty()) {
        display.emplace(args.display);
        if (!display->connected()) note(args, display->note());
    }
    const std::string view_name = args.scene.empty() ? "glint" : std::filesystem::path(args.scene).filename().string();

    using clock = std::chrono::steady_clock;
    const auto start = clock::now();
    auto last_checkpoint = start;
    const auto seconds_since = [](clock::time_point t) {
        return std::chrono::duration<double>(clock::now() - t).count();
    };
    const auto save = [&] {
        write_checkpoint(checkpoint, fingerprint, render.state());
        last_checkpoint = clock::now();
    };
    bool interrupted = false, budget_hit = false;
    while (!render.finished()) {
        if (cancelled()) {
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
        const bool done = cluster ? cluster->run_pass(n, hooks_.cancel, &progress) : render.run_pass(n, hooks_.cancel, &progress);
        if (!done) {  // the pass in flight is abandoned
            interrupted = true;
            break;
        }
        if (hooks_.pass_done) hooks_.pass_done(render, std::chrono::duration<double>(clock::now() - start).count());
        if (display && display->connected()) {
            render.resolve(film);
            if (job.denoise && render.spp_done() >= 2) denoise_film(film, job.options.threads);
            if (!display->send(view_name, film)) note(args, display->note());
        }
        if (!checkpoint.empty() && seconds_since(last_checkpoint) >= every && !render.finished()) save();
    }
    if (cluster) {
        ranks_stopped_ = true;  // by finish, even if it throws
        const std::vector<RankReport> reports = cluster->finish();
        if (!args.quiet) say(format_reports(reports));
    }
    if (interrupted && args.animation)
        return interrupted_status(fmt::format("frame {} not written; run the command again to go on from it", args.frame));
    if (render.passes() == 0) {
        if (interrupted) return interrupted_status("no pass completed; nothing written");
        if (budget_hit) throw IoError("--time: the budget ended before the first pass; nothing written");
    }
    if (!checkpoint.empty()) save();
    render.resolve(film);
    if (job.denoise) {
        if (render.spp_done() >= 2) {
            const double took = denoise_film(film, job.options.threads);
            note(args, fmt::format("denoised in {:.2f} s", took));
        } else {
            note(args, "not denoised: it needs at least 2 samples per pixel, and the render stopped at 1");
        }
    }
    const ProgressiveState& state = render.state();
    RenderStats stats;
    stats.complete = !interrupted;
    stats.seconds = state.seconds;
    stats.rays = state.rays;
    std::string what = spp_text(render);
    if (!render.finished()) what += fmt::format(" of {}", render.spp_target());
    if (budget_hit) what += " (time budget reached)";
    deliver(film, metadata(args, render.spp_done(), render.spp_target(), render.passes(), state.seconds,
                           render.finished()));
    progress.finish(stats, w, h, what);
    if (!args.quiet && !in_memory) {
        say(fmt::format("wrote {}{}\n", out.string(),
                        checkpoint.empty() ? "" : fmt::format(" and checkpoint {}", checkpoint.string())));
    }
    if (interrupted) return interrupted_status(fmt::format("the image holds {} passes ({})", render.passes(), what));
    return SessionResult::kComplete;
}

}  // namespace glint
