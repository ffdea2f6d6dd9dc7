#pragma once
// One render spread over the processes of an MPI job (`mpirun -np N glint render ...`).
//
// Every rank loads the scene itself (from a shared file system or identical copies: a fingerprint
// of the scene, its meshes and textures and the options is compared, and a rank that loaded
// something else is an error) and builds its own acceleration structure. A rank that cannot load
// it from its own files asks rank 0 for the files rank 0 read and loads a copy of them. Rank 0 runs the passes
// of the progressive renderer as a single process would and hands out each pass's tiles in
// chunks, on request: a rank asks for more when it has rendered what it had, so a slow or busy
// node takes fewer. Rank 0 renders tiles too, on a thread of its own, while its main thread
// answers the others. A tile goes out with its sums before the pass and comes back with them
// after it; its result is the same bytes whichever rank renders it, so the image
// is the single process's to the bit whatever N and whatever order the tiles came back in.
//
// Faults: a chunk whose rank has not answered within the timeout is handed out again (the first
// result for a tile is kept, a late duplicate dropped). A rank that dies takes the job with it
// (Open MPI aborts a job when a rank exits early); --checkpoint-every bounds what that loses.
//
// The messages go through `Transport`, implemented on MPI by libglint_mpi.so (loaded only in an
// MPI job, so that a single process never loads Open MPI's libraries). All MPI calls are made by
// the thread that started it (MPI_THREAD_FUNNELED).
#include <atomic>
#include <cstdint>
#include <deque>
#include <functional>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "glint/render/progress.h"
#include "glint/render/progressive.h"

namespace glint {

struct Message {
    int source = -1;
    int tag = -1;
    std::vector<std::uint8_t> bytes;
};

/// Point-to-point messages between the ranks of one job. Sends do not block (the bytes are kept
/// until delivered); receive takes one waiting message from any rank, or returns false.
class Transport {
public:
    virtual ~Transport() = default;
    virtual int rank() const = 0;
    virtual int size() const = 0;
    virtual void send(int to, int tag, std::vector<std::uint8_t> bytes) = 0;
    virtual bool receive(Message& message) = 0;
    /// Waits until every send has been delivered.
    virtual void flush() = 0;
    /// Ends the job at once, every rank (MPI_Abort).
    [[noreturn]] virtual void abort(int status) = 0;
};

/// True when this process was started by an MPI launcher (Open MPI's mpirun, or a PMIx launcher).
bool launched_by_mpi();
/// The ranks of this job on this host (to share the cores between them), 1 outside MPI.
int local_ranks();
/// MPI through libglint_mpi.so: initialises MPI. Throws IoError if this glint was built
/// without MPI or the module cannot be loaded.
std::unique_ptr<Transport> mpi_transport(int& argc, char**& argv);

/// The scheduler's chunk: for a rank of `k` threads asking when `left` tiles are queued and the
/// job has `all_threads` threads, ceil(left / (2 all_threads)) tiles per thread (guided
/// self-scheduling: chunks shrink as the queue does, so the ranks finish a pass together), at
/// least one per thread, at most `left`.
int chunk_tiles(int left, int all_threads, int k);

/// What each rank did, for the report at the end.
struct RankReport {
    int rank = 0;
    std::string host;
    int threads = 0;
    std::uint64_t tiles = 0, samples = 0;
    double busy = 0;  ///< seconds spent rendering tiles
    double idle = 0;  ///< seconds of the job not spent rendering
};

/// What rank 0 read to load the scene, for the ranks that cannot read it themselves.
struct SceneFiles {
    std::filesystem::path cwd;                           ///< rank 0's working folder
    std::vector<std::filesystem::path> files;            ///< absolute (files_read())
    std::vector<std::filesystem::path> model_folders;    ///< absolute, in search order
};

struct ClusterOptions {
    /// A chunk not answered within this many seconds is handed out again.
    double timeout = 60;
    int threads = 1;  ///< rank 0's render threads
    SceneFiles files;
};

/// Rank 0's side.
class Coordinator {
public:
    /// `fingerprint` identifies the render (render_fingerprint); every rank must have the same.
    Coordinator(Transport& transport, ProgressiveRender& render, const ClusterOptions& options,
                std::uint64_t fingerprint);
    ~Coordinator();
    Coordinator(const Coordinator&) = delete;
    Coordinator& operator=(const Coordinator&) = delete;

