#include <fmt/core.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "glint/formats/pbrt_parser.h"
#include "glint/math/motion.h"
#include "glint/shapes/subdivision.h"

namespace glint::pbrt_detail {

std::vector<Transform> Parser::motion_keys(const M4& start, const M4& end, const SourceLoc& loc) {
    if (start.m == end.m) return {};
    const auto a = start.affine() ? Transform::from(start.to34()) : std::nullopt;
    const auto b = end.affine() ? Transform::from(end.to34()) : std::nullopt;
    if (!a || !b) {
        diag_.error(loc, "the shape's transform at the start or end time is singular or projective");
        return {};
    }
    // pbrt interpolates between the transform times and holds the ends outside them; glint's keys
    // are at the shutter's opening and close.
    const Motion between({*a, *b});
    const std::array<double, 2> shutter = camera_seen_ ? d_.shutter : std::array<double, 2>{0, 1};  // pbrt's default
    return {between.at(transform_fraction(shutter[0])), between.at(transform_fraction(shutter[1]))};
}

void Parser::add_object(ObjectDesc o, const M4& m, std::optional<M4> end) {
    if (!defining_) o.motion = motion_keys(m, end ? *end : gs_.ctm_end, o.loc);
    if (defining_) {  // recorded for ObjectInstance, with the transform at definition
        if (!m.identity()) {
            o.transform = m.affine() ? Transform::from(m.to34()) : std::nullopt;
            if (!o.transform) {
                diag_.error(o.loc, "the shape's transform is singular or projective");
                return;
            }
        }
        instances_[defining_->first].push_back(std::move(o));
        return;
    }
    if (!m.affine()) {
        diag_.error(o.loc, "a shape under a projective transform");
        return;
    }
    if (!m.identity()) {
        const auto tr = Transform::from(m.to34());
        if (!tr) {
            diag_.error(o.loc, "the shape's transform is singular");
            return;
        }
        o.transform = *tr;
        o.transform_loc = o.loc;
    }
    if (!o.motion.empty()) o.transform_loc = o.loc;
    d_.objects.push_back(std::move(o));
}

// The material for the next shape: the current one, made emitting when an area light is active.
std::string Parser::material_for_shape() {
    std::string base = gs_.material;
    if (base.empty()) {  // pbrt's default: diffuse 0.5
        base = "pbrt-default";
        if (std::none_of(d_.materials.begin(), d_.materials.end(), [](const NamedMaterial& m) { return m.name == "pbrt-default"; })) {
            MaterialDesc m;
            m.kind = MaterialDesc::Kind::kDiffuse;
            m.color.value = Color{0.5f};
            d_.materials.push_back({"pbrt-default", m, {}});
        }
        gs_.material = base;
    }
    if (!gs_.area_light) return base;
    const auto it = std::find_if(d_.materials.begin(), d_.materials.end(), [&](const NamedMaterial& m) { return m.name == base; });
    MaterialDesc m = it->material;
    m.emission = *gs_.area_light;
    const std::string n = fmt::format("pbrt-emitter-{}", ++material_count_);
    d_.materials.push_back({n, m, gs_.area_light_loc});
    return n;
}

double Parser::world_area(Point3 a, Point3 b, Point3 c) const {
    const D3 pa = gs_.ctm.point(a.x, a.y, a.z), pb = gs_.ctm.point(b.x, b.y, b.z), pc = gs_.ctm.point(c.x, c.y, c.z);
    return 0.5 * len3(cross3(sub(pb, pa), sub(pc, pa)));
}

// An area light's "power" as pbrt-v4 applies it: every shape pbrt makes (each triangle of a
// mesh, each patch, a sphere, a disk) emits that power, L x scale x power / (sides x pi x area),
// with the object-space area for spheres, disks and cylinders and the world-space area for
// triangles and patches. glint's emission is per shape here, so a mesh whose triangles differ
// in area gets their mean (the same total power; pbrt's radiance varies from triangle to
// triangle) with a warning.
void Parser::apply_area_power(const ObjectDesc& o, const std::vector<double>& areas) {
    if (!gs_.area_light || !gs_.area_power || areas.empty()) return;
    const auto* name = std::get_if<std::string>(&o.material.value);
    if (!name) return;
    const auto it = std::find_if(d_.materials.begin(), d_.materials.end(), [&](const NamedMaterial& m) { return m.name == *name; });
    if (it == d_.materials.end()) return;
    double lo = areas[0], hi = areas[0], sum = 0;
    for (double a : areas) lo = std::min(lo, a), hi = std::max(hi, a), sum += a;
    const double area = sum / double(areas.size());
    if (hi > lo * (1 + 1e-3))
        warn(o.loc, fmt::format("area light \"power\" on {} shapes of different areas: each given the mean area's radiance "
                                "(pbrt gives each its own)", areas.size()));
    if (!(area > 0)) return;
    const double sides = gs_.area_light->two_sided ? 2 : 1;
    it->material.emission.radiance = it->material.emission.radiance * float(gs_.area_power->value / (sides * std::numbers::pi * area));
}

// A shape: its object (material, media, alpha) made here, the geometry by the step for its type.
void Parser::shape(const Token& t, const std::string& type, ParamList pl) {
    ObjectDesc o;
    o.loc = t.loc();
    o.material = MaterialRef{material_for_shape(), t.loc()};
    if (!gs_.inside.empty() || !gs_.outside.empty()) {
        o.interior = Located<std::string>{gs_.inside.empty() ? "none" : gs_.inside, t.loc()};
        o.exterior = Located<std::string>{gs_.outside.empty() ? "none" : gs_.outside, t.loc()};
    }
    // "alpha": pbrt's stochastic cut-out (a surface point is there for a fraction alpha of
    // the rays). Constant 1 is opaque, constant 0 no shape at all; meshes take the rest.
    std::optional<AlphaDesc> alpha;
    if (const Param* ap = pl.find("alpha")) {
        const SourceLoc aloc = ap->loc;
        if (auto tex = get_texture(pl, "alpha", true, 1)) {
            if (tex->kind == TextureDesc::Kind::kConstant && tex->value.g >= 1) {
                // opaque
            } else if (tex->kind == TextureDesc::Kind::kConstant && !(tex->value.g > 0)) {
                pl.use_all();
                return;  // never there
            } else {
                alpha = AlphaDesc{*tex, 0.5f, true, aloc};
            }
        }
    }
    ignore(pl, "emissionfilename", "\"emissionfilename\" not supported; the area light's L is used");
    if (type == "sphere") {
        sphere_shape(t, type, pl, std::move(o), alpha);
    } else if (type == "disk") {
        disk_shape(t, type, pl, std::move(o), alpha);
    } else if (type == "trianglemesh" || type == "bilinearmesh") {
        triangle_mesh_shape(t, type, pl, std::move(o), alpha);
    } else if (type == "loopsubdiv") {
        loop_subdiv_shape(t, type, pl, std::move(o), alpha);
    } else if (type == "cylinder") {
        cylinder_shape(t, type, pl, std::move(o), alpha);
    } else if (type == "plymesh") {
        ply_mesh_shape(t, type, pl, std::move(o), alpha);
    } else {
        warn(t.loc(), fmt::format("shape \"{}\" not supported; left out", type));
        pl.use_all();
    }
}

// "alpha" on a shape glint cannot cut out: warned about.
void Parser::no_alpha_here(const std::optional<AlphaDesc>& alpha, const std::string& type) {
    if (alpha) warn(alpha->loc, fmt::format("\"alpha\" on a {}: glint cuts out meshes only; the shape is opaque", type));
}

void Parser::sphere_shape(const Token& t, const std::string& type, ParamList& pl, ObjectDesc o,
                          const std::optional<AlphaDesc>& alpha) {
    const std::string what = "Shape \"" + type + "\"";
    const double r = get_float(pl, "radius").value_or(1);
    for (const char* partial : {"zmin", "zmax", "phimax"})
        if (get_float(pl, partial)) warn(pl.find(partial)->loc, fmt::format("\"{}\": partial spheres not supported; a whole sphere", partial));
    if (!(r > 0)) {
        diag_.error(t.loc(), "sphere: radius must be positive");
        return;
    }
    if (gs_.reverse_orientation && gs_.area_light) warn(t.loc(), "ReverseOrientation on an emitting sphere: glint's sphere emits outwards");
    apply_area_power(o, {4 * std::numbers::pi * r * r});
    no_alpha_here(alpha, type);
    o.shape = Sphere{{0, 0, 0}, Float(r)};
    check_unused(pl, what);
    add_object(std::move(o), gs_.ctm);
}

void Parser::disk_shape(const Token& t, const std::string& type, ParamList& pl, ObjectDesc o,
                        const std::optional<AlphaDesc>& alpha) {
    const std::string what = "Shape \"" + type + "\"";
    const double h = get_float(pl, "height").value_or(0), r = get_float(pl, "radius").value_or(1);
    if (get_float(pl, "innerradius").value_or(0) != 0) warn(pl.find("innerradius")->loc, "innerradius not supported; a full disk");
    if (get_float(pl, "phimax")) warn(pl.find("phimax")->loc, "phimax not supported; a full disk");
    if (!(r > 0)) {
        diag_.error(t.loc(), "disk: radius must be positive");
        return;
    }
    apply_area_power(o, {std::numbers::pi * r * r});
    no_alpha_here(alpha, type);
    o.shape = Disk{{0, 0, Float(h)}, Normal3{0, 0, gs_.reverse_orientation ? -1.0f : 1.0f}, Float(r)};
    check_unused(pl, what);
    add_object(std::move(o), gs_.ctm);
}

void Parser::triangle_mesh_shape(const Token& t, const std::string& type, ParamList& pl, ObjectDesc o,
                                 const std::optional<AlphaDesc>& alpha) {
    const std::string what = "Shape \"" + type + "\"";
    const bool bilinear = type == "bilinearmesh";
    const auto P = get_floats(pl, "P", "point3", 3);
    const std::vector<double>* indices = get_floats(pl, "indices", "integer", bilinear ? 4 : 3);
    std::vector<double> implied;  // indices 0, 1, 2 (3) when a lone face leaves them out
    const auto N = get_floats(pl, "N", "normal3", 3);
    const auto uv = get_floats(pl, "uv", "point2", 2);
    for (const char* name : {"S", "faceIndices"}) ignore(pl, name, fmt::format("\"{}\" ignored", name));
    check_unused(pl, what);
    if (!P) {
        diag_.error(t.loc(), fmt::format("{}: no \"point3 P\"", type));
        return;
    }
    const std::size_t nv = P->size() / 3, per = bilinear ? 4 : 3;
    if (!indices) {
        if (nv != per) {
            diag_.error(t.loc(), fmt::format("{}: \"indices\" may be left out only with {} vertices", type, per));
            return;
        }
        for (std::size_t i = 0; i < per; ++i) implied.push_back(double(i));
        indices = &implied;
    }
    for (double i : *indices)
        if (!(i >= 0 && i < double(nv))) {
            diag_.error(pl.find("indices") ? pl.find("indices")->loc : t.loc(),
                        fmt::format("{}: vertex index {} out of range ({} vertices)", type, i, nv));
            return;
        }
    if (N && N->size() != P->size()) {
        diag_.error(pl.find("N")->loc, fmt::format("{}: {} normals for {} vertices", type, N->size() / 3, nv));
        return;
    }
    if (uv && uv->size() / 2 != nv) {
        diag_.error(pl.find("uv")->loc, fmt::format("{}: {} uvs for {} vertices", type, uv->size() / 2, nv));
        return;
    }
    const auto point = [&](std::size_t i) { return Point3{Float((*P)[3 * i]), Float((*P)[3 * i + 1]), Float((*P)[3 * i + 2])}; };
    // A bilinear patch that is a flat parallelogram is glint's quad exactly.
    if (bilinear && indices->size() == 4 && !N && !uv && !alpha) {
        const Point3 p00 = point(std::size_t((*indices)[0])), p10 = point(std::size_t((*indices)[1])),
                     p01 = point(std::size_t((*indices)[2])), p11 = point(std::size_t((*indices)[3]));
        const Vector3 e1 = p10 - p00, e2 = p01 - p00;
        const Vector3 diag = (p11 - p00) - (e1 + e2);
        if (length(diag) <= 1e-6f * (length(e1) + length(e2)) && length(cross(e1, e2)) > 0) {
            // Under a mirroring transform both pbrt and glint's build keep the front side.
            apply_area_power(o, {2 * world_area(p00, p10, p01)});
            o.shape = gs_.reverse_orientation ? Quad::make(p00, e2, e1) : Quad::make(p00, e1, e2);
            add_object(std::move(o), gs_.ctm);
            return;
        }
    }
    auto mesh = std::make_shared<TriangleMesh>();
    for (std::size_t i = 0; i < nv; ++i) mesh->positions.push_back(point(i));
    if (N)
        for (std::size_t i = 0; i < nv; ++i)
            mesh->normals.push_back(Normal3{Float((*N)[3 * i]), Float((*N)[3 * i + 1]), Float((*N)[3 * i + 2])});
    if (uv)
        for (std::size_t i = 0; i < nv; ++i) mesh->uvs.push_back(Point2{Float((*uv)[2 * i]), Float((*uv)[2 * i + 1])});
    const auto add_tri = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
        // pbrt's front side: with normals, the side they point to; else flipped by ReverseOrientation.
        bool flip = gs_.reverse_orientation;
        if (N) {
            const Vector3 n = cross(mesh->positions[b] - mesh->positions[a], mesh->positions[c] - mesh->positions[a]);
            const Normal3 &na = mesh->normals[a], &nb = mesh->normals[b], &nc = mesh->normals[c];
            const Vector3 s{na.x + nb.x + nc.x, na.y + nb.y + nc.y, na.z + nb.z + nc.z};
            flip = dot(s, n) < 0;
        }
        if (flip) std::swap(b, c);
        mesh->indices.insert(mesh->indices.end(), {a, b, c});
    };
    for (std::size_t i = 0; i < indices->size(); i += per) {
        const auto at = [&](std::size_t k) { return static_cast<std::uint32_t>((*indices)[i + k]); };
        if (bilinear) {  // p00 p10 p01 p11: two triangles
            add_tri(at(0), at(1), at(3));
            add_tri(at(0), at(3), at(2));
        } else {
            add_tri(at(0), at(1), at(2));
        }
    }
    const std::size_t dropped = validate_and_drop_degenerate(*mesh);
    if (dropped > 0) warn(t.loc(), fmt::format("{}: dropped {} degenerate triangle{}", type, dropped, dropped == 1 ? "" : "s"));
    if (mesh->indices.empty()) return;
    if (gs_.area_power) {  // pbrt's shapes: triangles, or patches of two triangles
        std::vector<double> areas;
        const std::uint32_t step = bilinear ? 2 : 1;
        for (std::uint32_t tri = 0; tri + step <= mesh->triangle_count(); tri += step) {
            double a = 0;
            for (std::uint32_t k = 0; k < step; ++k) {
                const auto v3 = mesh->vertices(tri + k);
                a += world_area(v3[0], v3[1], v3[2]);
            }
            areas.push_back(a);
        }
        apply_area_power(o, areas);
    }
    // A few triangles without attributes become glint's triangle shapes, as the YAML reader's
    // polygons do; larger meshes are meshes (a BVH of their own, instanced).
    if (mesh->triangle_count() <= 8 && mesh->normals.empty() && mesh->uvs.empty() && !defining_ && !alpha) {
        for (std::uint32_t tri = 0; tri < mesh->triangle_count(); ++tri) {
            const auto v3 = mesh->vertices(tri);
            ObjectDesc one = o;
            one.shape = Triangle{v3[0], v3[1], v3[2]};  // the mesh's winding, flips applied
            add_object(std::move(one), gs_.ctm);
        }
        return;
    }
    o.shape = InlineMeshDesc{mesh};
    o.alpha = alpha;
    add_object(std::move(o), gs_.ctm);
}

