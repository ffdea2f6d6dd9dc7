#include "glint/image/tev.h"

#include <fcntl.h>
#include <netdb.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <unistd.h>

#include <fmt/core.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

namespace glint {

namespace {

enum PacketType : std::uint8_t { kCloseImage = 2, kCreateImage = 4, kUpdateImageV3 = 6 };

class Packet {
public:
    explicit Packet(PacketType type) {
        put(std::uint32_t{0});  // the length, filled in by done()
        put(type);
    }
    template <typename T>
    void put(T v) {
        const auto* p = reinterpret_cast<const char*>(&v);
        bytes_.insert(bytes_.end(), p, p + sizeof(T));
    }
    void put(const std::string& s) {
        bytes_.insert(bytes_.end(), s.begin(), s.end());
        bytes_.push_back('\0');
    }
    std::vector<char> done() {
        const auto n = static_cast<std::uint32_t>(bytes_.size());
        std::memcpy(bytes_.data(), &n, 4);
        return std::move(bytes_);
    }

private:
    std::vector<char> bytes_;
};

// Rows per update packet: about 4 MB of floats.
int strip_rows(int width) { return std::max(1, (1 << 20) / std::max(1, 3 * width)); }

}  // namespace

TevClient::TevClient(const std::string& address) : address_(address) {
    const auto colon = address.rfind(':');
    if (colon == std::string::npos || colon == 0 || colon + 1 == address.size()) {
        note_ = fmt::format("--display {}: expected HOST:PORT", address);
        return;
    }
    std::string host = address.substr(0, colon);
    const std::string port = address.substr(colon + 1);
    if (host.size() > 2 && host.front() == '[' && host.back() == ']') host = host.substr(1, host.size() - 2);
    addrinfo hints{};
    hints.ai_family = AF_UNSPEC;
    hints.ai_socktype = SOCK_STREAM;
    addrinfo* found = nullptr;
    if (const int e = ::getaddrinfo(host.c_str(), port.c_str(), &hints, &found); e != 0) {
        note_ = fmt::format("display {}: {}", address, ::gai_strerror(e));
        return;
    }
    std::string why = "no address";
    for (addrinfo* a = found; a; a = a->ai_next) {
        const int fd = ::socket(a->ai_family, a->ai_socktype | SOCK_CLOEXEC | SOCK_NONBLOCK, a->ai_protocol);
        if (fd < 0) {
            why = std::strerror(errno);
            continue;
        }
        int r = ::connect(fd, a->ai_addr, a->ai_addrlen);
        if (r != 0 && errno == EINPROGRESS) {  // wait at most 2 s
            pollfd p{fd, POLLOUT, 0};
            r = ::poll(&p, 1, 2000);
            int err = 0;
            socklen_t len = sizeof err;
            if (r == 1 && ::getsockopt(fd, SOL_SOCKET, SO_ERROR, &err, &len) == 0 && err == 0) {
                r = 0;
            } else {
                errno = r == 0 ? ETIMEDOUT : (err ? err : errno);
                r = -1;
            }
        }
        if (r != 0) {
            why = std::strerror(errno);
            ::close(fd);
            continue;
        }
        // Blocking from here on, with a send timeout: a stalled viewer costs at most 5 s once.
        ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) & ~O_NONBLOCK);
        timeval tv{5, 0};
        ::setsockopt(fd, SOL_SOCKET, SO_SNDTIMEO, &tv, sizeof tv);
        fd_ = fd;
        break;
    }
    ::freeaddrinfo(found);
    if (fd_ < 0) note_ = fmt::format("display {}: {}; rendering on without it", address, why);
}

TevClient::~TevClient() {
    if (fd_ >= 0) ::close(fd_);
}

void TevClient::give_up(const std::string& why) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
    note_ = fmt::format("display {}: {}; rendering on without it", address_, why);
}

bool TevClient::write_all(const std::vector<char>& packet) {
    std::size_t done = 0;
    while (fd_ >= 0 && done < packet.size()) {
        const ssize_t n = ::send(fd_, packet.data() + done, packet.size() - done, MSG_NOSIGNAL);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
            give_up(errno == EAGAIN || errno == EWOULDBLOCK ? "the viewer stopped reading"
                                                             : std::string("the viewer went away (") +
                                                                   std::strerror(errno) + ")");
            return false;
        }
        done += static_cast<std::size_t>(n);
    }
    return fd_ >= 0;
}

std::vector<char> TevClient::create_image_packet(const std::string& name, int width, int height,
                                                 const std::vector<std::string>& channels) {
    Packet p(kCreateImage);
    p.put(std::uint8_t{1});  // grab focus
    p.put(name);
    p.put(static_cast<std::int32_t>(width));
    p.put(static_cast<std::int32_t>(height));
    p.put(static_cast<std::int32_t>(channels.size()));
    for (const std::string& c : channels) p.put(c);
    return p.done();
}

std::vector<char> TevClient::update_packet(const std::string& name, const Film& film, int row0, int rows) {
    Packet p(kUpdateImageV3);
    p.put(std::uint8_t{0});
    p.put(name);
    p.put(std::int32_t{3});
    for (const char* c : {"R", "G", "B"}) p.put(std::string(c));
    p.put(std::int32_t{0});
    p.put(static_cast<std::int32_t>(row0));
    p.put(static_cast<std::int32_t>(film.width()));
    p.put(static_cast<std::int32_t>(rows));
    for (std::int64_t c = 0; c < 3; ++c) p.put(c);             // offsets: interleaved RGB
    for (int c = 0; c < 3; ++c) p.put(std::int64_t{3});        // strides
    for (int row = row0; row < row0 + rows; ++row) {
        for (int col = 0; col < film.width(); ++col) {
            const Color& v = film.at(col, row);
            p.put(v.r);
            p.put(v.g);
            p.put(v.b);
        }
    }
    return p.done();
}

std::vector<char> TevClient::close_packet(const std::string& name) {
    Packet p(kCloseImage);
    p.put(name);
    return p.done();
}

bool TevClient::send(const std::string& name, const Film& film) {
    if (fd_ < 0) return false;
    if (!created_) {  // an image of this name from an earlier render is replaced
        if (!write_all(close_packet(name))) return false;
        if (!write_all(create_image_packet(name, film.width(), film.height(), {"R", "G", "B"}))) return false;
        created_ = true;
    }
    const int step = strip_rows(film.width());
    for (int row = 0; row < film.height(); row += step) {
        if (!write_all(update_packet(name, film, row, std::min(step, film.height() - row)))) return false;
    }
    return true;
}

void TevClient::close_image(const std::string& name) {
    if (fd_ >= 0 && created_) write_all(close_packet(name));
}

}  // namespace glint
