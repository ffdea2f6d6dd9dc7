// A PLY reader of our own: ASCII and binary (little and big endian), any element order, the
// vertex properties x y z, nx ny nz, u v (or s t, texture_u texture_v), red green blue (8-bit or
// float), and faces as lists of vertex indices (polygons split into fans). Other elements and
// properties are read past. Every count is checked against the bytes left before anything is
// allocated, so a corrupt header cannot ask for gigabytes.
#include <bit>
#include <charconv>
#include <cstring>
#include <array>
#include <fstream>
#include <sstream>

#include <zlib.h>

#include <fmt/format.h>

#include "glint/base/diagnostics.h"
#include "glint/base/limits.h"
#include "glint/assets/mesh_import.h"
#include "glint/shapes/polygon.h"

namespace glint {

namespace {

enum class PlyType { kInt8, kUInt8, kInt16, kUInt16, kInt32, kUInt32, kFloat32, kFloat64 };

std::optional<PlyType> ply_type(const std::string& s) {
    if (s == "char" || s == "int8") return PlyType::kInt8;
    if (s == "uchar" || s == "uint8") return PlyType::kUInt8;
    if (s == "short" || s == "int16") return PlyType::kInt16;
    if (s == "ushort" || s == "uint16") return PlyType::kUInt16;
    if (s == "int" || s == "int32") return PlyType::kInt32;
    if (s == "uint" || s == "uint32") return PlyType::kUInt32;
    if (s == "float" || s == "float32") return PlyType::kFloat32;
    if (s == "double" || s == "float64") return PlyType::kFloat64;
    return std::nullopt;
}

int type_size(PlyType t) {
    switch (t) {
        case PlyType::kInt8: case PlyType::kUInt8: return 1;
        case PlyType::kInt16: case PlyType::kUInt16: return 2;
        case PlyType::kInt32: case PlyType::kUInt32: case PlyType::kFloat32: return 4;
        case PlyType::kFloat64: return 8;
    }
    return 1;
}

struct Property {
    std::string name;
    PlyType type = PlyType::kFloat32;
    bool list = false;
    PlyType count_type = PlyType::kUInt8;
};

struct Element {
    std::string name;
    std::uint64_t count = 0;
    std::vector<Property> properties;
    int line = 0;
};

enum class Format { kAscii, kLittle, kBig };

class PlyReader {
public:
    PlyReader(const std::string& bytes, std::string name) : b_(bytes), name_(std::move(name)) {}

    ImportedFile read() {
        header();
        ImportedFile out;
        TriangleMesh mesh;
        mesh.name = name_;
        mesh.material = kNoImportedMaterial;
        std::vector<std::uint32_t> counts, polygon;
        bool has_colors = false;
        for (const Element& e : elements_) {
            if (e.name == "vertex") {
                read_vertices(e, mesh, has_colors);
            } else if (e.name == "face") {
                read_faces(e, counts, polygon, mesh.positions.size());
            } else if (!e.properties.empty()) {  // an element of no properties holds no bytes, whatever its count
                elem_ = &e;
                for (index_ = 0; index_ < e.count; ++index_)
                    for (const Property& p : e.properties) skip(p);
            }
            elem_ = nullptr;
        }
        if (mesh.positions.empty()) fail(0, "no vertex element with x, y and z");
        if (!has_colors) mesh.colors.clear();
        try {
            triangulate_faces(counts, polygon, mesh.positions, mesh.indices);
            out.dropped_triangles = validate_and_drop_degenerate(mesh);
        } catch (const std::invalid_argument& e) {
            fail(0, e.what());
        }
        if (mesh.indices.empty() && out.dropped_triangles > 0)
            fail(0, fmt::format("all {} of its triangles are degenerate (no area, or a position not finite): nothing to "
                                "render", out.dropped_triangles));
        out.meshes.push_back(std::move(mesh));
        out.nodes.push_back({0, Transform{}});
        return out;
    }

private:
    [[noreturn]] void fail(int line, const std::string& what) const {
        throw IoError(line > 0 ? fmt::format("{}:{}: {}", name_, line, what) : fmt::format("{}: {}", name_, what));
    }
    // An error in the body: at the line (ASCII) or the byte offset (binary) of the value being
    // read, naming the element and its index: "bunny.ply: byte 1048592: face 12: ...".
    [[noreturn]] void fail_body(const std::string& what) const {
        const std::string element = elem_ ? fmt::format("{} {}: ", elem_->name, index_) : "";
        if (format_ == Format::kAscii) fail(line_, element + what);
        throw IoError(fmt::format("{}: byte {}: {}{}", name_, value_at_, element, what));
    }

