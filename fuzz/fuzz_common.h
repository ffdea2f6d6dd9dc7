#pragma once
// What every fuzz target shares: a scratch folder of its own (the only folder its inputs may make
// glint read: restrict_reads_to), and the rule that a located error (SceneError, IoError) is the
// right answer to a bad input and anything else escaping is a bug (libFuzzer reports the
// uncaught exception as a crash, as it does a sanitizer report, a timeout or running out of memory).
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#include "glint/base/diagnostics.h"
#include "glint/image/image_io.h"
#include "glint/base/limits.h"

namespace glint::fuzz {

/// The process's scratch folder (created once, under $TMPDIR or /tmp, removed at exit), reads
/// restricted to it.
inline const std::filesystem::path& scratch() {
    static const std::filesystem::path dir = [] {
        const char* tmp = std::getenv("TMPDIR");
        std::filesystem::path d = std::filesystem::path(tmp && *tmp ? tmp : "/tmp") /
                                  ("glint-fuzz-" + std::to_string(::getpid()));
        std::filesystem::create_directories(d);
        restrict_reads_to({d});
        // Half the fuzzers' 2 GB: what a scene may allocate stays well inside -rss_limit_mb, so
        // running out of memory means a limit was not checked, not that it was set high.
        set_limit(Limit::kMemory, 1LL << 30);
        static struct Remove {
            std::filesystem::path d;
            ~Remove() {
                std::error_code ec;
                std::filesystem::remove_all(d, ec);
            }
        } remove{d};
        return d;
    }();
    return dir;
}

/// Writes `bytes` to scratch()/name and returns the path.
inline std::filesystem::path put(const std::string& name, std::string_view bytes) {
    const std::filesystem::path p = scratch() / name;
    std::ofstream out(p, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    return p;
}

inline std::string_view as_text(const std::uint8_t* data, std::size_t size) {
    return {reinterpret_cast<const char*>(data), size};
}

/// Runs `f`; the located errors glint reports for bad input are the expected outcome.
template <class F>
void expect_located_errors(F&& f) {
    reset_memory_budget();
    try {
        f();
    } catch (const SceneError&) {
    } catch (const IoError&) {
    }
}

}  // namespace glint::fuzz
