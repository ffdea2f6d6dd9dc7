#pragma once
// The fixture of the command's end-to-end tests (cli_test.cpp, cli_long_render_test.cpp): runs
// the real glint binary in a private folder and captures its exit status and output.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "testing.h"

namespace glint_cli_test {

namespace fs = std::filesystem;

struct Result {
    int status;
    std::string out, err;
};

class Cli : public ::testing::Test {
protected:
    static std::string read(const fs::path& p) { return glint::testing::read_file(p); }
    // Runs glint in the test's folder; with `limit` seconds > 0 it is killed after that long, so
    // a regression to a hang fails instead of stalling the suite.
    Result run(const std::string& args, int limit = 0) {
        const std::string timeout = limit > 0 ? "timeout " + std::to_string(limit) + " " : "";
        const std::string cmd = std::string("cd '") + dir_.path().string() + "' && " + timeout + "'" + GLINT_CLI +
                                "' " + args + " >out.txt 2>err.txt </dev/null";
        const int raw = std::system(cmd.c_str());
        Result r{WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, read(dir_ / "out.txt"),
                 read(dir_ / "err.txt")};
        fs::remove(dir_ / "out.txt");
        fs::remove(dir_ / "err.txt");
        return r;
    }
    void write(const std::string& name, const std::string& text) { std::ofstream(dir_ / name) << text; }
    static std::string seed(const std::string& name) {
        return std::string(GLINT_SOURCE_DIR) + "/scenes/seed/" + name;
    }
    glint::testing::TempDir dir_;
};

}  // namespace glint_cli_test
