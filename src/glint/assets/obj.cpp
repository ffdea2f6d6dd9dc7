// OBJ + MTL through tinyobjloader. Each OBJ group/object becomes one mesh; faces are fans;
// vertices are welded per distinct (position, normal, uv) index triple.
//
// MTL mapping (decided here; docs/scene-format.md):
//   Ke > 0                       emission Ke on whatever the surface is
//   d < 1, or illum 4/6/7/9      dielectric, ior Ni (1.5 when absent), tinted by Kd
//   Ks > 0                       plastic: albedo Kd (or map_Kd), coat ior Ni, roughness from the
//                                Phong exponent Ns as (2 / (Ns + 2))^(1/4) (so alpha = r^2 is the
//                                Beckmann-equivalent sqrt(2 / (Ns + 2)))
//   otherwise                    diffuse Kd (or map_Kd)
// A map_Kd or normal map that does not exist is an error naming the material and the file.
// `norm` is a tangent-space normal map, and so is a map_Bump with -bm or "normal" in its name;
// other map_Bump height maps are not applied (a note says so).
#include <tiny_obj_loader.h>

#include <cmath>
#include <fmt/format.h>
#include <fstream>
#include <limits>
#include <sstream>
#include <string_view>
#include <map>
#include <tuple>

#include "glint/base/diagnostics.h"
#include "glint/base/limits.h"
#include "glint/assets/mesh_import.h"
#include "glint/shapes/polygon.h"

namespace glint {

namespace {

// tinyobjloader's `mtllib` reader, replaced: a material library is read only if glint may read it
// (why_not_readable: a FIFO would block, --restrict-paths may forbid it), and a missing one is
// an error at the OBJ's `mtllib` line, not a warning. It keeps each library's text so that a
// material's errors can name the .mtl file and line.
class MtlReader : public tinyobj::MaterialReader {
public:
    MtlReader(std::filesystem::path dir, std::string obj_file, const std::string& obj_text)
        : dir_(std::move(dir)), obj_file_(std::move(obj_file)), obj_text_(obj_text) {}
    bool operator()(const std::string& name, std::vector<tinyobj::material_t>* materials,
                    std::map<std::string, int>* names, std::string* warn, std::string* err) override {
        const std::filesystem::path mtl = dir_ / name;
        const auto refuse = [&](const std::string& why) {
            if (failure_.empty()) {
                const long long line = line_naming("mtllib", name, obj_text_);
                failure_ = fmt::format("{}{}: material library '{}' ({}): {}", obj_file_,
                                       line > 0 ? fmt::format(":{}", line) : "", name, mtl.string(), why);
            }
            if (err) *err += failure_;
            return false;
        };
        if (const std::string why = why_not_readable(mtl); !why.empty()) return refuse("cannot read: it " + why);
        std::ifstream in(mtl, std::ios::binary);
        std::error_code ec;  // (a name too long to check is no such file, not an exception)
        if (!in) return refuse(std::filesystem::exists(mtl, ec) ? "cannot open" : "no such file");
        std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        if (in.bad()) return refuse("cannot read");
        std::istringstream stream(text);
        std::string mtl_warn, mtl_err;
        tinyobj::LoadMtl(names, materials, &stream, &mtl_warn, &mtl_err);
        if (warn && !mtl_warn.empty()) *warn += mtl_warn;
        if (!mtl_err.empty()) return refuse(mtl_err);
        libraries_.push_back({mtl.string(), std::move(text)});
        return true;
    }
    /// The first failure, located at the OBJ's line, or empty.
    const std::string& failure() const { return failure_; }

