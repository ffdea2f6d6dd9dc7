// glTF 2.0 (.gltf and .glb) through tinygltf: the default scene's node hierarchy with its
// transforms, meshes (triangle primitives; strips and fans converted; every TEXCOORD set;
// KHR_mesh_quantization, KHR_draco_mesh_compression, EXT_meshopt_compression), metallic-roughness
// materials with their textures and samplers, alpha modes (MASK, BLEND) as cut-outs,
// KHR_materials_emissive_strength, _transmission, _ior, _volume, _clearcoat, _sheen, _specular,
// KHR_texture_transform, KHR_lights_punctual and cameras (perspective and orthographic). A file
// that requires an extension not in that list is refused.
//
// Frames: glTF is right-handed with +y up and cameras looking along -z; glint is left-handed. A
// glTF file is imported with z negated (a mirror applied to every node), so a model looks as it
// does in other viewers; winding-defined normals keep their sides (transforms.h: mirrors keep the
// front side). UVs: glTF's v runs down the image, glint's up: v' = 1 - v.
//
// Decisions where glTF and a path tracer part ways: occlusion textures are read but not applied
// (the path tracer computes occlusion); BLEND is stochastic transparency (each ray passes with
// probability 1 - alpha); light intensities are used as radiometric (candela -> W/sr, lux ->
// W/m^2) without the 683 lm/W conversion, as Blender's importer does by default; emission is
// one-sided unless the material is doubleSided.
#include <tiny_gltf.h>

#include <meshoptimizer.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <fmt/format.h>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <numbers>
#include <cstdio>
#include <cstring>
#include <set>
#include <sstream>

#include "glint/base/diagnostics.h"
#include "glint/assets/draco_decode.h"
#include "glint/base/json_locate.h"
#include "glint/base/limits.h"
#include "glint/assets/mesh_import.h"

#include "glint/assets/gltf_importer.h"
#include "glint/assets/gltf_validate.h"

