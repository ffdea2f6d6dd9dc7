// The ranks other than 0 of an MPI job (RenderSession::run_rank): each loads what rank 0 loads
// (from its own files, else a copy of rank 0's) and renders the tiles or whole frames rank 0
// hands out; what fails goes to rank 0, which reports it.
#include <fmt/core.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "glint/base/diagnostics.h"
#include "glint/image/image_io.h"
#include "glint/render/progressive.h"
#include "glint/samplers/hash.h"
#include "glint/session/checkpoint.h"
#include "glint/session/session.h"

namespace glint {

// A private folder under $TMPDIR (or /tmp), removed with everything in it when done.
struct RenderSession::TempFolder {
    std::filesystem::path path;
    TempFolder() {
        const char* tmp = std::getenv("TMPDIR");
        std::string pattern = (std::filesystem::path(tmp && *tmp ? tmp : "/tmp") / "glint-rank-XXXXXX").string();
        if (!::mkdtemp(pattern.data()))
            throw IoError(fmt::format("{}: cannot make a folder for rank 0's files: {}", pattern, std::strerror(errno)));
        path = pattern;
    }
    ~TempFolder() {
        std::error_code ec;
        std::filesystem::remove_all(path, ec);
    }
    TempFolder(const TempFolder&) = delete;
    TempFolder& operator=(const TempFolder&) = delete;
};

// What every frame of an animation shares, for ranks rendering whole frames to compare: the
// options that change the image and the bytes of every file the last load read (files_read(),
// emptied before it), whatever their paths.
std::uint64_t RenderSession::files_fingerprint(const SessionOptions& args, const RenderJob& job) {
    std::vector<std::uint64_t> files;
    for (const auto& path : files_read()) {
        std::ifstream in(path, std::ios::binary);
        const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        files.push_back(hash_bytes(bytes.data(), bytes.size()));
    }
    std::sort(files.begin(), files.end());
    const std::string settings = image_settings(args, job);
    std::uint64_t h = hash_bytes(settings.data(), settings.size());
    return hash_bytes(files.data(), files.size() * sizeof(files[0]), h);
}

// A rank whose own files failed it: asks rank 0 for the files it read, writes them into `copy`
// (made on first use) and loads `load(args)` from there: the scene as rank 0 named it, in the
// copy, and meshes found in rank 0's model folders, in the copy of them. `error` (this rank's
// own failure) gets the copy's failure added, with rank 0's paths rather than the copy's; it is
// cleared on success. False if rank 0 stopped the job first.
template <class Load>
bool RenderSession::load_from_rank0_copy(const SessionOptions& args, std::optional<TempFolder>& copy,
                                         std::optional<SessionOptions>& from_copy, std::deque<Message>& pending,
                                         std::string& error, const Load& load) {
    try {
        if (!copy) copy.emplace();
        const std::optional<SceneFiles> files = fetch_scene_files(*cluster_, copy->path, pending);
        if (!files) return false;
        SessionOptions local = args;
        local.scene = (copy->path / (files->cwd / args.scene).lexically_normal().relative_path()).string();
        std::string folders;
        for (const auto& f : files->model_folders)
            folders += (folders.empty() ? "" : ":") + (copy->path / f.relative_path()).string();
        ::setenv("GLINT_MODEL_PATH", folders.c_str(), 1);
        if (args.restrict_paths) restrict_reads_to({copy->path});
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
std::optional<std::vector<std::uint8_t>> RenderSession::render_frame_file(SessionOptions args, std::optional<RenderJob> job) {
    TempFolder out;
    args.local = true;
    args.quiet = true;
    args.output = (out.path / ("frame" + std::filesystem::path(args.output).extension().string())).string();
    if (render(args, std::move(job)) != SessionResult::kComplete) return std::nullopt;
    std::ifstream in(args.output, std::ios::binary);
    std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (!in.good() && !in.eof()) throw IoError(fmt::format("frame {}: cannot read back its image", args.frame));
    return bytes;
}

// A rank other than 0 of an animation handed out by whole frames: renders `args.frame` alone
// (from its own files, else rank 0's copy) into a private folder and sends the image file to
// rank 0. A failure goes to rank 0, which ends the job.
void RenderSession::run_rank_whole_frame(const SessionOptions& args, std::uint64_t expected,
                                         std::optional<TempFolder>& copy, std::optional<SessionOptions>& from_copy) {
    std::optional<RenderJob> job;
    SessionOptions used = args;
    const auto load = [&](const SessionOptions& a) {
        try {
            forget_files_read();
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
        SessionOptions a = *from_copy;
        a.frame = args.frame;
        if (load(a).empty()) error.clear();
    }
    if (!job && !args.scene.empty()) {
        std::deque<Message> pending;  // rank 0 sends nothing else while a frame is out
        if (!load_from_rank0_copy(args, copy, from_copy, pending, error, load)) return;
    }
    if (!job) {
        send_failure(*cluster_, fmt::format("could not load the scene at frame {}:\n{}", args.frame, error));
        return;
    }
    if (files_fingerprint(args, *job) != expected) {
        send_failure(*cluster_, fmt::format("frame {}: the scene, its files or the options differ from rank 0's "
                                                    "(each rank loads the scene itself: give every node the same files)",
                                                    args.frame));
        return;
    }
    try {
        used.scene_label = args.scene;
        std::optional<std::vector<std::uint8_t>> bytes = render_frame_file(used, std::move(job));
        if (!bytes) throw IoError(fmt::format("frame {} was interrupted", args.frame));
        send_frame_image(*cluster_, args.frame, *bytes);
    } catch (const std::exception& e) {
        send_failure(*cluster_, fmt::format("frame {}: {}", args.frame, e.what()));
    }
}

// A rank other than 0 of a distributed render: loads what rank 0 loads and renders the tiles it
// is given; what fails here is sent to rank 0, which reports it. A rank that cannot load the
// scene from its own files loads a copy of the files rank 0 read.
// `copy`: the folder of rank 0's files, kept from one frame of an animation to the next.
int RenderSession::run_rank_frame(const SessionOptions& args, std::optional<TempFolder>& copy,
                                  std::optional<SessionOptions>& from_copy) {
    std::optional<RenderJob> job;
    std::unique_ptr<ProgressiveRender> render;
    std::uint64_t fingerprint = 0;
    std::string error;
    const auto load = [&](const SessionOptions& a) {
        render.reset();  // before the scene it renders
        job.reset();
        try {
            job.emplace(prepare_job(a));
            render = std::make_unique<ProgressiveRender>(job->scene, job->camera, *job->integrator,
                                                                job->options, job->film_width, job->film_height,
                                                                job->features());
            fingerprint = render_fingerprint(*job, image_settings(a, *job));
            return std::string();
        } catch (const SceneError& e) {
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
    std::deque<Message> pending;
    if (!error.empty() && from_copy) {  // an earlier frame needed rank 0's files: try the copy first
        SessionOptions local = *from_copy;
        local.frame = args.frame;
        if (load(local).empty()) error.clear();
    }
    if (!error.empty() && !args.scene.empty() &&
        !load_from_rank0_copy(args, copy, from_copy, pending, error, load))
        return 0;  // rank 0 stopped the job first
    return serve(*cluster_, render.get(), fingerprint, job ? job->options.threads : 1, error,
                        std::move(pending));
}

int RenderSession::run_rank(const SessionOptions& args) {
    std::optional<TempFolder> copy;  // removed when this rank is done
    std::optional<SessionOptions> from_copy;
    if (args.frames.empty()) return run_rank_frame(args, copy, from_copy);
    // An animation: one render per frame rank 0 announces, until it stops the job; a frame is
    // either shared by tiles or this rank's alone.
    while (const std::optional<FrameOrder> order = wait_frame(*cluster_)) {
        SessionOptions a = args;
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

}  // namespace glint