    /// "lib.mtl:12" for the line of `keyword` (map_Kd, norm, ...) naming `value` in material
    /// `material`'s block, or the OBJ file's name when it cannot be found.
    std::string locate(const std::string& material, const std::string& value) const {
        for (const auto& [path, text] : libraries_) {
            const long long start = line_naming("newmtl", material, text);
            if (start == 0) continue;
            const long long line = line_naming("", value, text, start);
            return fmt::format("{}:{}", path, line > 0 ? line : start);
        }
        return obj_file_;
    }

private:
    // The 1-based line, from line `from` on, whose first word is `keyword` (any, if empty) and
    // which names `value`; 0 if none (for a `newmtl`, a later one ends the search).
    static long long line_naming(const std::string& keyword, const std::string& value, const std::string& text,
                                 long long from = 1) {
        long long line = 0;
        for (std::size_t at = 0; at <= text.size();) {
            std::size_t end = text.find('\n', at);
            if (end == std::string::npos) end = text.size();
            std::string_view l(text.data() + at, end - at);
            at = end + 1;
            if (++line < from) continue;
            while (!l.empty() && (l.back() == '\r' || l.back() == ' ' || l.back() == '\t')) l.remove_suffix(1);
            while (!l.empty() && (l.front() == ' ' || l.front() == '\t')) l.remove_prefix(1);
            if (keyword.empty() && line > from && l.rfind("newmtl", 0) == 0) return 0;  // the next material
            if (!keyword.empty() && l.rfind(keyword, 0) != 0) continue;
            if (l.find(value) != std::string_view::npos) return line;
            if (end == text.size()) break;
        }
        return 0;
    }

