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
#include <map>
#include <tuple>

#include "glint/io/diagnostics.h"
#include "glint/io/mesh_import.h"

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

}  // namespace

ImportedFile import_obj(const std::filesystem::path& path) {
    const std::string file = path.string();
    if (!std::filesystem::exists(path)) throw IoError(fmt::format("{}: cannot open: no such file", file));
    if (const std::string why = not_a_regular_file(path); !why.empty()) throw IoError(fmt::format("{}: cannot read: it {}", file, why));
    tinyobj::ObjReaderConfig config;
    config.triangulate = false;  // we split faces ourselves, keeping their material
    config.vertex_color = false;
    config.mtl_search_path = path.parent_path().string();
    tinyobj::ObjReader reader;
    if (!reader.ParseFromFile(file, config)) {
        std::string e = reader.Error();
        while (!e.empty() && (e.back() == '\n' || e.back() == ' ')) e.pop_back();
        throw IoError(fmt::format("{}: {}", file, e.empty() ? "cannot parse" : e));
    }
    ImportedFile out;
    if (!reader.Warning().empty()) {
        std::string w = reader.Warning();
        while (!w.empty() && w.back() == '\n') w.pop_back();
        // A missing .mtl is a warning in tinyobjloader; for us it is missing input.
        if (w.find("Material file") != std::string::npos || w.find("material file") != std::string::npos)
            throw IoError(fmt::format("{}: {}", file, w));
        out.notes.push_back(fmt::format("{}: {}", file, w));
    }
    // The line of every face, in file order (tinyobjloader keeps faces in that order across its
    // shapes), so that a bad face is reported at its line.
    std::vector<int> face_line;
    {
        std::ifstream in(path);
        std::string line;
        for (int n = 1; std::getline(in, line); ++n) {
            const std::size_t at = line.find_first_not_of(" \t");
            if (at != std::string::npos && line[at] == 'f' && at + 1 < line.size() &&
                (line[at + 1] == ' ' || line[at + 1] == '\t'))
                face_line.push_back(n);
        }
    }
    std::size_t face_base = 0;
    const auto where = [&](std::size_t face) {
        const std::size_t k = face_base + face;
        return k < face_line.size() ? fmt::format("{}:{}", file, face_line[k]) : file;
    };
    const tinyobj::attrib_t& a = reader.GetAttrib();
    for (const tinyobj::material_t& m : reader.GetMaterials())
        out.materials.push_back({m.name, map_material(m, path.parent_path(), file, out), std::nullopt});

    for (const tinyobj::shape_t& shape : reader.GetShapes()) {
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
