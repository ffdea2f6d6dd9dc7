// An animation's frames (RenderSession::frames): each frame rendered in turn, or handed out whole
// to the ranks of an MPI job; frames whose file exists are skipped, so a killed job goes on where
// it stopped.
#include <fmt/core.h>

#include <filesystem>
#include <mutex>
#include <string>
#include <vector>

#include "glint/base/diagnostics.h"
#include "glint/session/session.h"

namespace glint {

std::string RenderSession::frame_path(const std::string& pattern, long long frame, bool need_number) {
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
            throw IoError(fmt::format("-o {}: '%' at character {} must be %d, %0Nd (N from 1 to 9) or %%",
                                             pattern, i + 1));
        std::string digits = std::to_string(frame);
        const std::size_t w = static_cast<std::size_t>(width);
        if (digits.size() < w) digits.insert(digits.front() == '-' && zero ? 1 : 0, w - digits.size(), zero ? '0' : ' ');
        out += digits;
        ++numbers;
        i = j;
    }
    if (numbers > 1) throw IoError(fmt::format("-o {}: the frame number may appear once", pattern));
    if (numbers == 0 && need_number)
        throw IoError(fmt::format("-o {}: several frames need the frame number in the name, e.g. frame_%04d.exr",
                                         pattern));
    return out;
}

// --frames A:B -o out/frame_%04d.exr: each frame rendered in turn (across the
// ranks under mpirun), frames whose file exists skipped, so a killed job goes on where it stopped.
SessionResult RenderSession::frames(SessionOptions args) {
    const bool distributed = cluster_ && cluster_->size() > 1;
    if (distributed && cluster_->rank() > 0) {
        run_rank(args);
        return SessionResult::kComplete;
    }
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
            throw IoError(fmt::format("--frames {}: expected FIRST:LAST (whole numbers, 0 <= FIRST <= LAST) or one frame", f));
    }
    if (!args.checkpoint.empty() || !args.resume.empty())
        throw IoError("--frames renders frame by frame and skips the frames already written (that is how an "
                             "animation resumes); --checkpoint and --resume are for one image");
    const std::string pattern = args.output;
    if (pattern.empty()) throw IoError("--frames needs -o with the frame number in the name, e.g. -o out/frame_%04d.exr");
    frame_path(pattern, first, last > first);  // a bad pattern fails before anything renders
    args.animation = true;
    if (distributed) ranks_stopped_ = animation_ranks_ = true;  // the ranks wait for a frame
    long long rendered = 0, skipped = 0;
    std::vector<double> todo;
    for (long long f = first; f <= last; ++f) {
        const std::string out = frame_path(pattern, f, last > first);
        std::error_code ec;
        if (std::filesystem::exists(out, ec)) {  // written whole (images are renamed into place)
            ++skipped;
            if (!args.quiet) say(fmt::format("glint: frame {}: {} exists; skipped\n", f, out));
        } else {
            todo.push_back(static_cast<double>(f));
        }
    }
    if (distributed && !todo.empty() && todo.size() >= static_cast<std::size_t>(cluster_->size())) {
        // At least a frame per rank: frames go out whole. The first frame is loaded here first, so
        // its errors come before any rank starts and rank 0 knows its files for ranks that ask.
        SessionOptions a = args;
        a.frame = todo.front();
        forget_files_read();
        const std::uint64_t fingerprint = files_fingerprint(a, prepare_job(a));
        SceneFiles files{std::filesystem::current_path(), files_read(), {}};
        for (const auto& f : model_folders(std::filesystem::path(args.scene).parent_path()))
            files.model_folders.push_back(std::filesystem::absolute(f).lexically_normal());
        std::mutex print;
        const auto said = [&](double f, int rank) {
            if (args.quiet) return;
            std::lock_guard lock(print);
            say(fmt::format("glint: frame {} written by rank {}: {}\n", f, rank,
                            frame_path(pattern, static_cast<long long>(f), last > first)));
        };
        animation_ranks_ = false;  // dispatch_frames stops the ranks however it ends
        if (hooks_.arm) hooks_.arm();
        const std::vector<FrameReport> reports = dispatch_frames(
            *cluster_, todo, fingerprint, files,
            [&](double f) {
                SessionOptions one = args;
                one.frame = f;
                one.output = frame_path(pattern, static_cast<long long>(f), last > first);
                return render_frame_file(one, std::nullopt);
            },
            [&](double f, int rank, const std::vector<std::uint8_t>& bytes) {
                write_file_atomically(frame_path(pattern, static_cast<long long>(f), last > first), bytes, "the image");
                said(f, rank);
            },
            hooks_.cancel);
        for (const FrameReport& r : reports) rendered += r.frames;
        if (!args.quiet) {
            say(format_frame_reports(reports));
            say(fmt::format("glint: {} frame{} rendered, {} skipped (already written)\n", rendered,
                            rendered == 1 ? "" : "s", skipped));
        }
        if (cancelled()) return interrupted(args, "the frames in flight on rank 0 were not written");
        return SessionResult::kComplete;
    }
    for (const double frame : todo) {
        const auto f = static_cast<long long>(frame);
        const std::string out = frame_path(pattern, f, last > first);
        if (!args.quiet) say(fmt::format("glint: frame {} of {}:{}\n", f, first, last));
        SessionOptions a = args;
        a.output = out;
        a.frame = static_cast<double>(f);
        if (distributed) {
            send_frame(*cluster_, a.frame);
            ranks_stopped_ = false;  // until this frame's render stops them
        }
        if (const SessionResult status = render(a); status != SessionResult::kComplete) return status;
        ++rendered;
        if (cancelled()) break;  // a signal after the frame's last pass: the frame is whole
    }
    if (!args.quiet)
        say(fmt::format("glint: {} frame{} rendered, {} skipped (already written)\n", rendered,
                        rendered == 1 ? "" : "s", skipped));
    return cancelled() ? SessionResult::kInterrupted : SessionResult::kComplete;
}

}  // namespace glint
