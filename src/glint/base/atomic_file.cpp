#include "glint/base/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <fmt/core.h>

#include <cerrno>
#include <cstring>

#include "glint/base/errors.h"

namespace glint {

namespace fs = std::filesystem;

fs::path temporary_path(const fs::path& target) {
    const fs::path dir = target.parent_path().empty() ? fs::path(".") : target.parent_path();
    return dir / fmt::format(".{}.glint-{}.tmp", target.filename().string(), ::getpid());
}

void write_temporary(const fs::path& path, std::span<const std::uint8_t> bytes, std::string_view what, bool durable) {
    const fs::path tmp = temporary_path(path);
    const auto fail = [&](int e) {
        ::unlink(tmp.c_str());
        throw IoError(fmt::format("{}: cannot write {}: {}", path.string(), what, std::strerror(e)));
    };
    const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
    if (fd < 0) throw IoError(fmt::format("{}: cannot write {}: {}", path.string(), what, std::strerror(errno)));
    std::size_t done = 0;
    while (done < bytes.size()) {
        const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
            const int e = n == 0 ? EIO : errno;
            ::close(fd);
            fail(e);
        }
        done += static_cast<std::size_t>(n);
    }
    if (durable && ::fsync(fd) != 0) {
        const int e = errno;
        ::close(fd);
        fail(e);
    }
    if (::close(fd) != 0) fail(errno);
}

void move_into_place(const fs::path& path, std::string_view what, bool durable) {
    const fs::path tmp = temporary_path(path);
    if (::rename(tmp.c_str(), path.c_str()) != 0) {
        const int e = errno;
        ::unlink(tmp.c_str());
        throw IoError(fmt::format("{}: cannot move {} into place: {}", path.string(), what, std::strerror(e)));
    }
    if (!durable) return;
    const fs::path dir = path.parent_path().empty() ? fs::path(".") : path.parent_path();
    const int dfd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (dfd >= 0) {  // the rename itself on disk
        ::fsync(dfd);
        ::close(dfd);
    }
}

void write_file_atomically(const fs::path& path, std::span<const std::uint8_t> bytes, std::string_view what,
                           bool durable) {
    write_temporary(path, bytes, what, durable);
    move_into_place(path, what, durable);
}

}  // namespace glint
