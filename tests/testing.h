#pragma once
// Helpers shared by the tests.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace glint::testing {

/// Whether this is the sanitized build's run of the suite (`make test` runs the suite twice: the
/// release build, then ASan + UBSan, where the same code runs 5-20 times slower). A test whose
/// cost is repetitions of one check (rays against brute force, mutated scenes, BSDF samples) takes
/// `scaled(n)` of them: all of them in the release run, a fifth under the sanitizers, which look
/// for memory and undefined-behaviour errors on the same code paths, not for statistical power.
#if GLINT_TESTS_SANITIZED
inline constexpr bool kSanitized = true;
#else
inline constexpr bool kSanitized = false;
#endif
constexpr int scaled(int n) { return kSanitized ? (n + 4) / 5 : n; }

/// Of `n` variations of one check (viewing angles, seeds), whether the `i`th runs: every one in
/// the release run, one in `n` under the sanitizers; `offset` (a case's index) turns which one,
/// so that across cases every variation still runs.
constexpr bool variation_runs(int i, int offset, int n) { return !kSanitized || (i + offset) % n == 0; }

/// A fresh, empty folder named after the running test, removed with everything in it at the
/// end of the scope.
class TempDir {
public:
    TempDir() : path_(std::filesystem::temp_directory_path() / folder_name()) {
        std::filesystem::remove_all(path_);
        std::filesystem::create_directories(path_);
    }
    ~TempDir() {
        std::error_code ignored;
        std::filesystem::remove_all(path_, ignored);
    }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;

    const std::filesystem::path& path() const { return path_; }
    std::filesystem::path operator/(const std::string& name) const { return path_ / name; }
    std::size_t file_count() const {
        return static_cast<std::size_t>(
            std::distance(std::filesystem::directory_iterator(path_), {}));
    }

private:
    // One folder, not nested ones: a parameterised test's names hold slashes ("Backends/Suite",
    // "Name/0"), which would leave the parents behind.
    static std::string folder_name() {
        const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
        std::string name = "glint_" + std::to_string(::getpid()) + "_" +
                           info->test_suite_name() + "_" + info->name();
        for (char& c : name)
            if (c == '/') c = '-';
        return name;
    }

    std::filesystem::path path_;
};

inline std::string read_file(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

}  // namespace glint::testing