namespace glint {

namespace gltf_detail {

/// `count` elements of `n` components of type `ct` from buffer view `view`, starting `offset`
/// bytes into it, into `dst`; `strided`: the view's byteStride applies (vertex attributes),
/// else the elements are packed (sparse indices and values). Every range is checked, in 128-bit
/// arithmetic so that no offset or stride read from the file can wrap around. `at` is the
/// JSON pointer of the object naming the view, for errors.
void Importer::fetch(int view, std::size_t offset, std::size_t count, int n, int ct, bool normalized, bool strided,
           double* dst, const std::string& what, const std::string& at) const {
    if (view < 0 || view >= static_cast<int>(model.bufferViews.size()))
        fail_at(at + "/bufferView", fmt::format("{}: buffer view {} does not exist", what, view));
    const tinygltf::BufferView& bv = model.bufferViews[view];
    __extension__ typedef unsigned __int128 Wide;
    const unsigned char* bytes = nullptr;  // the view's first byte
    std::size_t length = 0;
    if (const auto it = bv.extensions.find("EXT_meshopt_compression"); it != bv.extensions.end()) {
        const std::vector<unsigned char>& decoded = meshopt_view(view, it->second, what);
        bytes = decoded.data();
        length = decoded.size();
    } else {
        if (bv.buffer < 0 || bv.buffer >= static_cast<int>(model.buffers.size()))
            fail_at(fmt::format("/bufferViews/{}/buffer", view), fmt::format("{}: buffer {} does not exist", what, bv.buffer));
        const std::vector<unsigned char>& data = model.buffers[bv.buffer].data;
        if (Wide{bv.byteOffset} + bv.byteLength > data.size())
            fail_at(fmt::format("/bufferViews/{}/byteLength", view),
                    fmt::format("{}: buffer view {} reaches past the end of buffer {}", what, view, bv.buffer));
        bytes = data.data() + bv.byteOffset;
        length = bv.byteLength;
    }
    const int size = component_size(ct);
    const std::size_t elem = static_cast<std::size_t>(n * size);
    const std::size_t stride = strided && bv.byteStride ? bv.byteStride : elem;
    if (count > 0 && Wide{offset} + Wide{count - 1} * stride + elem > length)
        fail_at(at + "/count", fmt::format("{} reaches past the end of its buffer", what));
    if (!dst) return;  // only the ranges were asked for
    const unsigned char* base = bytes + offset;
    for (std::size_t i = 0; i < count; ++i) {
        const unsigned char* p = base + i * stride;
        for (int c = 0; c < n; ++c) {
            const unsigned char* q = p + c * size;
            double x = 0;
            switch (ct) {
                case TINYGLTF_COMPONENT_TYPE_BYTE: { std::int8_t t; std::memcpy(&t, q, 1); x = normalized ? std::max(t / 127.0, -1.0) : t; break; }
                case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: { x = normalized ? *q / 255.0 : *q; break; }
                case TINYGLTF_COMPONENT_TYPE_SHORT: { std::int16_t t; std::memcpy(&t, q, 2); x = normalized ? std::max(t / 32767.0, -1.0) : t; break; }
                case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: { std::uint16_t t; std::memcpy(&t, q, 2); x = normalized ? t / 65535.0 : t; break; }
                case TINYGLTF_COMPONENT_TYPE_INT: { std::int32_t t; std::memcpy(&t, q, 4); x = t; break; }
                case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: { std::uint32_t t; std::memcpy(&t, q, 4); x = t; break; }
                case TINYGLTF_COMPONENT_TYPE_FLOAT: { float t; std::memcpy(&t, q, 4); x = t; break; }
                default: { double t; std::memcpy(&t, q, 8); x = t; break; }
            }
            dst[i * n + c] = x;
        }
    }
}

/// Buffer view `view` compressed by EXT_meshopt_compression (`ext`), decoded once: vertex
/// streams (mode ATTRIBUTES, with the OCTAHEDRAL, QUATERNION or EXPONENTIAL filter undone),
/// index buffers (TRIANGLES) and index sequences (INDICES), by meshoptimizer's decoders.
const std::vector<unsigned char>& Importer::meshopt_view(int view, const tinygltf::Value& ext, const std::string& what) const {
    if (const auto it = meshopt_views.find(view); it != meshopt_views.end()) return it->second;
    const std::string at = fmt::format("/bufferViews/{}/extensions/EXT_meshopt_compression", view);
    const auto integer = [&](const char* key, double fallback) {
        const double x = number(ext, key, fallback);
        if (!(x >= 0 && x <= 9e15) || x != std::floor(x))
            fail_at(at + "/" + key, fmt::format("{}: EXT_meshopt_compression: {} must be a whole number >= 0", what, key));
        return static_cast<std::size_t>(x);
    };
    const std::size_t buffer = integer("buffer", -1), offset = integer("byteOffset", 0),
                      length = integer("byteLength", -1), stride = integer("byteStride", -1),
                      count = integer("count", -1);
    const std::string mode = ext.Has("mode") && ext.Get("mode").IsString() ? ext.Get("mode").Get<std::string>() : "";
    const std::string filter =
        ext.Has("filter") && ext.Get("filter").IsString() ? ext.Get("filter").Get<std::string>() : "NONE";
    if (buffer >= model.buffers.size())
        fail_at(at + "/buffer", fmt::format("{}: EXT_meshopt_compression: buffer {} does not exist", what, buffer));
    const std::vector<unsigned char>& data = model.buffers[buffer].data;
    if (offset > data.size() || length > data.size() - offset)
        fail_at(at + "/byteLength", fmt::format("{}: EXT_meshopt_compression: bytes {} to {} are past the end of buffer {} ({} bytes)",
                                                what, offset, offset + length, buffer, data.size()));
    if (stride == 0 || stride > 256 || count > kMaxAccessorValues / stride)
        fail_at(at + "/count", fmt::format("{}: EXT_meshopt_compression: {} elements of {} bytes is out of range", what,
                                           count, stride));
    std::vector<unsigned char> decoded(count * stride);
    const unsigned char* src = data.data() + offset;
    int status = -1;
    if (mode == "ATTRIBUTES") {
        if (stride % 4 == 0) status = meshopt_decodeVertexBuffer(decoded.data(), count, stride, src, length);
        if (status == 0 && filter != "NONE") {
            if (filter == "OCTAHEDRAL" && (stride == 4 || stride == 8)) meshopt_decodeFilterOct(decoded.data(), count, stride);
            else if (filter == "QUATERNION" && stride == 8) meshopt_decodeFilterQuat(decoded.data(), count, stride);
            else if (filter == "EXPONENTIAL") meshopt_decodeFilterExp(decoded.data(), count, stride);
            else
                fail_at(at + "/filter", fmt::format("{}: EXT_meshopt_compression: filter '{}' with {}-byte elements", what,
                                                    filter, stride));
        }
    } else if (mode == "TRIANGLES" || mode == "INDICES") {
        if (stride == 2 || stride == 4)
            status = mode == "TRIANGLES" ? meshopt_decodeIndexBuffer(decoded.data(), count, stride, src, length)
                                         : meshopt_decodeIndexSequence(decoded.data(), count, stride, src, length);
    } else {
        fail_at(at + "/mode", fmt::format("{}: EXT_meshopt_compression: mode '{}' (ATTRIBUTES, TRIANGLES or INDICES)", what, mode));
    }
    if (status != 0)
        fail_at(at, fmt::format("{}: EXT_meshopt_compression: the {} data of buffer view {} cannot be decoded", what,
                                mode, view));
    return meshopt_views.emplace(view, std::move(decoded)).first->second;
}

/// Accessor `index` as doubles, `n` components per element (normalised integers mapped to
/// [0, 1] or [-1, 1] when the accessor says so), sparse substitutions applied. `ref` is the
/// JSON pointer of the reference to the accessor, for errors.
std::vector<double> Importer::read(int index, int n, const std::string& what, const std::string& ref) const {
    if (index < 0 || index >= static_cast<int>(model.accessors.size()))
        fail_at(ref, fmt::format("{}: accessor {} does not exist", what, index));
    const tinygltf::Accessor& a = model.accessors[index];
    const std::string at = fmt::format("/accessors/{}", index);
    const int comps = components(a.type), size = component_size(a.componentType);
    if (comps != n || size == 0)
        fail_at(at + (comps != n ? "/type" : "/componentType"),
                fmt::format("{}: accessor {} has the wrong type", what, index));
    // Checked before anything is allocated: without a buffer view the values are zeros (the
    // spec) and nothing else bounds the count.
    if (a.count > kMaxAccessorValues / static_cast<std::size_t>(n))
        fail_at(at + "/count", fmt::format("{}: accessor {} has {} elements; the limit is {} values", what, index,
                                           a.count, kMaxAccessorValues));
    const std::string name = fmt::format("{}: accessor {}", what, index);
    // Sized from what the file holds, before allocating: the view's bytes must reach the last
    // element; without a view the elements are zeros but for the sparse ones, and glint takes at
    // most kMaxZeroElements more zeros than the file gives sparse values.
    if (a.bufferView >= 0) {
        fetch(a.bufferView, a.byteOffset, a.count, n, a.componentType, a.normalized, true, nullptr, name, at);
    } else {
        const std::size_t given = a.sparse.isSparse ? static_cast<std::size_t>(std::max(a.sparse.count, 0)) : 0;
        if (a.count > given + kMaxZeroElements)
            fail_at(at + "/count", fmt::format("{}: {} elements with no bufferView (all zero but {} sparse ones): at most {} "
                                               "more than the file gives values for", name, a.count, given, kMaxZeroElements));
    }
    std::vector<double> v(a.count * static_cast<std::size_t>(n), 0.0);
    if (a.bufferView >= 0)
        fetch(a.bufferView, a.byteOffset, a.count, n, a.componentType, a.normalized, true, v.data(), name, at);
    if (a.sparse.isSparse) {  // sparse.count (index, value) pairs replace elements
        const auto& sp = a.sparse;
        const std::string sat = at + "/sparse";
        if (sp.count < 0 || static_cast<std::size_t>(sp.count) > a.count)
            fail_at(sat + "/count", fmt::format("{}: {} sparse elements in an accessor of {}", name, sp.count, a.count));
        const int ict = sp.indices.componentType;
        if (ict != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && ict != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
            ict != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
            fail_at(sat + "/indices/componentType", fmt::format("{}: sparse indices must be unsigned integers", name));
        const std::size_t sn = static_cast<std::size_t>(sp.count);
        fetch(sp.indices.bufferView, static_cast<std::size_t>(std::max(sp.indices.byteOffset, 0)), sn, 1, ict, false, false,
              nullptr, name + "'s sparse indices", sat + "/indices");
        fetch(sp.values.bufferView, static_cast<std::size_t>(std::max(sp.values.byteOffset, 0)), sn, n, a.componentType,
              a.normalized, false, nullptr, name + "'s sparse values", sat + "/values");
        std::vector<double> idx(sn), val(idx.size() * n);
        fetch(sp.indices.bufferView, static_cast<std::size_t>(std::max(sp.indices.byteOffset, 0)), idx.size(), 1, ict,
              false, false, idx.data(), name + "'s sparse indices", sat + "/indices");
        fetch(sp.values.bufferView, static_cast<std::size_t>(std::max(sp.values.byteOffset, 0)), idx.size(), n,
              a.componentType, a.normalized, false, val.data(), name + "'s sparse values", sat + "/values");
        for (std::size_t k = 0; k < idx.size(); ++k) {
            if (idx[k] >= double(a.count))
                fail_at(sat + "/indices", fmt::format("{}: sparse index {} is past its {} elements", name, idx[k], a.count));
            std::copy_n(val.data() + k * n, n, v.data() + static_cast<std::size_t>(idx[k]) * n);
        }
    }
    return v;
}

Importer::DracoPrimitive Importer::decode_draco(const tinygltf::Value& ext, const std::string& at, const std::string& what) const {
    if (!ext.Has("bufferView") || !ext.Get("bufferView").IsNumber())
        fail_at(at, what + ": KHR_draco_mesh_compression needs a bufferView");
    const int view = whole(ext.Get("bufferView"));
    if (view < 0 || view >= static_cast<int>(model.bufferViews.size()))
        fail_at(at + "/bufferView", fmt::format("{}: buffer view {} does not exist", what, view));
    const tinygltf::BufferView& bv = model.bufferViews[view];
    if (bv.buffer < 0 || bv.buffer >= static_cast<int>(model.buffers.size()))
        fail_at(fmt::format("/bufferViews/{}/buffer", view), fmt::format("{}: buffer {} does not exist", what, bv.buffer));
    const std::vector<unsigned char>& data = model.buffers[bv.buffer].data;
    if (bv.byteOffset > data.size() || bv.byteLength > data.size() - bv.byteOffset)
        fail_at(fmt::format("/bufferViews/{}/byteLength", view),
                fmt::format("{}: buffer view {} reaches past the end of buffer {}", what, view, bv.buffer));
    DracoPrimitive d;
    try {
        d.mesh = decode_draco_mesh(data.data() + bv.byteOffset, bv.byteLength, kMaxAccessorValues);
    } catch (const std::exception& e) {
        fail_at(at, fmt::format("{}: the Draco data cannot be decoded: {}", what, e.what()));
    }
    if (ext.Has("attributes") && ext.Get("attributes").IsObject()) {
        const tinygltf::Value& a = ext.Get("attributes");
        for (const std::string& key : a.Keys())
            if (a.Get(key).IsNumber()) d.ids[key] = whole(a.Get(key));
    }
    return d;
}

/// Attribute `name` of a Draco primitive as doubles, `n` components per point; nothing if the
/// primitive's extension does not list it.
std::optional<std::vector<double>> Importer::draco_attribute(const DracoPrimitive& d, const std::string& name, int n,
                                                   const std::string& at, const std::string& what) const {
    const auto it = d.ids.find(name);
    if (it == d.ids.end()) return std::nullopt;
    const auto a = std::find_if(d.mesh.attributes.begin(), d.mesh.attributes.end(),
                                [&](const DracoAttribute& x) { return x.unique_id == it->second; });
    if (a == d.mesh.attributes.end())
        fail_at(at + "/attributes/" + name, fmt::format("{}: {} names Draco attribute {}, which the data lacks", what, name, it->second));
    if (a->components != n)
        fail_at(at + "/attributes/" + name, fmt::format("{}: Draco attribute {} has {} components; {} needs {}", what,
                                                        it->second, a->components, name, n));
    return std::vector<double>(a->values.begin(), a->values.end());
}

void Importer::mesh(int index) {
    const tinygltf::Mesh& gm = model.meshes[index];
    mesh_first[index] = static_cast<std::uint32_t>(out.meshes.size());
    std::uint32_t count = 0;
    for (std::size_t p = 0; p < gm.primitives.size(); ++p) {
        const tinygltf::Primitive& prim = gm.primitives[p];
        const std::string what = fmt::format("mesh '{}' primitive {}", gm.name, p);
        const std::string at = fmt::format("/meshes/{}/primitives/{}", index, p);
        const auto attribute = [&](const std::string& name) { return at + "/attributes/" + name; };
        if (prim.mode != TINYGLTF_MODE_TRIANGLES && prim.mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
            prim.mode != TINYGLTF_MODE_TRIANGLE_FAN && prim.mode != -1) {
            out.notes.push_back(fmt::format("{}: {}: points and lines are skipped", file, what));
            continue;
        }
        std::optional<DracoPrimitive> draco;
        if (const auto it = prim.extensions.find("KHR_draco_mesh_compression"); it != prim.extensions.end())
            draco = decode_draco(it->second, at + "/extensions/KHR_draco_mesh_compression", what);
        // An attribute from the Draco data when the primitive is compressed and lists it, else
        // from its accessor.
        const auto values = [&](const std::string& name, int accessor, int n) {
            if (draco)
                if (auto v = draco_attribute(*draco, name, n, at + "/extensions/KHR_draco_mesh_compression", what))
                    return std::move(*v);
            return read(accessor, n, what, attribute(name));
        };
        const auto pos_it = prim.attributes.find("POSITION");
        if (pos_it == prim.attributes.end()) fail_at(at, what + ": no POSITION attribute");
        TriangleMesh m;
        m.name = gm.name;
        const std::vector<double> pos = values("POSITION", pos_it->second, 3);
        const std::size_t nv = pos.size() / 3;
        for (std::size_t i = 0; i < nv; ++i)
            m.positions.push_back({float(pos[3 * i]), float(pos[3 * i + 1]), float(-pos[3 * i + 2])});
        if (const auto it = prim.attributes.find("NORMAL"); it != prim.attributes.end()) {
            const auto n = values("NORMAL", it->second, 3);
            if (n.size() == pos.size())
                for (std::size_t i = 0; i < nv; ++i) m.normals.push_back(Normal3{float(n[3 * i]), float(n[3 * i + 1]), float(-n[3 * i + 2])});
        }
        for (int set = 0; set < kMaxUvSets; ++set) {
            const std::string name = fmt::format("TEXCOORD_{}", set);
            const auto it = prim.attributes.find(name);
            if (it == prim.attributes.end()) continue;
            const auto t = values(name, it->second, 2);
            if (t.size() != 2 * nv) continue;
            std::vector<Point2>* dst = &m.uvs;
            if (set > 0) {  // sets come in increasing order; missing ones stay empty
                m.more_uvs.resize(static_cast<std::size_t>(set));
                dst = &m.more_uvs.back();
            }
            for (std::size_t i = 0; i < nv; ++i) dst->push_back({float(t[2 * i]), float(1 - t[2 * i + 1])});
        }
        if (const auto it = prim.attributes.find("TANGENT"); it != prim.attributes.end()) {
            const auto t = values("TANGENT", it->second, 4);
            // z negated like positions; the mirror also flips the bitangent's handedness,
            // and so does the v flip: the two cancel, w stays.
            if (t.size() == 4 * nv)
                for (std::size_t i = 0; i < nv; ++i)
                    m.tangents.push_back({float(t[4 * i]), float(t[4 * i + 1]), float(-t[4 * i + 2]), float(t[4 * i + 3])});
        }
        if (const auto it = prim.attributes.find("COLOR_0"); it != prim.attributes.end()) {
            // RGB or RGBA; read() reports a missing accessor.
            const bool exists = it->second >= 0 && it->second < static_cast<int>(model.accessors.size());
            const int n = exists && components(model.accessors[it->second].type) == 4 ? 4 : 3;
            const auto c = values("COLOR_0", it->second, n);
            for (std::size_t i = 0; i < nv && c.size() == n * nv; ++i) {
                m.colors.push_back(Color{float(c[n * i]), float(c[n * i + 1]), float(c[n * i + 2])});
                if (n == 4) m.alphas.push_back(float(c[n * i + 3]));
            }
            if (std::all_of(m.alphas.begin(), m.alphas.end(), [](Float a) { return a >= 1; })) m.alphas.clear();
        }
        std::vector<std::uint32_t> idx;
        if (draco) {  // Draco's faces are triangles of point indices
            for (std::size_t k = 0; k < draco->mesh.indices.size(); ++k) {
                const std::uint32_t v = draco->mesh.indices[k];
                if (v >= nv) fail_at(at + "/extensions/KHR_draco_mesh_compression",
                                     fmt::format("{}: Draco face {} uses point {} of {}", what, k / 3, v, nv));
                idx.push_back(v);
            }
        } else if (prim.indices >= 0) {
            // The largest value of the index type is the primitive restart value, which glTF
            // forbids (the spec: "MUST NOT contain the maximum possible value").
            const int ict = prim.indices < static_cast<int>(model.accessors.size()) ? model.accessors[prim.indices].componentType : 0;
            const double restart = ict == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE    ? 255.0
                                   : ict == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ? 65535.0
                                                                                   : 4294967295.0;
            for (double x : read(prim.indices, 1, what, at + "/indices")) {
                if (x == restart)
                    fail_at(fmt::format("/accessors/{}", prim.indices),
                            fmt::format("{}: index {} is the primitive restart value, which glTF does not allow", what, x));
                if (!(x >= 0 && x < double(nv)))
                    fail_at(fmt::format("/accessors/{}", prim.indices),
                            fmt::format("{}: index {} out of range ({} vertices)", what, x, nv));
                idx.push_back(static_cast<std::uint32_t>(x));
            }
        } else {
            for (std::uint32_t i = 0; i < nv; ++i) idx.push_back(i);
        }
        const int mode = draco ? TINYGLTF_MODE_TRIANGLES : prim.mode;  // Draco decodes to triangles
        if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
            for (std::size_t i = 0; i + 2 < idx.size(); ++i) {
                if (i % 2 == 0) m.indices.insert(m.indices.end(), {idx[i], idx[i + 1], idx[i + 2]});
                else m.indices.insert(m.indices.end(), {idx[i + 1], idx[i], idx[i + 2]});
            }
        } else if (mode == TINYGLTF_MODE_TRIANGLE_FAN) {
            for (std::size_t i = 1; i + 1 < idx.size(); ++i) m.indices.insert(m.indices.end(), {idx[0], idx[i], idx[i + 1]});
        } else {
            if (idx.size() % 3 != 0)
                fail_at(prim.indices >= 0 ? at + "/indices" : attribute("POSITION"),
                        fmt::format("{}: {} indices is not a whole number of triangles", what, idx.size()));
            m.indices = std::move(idx);
        }
        // Positions are mirrored (z negated), which turns each triangle's winding around: with no
        // NORMAL the faces' own normals must still point to glTF's front (counter-clockwise) side,
        // so that one-sided emission and the flat normals face the way the file means.
        if (m.normals.empty())
            for (std::size_t t = 0; t + 2 < m.indices.size(); t += 3) std::swap(m.indices[t + 1], m.indices[t + 2]);
        m.material = prim.material >= 0 && prim.material < static_cast<int>(out.materials.size())
                         ? static_cast<MaterialId>(prim.material)
                         : kNoImportedMaterial;
        try {
            out.dropped_triangles += validate_and_drop_degenerate(m);
        } catch (const std::invalid_argument& e) {
            fail_at(attribute("POSITION"), what + ": " + e.what());
        }
        out.meshes.push_back(std::move(m));
        ++count;
    }
    mesh_count[index] = count;
}

/// A file that requires an extension glint lacks cannot be shown as its author meant: an
/// error. One that only uses such an extension renders without it, with a note naming it.
void Importer::check_extensions() {
    static const std::set<std::string> supported = {
        "EXT_meshopt_compression",    "KHR_draco_mesh_compression",
        "KHR_lights_punctual",        "KHR_materials_clearcoat", "KHR_materials_dispersion",
        "KHR_materials_emissive_strength",
        "KHR_materials_ior",          "KHR_materials_sheen",     "KHR_materials_specular",
        "KHR_materials_transmission", "KHR_materials_volume",    "KHR_mesh_quantization",
        "KHR_texture_transform"};
    for (std::size_t i = 0; i < model.extensionsRequired.size(); ++i) {
        const std::string& e = model.extensionsRequired[i];
        if (!supported.count(e))
            fail_at(fmt::format("/extensionsRequired/{}", i),
                    fmt::format("the file requires the extension {}, which glint does not support", e));
    }
    for (const std::string& e : model.extensionsUsed)
        if (!supported.count(e)) out.notes.push_back(fmt::format("{}: uses the extension {}, which glint ignores", file, e));
}

/// The nodes must form trees (the spec): a node listed as the child of two parents, or twice,
/// would be visited once per path, exponentially many times in a chain of such nodes.
void Importer::check_trees() const {
    std::vector<int> parent(model.nodes.size(), -1);
    // Each entry of `list` (at JSON pointer `at`) must name a node; `check` then sees it.
    const auto each = [&](const std::vector<int>& list, const std::string& at, auto&& check) {
        for (std::size_t k = 0; k < list.size(); ++k) {
            const std::string where = fmt::format("{}/{}", at, k);
            if (list[k] < 0 || list[k] >= static_cast<int>(model.nodes.size()))
                fail_at(where, fmt::format("node {} does not exist", list[k]));
            check(list[k], where);
        }
    };
    for (std::size_t i = 0; i < model.nodes.size(); ++i)
        each(model.nodes[i].children, fmt::format("/nodes/{}/children", i), [&](int c, const std::string& where) {
            if (parent[c] >= 0)
                fail_at(where, fmt::format("node {} is a child of node {} and of node {}; nodes must form trees", c,
                                           parent[c], i));
            parent[c] = static_cast<int>(i);
        });
    for (std::size_t s = 0; s < model.scenes.size(); ++s)
        each(model.scenes[s].nodes, fmt::format("/scenes/{}/nodes", s), [&](int r, const std::string& where) {
            if (parent[r] >= 0)
                fail_at(where, fmt::format("node {} is a scene root and a child of node {}; nodes must form trees", r,
                                           parent[r]));
        });
}

/// The nodes no node lists as a child.
std::vector<int> Importer::roots() const {
    std::vector<bool> child(model.nodes.size(), false);
    for (const tinygltf::Node& n : model.nodes)
        for (int c : n.children) child[c] = true;  // in range: check_trees() ran
    std::vector<int> result;
    for (std::size_t i = 0; i < model.nodes.size(); ++i)
        if (!child[i]) result.push_back(static_cast<int>(i));
    return result;
}

// Indices are valid and the nodes form trees (check_trees()), so a cycle of children cannot be
// reached: each of its nodes has its parent in the cycle, so none is a root. The depth limit
// only keeps the recursion's stack small.
void Importer::visit(int index, const Matrix34& parent, int depth) {
    if (depth >= limit(Limit::kNesting))
        fail_at(fmt::format("/nodes/{}", index), "the node hierarchy: " + over_limit(Limit::kNesting, depth + 1));
    const tinygltf::Node& n = model.nodes[index];
    const Matrix34 world = parent * node_matrix(index);  // glTF space
    // To glint: M' = F M F with F = diag(1, 1, -1).
    Matrix34 g = world;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 4; ++j)
            if ((i == 2) != (j == 2) && j != 3) g.m[i][j] = -g.m[i][j];
    g.m[2][3] = -g.m[2][3];
    if (n.mesh >= 0) {
        if (n.mesh >= static_cast<int>(model.meshes.size()))
            fail_at(fmt::format("/nodes/{}/mesh", index), fmt::format("node {} uses mesh {} that does not exist", index, n.mesh));
        if (!mesh_first.count(n.mesh)) mesh(n.mesh);
        const auto t = Transform::from(g);
        if (!t) {
            out.notes.push_back(fmt::format("{}: node {} has a singular transform; skipped", file, index));
        } else {
            for (std::uint32_t k = 0; k < mesh_count[n.mesh]; ++k) {
                out.nodes.push_back({mesh_first[n.mesh] + k, *t});
                node_of.push_back(index);
            }
        }
    }
    const auto place = [&](Vector3 local) { return g.apply(local); };
    if (n.camera >= 0 && n.camera < static_cast<int>(model.cameras.size())) {
        const tinygltf::Camera& c = model.cameras[n.camera];
        // Wanted: the first camera; or the one named; or, for "#N" when no camera has that
        // name, the N-th met (from 0; unnamed cameras have no other handle).
        const bool wanted = camera_name.empty()    ? !camera.has_value()
                            : c.name == camera_name ? !camera.has_value() || camera->name != camera_name
                            : !camera.has_value() && camera_name == fmt::format("#{}", out.cameras.size());
        if (c.type == "perspective" || c.type == "orthographic") {
            GltfCamera cam;
            cam.name = c.name;
            cam.position = g.apply(Point3{0, 0, 0});
            cam.direction = normalize(place({0, 0, 1}));  // glTF's -z, mirrored
            cam.up = normalize(place({0, 1, 0}));
            if (c.type == "perspective") {
                const double yfov = c.perspective.yfov;  // the specification: > 0
                if (!(yfov > 0 && yfov < std::numbers::pi))
                    fail_at(fmt::format("/cameras/{}/perspective/yfov", n.camera),
                            fmt::format("yfov must be in (0, pi) radians, got {}", yfov));
                cam.yfov_degrees = float(yfov * 180 / std::numbers::pi);
            } else {
                cam.orthographic = true;
                cam.ymag = float(c.orthographic.ymag);
                if (!(cam.ymag > 0) || !std::isfinite(cam.ymag))
                    fail_at(fmt::format("/cameras/{}/orthographic/ymag", n.camera), "ymag must be positive");
            }
            out.cameras.push_back(cam);
            if (wanted) camera = cam;
        }
    }
    if (const auto it = n.extensions.find("KHR_lights_punctual"); it != n.extensions.end() && it->second.Has("light")) {
        const int li = whole(it->second.Get("light"));
        if (li >= 0 && li < static_cast<int>(model.lights.size())) {
            const tinygltf::Light& l = model.lights[li];
            Color c{1};
            if (l.color.size() == 3) c = Color{float(l.color[0]), float(l.color[1]), float(l.color[2])};
            c = c * float(l.intensity);
            const Point3 p = g.apply(Point3{0, 0, 0});
            const Vector3 d = normalize(place({0, 0, 1}));  // lights shine along glTF's -z
            if (l.type == "point") {
                out.lights.push_back(PointLight{p, c});
            } else if (l.type == "spot") {
                const float outer = float(std::cos(l.spot.outerConeAngle));
                const float inner = std::max(float(std::cos(l.spot.innerConeAngle)), outer + 1e-4f);
                out.lights.push_back(SpotLight{p, d, c, inner, outer});
            } else if (l.type == "directional") {
                out.lights.push_back(DirectionalLight{d, c});
            }
        }
    }
    for (int child : n.children) visit(child, world, depth + 1);
}

}  // namespace gltf_detail

