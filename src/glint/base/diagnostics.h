#pragma once
// Errors in user input, compiler-style (pbrt-v4's FileLoc, Tungsten's caret):
//
//   scenes/demo.yaml:12:17: error: unknown material 'chrome' (known: red, floor)
//       material: chrome
//                 ^~~~~~
//
// Every value parsed from a file carries a SourceLoc. Errors are collected, not thrown one at a
// time; when a stage ends with errors it throws one SceneError holding all of them.
#include <filesystem>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace glint {

struct SourceLoc {
    std::string file;  ///< path as the user gave it, or "<command line>"
    int line = 0;      ///< 1-based; 0 when the error is about the whole file or a flag
    int column = 0;    ///< 1-based
};

struct Diagnostic {
    SourceLoc loc;
    std::string message;
};

/// The folders of a search-path list ("a:b:c"; empty entries skipped), e.g. from an environment
/// variable.
std::vector<std::filesystem::path> split_search_path(const std::string& list);

/// Why glint must not read `path`, as the end of a sentence starting "it ": it lies outside the
/// folders given to restrict_reads_to ("is outside the folders --restrict-paths allows (...)"),
/// or it names a folder, a device, a FIFO or a socket (reading those blocks or never ends): "is
/// a folder", "is not a regular file (a device, FIFO or socket)". Empty for a regular file, or
/// for a path that does not exist (opening it says so). Every file glint reads is asked first.
std::string why_not_readable(const std::filesystem::path& path);

/// Every regular file why_not_readable has let through in this process, as absolute, lexically
/// normal paths, sorted: the files a render read (a distributed render's rank 0 sends them to the
/// ranks that cannot read them).
std::vector<std::filesystem::path> files_read();
/// Starts files_read() afresh (before loading one frame of an animation).
void forget_files_read();

/// --restrict-paths: from now on only files under `folders` (resolved: symbolic links and ".."
/// followed) may be read; an empty list lifts the restriction. Set once, before reading starts.
void restrict_reads_to(const std::vector<std::filesystem::path>& folders);

/// The text of the files diagnostics point into, so that messages can quote the line.
class SourceFiles {
public:
    void add(const std::string& path, std::string text);
    /// Line `line` (1-based) of `path`, without its newline; empty if unknown.
    std::string line(const std::string& path, int line) const;
    /// Every file read, by path.
    const std::map<std::string, std::string>& texts() const { return texts_; }

private:
    std::map<std::string, std::string> texts_;
};

class Diagnostics {
public:
    explicit Diagnostics(std::shared_ptr<SourceFiles> sources = std::make_shared<SourceFiles>())
        : sources_(std::move(sources)) {}
    void error(const SourceLoc& loc, std::string message);
    bool empty() const { return errors_.empty(); }
    const std::vector<Diagnostic>& errors() const { return errors_; }
    SourceFiles& sources() { return *sources_; }
    /// Throws SceneError if any error was recorded.
    void throw_if_errors() const;

private:
    std::shared_ptr<SourceFiles> sources_;
    std::vector<Diagnostic> errors_;
};

/// One diagnostic as text: "file:line:col: error: message", then the source line and a caret
/// under the offending token (~ under the rest of it).
std::string format_diagnostic(const Diagnostic& d, const SourceFiles& sources);
/// The same with "warning" in place of "error".
std::string format_warning(const Diagnostic& d, const SourceFiles& sources);

class SceneError : public std::runtime_error {
public:
    SceneError(std::vector<Diagnostic> diagnostics, const SourceFiles& sources);
    const std::vector<Diagnostic>& diagnostics() const { return diagnostics_; }

private:
    std::vector<Diagnostic> diagnostics_;
};

/// A scene file's whole text; a file that cannot be opened or read is a SceneError naming it.
std::string read_scene_text(const std::string& path, const std::shared_ptr<SourceFiles>& sources);

/// The closest of `candidates` to `word` by edit distance, if close enough to be a likely typo.
std::string closest_match(const std::string& word, const std::vector<std::string>& candidates);

}  // namespace glint