void Parser::loop_subdiv_shape(const Token& t, const std::string& type, ParamList& pl, ObjectDesc o,
                               const std::optional<AlphaDesc>& alpha) {
    const std::string what = "Shape \"" + type + "\"";
    const auto P = get_floats(pl, "P", "point3", 3);
    const auto indices = get_floats(pl, "indices", "integer", 3);
    const int levels = get_int(pl, "levels").value_or(3);
    check_unused(pl, what);
    if (!P || !indices) {
        diag_.error(t.loc(), "loopsubdiv: needs \"point3 P\" and \"integer indices\"");
        return;
    }
    if (levels < 0 || levels > 8) {
        diag_.error(pl.find("levels")->loc, "loopsubdiv: levels must be in [0, 8]");
        return;
    }
    const std::size_t nv = P->size() / 3;
    std::vector<Point3> points;
    for (std::size_t i = 0; i < nv; ++i) points.push_back({Float((*P)[3 * i]), Float((*P)[3 * i + 1]), Float((*P)[3 * i + 2])});
    std::vector<std::uint32_t> idx;
    for (double i : *indices) {
        if (!(i >= 0 && i < double(nv))) {
            diag_.error(pl.find("indices")->loc, fmt::format("loopsubdiv: vertex index {} out of range ({} vertices)", i, nv));
            return;
        }
        idx.push_back(static_cast<std::uint32_t>(i));
    }
    if (double(idx.size()) * std::pow(4.0, levels) > 1e8) {
        diag_.error(pl.find("levels") ? pl.find("levels")->loc : t.loc(), "loopsubdiv: more than 10^8 triangles after subdivision");
        return;
    }
    SubdividedMesh sub = loop_subdivide(std::move(points), std::move(idx), levels);
    auto mesh = std::make_shared<TriangleMesh>();
    mesh->positions = std::move(sub.positions);
    mesh->normals = std::move(sub.normals);
    mesh->indices = std::move(sub.indices);
    if (gs_.reverse_orientation) {
        for (std::size_t i = 0; i < mesh->indices.size(); i += 3) std::swap(mesh->indices[i + 1], mesh->indices[i + 2]);
        for (Normal3& n : mesh->normals) n = -n;
    }
    validate_and_drop_degenerate(*mesh);
    if (mesh->indices.empty()) return;
    if (gs_.area_power) {
        std::vector<double> areas;
        for (std::uint32_t tri = 0; tri < mesh->triangle_count(); ++tri) {
            const auto v3 = mesh->vertices(tri);
            areas.push_back(world_area(v3[0], v3[1], v3[2]));
        }
        apply_area_power(o, areas);
    }
    o.shape = InlineMeshDesc{mesh};
    o.alpha = alpha;
    add_object(std::move(o), gs_.ctm);
}