namespace {

using gltf_detail::Importer;
using gltf_detail::kMaxAccessorValues;

/// The container of a .glb checked by glint, so that a broken one is reported at its byte offset
/// in glint's words (tinygltf says "Invalid glTF binary."): the 12-byte header (magic "glTF",
/// version 2, the total length), the JSON chunk (length, type "JSON", within the file, padded to
/// 4 bytes), then an optional BIN chunk the same way. Returns the error text, or empty.
std::string glb_container_error(const std::string& bytes) {
    const auto u32 = [&](std::size_t at) {
        std::uint32_t v = 0;
        std::memcpy(&v, bytes.data() + at, 4);
        return v;  // little-endian, as the machines glint builds for
    };
    const std::size_t size = bytes.size();
    if (size < 12) return fmt::format("byte 0: {} bytes, too short for the 12-byte header of a binary glTF", size);
    if (bytes.compare(0, 4, "glTF") != 0) return "byte 0: not a binary glTF (it does not start with 'glTF')";
    if (u32(4) != 2) return fmt::format("byte 4: version {}; glint reads glTF 2", u32(4));
    if (u32(8) != size) return fmt::format("byte 8: the header gives the length as {} bytes; the file has {}", u32(8), size);
    if (size < 20) return fmt::format("byte 12: the JSON chunk's header is cut short ({} bytes)", size);
    const std::uint32_t json = u32(12);
    if (bytes.compare(16, 4, "JSON") != 0) return "byte 16: the first chunk must be of type 'JSON'";
    if (json > size - 20) return fmt::format("byte 12: the JSON chunk's length {} runs past the end of the file ({} bytes)", json, size);
    if (json % 4 != 0) return fmt::format("byte 12: the JSON chunk's length {} is not a multiple of 4", json);
    const std::size_t bin = 20 + std::size_t{json};
    if (bin == size) return {};
    if (size - bin < 8) return fmt::format("byte {}: a chunk header is cut short ({} bytes left)", bin, size - bin);
    const std::uint32_t n = u32(bin);
    if (bytes.compare(bin + 4, 4, std::string("BIN\0", 4)) != 0) return fmt::format("byte {}: the second chunk must be of type 'BIN'", bin + 4);
    if (n > size - bin - 8) return fmt::format("byte {}: the BIN chunk's length {} runs past the end of the file ({} bytes)", bin, n, size);
    return {};
}

/// tinygltf's messages for what glint does not check first, in glint's form: no trailing periods
/// or line breaks, a lower-case start, "File read error : X : why" as "cannot read 'X': why".
std::string tinygltf_message(std::string why) {
    while (!why.empty() && (why.back() == '\n' || why.back() == ' ' || why.back() == '.')) why.pop_back();
    // Matched by hand, not with std::regex: libstdc++'s matcher recurses per character, and a
    // message quoting a long stretch of the file overflowed the stack (found by fuzz_gltf).
    const auto line_from = [&](std::size_t at) { return why.substr(at, why.find('\n', at) - at); };
    for (const char* kind : {"File read error : ", "File open error : "}) {
        const std::size_t at = why.find(kind);
        if (at == std::string::npos) continue;
        const std::string rest = line_from(at + std::strlen(kind));
        if (const std::size_t sep = rest.find(" : "); sep != std::string::npos)
            return fmt::format("cannot read '{}': {}", rest.substr(0, sep), rest.substr(sep + 3));
        if (kind[5] == 'o') return fmt::format("cannot open '{}'", rest);
    }
    for (std::size_t at = 0; (at = why.find(".\n", at)) != std::string::npos;) why.replace(at, 2, "; ");
    for (char& c : why)
        if (c == '\n') c = ' ';
    if (why.size() > 1 && std::isupper(static_cast<unsigned char>(why[0])) && std::islower(static_cast<unsigned char>(why[1])))
        why[0] = static_cast<char>(std::tolower(static_cast<unsigned char>(why[0])));
    return why;
}

/// Two things tinygltf (built without the extensions) refuses in files that use them, and which
/// glint's importer does not read anyway: gltfpack's EXT_meshopt_compression fallback buffers (a
/// length and no data: tinygltf would look for a file) become a 4-byte data URI, and the index
/// accessors of KHR_draco_mesh_compression primitives (no buffer view: the indices are in the
/// Draco data) are detached from them. The file's bytes so changed, or nothing when neither occurs
/// (the file is then loaded as it is). JSON pointers into the file stay valid for messages.
std::optional<std::string> prepare_for_tinygltf(const std::string& bytes, bool glb) {
    if (bytes.find("EXT_meshopt_compression") == std::string::npos &&
        bytes.find("KHR_draco_mesh_compression") == std::string::npos)
        return std::nullopt;
    // A .glb: a 12-byte header, then the JSON chunk (length, type, text), then the rest.
    std::size_t json_at = 0, json_size = bytes.size();
    if (glb) {
        if (bytes.size() < 20) return std::nullopt;  // tinygltf reports the broken header
        std::uint32_t n = 0;
        std::memcpy(&n, bytes.data() + 12, 4);
        if (n > bytes.size() - 20) return std::nullopt;
        json_at = 20;
        json_size = n;
    }
    nlohmann::json j = nlohmann::json::parse(bytes.begin() + static_cast<std::ptrdiff_t>(json_at),
                                             bytes.begin() + static_cast<std::ptrdiff_t>(json_at + json_size), nullptr, false);
    if (j.is_discarded() || !j.is_object()) return std::nullopt;
    bool changed = false;
    if (j.contains("meshes") && j["meshes"].is_array())
        for (nlohmann::json& mesh : j["meshes"]) {
            if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array()) continue;
            for (nlohmann::json& prim : mesh["primitives"]) {
                if (!prim.is_object() || !prim.contains("extensions") || !prim["extensions"].is_object() ||
                    !prim["extensions"].contains("KHR_draco_mesh_compression") || !prim.contains("indices"))
                    continue;
                prim.erase("indices");
                changed = true;
            }
        }
    nlohmann::json no_buffers = nlohmann::json::array();
    nlohmann::json& buffers = j.contains("buffers") && j["buffers"].is_array() ? j["buffers"] : no_buffers;
    for (nlohmann::json& b : buffers) {
        if (!b.is_object() || b.contains("uri") || !b.contains("extensions") || !b["extensions"].is_object()) continue;
        const nlohmann::json& e = b["extensions"];
        if (!e.contains("EXT_meshopt_compression") || !e["EXT_meshopt_compression"].is_object()) continue;
        const nlohmann::json& m = e["EXT_meshopt_compression"];
        if (!m.contains("fallback") || m["fallback"] != true) continue;
        b["uri"] = "data:application/octet-stream;base64,AAAAAA==";
        b["byteLength"] = 4;
        changed = true;
    }
    if (!changed) return std::nullopt;
    std::string text = j.dump();
    if (!glb) return text;
    while (text.size() % 4) text += ' ';
    std::string out = bytes.substr(0, 12);
    const std::uint32_t n = static_cast<std::uint32_t>(text.size());
    out.append(reinterpret_cast<const char*>(&n), 4);
    out.append(bytes, 16, 4);  // the chunk type, JSON
    out += text;
    out.append(bytes, json_at + json_size, std::string::npos);
    const std::uint32_t total = static_cast<std::uint32_t>(out.size());
    std::memcpy(out.data() + 8, &total, 4);
    return out;
}