    // One header line, without its end of line; false at the end of the bytes.
    bool next_line(std::string& line) {
        if (pos_ >= b_.size()) return false;
        const std::size_t end = b_.find('\n', pos_);
        const std::size_t stop = end == std::string::npos ? b_.size() : end;
        line.assign(b_, pos_, stop - pos_);
        if (!line.empty() && line.back() == '\r') line.pop_back();
        pos_ = end == std::string::npos ? b_.size() : end + 1;
        ++line_;
        return true;
    }

    void header() {
        std::string line;
        if (!next_line(line) || line != "ply") fail(1, "not a PLY file (the first line must be 'ply')");
        bool have_format = false;
        for (;;) {
            if (!next_line(line)) fail(line_, "the header has no 'end_header'");
            std::istringstream in(line);
            std::string word;
            in >> word;
            if (word == "end_header") break;
            if (word.empty() || word == "comment" || word == "obj_info") continue;
            if (word == "format") {
                std::string f, version;
                in >> f >> version;
                if (f == "ascii") format_ = Format::kAscii;
                else if (f == "binary_little_endian") format_ = Format::kLittle;
                else if (f == "binary_big_endian") format_ = Format::kBig;
                else fail(line_, fmt::format("unknown format '{}' (known: ascii, binary_little_endian, binary_big_endian)", f));
                have_format = true;
            } else if (word == "element") {
                Element e;
                std::string count;
                in >> e.name >> count;
                const auto r = std::from_chars(count.data(), count.data() + count.size(), e.count);
                if (e.name.empty() || r.ec != std::errc{} || r.ptr != count.data() + count.size())
                    fail(line_, "expected 'element NAME COUNT'");
                e.line = line_;
                elements_.push_back(e);
            } else if (word == "property") {
                if (elements_.empty()) fail(line_, "a property before any element");
                Property p;
                std::string t;
                in >> t;
                if (t == "list") {
                    std::string ct, it;
                    in >> ct >> it >> p.name;
                    const auto c = ply_type(ct), i = ply_type(it);
                    if (!c || !i || p.name.empty()) fail(line_, "expected 'property list COUNT_TYPE ITEM_TYPE NAME'");
                    if (*c == PlyType::kFloat32 || *c == PlyType::kFloat64) fail(line_, "a list count must be an integer type");
                    p.list = true;
                    p.count_type = *c;
                    p.type = *i;
                } else {
                    const auto ty = ply_type(t);
                    in >> p.name;
                    if (!ty || p.name.empty()) fail(line_, fmt::format("unknown property type '{}'", t));
                    p.type = *ty;
                }
                elements_.back().properties.push_back(p);
            } else {
                fail(line_, fmt::format("unknown header keyword '{}'", word));
            }
        }
        if (!have_format) fail(line_, "the header has no 'format' line");
        if (format_ == Format::kAscii) ++line_;  // the body starts on the next line
        // Counts against the bytes left: every binary value takes at least one byte, every ASCII
        // value at least two (a digit and a separator).
        const std::uint64_t left = b_.size() - pos_;
        for (const Element& e : elements_) {
            const std::uint64_t per = format_ == Format::kAscii ? 2 * std::max<std::size_t>(1, e.properties.size())
                                                                : min_binary_size(e);
            if (e.count > 0 && per > 0 && e.count > left / per)
                fail(e.line, fmt::format("element '{}' claims {} entries, more than the {} bytes after the header can hold",
                                         e.name, e.count, left));
        }
        // The limits, from the counts the header states (a face is at least one triangle).
        std::uint64_t vertices = 0, faces = 0;
        int vertex_line = 0;
        for (const Element& e : elements_) {
            if (e.name == "vertex") vertices += e.count, vertex_line = e.line;
            if (e.name == "face") faces += e.count;
        }
        if (const std::string why = mesh_size_error(static_cast<long long>(vertices), static_cast<long long>(faces));
            !why.empty())
            fail(vertex_line, why);
    }

    static std::uint64_t min_binary_size(const Element& e) {
        std::uint64_t n = 0;
        for (const Property& p : e.properties) n += p.list ? type_size(p.count_type) : type_size(p.type);
        return n;
    }