void Parser::cylinder_shape(const Token& t, const std::string& type, ParamList& pl, ObjectDesc o,
                            const std::optional<AlphaDesc>& alpha) {
    const std::string what = "Shape \"" + type + "\"";
    // Tessellated: 256 quads around, each two triangles, with the exact radial normals.
    const double r = get_float(pl, "radius").value_or(1), z0 = get_float(pl, "zmin").value_or(-1),
                 z1 = get_float(pl, "zmax").value_or(1), phimax = get_float(pl, "phimax").value_or(360);
    check_unused(pl, what);
    if (!(r > 0) || !(z1 != z0) || !(phimax > 0 && phimax <= 360)) {
        diag_.error(t.loc(), "cylinder: radius > 0, zmin != zmax and phimax in (0, 360] needed");
        return;
    }
    const int n = 256;
    const bool closed = phimax == 360;
    auto mesh = std::make_shared<TriangleMesh>();
    const int columns = closed ? n : n + 1;
    for (int i = 0; i < columns; ++i) {
        const double phi = phimax * std::numbers::pi / 180 * i / n;
        const Float x = Float(r * std::cos(phi)), y = Float(r * std::sin(phi));
        const Float sign = gs_.reverse_orientation ? -1.0f : 1.0f;
        for (const double z : {z0, z1}) {
            mesh->positions.push_back({x, y, Float(z)});
            mesh->normals.push_back(Normal3{Float(std::cos(phi)) * sign, Float(std::sin(phi)) * sign, 0});
        }
    }
    for (int i = 0; i < n; ++i) {
        const auto a = std::uint32_t(2 * i), b = std::uint32_t(2 * ((i + 1) % columns));
        // Outward (for zmax > zmin): (a0, b0, b1) and (a0, b1, a1).
        std::array<std::uint32_t, 6> q{a, b, b + 1, a, b + 1, a + 1};
        const bool flip = gs_.reverse_orientation != (z1 < z0);
        if (flip) std::swap(q[1], q[2]), std::swap(q[4], q[5]);
        mesh->indices.insert(mesh->indices.end(), q.begin(), q.end());
    }
    apply_area_power(o, {std::abs(z1 - z0) * r * phimax * std::numbers::pi / 180});
    o.shape = InlineMeshDesc{mesh};
    o.alpha = alpha;
    add_object(std::move(o), gs_.ctm);
}

void Parser::ply_mesh_shape(const Token& t, const std::string& type, ParamList& pl, ObjectDesc o,
                            const std::optional<AlphaDesc>& alpha) {
    const std::string what = "Shape \"" + type + "\"";
    const auto file = get_string(pl, "filename");
    for (const char* name : {"displacement", "edgelength"}) ignore(pl, name, fmt::format("\"{}\" ignored (no displacement)", name));
    check_unused(pl, what);
    if (!file) {
        diag_.error(t.loc(), "plymesh: no \"string filename\"");
        return;
    }
    if (gs_.reverse_orientation && gs_.area_light) warn(t.loc(), "ReverseOrientation on an emitting plymesh is not applied");
    if (gs_.area_light && gs_.area_power)
        warn(gs_.area_power->loc, "area light \"power\" on a plymesh not applied (the mesh is read later); using L x scale");
    MeshFileDesc f;
    f.file = {*file, pl.find("filename")->loc};
    o.shape = f;
    o.material_given = true;
    o.alpha = alpha;
    add_object(std::move(o), gs_.ctm);
}

}  // namespace glint::pbrt_detail
