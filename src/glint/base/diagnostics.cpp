#include "glint/base/diagnostics.h"

#include <fmt/core.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <mutex>
#include <set>
#include <sstream>
#include <numeric>

namespace glint {

void SourceFiles::add(const std::string& path, std::string text) { texts_[path] = std::move(text); }

std::string SourceFiles::line(const std::string& path, int line) const {
    const auto it = texts_.find(path);
    if (it == texts_.end() || line < 1) return {};
    const std::string& text = it->second;
    std::size_t start = 0;
    for (int i = 1; i < line; ++i) {
        start = text.find('\n', start);
        if (start == std::string::npos) return {};
        ++start;
    }
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    if (end > start && text[end - 1] == '\r') --end;
    return text.substr(start, end - start);
}

void Diagnostics::error(const SourceLoc& loc, std::string message) {
    errors_.push_back({loc, std::move(message)});
}

void Diagnostics::throw_if_errors() const {
    if (!errors_.empty()) throw SceneError(errors_, *sources_);
}

namespace {

// How many characters the token starting at `col` (0-based) spans: a quoted string, a flow
// list or map up to its matching bracket, or a plain scalar up to a separator.
std::size_t token_length(const std::string& line, std::size_t col, bool words = false) {
    if (col >= line.size()) return 1;
    const char c = line[col];
    if (c == '"' || c == '\'') {
        const auto end = line.find(c, col + 1);
        return end == std::string::npos ? line.size() - col : end - col + 1;
    }
    if (c == '[' || c == '{') {
        const char close = c == '[' ? ']' : '}';
        int depth = 0;
        for (std::size_t i = col; i < line.size(); ++i) {
            if (line[i] == c) ++depth;
            if (line[i] == close && --depth == 0) return i - col + 1;
        }
        return line.size() - col;
    }
    std::size_t end = col;
    if (words) {  // pbrt: a token ends at white space or a bracket
        while (end < line.size() && line[end] != ' ' && line[end] != '\t' && line[end] != '[' && line[end] != ']') ++end;
        return std::max<std::size_t>(1, end - col);
    }
    while (end < line.size() && line[end] != ',' && line[end] != ']' && line[end] != '}' &&
           line[end] != '#' && !(line[end] == ':' && (end + 1 == line.size() || line[end + 1] == ' ')))
        ++end;
    while (end > col && line[end - 1] == ' ') --end;
    return std::max<std::size_t>(1, end - col);
}

}  // namespace

namespace {

std::string format_as(const Diagnostic& d, const SourceFiles& sources, const char* severity) {
    std::string out;
    if (d.loc.line > 0) {
        out = fmt::format("{}:{}:{}: {}: {}\n", d.loc.file, d.loc.line, d.loc.column, severity, d.message);
        const std::string text = sources.line(d.loc.file, d.loc.line);
        if (!text.empty()) {
            const auto col = static_cast<std::size_t>(std::max(0, d.loc.column - 1));
            std::string caret;
            for (std::size_t i = 0; i < col && i < text.size(); ++i)
                caret += text[i] == '\t' ? '\t' : ' ';
            caret += '^';
            const bool pbrt = d.loc.file.size() >= 5 && d.loc.file.compare(d.loc.file.size() - 5, 5, ".pbrt") == 0;
            caret += std::string(token_length(text, col, pbrt) - 1, '~');
            out += fmt::format("    {}\n    {}\n", text, caret);
        }
    } else if (!d.loc.file.empty()) {
        out = fmt::format("{}: {}: {}\n", d.loc.file, severity, d.message);
    } else {
        out = fmt::format("{}: {}\n", severity, d.message);
    }
    return out;
}

}  // namespace

std::string format_diagnostic(const Diagnostic& d, const SourceFiles& sources) { return format_as(d, sources, "error"); }

std::string format_warning(const Diagnostic& d, const SourceFiles& sources) { return format_as(d, sources, "warning"); }

SceneError::SceneError(std::vector<Diagnostic> diagnostics, const SourceFiles& sources)
    : std::runtime_error([&] {
          std::string all;
          for (const auto& d : diagnostics) all += format_diagnostic(d, sources);
          return all;
      }()),
      diagnostics_(std::move(diagnostics)) {}

namespace {
std::vector<std::filesystem::path>& roots() {
    static std::vector<std::filesystem::path> folders;
    return folders;
}

// files_read(): readers run on several threads (meshes load in parallel).
std::mutex& read_mutex() {
    static std::mutex m;
    return m;
}
std::set<std::filesystem::path>& read_set() {
    static std::set<std::filesystem::path> files;
    return files;
}

// Whether `inner` is `outer` or lies inside it, component by component (both resolved).
bool within(const std::filesystem::path& inner, const std::filesystem::path& outer) {
    auto i = inner.begin();
    for (auto o = outer.begin(); o != outer.end(); ++o, ++i) {
        if (o->empty()) continue;  // a trailing separator
        if (i == inner.end() || *i != *o) return false;
    }
    return true;
}
}  // namespace

std::vector<std::filesystem::path> files_read() {
    const std::lock_guard lock(read_mutex());
    return {read_set().begin(), read_set().end()};
}

void forget_files_read() {
    const std::lock_guard lock(read_mutex());
    read_set().clear();
}

void restrict_reads_to(const std::vector<std::filesystem::path>& folders) {
    roots().clear();
    for (const auto& f : folders) {
        std::error_code ec;
        auto resolved = std::filesystem::weakly_canonical(std::filesystem::absolute(f), ec);
        roots().push_back(ec ? std::filesystem::absolute(f).lexically_normal() : resolved);
    }
}

std::vector<std::filesystem::path> split_search_path(const std::string& list) {
    std::vector<std::filesystem::path> dirs;
    for (std::size_t at = 0; at <= list.size();) {
        const std::size_t end = std::min(list.find(':', at), list.size());
        if (end > at) dirs.emplace_back(list.substr(at, end - at));
        at = end + 1;
    }
    return dirs;
}

std::string why_not_readable(const std::filesystem::path& path) {
    std::error_code ec;
    if (!roots().empty()) {
        const auto resolved = std::filesystem::weakly_canonical(std::filesystem::absolute(path, ec), ec);
        const bool allowed = !ec && std::any_of(roots().begin(), roots().end(),
                                                [&](const auto& root) { return within(resolved, root); });
        if (!allowed) {
            std::string list;
            for (const auto& root : roots()) list += (list.empty() ? "" : ", ") + root.string();
            return fmt::format("is outside the folders --restrict-paths allows ({})", list);
        }
    }
    const auto status = std::filesystem::status(path, ec);  // follows symbolic links
    if (ec || !std::filesystem::exists(status)) return {};
    if (std::filesystem::is_regular_file(status)) {
        const std::lock_guard lock(read_mutex());
        read_set().insert(std::filesystem::absolute(path, ec).lexically_normal());
        return {};
    }
    if (std::filesystem::is_directory(status)) return "is a folder";
    return "is not a regular file (a device, FIFO or socket)";
}

std::string read_scene_text(const std::string& path, const std::shared_ptr<SourceFiles>& sources) {
    if (const std::string why = why_not_readable(path); !why.empty()) {
        Diagnostics d(sources);
        d.error({path, 0, 0}, fmt::format("cannot read scene file: it {}", why));
        d.throw_if_errors();
    }
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        Diagnostics d(sources);
        d.error({path, 0, 0}, fmt::format("cannot open scene file: {}", std::strerror(errno)));
        d.throw_if_errors();
    }
    std::ostringstream text;
    text << in.rdbuf();
    if (in.bad()) {
        Diagnostics d(sources);
        d.error({path, 0, 0}, "cannot read scene file");
        d.throw_if_errors();
    }
    std::string s = text.str();
    // UTF-8 is read (its byte-order mark dropped); UTF-16 and UTF-32 are refused by name rather
    // than read as garbage keys.
    if (s.size() >= 3 && s.compare(0, 3, "\xEF\xBB\xBF") == 0) s.erase(0, 3);
    const auto starts = [&s](const char* bom, std::size_t n) { return s.size() >= n && s.compare(0, n, bom, n) == 0; };
    const char* encoding = starts("\xFF\xFE\0\0", 4) || starts("\0\0\xFE\xFF", 4) ? "UTF-32"
                           : starts("\xFF\xFE", 2) || starts("\xFE\xFF", 2)           ? "UTF-16"
                                                                                        : nullptr;
    if (encoding) {
        Diagnostics d(sources);
        d.error({path, 1, 1}, fmt::format("the file is {}; glint reads scene files as UTF-8: save it as UTF-8", encoding));
        d.throw_if_errors();
    }
    // A NUL byte anywhere: at its line and column (a parser would stop there, or read past it).
    if (const std::size_t nul = s.find('\0'); nul != std::string::npos) {
        const std::size_t line_start = s.rfind('\n', nul) == std::string::npos ? 0 : s.rfind('\n', nul) + 1;
        const int line = 1 + static_cast<int>(std::count(s.begin(), s.begin() + static_cast<std::ptrdiff_t>(nul), '\n'));
        const int column = 1 + static_cast<int>(nul - line_start);
        Diagnostics d(sources);
        d.error({path, line, column},
                line == 1 && s.find('\0', nul + 1) != std::string::npos
                    ? std::string("the file is not text (it holds NUL bytes; UTF-16 without a byte-order mark?); glint "
                                  "reads scene files as UTF-8")
                    : std::string("a NUL byte: scene files are UTF-8 text"));
        d.throw_if_errors();
    }
    return s;
}

