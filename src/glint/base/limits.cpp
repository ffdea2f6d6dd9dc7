#include "glint/base/limits.h"

#include <unistd.h>

#include <array>
#include <atomic>
#include <charconv>
#include <cmath>

#include <fmt/format.h>

#include "glint/base/errors.h"

namespace glint {

namespace {

struct Entry {
    const char* name;
    const char* unit;  // how asked values read in messages
};
constexpr std::array<Entry, kLimitCount> kEntries{{
    {"film-pixels", "film pixels"},
    {"texture-pixels", "image pixels"},
    {"triangles", "triangles"},
    {"vertices", "vertices"},
    {"grid-voxels", "voxels"},
    {"nesting", "levels of nesting"},
    {"includes", "levels of included files"},
    {"memory", "bytes"},
    {"nodes", "values"},
}};

long long physical_memory() {
    const long pages = ::sysconf(_SC_PHYS_PAGES), page = ::sysconf(_SC_PAGESIZE);
    return pages > 0 && page > 0 ? static_cast<long long>(pages) * page : 16LL << 30;
}

std::array<std::atomic<long long>, kLimitCount>& values() {
    static std::array<std::atomic<long long>, kLimitCount> v{{
        {1LL << 27},          // film-pixels
        {1LL << 27},          // texture-pixels
        {1LL << 28},          // triangles
        {1LL << 28},          // vertices
        {1LL << 28},          // grid-voxels
        {256},                // nesting
        {32},                 // includes
        {physical_memory()},  // memory
        {1LL << 24},          // nodes
    }};
    return v;
}

std::atomic<long long> charged{0};

}  // namespace

long long limit(Limit l) { return values()[int(l)].load(std::memory_order_relaxed); }
void set_limit(Limit l, long long value) { values()[int(l)].store(value, std::memory_order_relaxed); }

std::optional<Limit> limit_named(std::string_view name) {
    for (int i = 0; i < kLimitCount; ++i)
        if (name == kEntries[i].name) return static_cast<Limit>(i);
    return std::nullopt;
}

std::string limit_names() {
    std::string s;
    for (const Entry& e : kEntries) s += (s.empty() ? "" : ", ") + std::string(e.name);
    return s;
}

void set_limit_from_text(const std::string& assignment) {
    const auto eq = assignment.find('=');
    const std::string name = assignment.substr(0, eq);
    const auto l = limit_named(name);
    if (!l) throw IoError(fmt::format("--limit {}: unknown limit '{}' (known: {})", assignment, name, limit_names()));
    if (eq == std::string::npos) throw IoError(fmt::format("--limit {}: expected {}=N", assignment, name));
    const std::string text = assignment.substr(eq + 1);
    double v = 0;
    const auto r = std::from_chars(text.data(), text.data() + text.size(), v);
    const std::string suffix(r.ptr, text.data() + text.size());
    double scale = 1;
    if (suffix == "k") scale = 1e3;
    else if (suffix == "M") scale = 1e6;
    else if (suffix == "G") scale = 1e9;
    else if (suffix == "T") scale = 1e12;
    else if (suffix == "KiB") scale = 1024.0;
    else if (suffix == "MiB") scale = 1024.0 * 1024;
    else if (suffix == "GiB") scale = 1024.0 * 1024 * 1024;
    else if (suffix == "TiB") scale = 1024.0 * 1024 * 1024 * 1024;
    else if (!suffix.empty()) scale = -1;
    const double n = v * scale;
    if (r.ec != std::errc{} || r.ptr == text.data() || scale < 0 || !(n >= 1) || n > 9.0e18 || n != std::floor(n))
        throw IoError(fmt::format("--limit {}: '{}' is not a whole number of at least 1 (suffixes: k, M, G, T, KiB, MiB, "
                                  "GiB, TiB)", assignment, text));
    set_limit(*l, static_cast<long long>(n));
}

std::string over_limit(Limit l, long long asked, long long cap) {
    const Entry& e = kEntries[int(l)];
    if (cap > 0 && cap != limit(l)) return fmt::format("{} {} exceed the limit of {}", asked, e.unit, cap);
    return fmt::format("{} {} exceed the limit of {} (raise it with --limit {}=N)", asked, e.unit, limit(l), e.name);
}

void reset_memory_budget() { charged.store(0); }

std::string charge_memory(long long bytes, std::string_view what) {
    const long long cap = limit(Limit::kMemory);
    long long now = charged.load();
    for (;;) {
        if (bytes > cap - now)
            return fmt::format("{} needs {:.1f} MB; with the {:.1f} MB asked for before it, that exceeds the memory limit of "
                               "{:.1f} MB (raise it with --limit memory=N)",
                               what, bytes / 1e6, now / 1e6, cap / 1e6);
        if (charged.compare_exchange_weak(now, now + bytes)) return {};
    }
}

long long memory_charged() { return charged.load(); }

}  // namespace glint