    // --- values ---
    double value(PlyType t) {
        if (format_ == Format::kAscii) return ascii_value(t);
        value_at_ = pos_;
        const int n = std::min(type_size(t), 8);
        if (b_.size() - pos_ < static_cast<std::size_t>(n)) fail_body("unexpected end of file");
        unsigned char raw[8] = {};
        std::memcpy(raw, b_.data() + pos_, n);
        pos_ += n;
        const bool swap = (format_ == Format::kBig) == (std::endian::native == std::endian::little);
        if (swap)
            for (int i = 0, j = n - 1; i < j; ++i, --j) {
                const unsigned char x = raw[i];
                raw[i] = raw[j];
                raw[j] = x;
            }
        switch (t) {
            case PlyType::kInt8: { std::int8_t v; std::memcpy(&v, raw, 1); return v; }
            case PlyType::kUInt8: return raw[0];
            case PlyType::kInt16: { std::int16_t v; std::memcpy(&v, raw, 2); return v; }
            case PlyType::kUInt16: { std::uint16_t v; std::memcpy(&v, raw, 2); return v; }
            case PlyType::kInt32: { std::int32_t v; std::memcpy(&v, raw, 4); return v; }
            case PlyType::kUInt32: { std::uint32_t v; std::memcpy(&v, raw, 4); return v; }
            case PlyType::kFloat32: { float v; std::memcpy(&v, raw, 4); return v; }
            case PlyType::kFloat64: { double v; std::memcpy(&v, raw, 8); return v; }
        }
        return 0;
    }

    double ascii_value(PlyType) {
        // Skip blanks; count lines.
        while (pos_ < b_.size() && (b_[pos_] == ' ' || b_[pos_] == '\t' || b_[pos_] == '\r' || b_[pos_] == '\n')) {
            if (b_[pos_] == '\n') ++line_;
            ++pos_;
        }
        value_at_ = pos_;
        if (pos_ >= b_.size()) fail_body("unexpected end of file");
        std::size_t end = pos_;
        while (end < b_.size() && !std::isspace(static_cast<unsigned char>(b_[end]))) ++end;
        double v = 0;
        const auto r = std::from_chars(b_.data() + pos_, b_.data() + end, v);
        if (r.ec != std::errc{} || r.ptr != b_.data() + end)
            fail_body(fmt::format("expected a number, got '{}'", b_.substr(pos_, std::min<std::size_t>(end - pos_, 20))));
        pos_ = end;
        return v;
    }

    std::uint64_t list_count(const Property& p) {
        const double c = value(p.count_type);
        if (!(c >= 0) || c != std::floor(c)) fail_body(fmt::format("list '{}' has a negative count", p.name));
        const std::uint64_t per = format_ == Format::kAscii ? 2 : static_cast<std::uint64_t>(type_size(p.type));
        // Compared as a double first: an ASCII count may be 1e23, beyond any integer type.
        if (c > static_cast<double>((b_.size() - pos_) / per + 1))
            fail_body(fmt::format("list '{}' claims {} entries past the end of the file", p.name, c));
        return static_cast<std::uint64_t>(c);
    }

    void skip(const Property& p) {
        if (!p.list) {
            value(p.type);
            return;
        }
        const std::uint64_t n = list_count(p);
        for (std::uint64_t i = 0; i < n; ++i) value(p.type);
    }

    void read_vertices(const Element& e, TriangleMesh& mesh, bool& has_colors) {
        // Which slot each property fills: 0..2 position, 3..5 normal, 6..7 uv, 8..10 colour.
        std::vector<int> slot(e.properties.size(), -1);
        bool color_is_byte = true;
        const char* names[][3] = {{"x", "y", "z"}, {"nx", "ny", "nz"}, {"u", "v", nullptr},
                                  {"s", "t", nullptr}, {"texture_u", "texture_v", nullptr},
                                  {"red", "green", "blue"}};
        const int base[] = {0, 3, 6, 6, 6, 8};
        int found = 0;
        for (std::size_t i = 0; i < e.properties.size(); ++i) {
            const Property& p = e.properties[i];
            for (int g = 0; g < 6; ++g)
                for (int k = 0; k < 3; ++k)
                    if (names[g][k] && p.name == names[g][k] && !p.list) {
                        slot[i] = base[g] + k;
                        found |= 1 << slot[i];
                        if (g == 5) color_is_byte = p.type == PlyType::kUInt8;
                    }
        }
        if ((found & 7) != 7) fail(e.line, "the vertex element needs properties x, y and z");
        const bool normals = (found & (7 << 3)) == (7 << 3), uvs = (found & (3 << 6)) == (3 << 6);
        has_colors = (found & (7 << 8)) == (7 << 8);
        mesh.positions.resize(e.count);
        if (normals) mesh.normals.resize(e.count);
        if (uvs) mesh.uvs.resize(e.count);
        if (has_colors) mesh.colors.resize(e.count);
        double v[11] = {};
        elem_ = &e;
        for (std::uint64_t i = 0; i < e.count; ++i) {
            index_ = i;
            for (std::size_t k = 0; k < e.properties.size(); ++k) {
                if (slot[k] < 0) {
                    skip(e.properties[k]);
                } else {
                    v[slot[k]] = value(e.properties[k].type);
                }
            }
            mesh.positions[i] = {float(v[0]), float(v[1]), float(v[2])};
            if (normals) mesh.normals[i] = Normal3{float(v[3]), float(v[4]), float(v[5])};
            if (uvs) mesh.uvs[i] = {float(v[6]), float(v[7])};
            if (has_colors) {
                // 8-bit colours are sRGB-encoded; float colours are taken as linear.
                const auto channel = [&](double x) {
                    return color_is_byte ? srgb_decode(float(x) / 255) : float(x);
                };
                mesh.colors[i] = Color{channel(v[8]), channel(v[9]), channel(v[10])};
            }
        }
    }

