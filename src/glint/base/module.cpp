#include "glint/base/module.h"

#include <dlfcn.h>
#include <fmt/core.h>

#include <cstdlib>
#include <filesystem>
#include <map>
#include <mutex>
#include <vector>

#include "glint/base/diagnostics.h"
#include "glint/base/errors.h"

namespace glint {

namespace fs = std::filesystem;

namespace {

std::vector<fs::path> module_folders() {
    std::vector<fs::path> dirs;
    if (const char* env = std::getenv("GLINT_MODULE_PATH")) dirs = split_search_path(env);
    Dl_info info{};
    if (dladdr(reinterpret_cast<void*>(&module_entry), &info) != 0 && info.dli_fname) {
        std::error_code ec;
        const fs::path self = fs::canonical(info.dli_fname, ec);
        if (!ec) {
            dirs.push_back(self.parent_path());
            dirs.push_back(self.parent_path().parent_path() / "lib" / "glint");
        }
    }
#ifdef GLINT_MODULE_BUILD_DIR
    dirs.emplace_back(GLINT_MODULE_BUILD_DIR);
#endif
    return dirs;
}

}  // namespace

void* module_entry(const std::string& name) {
    static std::mutex mutex;
    static std::map<std::string, void*> loaded;
    const std::lock_guard lock(mutex);
    if (const auto it = loaded.find(name); it != loaded.end()) return it->second;
    const std::string file = "libglint_" + name + ".so";
    const std::string symbol = "glint_" + name + "_module";
    std::string tried;
    for (const fs::path& dir : module_folders()) {
        const fs::path path = dir / file;
        std::error_code ec;
        if (!fs::is_regular_file(path, ec)) {
            tried += fmt::format("{}{}", tried.empty() ? "" : ", ", dir.string());
            continue;
        }
        void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
        if (!handle) throw IoError(fmt::format("cannot load glint's module '{}': {}", path.string(), dlerror()));
        void* entry = dlsym(handle, symbol.c_str());
        if (!entry)
            throw IoError(fmt::format("cannot load glint's module '{}': it has no {}", path.string(), symbol));
        loaded.emplace(name, entry);  // never unloaded: its code may be on a stack until exit
        return entry;
    }
    throw IoError(fmt::format("glint's module {} was not found (looked in {}; set GLINT_MODULE_PATH to the "
                              "folder that holds it)", file, tried.empty() ? "no folder" : tried));
}

}  // namespace glint