// tinygltf's file callbacks without opening anything but regular files: its own FileExists
// opens the file (which blocks on a FIFO), its reader would read a device for ever.
bool file_exists(const std::string& file, void*) {
    std::error_code ec;
    return std::filesystem::exists(file, ec);
}

// tinygltf's file reader, refusing what is not a regular file (see why_not_readable).
bool read_regular_file(std::vector<unsigned char>* out, std::string* err, const std::string& file, void* user) {
    if (const std::string why = why_not_readable(file); !why.empty()) {
        if (err) *err += "it " + why;  // tinygltf adds "File read error : FILE : "
        return false;
    }
    return tinygltf::ReadWholeFile(out, err, file, user);
}

}  // namespace

void Importer::world_matrices(int index, const Matrix34& parent, int depth, std::map<int, Matrix34>& out_m) const {
    if (depth >= limit(Limit::kNesting)) return;  // the first walk reported it
    const Matrix34 world = parent * node_matrix(index);
    Matrix34 g = world;  // to glint, as visit() does
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 4; ++j)
            if ((i == 2) != (j == 2) && j != 3) g.m[i][j] = -g.m[i][j];
    g.m[2][3] = -g.m[2][3];
    out_m[index] = g;
    for (int c : model.nodes[index].children)
        if (c >= 0 && c < static_cast<int>(model.nodes.size())) world_matrices(c, world, depth + 1, out_m);
}

