#include "glint/session/checkpoint.h"
#include "glint/base/atomic_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fmt/core.h>

#include <bit>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <vector>

#include "glint/image/image_io.h"
#include "glint/samplers/hash.h"

namespace glint {

static_assert(std::endian::native == std::endian::little, "checkpoints are written little-endian");

namespace fs = std::filesystem;

namespace {

constexpr char kMagic[8] = {'G', 'L', 'I', 'N', 'T', 'C', 'K', 'P'};
constexpr std::uint32_t kVersion = 3;  // 2: AOVs bring the odd-numbered samples' sums; 3: and albedo
constexpr std::size_t kHeaderBytes = 72;

// Bytes per pixel of the planes the flags call for.
std::size_t pixel_bytes(bool adaptive, bool aovs) {
    std::size_t b = 12 + 4;
    if (adaptive || aovs) b += 12 + 4;
    if (adaptive) b += 4 + 1;
    if (aovs) b += 12 + 12 + 12 + 4 + 4;
    return b;
}

class Writer {
public:
    template <typename T>
    void put(const T& v) {
        const auto* p = reinterpret_cast<const char*>(&v);
        bytes.insert(bytes.end(), p, p + sizeof(T));
    }
    template <typename T>
    void plane(const std::vector<T>& v) {
        const auto* p = reinterpret_cast<const char*>(v.data());
        bytes.insert(bytes.end(), p, p + v.size() * sizeof(T));
    }
    std::vector<char> bytes;
};

class Reader {
public:
    Reader(const std::vector<char>& bytes, const fs::path& path) : bytes_(bytes), path_(path) {}
    template <typename T>
    T get() {
        T v;
        need(sizeof(T));
        std::memcpy(&v, bytes_.data() + at_, sizeof(T));
        at_ += sizeof(T);
        return v;
    }
    template <typename T>
    void plane(std::vector<T>& v, std::size_t n) {
        need(n * sizeof(T));
        v.resize(n);
        std::memcpy(v.data(), bytes_.data() + at_, n * sizeof(T));
        at_ += n * sizeof(T);
    }
    std::size_t at() const { return at_; }
    [[noreturn]] void fail(std::size_t at, const std::string& why) const {
        throw IoError(fmt::format("{}: byte {}: {}", path_.string(), at, why));
    }

private:
    void need(std::size_t n) const {
        if (bytes_.size() - at_ < n) fail(at_, "the file ends early: truncated");
    }
    const std::vector<char>& bytes_;
    const fs::path& path_;
    std::size_t at_ = 0;
};

}  // namespace

std::uint64_t hash_bytes(const void* data, std::size_t size, std::uint64_t seed) {
    const auto* p = static_cast<const unsigned char*>(data);
    std::uint64_t h = mix64(seed ^ 0x676c696e74ULL) ^ size;
    std::size_t i = 0;
    for (; i + 8 <= size; i += 8) {
        std::uint64_t w;
        std::memcpy(&w, p + i, 8);
        h = (h ^ mix64(w)) * 0x9e3779b97f4a7c15ULL;
        h ^= h >> 29;
    }
    std::uint64_t tail = 0;
    std::memcpy(&tail, p + i, size - i);
    return mix64(h ^ mix64(tail + (size - i)));
}

std::uint64_t render_fingerprint(const RenderJob& job, std::string_view settings) {
    std::uint64_t h = hash_bytes(settings.data(), settings.size());
    const auto add = [&h](const void* data, std::size_t bytes) { h = hash_bytes(data, bytes, h); };
    const auto add_vector = [&add](const auto& v) {
        const std::uint64_t n = v.size();
        add(&n, sizeof n);
        if (!v.empty()) add(v.data(), v.size() * sizeof(v[0]));
    };
    if (job.sources)
        for (const auto& [path, text] : job.sources->texts()) add(text.data(), text.size());  // not the paths
    for (const TriangleMesh& m : job.scene.meshes) {
        add_vector(m.positions);
        add_vector(m.normals);
        add_vector(m.uvs);
        add_vector(m.colors);
        add_vector(m.alphas);
        add_vector(m.indices);
        add_vector(m.face_materials);
        for (const auto& uv : m.more_uvs) add_vector(uv);
    }
    for (const Image& image : job.scene.images) {
        add_vector(image.texels);
        add_vector(image.alpha);
    }
    // The camera, by what it does: rays through the corners and the centre of the film.
    const float w = static_cast<float>(job.width), ht = static_cast<float>(job.height);
    for (const auto& [x, y] : {std::pair{0.0f, 0.0f}, {w, 0.0f}, {0.0f, ht}, {w, ht}, {w / 2, ht / 2}}) {
        for (const Sample2 lens : {Sample2{0.5f, 0.5f}, Sample2{0.1f, 0.9f}}) {
            const Ray r = job.camera.generate_ray(x, y, lens);
            const float v[6] = {r.origin.x, r.origin.y, r.origin.z, r.direction.x, r.direction.y, r.direction.z};
            add(v, sizeof v);
        }
    }
    const int accel = static_cast<int>(job.scene.accel);
    add(&accel, sizeof accel);
    const int light_sampling = static_cast<int>(job.scene.light_sampling);
    add(&light_sampling, sizeof light_sampling);
    const int texture_filter = static_cast<int>(job.texture_filter);
    add(&texture_filter, sizeof texture_filter);
    if (job.spectral) add("spectral", 8);  // only when on: RGB checkpoints keep their fingerprint
    if (job.white_balance > 0) add(&job.white_balance, sizeof job.white_balance);
    return h;
}

void write_checkpoint(const fs::path& path, std::uint64_t fingerprint, const ProgressiveState& s) {
    Writer w;
    w.bytes.reserve(kHeaderBytes + s.pixels() * pixel_bytes(s.adaptive, s.aovs) + 8);
    w.bytes.insert(w.bytes.end(), kMagic, kMagic + 8);
    w.put(kVersion);
    w.put(static_cast<std::uint32_t>((s.adaptive ? 1U : 0U) | (s.aovs ? 2U : 0U)));
    w.put(fingerprint);
    for (const std::int32_t v : {s.width, s.height, s.spp_target, s.spp_done, s.passes, 0}) w.put(v);
    w.put(s.seconds);
    w.put(s.rays);
    w.put(static_cast<std::uint64_t>(s.pixels() * pixel_bytes(s.adaptive, s.aovs)));
    w.plane(s.sum);
    w.plane(s.weight);
    if (s.halves()) {
        w.plane(s.odd_sum);
        w.plane(s.odd_weight);
    }
    if (s.adaptive) {
        w.plane(s.samples);
        w.plane(s.active);
    }
    if (s.aovs) {
        w.plane(s.albedo);
        w.plane(s.odd_albedo);
        w.plane(s.normal);
        w.plane(s.depth);
        w.plane(s.hit_weight);
    }
    w.put(hash_bytes(w.bytes.data(), w.bytes.size()));

    // Flushed to the disk before and after the rename: a reader (or a resumed run after a crash
    // or a power cut) sees the old checkpoint or the new one.
    write_file_atomically(path, std::span(reinterpret_cast<const std::uint8_t*>(w.bytes.data()), w.bytes.size()),
                          "the checkpoint", true);
}

Checkpoint read_checkpoint(const fs::path& path) {
    std::error_code ec;
    const auto status = fs::status(path, ec);
    if (ec || !fs::exists(status)) throw IoError(fmt::format("{}: no such checkpoint", path.string()));
    if (!fs::is_regular_file(status)) throw IoError(fmt::format("{}: not a regular file", path.string()));
    const std::uintmax_t size = fs::file_size(path, ec);
    if (ec) throw IoError(fmt::format("{}: cannot read: {}", path.string(), ec.message()));
    if (size < kHeaderBytes + 8)
        throw IoError(fmt::format("{}: {} bytes: too short for a glint checkpoint", path.string(), size));
    // The header first: the sizes it states are checked against the file's before the rest is read.
    std::ifstream in(path, std::ios::binary);
    std::vector<char> bytes(kHeaderBytes);
    if (!in.read(bytes.data(), static_cast<std::streamsize>(kHeaderBytes)))
        throw IoError(fmt::format("{}: cannot read", path.string()));
    Reader r(bytes, path);
    if (std::memcmp(bytes.data(), kMagic, 8) != 0) r.fail(0, "not a glint checkpoint (no GLINTCKP signature)");
    r.get<std::uint64_t>();
    const auto version = r.get<std::uint32_t>();
    if (version != kVersion)
        r.fail(8, fmt::format("checkpoint version {}; this glint reads version {}", version, kVersion));
    const auto flags = r.get<std::uint32_t>();
    if (flags > 3) r.fail(12, fmt::format("unknown flags {:#x}", flags));
    Checkpoint c;
    c.fingerprint = r.get<std::uint64_t>();
    ProgressiveState& s = c.state;
    s.adaptive = (flags & 1U) != 0;
    s.aovs = (flags & 2U) != 0;
    s.width = r.get<std::int32_t>();
    s.height = r.get<std::int32_t>();
    s.spp_target = r.get<std::int32_t>();
    s.spp_done = r.get<std::int32_t>();
    s.passes = r.get<std::int32_t>();
    r.get<std::int32_t>();
    if (s.width < 1 || s.height < 1 || s.width > (1 << 20) || s.height > (1 << 20))
        r.fail(24, fmt::format("film {}x{} out of range", s.width, s.height));
    if (s.spp_target < 1 || s.spp_done < 0 || s.spp_done > s.spp_target || s.passes < 0)
        r.fail(32, fmt::format("spp {} of {} after {} passes: inconsistent", s.spp_done, s.spp_target, s.passes));
    s.seconds = r.get<double>();
    s.rays = r.get<std::uint64_t>();
    if (!(s.seconds >= 0) || !std::isfinite(s.seconds)) r.fail(48, "render time not a finite positive number");
    const auto payload = r.get<std::uint64_t>();
    const std::uint64_t want = static_cast<std::uint64_t>(s.pixels()) * pixel_bytes(s.adaptive, s.aovs);
    if (payload != want)
        r.fail(64, fmt::format("{} bytes of planes stated; a {}x{} film with these flags has {}", payload,
                               s.width, s.height, want));
    if (size != kHeaderBytes + payload + 8)
        throw IoError(fmt::format("{}: {} bytes, the header says {}: truncated or damaged", path.string(), size,
                                  kHeaderBytes + payload + 8));
    bytes.resize(static_cast<std::size_t>(size));
    if (!in.read(bytes.data() + kHeaderBytes, static_cast<std::streamsize>(size - kHeaderBytes)))
        throw IoError(fmt::format("{}: cannot read", path.string()));
    std::uint64_t stored;
    std::memcpy(&stored, bytes.data() + size - 8, 8);
    if (stored != hash_bytes(bytes.data(), static_cast<std::size_t>(size - 8)))
        r.fail(static_cast<std::size_t>(size - 8), "checksum mismatch: the file is damaged");
    const std::size_t n = s.pixels();
    r.plane(s.sum, n);
    r.plane(s.weight, n);
    if (s.halves()) {
        r.plane(s.odd_sum, n);
        r.plane(s.odd_weight, n);
    }
    if (s.adaptive) {
        r.plane(s.samples, n);
        r.plane(s.active, n);
        for (std::size_t i = 0; i < n; ++i) {
            if (s.samples[i] > static_cast<std::uint32_t>(s.spp_target) || s.active[i] > 1)
                r.fail(kHeaderBytes, fmt::format("pixel {}: sample count {} or active flag {} out of range", i,
                                                 s.samples[i], s.active[i]));
        }
    }
    if (s.aovs) {
        r.plane(s.albedo, n);
        r.plane(s.odd_albedo, n);
        r.plane(s.normal, n);
        r.plane(s.depth, n);
        r.plane(s.hit_weight, n);
    }
    return c;
}

double parse_duration(const std::string& text, const std::string& what) {
    const auto bad = [&] {
        return IoError(fmt::format("{}: '{}' is not a duration (examples: 90, 90s, 10m, 1h30m, 2.5h)", what, text));
    };
    if (text.empty()) throw bad();
    double total = 0;
    std::size_t i = 0;
    bool any = false;
    while (i < text.size()) {
        std::size_t used = 0;
        double v;
        try {
            v = std::stod(text.substr(i), &used);
        } catch (const std::exception&) {
            throw bad();
        }
        if (used == 0 || !std::isfinite(v) || v < 0 || text[i] == '-' || text[i] == '+' || std::isspace(static_cast<unsigned char>(text[i])))
            throw bad();
        i += used;
        double unit = 1;
        if (i < text.size()) {
            switch (text[i]) {
                case 's': unit = 1; break;
                case 'm': unit = 60; break;
                case 'h': unit = 3600; break;
                case 'd': unit = 86400; break;
                default: throw bad();
            }
            ++i;
        } else if (any) {
            throw bad();  // "1h30": a bare number only alone
        }
        total += v * unit;
        any = true;
    }
    if (!std::isfinite(total)) throw bad();
    return total;
}

}  // namespace glint
