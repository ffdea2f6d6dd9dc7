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

namespace glint {

namespace {

MaterialDesc map_material(const tinyobj::material_t& m, const std::filesystem::path& dir,
                          const std::string& file, ImportedFile& out) {
    MaterialDesc d;
    const Color kd{m.diffuse[0], m.diffuse[1], m.diffuse[2]};
    const Color ks{m.specular[0], m.specular[1], m.specular[2]};
    const Color ke{m.emission[0], m.emission[1], m.emission[2]};
    d.color.kind = TextureDesc::Kind::kConstant;
    d.color.value = kd;
    if (!m.diffuse_texname.empty()) {
        const std::filesystem::path tex = dir / m.diffuse_texname;
        if (!std::filesystem::exists(tex))
            throw IoError(fmt::format("{}: material '{}': texture map_Kd '{}' not found (looked for {})", file,
                                      m.name, m.diffuse_texname, tex.string()));
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
    if (ke.max_component() > 0) d.emission = Emission{ke, false, std::nullopt};
    // `norm` (and `map_Bump` with -bm or a name containing "normal", the common export of
    // normal maps under the bump keyword): a tangent-space normal map. A height bump map proper
    // is not applied; the notes say so.
    const bool bump_is_normal = !m.bump_texname.empty() &&
                                (m.bump_texopt.bump_multiplier != 1 || m.bump_texname.find("normal") != std::string::npos ||
                                 m.bump_texname.find("Normal") != std::string::npos);
    const std::string normal_name = !m.normal_texname.empty() ? m.normal_texname : bump_is_normal ? m.bump_texname : "";
    if (!normal_name.empty()) {
        const std::filesystem::path tex = dir / normal_name;
        if (!std::filesystem::exists(tex))
            throw IoError(fmt::format("{}: material '{}': normal map '{}' not found (looked for {})", file, m.name,
                                      normal_name, tex.string()));
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
// is reported as that), located at line and column. Returns the line of every face, in order.
std::vector<long long> check_obj_indices(const std::string& text, const std::string& file) {
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
    std::vector<long long> face_line;
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
        if (key == "f") {
            triangles += std::max(corners - 2, 0);
            if (corners > 255)
                fail(line_no, 1, fmt::format("a face with {} corners (at most 255; split it)", corners));
            face_line.push_back(line_no);
        }
    });
    if (const std::string e = mesh_size_error(total[0], triangles); !e.empty()) throw IoError(fmt::format("{}: {}", file, e));
    return face_line;
}

// tinyobjloader's `mtllib` reader, replaced: a material library is read only if glint may read it
// (why_not_readable: a FIFO would block, --restrict-paths may forbid it), and a missing one is
// an error, not a warning.
class MtlReader : public tinyobj::MaterialReader {
public:
    explicit MtlReader(std::filesystem::path dir) : dir_(std::move(dir)) {}
    bool operator()(const std::string& name, std::vector<tinyobj::material_t>* materials,
                    std::map<std::string, int>* names, std::string* warn, std::string* err) override {
        const std::filesystem::path mtl = dir_ / name;
        const auto refuse = [&](const std::string& why) {
            if (err) *err += fmt::format("material library '{}' ({}): {}", name, mtl.string(), why);
            return false;
        };
        if (const std::string why = why_not_readable(mtl); !why.empty()) return refuse("cannot read: it " + why);
        std::ifstream in(mtl, std::ios::binary);
        if (!in) return refuse("no such file");
        std::string mtl_warn, mtl_err;
        tinyobj::LoadMtl(names, materials, &in, &mtl_warn, &mtl_err);
        if (warn && !mtl_warn.empty()) *warn += mtl_warn;
        if (!mtl_err.empty()) return refuse(mtl_err);
        return true;
    }

private:
    std::filesystem::path dir_;
};

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
    const std::vector<long long> face_line = check_obj_indices(text, file);
    tinyobj::attrib_t attrib;
    std::vector<tinyobj::shape_t> shapes;
    std::vector<tinyobj::material_t> materials;
    std::string warning, error;
    {
        std::istringstream stream(text);
        MtlReader mtl(dir);
        // Faces are split into triangles by us, keeping their material; no vertex colours.
        const bool ok = tinyobj::LoadObj(&attrib, &shapes, &materials, &warning, &error, &stream, &mtl,
                                         /*triangulate=*/false, /*default_vcols_fallback=*/false);
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
    for (const tinyobj::material_t& m : materials) out.materials.push_back({m.name, map_material(m, dir, file, out), std::nullopt});

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
        std::size_t face = 0, left_in_face = sm.num_face_vertices[0];
        for (const tinyobj::index_t& i : sm.indices) {
            while (left_in_face == 0 && face + 1 < sm.num_face_vertices.size()) left_in_face = sm.num_face_vertices[++face];
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
        for (unsigned char c : sm.num_face_vertices) counts.push_back(c);
        triangulate_fans(counts, polygon, mesh.indices, &face_of);
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
    return out;
}

}  // namespace glint