    std::filesystem::path dir_;
    std::string obj_file_;
    const std::string& obj_text_;
    std::string failure_;
    std::vector<std::pair<std::string, std::string>> libraries_;  // path, text
};

MaterialDesc map_material(const tinyobj::material_t& m, const std::filesystem::path& dir,
                          const std::string& file, ImportedFile& out, const MtlReader& mtl) {
    MaterialDesc d;
    const Color kd{m.diffuse[0], m.diffuse[1], m.diffuse[2]};
    const Color ks{m.specular[0], m.specular[1], m.specular[2]};
    const Color ke{m.emission[0], m.emission[1], m.emission[2]};
    d.color.kind = TextureDesc::Kind::kConstant;
    d.color.value = kd;
    if (!m.diffuse_texname.empty()) {
        const std::filesystem::path tex = dir / m.diffuse_texname;
        if (std::error_code ec; !std::filesystem::exists(tex, ec))
            throw IoError(fmt::format("{}: material '{}': texture map_Kd '{}' not found (looked for {})",
                                      mtl.locate(m.name, m.diffuse_texname), m.name, m.diffuse_texname, tex.string()));
        d.color.kind = TextureDesc::Kind::kImage;
        d.color.filename.value = tex.string();
        d.color.encoding = ImageEncoding::kSrgb;
    }
    const bool glass = m.dissolve < 1 || m.illum == 4 || m.illum == 6 || m.illum == 7 || m.illum == 9;
    const float ior = m.ior > 0 && m.ior != 1 ? m.ior : 1.5f;
    if (glass) {
        d.kind = MaterialDesc::Kind::kDielectric;
        d.ior = ior;
        d.tint = kd.max_component() > 0 ? kd : Color{1};
    } else if (ks.max_component() > 0) {
        d.kind = MaterialDesc::Kind::kPlastic;
        d.ior = ior;
        d.roughness = std::pow(2.0f / (std::max(m.shininess, 0.0f) + 2), 0.25f);
    } else {
        d.kind = MaterialDesc::Kind::kDiffuse;
    }
    if (ke.max_component() > 0) d.emission = Emission{ke, false, std::nullopt, nullptr};
    // `norm` (and `map_Bump` with -bm or a name containing "normal", the common export of
    // normal maps under the bump keyword): a tangent-space normal map. A height bump map proper
    // is not applied; the notes say so.
    const bool bump_is_normal = !m.bump_texname.empty() &&
                                (m.bump_texopt.bump_multiplier != 1 || m.bump_texname.find("normal") != std::string::npos ||
                                 m.bump_texname.find("Normal") != std::string::npos);
    const std::string normal_name = !m.normal_texname.empty() ? m.normal_texname : bump_is_normal ? m.bump_texname : "";
    if (!normal_name.empty()) {
        const std::filesystem::path tex = dir / normal_name;
        if (std::error_code ec; !std::filesystem::exists(tex, ec))
            throw IoError(fmt::format("{}: material '{}': normal map '{}' not found (looked for {})",
                                      mtl.locate(m.name, normal_name), m.name, normal_name, tex.string()));
        TextureDesc n;
        n.kind = TextureDesc::Kind::kImage;
        n.filename.value = tex.string();
        n.encoding = ImageEncoding::kLinear;
        d.normal_map = n;
        d.normal_scale = m.normal_texname.empty() ? m.bump_texopt.bump_multiplier : m.normal_texopt.bump_multiplier;
    } else if (!m.bump_texname.empty()) {
        out.notes.push_back(fmt::format("{}: material '{}': bump (height) map '{}' is not applied", file, m.name,
                                        m.bump_texname));
    }
    return d;
}

// What tinyobjloader would otherwise report in its own words, or get wrong: every index of an
// `f`, `l` or `p` line checked here first, read as written (in 64 bits: an index of 4000000000
// is reported as that), located at line and column. Returns the line and corner count of every face
// of three or more corners (the faces tinyobjloader keeps), in order.
struct ObjFaces {
    std::vector<long long> line;
    std::vector<std::uint32_t> corners;  ///< tinyobjloader keeps a face's count in a byte: 256 reads as 0
};
ObjFaces check_obj_indices(const std::string& text, const std::string& file) {
    const auto fail = [&](long long line, std::size_t column, const std::string& what) -> void {
        throw IoError(fmt::format("{}:{}:{}: {}", file, line, column, what));
    };
    static constexpr const char* kWhat[3] = {"vertex", "texture coordinate", "normal"};
    static constexpr const char* kWhats[3] = {"vertices", "texture coordinates", "normals"};
    const auto blank = [](char c) { return c == ' ' || c == '\t' || c == '\r'; };
    // Calls f(line number, line without its comment, where its keyword ends, keyword) per line.
    const auto each_line = [&](auto&& f) {
        long long line_no = 0;
        for (std::size_t at = 0; at < text.size();) {
            std::size_t end = text.find('\n', at);
            if (end == std::string::npos) end = text.size();
            std::string_view line(text.data() + at, end - at);
            at = end + 1;
            if (const auto hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
            std::size_t i = 0;
            while (i < line.size() && blank(line[i])) ++i;
            std::size_t k = i;
            while (k < line.size() && !blank(line[k])) ++k;
            f(++line_no, line, k, line.substr(i, k - i));
        }
    };
    // The totals first, so that every index is checked where it is written (OBJ lets a face name
    // vertices defined after it); negative indices count back from the line.
    long long total[3] = {0, 0, 0};
    each_line([&](long long, std::string_view, std::size_t, std::string_view key) {
        if (key == "v") ++total[0];
        if (key == "vt") ++total[1];
        if (key == "vn") ++total[2];
    });
    long long count[3] = {0, 0, 0};
    long long triangles = 0;
    ObjFaces faces;
    each_line([&](long long line_no, std::string_view line, std::size_t i, std::string_view key) {
        if (key == "v") ++count[0];
        if (key == "vt") ++count[1];
        if (key == "vn") ++count[2];
        if (key != "f" && key != "l" && key != "p") return;
        int corners = 0;
        for (;;) {
            while (i < line.size() && blank(line[i])) ++i;
            if (i >= line.size()) break;
            ++corners;
            // One corner: v, v/vt, v//vn or v/vt/vn.
            for (int kind = 0; kind < 3 && i < line.size() && !blank(line[i]); ++kind) {
                const std::size_t column = i + 1;
                if (line[i] == '/') {
                    if (kind == 0) fail(line_no, column, "a corner without a vertex index");
                    ++i;
                    if (kind == 2) fail(line_no, column, "a corner has more than three indices");
                    continue;
                }
                const std::size_t from = i;
                bool negative = false;
                if (line[i] == '-' || line[i] == '+') negative = line[i++] == '-';
                long long value = 0;
                bool digits = false, overflow = false;
                for (; i < line.size() && line[i] >= '0' && line[i] <= '9'; ++i) {
                    digits = true;
                    if (value > (std::numeric_limits<long long>::max() - 9) / 10) overflow = true;
                    else value = 10 * value + (line[i] - '0');
                }
                std::size_t to = i;
                while (to < line.size() && !blank(line[to]) && line[to] != '/') ++to;
                const std::string written(line.substr(from, to - from));
                if (!digits || to != i)
                    fail(line_no, column, fmt::format("'{}' is not a {} index", written, kWhat[kind]));
                if (overflow) fail(line_no, column, fmt::format("{} index {} is out of range", kWhat[kind], written));
                if (value == 0) fail(line_no, column, fmt::format("{} index 0: OBJ indices start at 1", kWhat[kind]));
                if (negative && value > count[kind])
                    fail(line_no, column, fmt::format("{} index {} is out of range ({} {} before this line)", kWhat[kind],
                                                      written, count[kind], kWhats[kind]));
                if (!negative && value > total[kind])
                    fail(line_no, column, fmt::format("{} index {} is out of range ({} {})", kWhat[kind], value,
                                                      total[kind], kWhats[kind]));
                if (i < line.size() && line[i] == '/') {
                    ++i;
                    if (kind == 0 && i < line.size() && line[i] == '/') {  // v//vn
                        ++i;
                        ++kind;
                    }
                    if (kind == 2) fail(line_no, column, "a corner has more than three indices");
                }
            }
        }
        if (key == "f" && corners >= 3) {
            triangles += corners - 2;
            faces.line.push_back(line_no);
            faces.corners.push_back(static_cast<std::uint32_t>(corners));
        }
    });
    if (const std::string e = mesh_size_error(total[0], triangles); !e.empty()) throw IoError(fmt::format("{}: {}", file, e));
    return faces;
}

}  // namespace

ImportedFile import_obj(const std::filesystem::path& path) {
    const std::string file = path.string();
    if (const std::string why = why_not_readable(path); !why.empty()) throw IoError(fmt::format("{}: cannot read: it {}", file, why));
    std::ifstream in(path, std::ios::binary);
    if (!in) throw IoError(fmt::format("{}: cannot open: no such file", file));
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (in.bad()) throw IoError(fmt::format("{}: cannot read", file));
    return parse_obj(text, file, path.parent_path());
}

ImportedFile parse_obj(const std::string& text, const std::string& file, const std::filesystem::path& dir) {
    const ObjFaces faces = check_obj_indices(text, file);
    const std::vector<long long>& face_line = faces.line;
    MtlReader mtl(dir, file, text);
    tinyobj::attrib_t attrib;
    std::vector<tinyobj::shape_t> shapes;
    std::vector<tinyobj::material_t> materials;
    std::string warning, error;
    {
        std::istringstream stream(text);
        // Faces are split into triangles by us, keeping their material; no vertex colours.
        const bool ok = tinyobj::LoadObj(&attrib, &shapes, &materials, &warning, &error, &stream, &mtl,
                                         /*triangulate=*/false, /*default_vcols_fallback=*/false);
        if (!mtl.failure().empty()) throw IoError(mtl.failure());
        while (!error.empty() && (error.back() == '\n' || error.back() == ' ')) error.pop_back();
        if (!error.empty()) throw IoError(fmt::format("{}: {}", file, error));
        if (!ok) throw IoError(fmt::format("{}: cannot parse", file));
    }
    ImportedFile out;
    if (!warning.empty()) {
        while (!warning.empty() && warning.back() == '\n') warning.pop_back();
        out.notes.push_back(fmt::format("{}: {}", file, warning));
    }
    std::size_t face_base = 0;
    const auto where = [&](std::size_t face) {
        const std::size_t k = face_base + face;
        return k < face_line.size() ? fmt::format("{}:{}", file, face_line[k]) : file;
    };
    const tinyobj::attrib_t& a = attrib;
    for (const tinyobj::material_t& m : materials) out.materials.push_back({m.name, map_material(m, dir, file, out, mtl), std::nullopt});

    for (const tinyobj::shape_t& shape : shapes) {
        const tinyobj::mesh_t& sm = shape.mesh;
        if (sm.num_face_vertices.empty()) continue;
        TriangleMesh mesh;
        mesh.name = shape.name;
        const bool normals = !a.normals.empty() &&
                             std::all_of(sm.indices.begin(), sm.indices.end(), [](const tinyobj::index_t& i) { return i.normal_index >= 0; });
        const bool uvs = !a.texcoords.empty() &&
                         std::all_of(sm.indices.begin(), sm.indices.end(), [](const tinyobj::index_t& i) { return i.texcoord_index >= 0; });
        std::map<std::tuple<int, int, int>, std::uint32_t> weld;
        std::vector<std::uint32_t> counts, polygon, face_of;
        // The faces' true corner counts (tinyobjloader keeps them in a byte, so 256 reads as 0),
        // when its faces are the ones check_obj_indices read.
        for (std::size_t f = 0; f < sm.num_face_vertices.size(); ++f) {
            const std::size_t k = face_base + f;
            const bool ours = k < faces.corners.size() && faces.corners[k] % 256 == sm.num_face_vertices[f];
            counts.push_back(ours ? faces.corners[k] : sm.num_face_vertices[f]);
        }
        std::size_t face = 0, left_in_face = counts[0];
        for (const tinyobj::index_t& i : sm.indices) {
            while (left_in_face == 0 && face + 1 < counts.size()) left_in_face = counts[++face];
            --left_in_face;
            const auto key = std::make_tuple(i.vertex_index, normals ? i.normal_index : -1, uvs ? i.texcoord_index : -1);
            auto [it, fresh] = weld.try_emplace(key, static_cast<std::uint32_t>(mesh.positions.size()));
            if (fresh) {
                const std::size_t v = static_cast<std::size_t>(i.vertex_index);
                if (i.vertex_index < 0 || 3 * v + 2 >= a.vertices.size())
                    throw IoError(fmt::format("{}: a face uses vertex {}, but there are {} vertices", where(face),
                                              i.vertex_index + 1, a.vertices.size() / 3));
                mesh.positions.push_back({a.vertices[3 * v], a.vertices[3 * v + 1], a.vertices[3 * v + 2]});
                if (normals) {
                    const std::size_t n = static_cast<std::size_t>(i.normal_index);
                    if (3 * n + 2 >= a.normals.size()) throw IoError(fmt::format("{}: normal index {} out of range ({} normals)", where(face), n + 1, a.normals.size() / 3));
                    mesh.normals.push_back(Normal3{a.normals[3 * n], a.normals[3 * n + 1], a.normals[3 * n + 2]});
                }
                if (uvs) {
                    const std::size_t t = static_cast<std::size_t>(i.texcoord_index);
                    if (2 * t + 1 >= a.texcoords.size()) throw IoError(fmt::format("{}: texture coordinate index {} out of range ({} given)", where(face), t + 1, a.texcoords.size() / 2));
                    mesh.uvs.push_back({a.texcoords[2 * t], a.texcoords[2 * t + 1]});
                }
            }
            polygon.push_back(it->second);
        }
        face_base += sm.num_face_vertices.size();
        triangulate_faces(counts, polygon, mesh.positions, mesh.indices, &face_of);
        bool any_material = false;
        for (std::uint32_t f : face_of) {
            const int id = f < sm.material_ids.size() ? sm.material_ids[f] : -1;
            const bool valid = id >= 0 && static_cast<std::size_t>(id) < out.materials.size();
            mesh.face_materials.push_back(valid ? static_cast<MaterialId>(id) : kNoImportedMaterial);
            any_material |= valid;
        }
        if (!any_material) {
            mesh.face_materials.clear();
            mesh.material = kNoImportedMaterial;
        }
        out.dropped_triangles += validate_and_drop_degenerate(mesh);
        out.nodes.push_back({static_cast<std::uint32_t>(out.meshes.size()), Transform{}});
        out.meshes.push_back(std::move(mesh));
    }
    if (out.meshes.empty()) throw IoError(fmt::format("{}: no faces", file));
    if (std::all_of(out.meshes.begin(), out.meshes.end(), [](const TriangleMesh& m) { return m.indices.empty(); }))
        throw IoError(fmt::format("{}: all {} of its triangles are degenerate (no area, or a position not finite): "
                                  "nothing to render", file, out.dropped_triangles));
    return out;
}

}  // namespace glint