void Importer::sample_motion(const std::vector<double>& times, const std::vector<int>& scene_roots) {
    out.node_motion.assign(out.nodes.size(), {});
    const std::size_t notes = out.notes.size();
    for (const double t : times) {
        posed.clear();
        animate(t);
        out.notes.resize(notes);  // said once, at the frame
        std::map<int, Matrix34> world;
        for (int r : scene_roots) world_matrices(r, Matrix34{}, 0, world);
        for (std::size_t i = 0; i < out.nodes.size(); ++i) {
            const auto it = world.find(node_of[i]);
            const auto x = it != world.end() ? Transform::from(it->second) : std::nullopt;
            out.node_motion[i].push_back(x ? *x : out.nodes[i].transform);
        }
    }
}

ImportedFile import_gltf(const std::filesystem::path& path, const std::string& camera_name, double time,
                         const std::vector<double>& motion_times) {
    const std::string file = path.string();
    if (std::error_code ec; !std::filesystem::exists(path, ec))
        throw IoError(fmt::format("{}: cannot open: no such file", file));
    tinygltf::TinyGLTF loader;
    // External buffers and images go through tinygltf's own reader, but only from regular files:
    // a uri naming a FIFO would block for ever, a device never end.
    loader.SetFsCallbacks({&file_exists, &tinygltf::ExpandFilePath, &read_regular_file,
                           &tinygltf::WriteWholeFile, nullptr});
    tinygltf::Model model;
    std::string err, warn;
    const bool glb = mesh_format(path) == MeshFormat::kGlb;
    // The file is read once, here; tinygltf parses it from memory (adjusted when it uses the
    // compression extensions).
    if (const std::string why = why_not_readable(path); !why.empty()) throw IoError(fmt::format("{}: cannot read: it {}", file, why));
    std::ifstream in(path, std::ios::binary);
    if (!in) throw IoError(fmt::format("{}: cannot open", file));
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (glb)
        if (const std::string why = glb_container_error(bytes); !why.empty()) throw IoError(fmt::format("{}: {}", file, why));
    {
        // Nesting is checked on the text, before the JSON parsers (which recurse, tinygltf on
        // `extras` without a bound) see it; a .glb's JSON chunk starts at byte 20.
        std::string_view json(bytes);
        if (glb) {
            std::uint32_t n = 0;
            std::memcpy(&n, bytes.data() + 12, 4);
            json = json.substr(20, n);
        }
        if (const auto at = json_too_deep(json, limit(Limit::kNesting)))
            throw IoError(fmt::format("{}:{}:{}: JSON: {}", file, at->line, at->column,
                                      over_limit(Limit::kNesting, limit(Limit::kNesting) + 1)));
        // The specification's types, ranges and version, at the value that breaks them.
        if (const auto e = gltf_rule_error(json)) {
            std::optional<TextPosition> at;
            for (std::string p = e->pointer; !glb && !at; p.erase(p.rfind('/'))) {
                at = json_locate(json, p);
                if (p.empty()) break;
            }
            if (at) throw IoError(fmt::format("{}:{}:{}: {}", file, at->line, at->column, e->message));
            throw IoError(fmt::format("{}: {}", file, e->message));
        }
    }
    if (auto patched = prepare_for_tinygltf(bytes, glb)) bytes = std::move(*patched);
    if (bytes.size() > std::numeric_limits<unsigned int>::max()) throw IoError(fmt::format("{}: too large", file));
    const auto size = static_cast<unsigned int>(bytes.size());
    const std::string base = path.parent_path().string();
    const bool ok = glb ? loader.LoadBinaryFromMemory(&model, &err, &warn, reinterpret_cast<const unsigned char*>(bytes.data()),
                                                      size, base)
                        : loader.LoadASCIIFromString(&model, &err, &warn, bytes.data(), size, base);
    const auto trim = [](std::string s) {
        while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
        return s;
    };
    if (!ok) {
        // nlohmann::json's syntax errors name a line and column: put them where the OBJ and PLY
        // readers put theirs, after the file's name.
        const std::string why = trim(err);
        // "parse error at line L, column C: what", read by hand (see tinygltf_message).
        if (const std::size_t at = why.find("parse error at line "); at != std::string::npos) {
            unsigned long line = 0, column = 0;
            int used = 0;
            if (std::sscanf(why.c_str() + at, "parse error at line %lu, column %lu: %n", &line, &column, &used) == 2 && used > 0) {
                const std::size_t from = at + static_cast<std::size_t>(used);
                std::string what = why.substr(from, why.find('\n', from) - from);
                if (what.size() > 240) what = what.substr(0, 240) + "...";  // it may quote a long stretch of the file
                throw IoError(fmt::format("{}:{}:{}: JSON {}", file, line, column, what));
            }
        }
        throw IoError(fmt::format("{}: {}", file, why.empty() ? "cannot parse" : tinygltf_message(why)));
    }
    // A primitive without a material gets the spec's default material, which multiplies COLOR_0
    // like any other: one such material, added when a primitive has vertex colours and no material.
    {
        int default_material = -1;
        for (tinygltf::Mesh& mesh : model.meshes)
            for (tinygltf::Primitive& p : mesh.primitives)
                if (p.material < 0 && p.attributes.count("COLOR_0")) {
                    if (default_material < 0) {
                        default_material = static_cast<int>(model.materials.size());
                        tinygltf::Material m;  // the spec's defaults: base colour 1, metallic 1, roughness 1
                        m.name = "(glTF default material)";
                        m.pbrMetallicRoughness.baseColorFactor = {1, 1, 1, 1};
                        m.pbrMetallicRoughness.metallicFactor = 1;
                        m.pbrMetallicRoughness.roughnessFactor = 1;
                        m.emissiveFactor = {0, 0, 0};
                        m.alphaMode = "OPAQUE";
                        m.alphaCutoff = 0.5;
                        model.materials.push_back(m);
                    }
                    p.material = default_material;
                }
    }
    Importer im{model, file, glb, {}, {}, {}, {}, {}, {}, std::nullopt, camera_name, {}};
    if (!warn.empty()) im.out.notes.push_back(fmt::format("{}: {}", file, tinygltf_message(warn)));
    im.check_extensions();
    im.vertex_colored.assign(model.materials.size(), false);
    for (const tinygltf::Mesh& mesh : model.meshes)
        for (const tinygltf::Primitive& p : mesh.primitives)
            if (p.material >= 0 && p.material < static_cast<int>(model.materials.size()) && p.attributes.count("COLOR_0"))
                im.vertex_colored[static_cast<std::size_t>(p.material)] = true;
    for (std::size_t m = 0; m < model.materials.size(); ++m)
        im.out.materials.push_back({model.materials[m].name, im.material(static_cast<int>(m)), im.alpha(static_cast<int>(m))});
    im.check_trees();
    im.animate(time);
    const int scene = model.defaultScene >= 0 ? model.defaultScene : 0;
    std::vector<int> roots;
    if (model.scenes.empty()) {  // no scene to show: every tree of nodes
        roots = im.roots();
    } else {
        if (scene >= static_cast<int>(model.scenes.size()))
            im.fail_at("/scene", fmt::format("scene {} does not exist", scene));
        roots = model.scenes[scene].nodes;
    }
    for (int n : roots) im.visit(n, Matrix34{}, 0);
    if (!motion_times.empty() && !model.animations.empty()) im.sample_motion(motion_times, roots);
    if (!camera_name.empty() && !im.camera)
        throw IoError(im.out.cameras.empty()
                          ? fmt::format("{}: no camera named '{}' (the file has no cameras)", file, camera_name)
                          : fmt::format("{}: no camera named '{}' (the file has {}; '#0' to '#{}' pick them in order)", file,
                                        camera_name, im.out.cameras.size(), im.out.cameras.size() - 1));
    im.out.camera = im.camera;
    if (im.out.meshes.empty()) throw IoError(fmt::format("{}: no triangle meshes in the scene", file));
    if (std::all_of(im.out.meshes.begin(), im.out.meshes.end(), [](const TriangleMesh& m) { return m.indices.empty(); }))
        throw IoError(fmt::format("{}: all {} of its triangles are degenerate (no area, or a position not finite): nothing "
                                  "to render", file, im.out.dropped_triangles));
    return std::move(im.out);
}

}  // namespace glint