std::string closest_match(const std::string& word, const std::vector<std::string>& candidates) {
    std::string best;
    std::size_t best_distance = std::max<std::size_t>(2, word.size() / 3) + 1;
    std::vector<std::size_t> row;
    for (const std::string& c : candidates) {
        // The distance is at least the difference in length: a candidate that cannot beat the
        // best so far is not compared. (A mistyped or garbage word of thousands of characters,
        // which fuzzers and hostile files are full of, costs nothing against short names.)
        const std::size_t gap = word.size() > c.size() ? word.size() - c.size() : c.size() - word.size();
        if (gap >= best_distance) continue;
        // Levenshtein distance, one row at a time; a row's smallest entry never falls in the rows
        // below it, so once it reaches the best so far this candidate is out.
        row.resize(c.size() + 1);
        std::iota(row.begin(), row.end(), 0);
        bool out = false;
        for (std::size_t i = 1; i <= word.size() && !out; ++i) {
            std::size_t diagonal = row[0];
            row[0] = i;
            std::size_t smallest = row[0];
            for (std::size_t j = 1; j <= c.size(); ++j) {
                const std::size_t above = row[j];
                row[j] = std::min({row[j] + 1, row[j - 1] + 1,
                                   diagonal + (word[i - 1] == c[j - 1] ? 0 : 1)});
                diagonal = above;
                smallest = std::min(smallest, row[j]);
            }
            out = smallest >= best_distance;
        }
        if (!out && row[c.size()] < best_distance) {
            best_distance = row[c.size()];
            best = c;
        }
    }
    return best;
}

}  // namespace glint