    void read_faces(const Element& e, std::vector<std::uint32_t>& counts, std::vector<std::uint32_t>& polygon,
                    std::size_t vertex_count) {
        int which = -1;
        for (std::size_t k = 0; k < e.properties.size(); ++k)
            if (e.properties[k].list && (e.properties[k].name == "vertex_indices" || e.properties[k].name == "vertex_index"))
                which = static_cast<int>(k);
        if (which < 0) fail(e.line, "the face element needs a list property vertex_indices");
        elem_ = &e;
        for (std::uint64_t i = 0; i < e.count; ++i) {
            index_ = i;
            for (std::size_t k = 0; k < e.properties.size(); ++k) {
                if (static_cast<int>(k) != which) {
                    skip(e.properties[k]);
                    continue;
                }
                const std::uint64_t n = list_count(e.properties[k]);
                counts.push_back(static_cast<std::uint32_t>(n));
                for (std::uint64_t j = 0; j < n; ++j) {
                    const double ix = value(e.properties[k].type);
                    if (!(ix >= 0) || ix >= static_cast<double>(vertex_count) || ix != std::floor(ix))
                        fail_body(fmt::format("vertex index {} out of range ({} vertices)", ix, vertex_count));
                    polygon.push_back(static_cast<std::uint32_t>(ix));
                }
            }
        }
    }

    const std::string& b_;
    std::string name_;
    std::size_t pos_ = 0;
    int line_ = 0;
    Format format_ = Format::kAscii;
    std::vector<Element> elements_;
    const Element* elem_ = nullptr;  // the element and index being read, for messages
    std::uint64_t index_ = 0;
    std::size_t value_at_ = 0;  // where the value being read starts
};

}  // namespace

ImportedFile parse_ply(const std::string& bytes, const std::string& name) {
    return PlyReader(bytes, name).read();
}

namespace {

// The bytes of a gzip file (pbrt scenes ship meshes as .ply.gz), inflated by zlib; a limit on
// the inflated size guards against a small file that inflates to exhaust memory.
std::string gunzip(const std::string& bytes, const std::string& name) {
    constexpr std::size_t kMaxInflated = std::size_t(8) << 30;
    z_stream z{};
    if (inflateInit2(&z, 16 + MAX_WBITS) != Z_OK) throw IoError(fmt::format("{}: cannot start zlib", name));
    z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(bytes.data()));
    z.avail_in = static_cast<uInt>(std::min<std::size_t>(bytes.size(), 0xffffffffu));
    std::string out;
    std::array<char, 1 << 16> chunk;
    int rc = Z_OK;
    while (rc != Z_STREAM_END) {
        z.next_out = reinterpret_cast<Bytef*>(chunk.data());
        z.avail_out = static_cast<uInt>(chunk.size());
        rc = inflate(&z, Z_NO_FLUSH);
        if (rc != Z_OK && rc != Z_STREAM_END) {
            const std::string why = z.msg ? z.msg : "truncated or corrupt data";
            const auto at = z.total_in;
            inflateEnd(&z);
            throw IoError(fmt::format("{}: byte {}: gzip: {}", name, at, rc == Z_BUF_ERROR ? "truncated" : why));
        }
        out.append(chunk.data(), chunk.size() - z.avail_out);
        if (out.size() > kMaxInflated) {
            inflateEnd(&z);
            throw IoError(fmt::format("{}: inflates to more than 8 GiB", name));
        }
        if (rc == Z_OK && z.avail_in == 0 && z.avail_out != 0) {
            inflateEnd(&z);
            throw IoError(fmt::format("{}: byte {}: gzip: truncated", name, bytes.size()));
        }
    }
    inflateEnd(&z);
    return out;
}

}  // namespace

ImportedFile import_ply(const std::filesystem::path& path) {
    if (const std::string why = why_not_readable(path); !why.empty())
        throw IoError(fmt::format("{}: cannot read: it {}", path.string(), why));
    std::ifstream in(path, std::ios::binary);
    if (!in) throw IoError(fmt::format("{}: cannot open: {}", path.string(), std::strerror(errno)));
    std::ostringstream s;
    s << in.rdbuf();
    std::string ext = path.extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (ext == ".gz") return parse_ply(gunzip(s.str(), path.string()), path.string());
    return parse_ply(s.str(), path.string());
}

}  // namespace glint