    /// ProgressiveRender::run_pass over every rank. Returns false, the state unchanged, if
    /// `cancel` became true first. Throws IoError if a rank failed (its message).
    bool run_pass(int n, const std::atomic<bool>* cancel, Progress* progress);
    /// Tells every rank to stop and waits for their reports (rank 0's first). Throws IoError if
    /// a rank reported a failure; the ranks are stopped either way.
    std::vector<RankReport> finish();

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

/// A rank other than 0 that could not load the scene from its own files: asks rank 0 for every
/// file rank 0 read and writes each one under `folder` at rank 0's path (`/a/b.ply` as
/// `folder/a/b.ply`). Returns rank 0's working folder and model folders; nullopt if rank 0
/// stopped the job first (this rank has then reported and may exit). Messages meant for later
/// (a pass) are kept in `pending` for serve. Throws IoError if rank 0 could not send a file.
std::optional<SceneFiles> fetch_scene_files(Transport& transport, const std::filesystem::path& folder,
                                            std::deque<Message>& pending);

/// A rank other than 0: takes passes and tiles from rank 0 until told to stop, starting with the
/// messages in `pending`. `render` is null when this rank could not load the scene: `error` then
/// says why, and it goes to rank 0. Returns the process's exit status.
int serve(Transport& transport, ProgressiveRender* render, std::uint64_t fingerprint, int threads,
          const std::string& error, std::deque<Message> pending = {});

/// Animations (`--frames`): rank 0 tells every rank which frame comes next, before that frame's
/// Coordinator; each frame is then a render of its own, ended by the Coordinator's finish.
void send_frame(Transport& transport, double frame);
/// What a rank other than 0 is told between frames: a frame rendered by tiles with everyone
/// (serve), or one to render whole on its own (send_frame_image).
struct FrameOrder {
    double frame = 0;
    bool whole = false;
    std::uint64_t fingerprint = 0;  ///< whole: what the rank's files_fingerprint must be
};
/// A rank other than 0: the next frame, or nullopt when rank 0 stopped the job (this rank has
/// then said goodbye and may exit).
std::optional<FrameOrder> wait_frame(Transport& transport);

/// What a rank did in an animation rendered by whole frames.
struct FrameReport {
    int rank = 0;
    int frames = 0;   ///< frames of this rank's that were written
    /// Seconds at work: rank 0's render thread rendering; another rank, from each frame's
    /// hand-out to its image's arrival at rank 0 (loading, rendering and sending).
    double busy = 0;
    double wall = 0;  ///< the whole dispatch
};

/// Rank 0 of an animation with at least as many frames as ranks: frames go out whole, one at a
/// time, to each rank as it finishes its last (a slow rank takes fewer); when none is left, a
/// rank that asks (rank 0's thread too) gets a duplicate of a frame still being rendered elsewhere (a straggler's), and
/// the first image of a frame is the one written. Rank 0 renders frames on a thread of its own
/// through `render_here`, which returns the image file's bytes (nothing: interrupted, stop);
/// `write(frame, rank, file bytes)` is called once per frame, for the first copy to arrive,
/// on this thread or rank 0's render thread (never twice for a frame, possibly at once for two). Ends by stopping every rank, writing the frames
/// that arrive meanwhile. Throws IoError with a rank's failure.
/// `fingerprint` (files_fingerprint on rank 0) goes with every frame; a rank whose own differs
/// reports a failure instead of rendering.
std::vector<FrameReport> dispatch_frames(Transport& transport, const std::vector<double>& frames,
                                         std::uint64_t fingerprint, const SceneFiles& files,
                                         const std::function<std::optional<std::vector<std::uint8_t>>(double)>& render_here,
                                         const std::function<void(double, int, const std::vector<std::uint8_t>&)>& write,
                                         const std::atomic<bool>* cancel);
/// A rank other than 0: the image file of a frame it rendered whole, to rank 0.
void send_frame_image(Transport& transport, double frame, const std::vector<std::uint8_t>& image);
/// A rank other than 0: a failure, reported by rank 0 as its own error.
void send_failure(Transport& transport, const std::string& text);

/// Rank 0, leaving without a Coordinator's finish (an error before or during the render): tells
/// every other rank to stop and waits until each has.
void stop_ranks(Transport& transport) noexcept;

/// The per-rank table printed at the end of a distributed render.
std::string format_reports(const std::vector<RankReport>& reports);
/// The same for an animation rendered by whole frames: frames written, their share, busy and idle
/// seconds (idle = the dispatch's wall time less busy).
std::string format_frame_reports(const std::vector<FrameReport>& reports);

}  // namespace glint
