#pragma once
// A render session: everything `glint render` does between reading its flags and choosing its
// exit status, as a library call, so that every front end (the command line, the Python module)
// runs the same code: load the scene (formats.h), build it, render it in progressive passes
// (a time budget, checkpoints and resume, adaptive sampling, a tev display), write the image,
// render an animation's frames, and share the work with the other ranks of an MPI job.
//
// The session prints nothing itself: what a user should read (notes, "wrote ...", the ranks'
// reports) goes to SessionHooks::print as finished text, the progress bar to `progress_stream`.
// It stops when `cancel` becomes true (the CLI sets it from SIGINT/SIGTERM), between tiles.
#include <atomic>
#include <cstdint>
#include <cstdio>
#include <deque>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "glint/builder/build.h"
#include "glint/denoise/denoise.h"
#include "glint/formats/scene_writer.h"
#include "glint/render/distributed.h"
#include "glint/render/progress.h"
#include "glint/render/progressive.h"

namespace glint {

/// A scene read but not yet built (the Python module's glint.load and glint.load_dict): a
/// session given one builds it for each render with that render's options.
struct LoadedScene {
    SceneDescription description;
    std::shared_ptr<SourceFiles> sources;
    bool mesh = false;  ///< a mesh file rendered directly: framed by its bounds or its own camera
};

/// What to render and how: `glint render`'s options, one field per flag.
struct SessionOptions {
    std::string scene;   ///< a scene or mesh file; empty: the built-in demo
    /// A scene already read, rendered instead of reading `scene` (which then only names it).
    std::shared_ptr<const LoadedScene> loaded;
    std::string output;  ///< the image; empty: the scene's film.filename, else <scene stem>.png
    std::optional<long long> width, height, spp, threads, max_depth;
    std::optional<std::uint64_t> seed;
    bool quiet = false;   ///< nothing printed but errors (no notes, no progress)
    bool aovs = false;
    bool denoise = false; ///< the written image is denoised (the scene's film.denoise also asks)
    bool strict = false;  ///< pbrt: what glint cannot render is an error
    std::string accel;    ///< bvh, sbvh, embree; empty: the scene's or the default
    std::string light_sampler;  ///< bvh, power; empty: the scene's or the default
    std::string texture_filter;  ///< ewa, trilinear, none; empty: the scene's or the default
    std::optional<bool> spectral;  ///< --spectral (true) / --rgb (false); unset: the scene's
    std::string camera;   ///< a glTF file rendered directly: its camera by name
    // Long renders.
    std::string time, checkpoint, checkpoint_every = "5m", resume, display;
    std::optional<double> noise_threshold;
    std::optional<long long> min_spp;
    // Distributed rendering (mpirun).
    double rank_timeout = 60;
    // Animation: `frames` A:B (or N) and fps; `frame` is the one being rendered, `animation` says
    // it is a frame of `frames` (an interrupted frame is then not written: it is rendered again).
    std::string frames;
    std::optional<double> fps;
    double frame = 0;
    bool animation = false;
    // Under mpirun, a frame this process renders whole, alone (an animation's frames handed out whole).
    bool local = false;
    std::string scene_label;  ///< the scene as the image's metadata names it, if not `scene` (a copy's)
    bool restrict_paths = false;  ///< reads were restricted (a rank loading rank 0's copy restricts to it)
    ProgressMode progress = ProgressMode::kSummary;  ///< when not quiet
};

/// How a session reaches its front end.
struct SessionHooks {
    /// Text for the user, whole lines (the CLI writes it to stderr). Null: dropped.
    std::function<void(const std::string&)> print;
    /// Polled between tiles and passes: the render stops, keeping its completed passes.
    const std::atomic<bool>* cancel = nullptr;
    /// What stopped it, for messages ("SIGINT"); null: "a cancellation".
    std::function<std::string()> cancel_reason;
    /// Called before each render starts (the CLI installs its signal handlers there).
    std::function<void()> arm;
    /// A file about to be written through a temporary (slot 0: the image, 1: the checkpoint),
    /// so that a front end killed hard can remove the temporary (image/image_io.h).
    std::function<void(int slot, const std::filesystem::path& target)> writing;
    /// The stream of the progress bar or summary (the CLI: stderr).
    std::FILE* progress_stream = stderr;
    /// After each completed pass of a progressive render: how far it is, and the render itself,
    /// whose resolve(film) gives the image so far (a notebook's live view). Not called by the
    /// one-sample sweep (a single pass) nor on the ranks other than 0.
    std::function<void(const ProgressiveRender& render, double seconds)> pass_done;
    /// Set: the image is handed over in memory instead of written (the Python module). Called
    /// once, at the end, with the film (its AOVs, and the noisy image when denoised) and what a
    /// file's header would say of it (glint:spp, glint:complete, ...). `output` is then unused,
    /// AOVs need no EXR, and nothing is written but a checkpoint if one was asked for.
    std::function<void(const Film& film, const DisplaySettings& display, const ImageMetadata& metadata)> image;
};

/// How a render ended, when it did not throw.
enum class SessionResult {
    kComplete = 0,     ///< every image asked for written
    kInterrupted = 3,  ///< cancelled: the completed passes were written where that is possible
};

/// `options.scene` (a scene or mesh file, or the built-in demo) read at `options.frame`, not
/// built. Throws SceneError or IoError.
LoadedScene read_scene(const SessionOptions& options);

/// The scene loaded (or `options.loaded`) and built with every option that changes the image (no MPI thread share).
/// Notes for the user are in RenderJob::notes. Throws SceneError or IoError.
RenderJob load_job(const SessionOptions& options);

/// `glint convert`: reads `scene` (a scene file, not a mesh), builds it to report every error
/// before anything is written, then writes it as YAML to `out` (atomically), with its inline
/// meshes and grids beside it. `note` receives the source's warnings, formatted, before the
/// writing starts.
WrittenScene convert_scene(const std::string& scene, const std::filesystem::path& out, bool strict,
                           const std::function<void(const std::string&)>& note);

/// The AccelKind for a --accel name; nullopt for "". Throws IoError naming the known ones.
std::optional<AccelKind> parse_accel(const std::string& name);
/// The LightSamplerKind for a --light-sampler name; nullopt for "". Throws IoError naming the known ones.
std::optional<LightSamplerKind> parse_light_sampler(const std::string& name);
/// The TextureFilter for a --texture-filter name; nullopt for "". Throws IoError naming the known ones.
std::optional<TextureFilter> parse_texture_filter(const std::string& name);

class RenderSession {
public:
    /// `cluster`: the MPI job this process is a rank of (null: alone).
    RenderSession(SessionOptions options, SessionHooks hooks, Transport* cluster = nullptr);
    /// Rank 0: stops the other ranks if a render has not (an error ended it).
    ~RenderSession();
    RenderSession(const RenderSession&) = delete;
    RenderSession& operator=(const RenderSession&) = delete;

    /// Renders the image, or the animation's frames if `frames` is set. On ranks other than 0
    /// of an MPI job: serves rank 0 until it is done. Throws SceneError or IoError.
    SessionResult run();

    /// The file of frame `frame` for an output pattern: printf's %d, %0Nd or %Nd (N up to 9)
    /// once, %% for a percent sign. Throws IoError naming what is wrong with the pattern.
    static std::string frame_path(const std::string& pattern, long long frame, bool need_number);

private:
    struct TempFolder;
    SessionResult render(const SessionOptions& args, std::optional<RenderJob> preloaded = std::nullopt);
    SessionResult frames(SessionOptions args);
    RenderJob prepare_job(const SessionOptions& args);
    SessionResult interrupted(const SessionOptions& args, const std::string& what);
    void say(const std::string& text) const;
    void note(const SessionOptions& args, const std::string& text) const;
    bool cancelled() const { return hooks_.cancel && hooks_.cancel->load(); }
    // Ranks other than 0 (ranks.cpp).
    int run_rank(const SessionOptions& args);
    int run_rank_frame(const SessionOptions& args, std::optional<TempFolder>& copy,
                       std::optional<SessionOptions>& from_copy);
    void run_rank_whole_frame(const SessionOptions& args, std::uint64_t expected, std::optional<TempFolder>& copy,
                              std::optional<SessionOptions>& from_copy);
    template <class Load>
    bool load_from_rank0_copy(const SessionOptions& args, std::optional<TempFolder>& copy,
                              std::optional<SessionOptions>& from_copy, std::deque<Message>& pending,
                              std::string& error, const Load& load);
    std::optional<std::vector<std::uint8_t>> render_frame_file(SessionOptions args, std::optional<RenderJob> job);
    std::uint64_t files_fingerprint(const SessionOptions& args, const RenderJob& job);

    SessionOptions options_;
    SessionHooks hooks_;
    Transport* cluster_ = nullptr;
    bool ranks_stopped_ = false;    ///< rank 0 has told the other ranks to stop
    bool animation_ranks_ = false;  ///< rank 0 of a distributed animation: the ranks wait for a frame
};

/// `glint denoise`: the image of an EXR written by `glint render --aovs` (or any EXR with channels
/// R, G, B, the half images even.R/G/B and odd.R/G/B, and optionally albedo.R/G/B, N.X/Y/Z, Z
/// and the albedo's halves albedo.even.R/G/B and albedo.odd.R/G/B), denoised, written to `out` (EXR: with the input's channels and noisy.R/G/B; PNG, JPEG ...:
/// the image alone). `threads` 0: every core. Returns the seconds the filter took. Throws IoError
/// naming the file, the channel or the pixel at fault; nothing is written then.
/// `radius`: the filter window's half size in pixels (denoise/denoise.h).
double denoise_file(const std::filesystem::path& in, const std::filesystem::path& out, int threads,
                    int radius = DenoiseOptions{}.radius);

/// The options that change the image, as text: part of a checkpoint's fingerprint.
std::string image_settings(const SessionOptions& args, const RenderJob& job);

}  // namespace glint
