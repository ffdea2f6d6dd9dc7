#include <fmt/core.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "glint/base/limits.h"
#include "glint/description/vocabulary.h"
#include "glint/formats/scene_yaml_parser.h"

namespace glint::yaml_detail {

void SceneParser::objects(const YAML::Node& node, std::vector<ObjectDesc>& out) {
    if (!node.IsSequence()) {
        r_.error(node, fmt::format("objects: expected a list, got {}", describe(node)));
        return;
    }
    for (const YAML::Node& item : node) {
        const auto type =
            type_of(item, "object", vocabulary_types("object"));
        if (!type) continue;
        const std::size_t first = out.size();
        std::optional<YAML::Node> mat;
        if (*type == "sphere") {
            Sphere s{{0, 0, 0}, 1};
            MapReader m(r_, item, "sphere", vocabulary_keys("object", "sphere"));
            assign(m.require("center"), s.center, point());
            assign(m.require("radius"), s.radius, positive("radius"));
            // Its bounds, centre +- radius, must be floats: one past 3.4e38 could be neither
            // stored in the BVH nor hit.
            if (const auto r = m.get("radius"))
                for (int a = 0; a < 3; ++a)
                    if (!std::isfinite(std::abs(s.center[a]) + s.radius)) {
                        r_.error(*r, fmt::format("sphere: centre ± radius reaches past float's range (3.4e38) on "
                                                 "axis {}", "xyz"[a]));
                        break;
                    }
            out.push_back(object_of(s));
            mat = m.get("material");
        } else if (*type == "plane") {
            Plane p{{0, 0, 0}, {0, 1, 0}};
            MapReader m(r_, item, "plane", vocabulary_keys("object", "plane"));
            assign(m.require("point"), p.point, point());
            Vector3 n{0, 1, 0};
            assign(m.require("normal"), n, direction("normal"));
            p.normal = Normal3(normalize(n));
            out.push_back(object_of(p));
            mat = m.get("material");
        } else if (*type == "quad") {
            Point3 corner{0, 0, 0};
            Vector3 e1{1, 0, 0}, e2{0, 1, 0};
            MapReader m(r_, item, "quad", vocabulary_keys("object", "quad"));
            assign(m.require("corner"), corner, point());
            assign(m.require("edge1"), e1, direction("edge1"));
            const auto edge2 = m.require("edge2");
            assign(edge2, e2, direction("edge2"));
            if (edge2 && !(length(cross(e1, e2)) > 0)) {
                r_.error(*edge2, "quad: edge1 and edge2 must not be parallel");
            }
            out.push_back(object_of(Quad::make(corner, e1, e2)));
            mat = m.get("material");
        } else if (*type == "disk") {
            Disk d{{0, 0, 0}, {0, 1, 0}, 1};
            MapReader m(r_, item, "disk", vocabulary_keys("object", "disk"));
            assign(m.require("center"), d.center, point());
            Vector3 n{0, 1, 0};
            assign(m.require("normal"), n, direction("normal"));
            d.normal = Normal3(normalize(n));
            assign(m.require("radius"), d.radius, positive("radius"));
            out.push_back(object_of(d));
            mat = m.get("material");
        } else if (*type == "triangle" || *type == "polygon") {
            // A triangle, or a convex polygon split into a fan of triangles around vertex 0.
            const bool polygon = *type == "polygon";
            MapReader m(r_, item, *type, vocabulary_keys("object", *type));
            if (const auto v = m.require("vertices")) {
                const bool count_ok =
                    v->IsSequence() && (polygon ? v->size() >= 3 : v->size() == 3);
                if (!count_ok) {
                    r_.error(*v, fmt::format("{}: expected a list of {} vertices, got {}", *type,
                                             polygon ? "3 or more" : "3",
                                             v->IsSequence() ? fmt::format("a list of {}", v->size())
                                                             : describe(*v)));
                } else {
                    std::vector<Point3> points;
                    for (const YAML::Node& vertex : *v) {
                        if (auto p = r_.point(vertex)) points.push_back(*p);
                    }
                    for (std::size_t i = 1; points.size() == v->size() && i + 1 < points.size(); ++i) {
                        const Point3 a = points[0], b = points[i], c = points[i + 1];
                        if (!(length(cross(b - a, c - a)) > 0)) {
                            r_.error(*v, polygon ? fmt::format("polygon: vertices 0, {} and {} "
                                                               "are collinear (zero area)", i, i + 1)
                                                 : "triangle: the vertices are collinear (zero area)");
                        }
                        out.push_back(object_of(Triangle{a, b, c}));
                    }
                }
            }
            mat = m.get("material");
        } else if (*type == "mesh") {
            MapReader m(r_, item, "mesh", vocabulary_keys("object", "mesh"));
            if (m.has("positions")) {  // the mesh itself
                if (m.has("file")) r_.error(item, "mesh: give 'file' or 'positions' (the mesh itself), not both");
                const auto mesh = inline_mesh(m, item);
                if (!mesh) continue;
                out.push_back(object_of(InlineMeshDesc{mesh}));
            } else {
                MeshFileDesc f;
                if (const auto n = m.require("file")) {
                    f.file.loc = r_.loc(*n);
                    assign(n, f.file.value, [this](const YAML::Node& v) { return r_.string(v); });
                }
                out.push_back(object_of(f));
            }
            if (const auto n = m.get("alpha")) {
                AlphaDesc a;
                a.loc = r_.loc(*n);
                if (auto t = texture(*n)) a.texture = *t;
                if (const auto mode = m.get("alpha_mode"))
                    if (auto b = choice<bool>(*mode, "alpha_mode", {{"mask", false}, {"blend", true}})) a.stochastic = *b;
                assign(m.get("alpha_cutoff"), a.cutoff, [this](const YAML::Node& v) {
                    return r_.number_in(v, "alpha_cutoff", 0, 1);
                });
                out.back().alpha = a;
            } else if (m.has("alpha_mode") || m.has("alpha_cutoff")) {
                r_.error(item, "mesh: alpha_mode and alpha_cutoff need an 'alpha' texture");
            }
            mat = m.get("material");
        } else {
            Point3 lo{0, 0, 0}, hi{1, 1, 1};
            MapReader m(r_, item, "box", vocabulary_keys("object", "box"));
            assign(m.require("min"), lo, point());
            const auto max_node = m.require("max");
            assign(max_node, hi, point());
            if (max_node && !(hi.x > lo.x && hi.y > lo.y && hi.z > lo.z)) {
                r_.error(*max_node, "box: max must exceed min on every axis");
            }
            for (const Quad& q : box_faces(lo, hi)) out.push_back(object_of(q));
            mat = m.get("material");
        }
        const MaterialRef ref = mat ? material_ref(*mat) : MaterialRef{MaterialDesc{}, r_.loc(item)};
        std::optional<Transform> xf;
        SourceLoc xf_loc;
        if (item.IsMap() && item["transform"].IsDefined()) {
            xf = transform(item["transform"]);
            xf_loc = r_.loc(item["transform"]);
        }
        std::optional<Located<std::string>> interior, exterior;
        if (item.IsMap() && item["interior"].IsDefined()) interior = located_name(item["interior"]);
        if (item.IsMap() && item["exterior"].IsDefined()) exterior = located_name(item["exterior"]);
        for (std::size_t i = first; i < out.size(); ++i) {
            out[i].material = ref;
            out[i].material_given = mat.has_value();
            out[i].loc = r_.loc(item);
            out[i].transform = xf;
            out[i].transform_loc = xf_loc;
            out[i].interior = interior;
            out[i].exterior = exterior;
        }
    }
}

// `transform`: one step or a list of steps, applied in the order listed (the first step acts
// on the object first). Each step is a one-key map: translate, scale (a number or three),
// rotate {angle (degrees), axis}, matrix (3 or 4 rows of 4; a 4th row must be 0 0 0 1), or
// look_at {from, to, up}.
std::optional<Transform> SceneParser::transform(const YAML::Node& node) {
    Transform total;
    bool ok = true;
    const auto step = [&](const YAML::Node& st) {
        if (!st.IsMap() || st.size() != 1 || !st.begin()->first.IsScalar()) {
            r_.error(st, fmt::format("transform: expected a one-key map (translate, scale, rotate, "
                                     "matrix or look_at), got {}", describe(st)));
            ok = false;
            return;
        }
        const std::string key = st.begin()->first.as<std::string>();
        const YAML::Node v = st.begin()->second;
        std::optional<Transform> t;
        if (key == "translate") {
            if (const auto p = r_.triple(v)) t = Transform::translate({float((*p)[0]), float((*p)[1]), float((*p)[2])});
        } else if (key == "scale") {
            std::optional<std::array<double, 3>> f;
            if (v.IsScalar()) {
                if (const auto k = r_.number(v)) f = std::array<double, 3>{*k, *k, *k};
            } else {
                f = r_.triple(v);
            }
            if (f) {
                if ((*f)[0] == 0 || (*f)[1] == 0 || (*f)[2] == 0)
                    r_.error(v, "transform: scale factors must not be zero");
                else
                    t = Transform::scale({float((*f)[0]), float((*f)[1]), float((*f)[2])});
            }
        } else if (key == "rotate") {
            MapReader m(r_, v, "rotate", vocabulary_keys("transform", "rotate"));
            double angle = 0;
            Vector3 axis{0, 1, 0};
            bool got = true;
            if (const auto a = m.require("angle")) {
                if (const auto x = r_.number(*a)) angle = *x; else got = false;
            } else {
                got = false;
            }
            if (const auto a = m.require("axis")) {
                if (const auto x = r_.direction(*a, "axis")) axis = *x; else got = false;
            } else {
                got = false;
            }
            if (got && m.valid()) t = Transform::rotate(static_cast<Float>(angle), axis);
        } else if (key == "matrix") {
            if (!v.IsSequence() || (v.size() != 3 && v.size() != 4)) {
                r_.error(v, fmt::format("transform: matrix expects 3 or 4 rows of 4 numbers, got {}", describe(v)));
            } else {
                Matrix34 mx;
                bool good = true;
                for (std::size_t i = 0; i < v.size(); ++i) {
                    const YAML::Node row = v[i];
                    if (!row.IsSequence() || row.size() != 4) {
                        r_.error(row, fmt::format("transform: matrix row {} must have 4 numbers", i + 1));
                        good = false;
                        continue;
                    }
                    for (std::size_t j = 0; j < 4; ++j) {
                        const auto x = r_.number(row[j]);
                        if (!x) { good = false; continue; }
                        if (i < 3) mx.m[i][j] = static_cast<Float>(*x);
                        else if (*x != (j == 3 ? 1.0 : 0.0)) {
                            r_.error(row, "transform: the 4th matrix row must be 0 0 0 1 (no projections)");
                            good = false;
                            break;
                        }
                    }
                }
                if (good) {
                    t = Transform::from(mx);
                    if (!t) r_.error(v, "transform: the matrix is singular (not invertible)");
                }
            }
        } else if (key == "look_at") {
            MapReader m(r_, v, "look_at", vocabulary_keys("transform", "look_at"));
            Point3 from{0, 0, 0}, to{0, 0, 1};
            Vector3 up{0, 1, 0};
            assign(m.require("from"), from, point());
            assign(m.require("to"), to, point());
            if (const auto u = m.get("up")) assign(u, up, direction("up"));
            if (m.valid()) {
                t = Transform::look_at(from, to, up);
                if (!t) r_.error(v, "transform: look_at needs from != to and an up not along the view");
            }
        } else {
            const std::vector<std::string> known{"translate", "scale", "rotate", "matrix", "look_at"};
            const std::string guess = closest_match(key, known);
            r_.error(st, fmt::format("unknown transform step '{}'{} (known: {})", key,
                                     guess.empty() ? "" : fmt::format("; did you mean '{}'?", guess),
                                     join(known)));
        }
        if (!t) {
            ok = false;
            return;
        }
        total = *t * total;
    };
    if (node.IsSequence()) {
        for (const YAML::Node& st : node) step(st);
    } else {
        step(node);
    }
    if (!ok) return std::nullopt;
    return total;
}

// The six faces of an axis-aligned box as quads whose normals (edge1 x edge2) point outward.
std::array<Quad, 6> SceneParser::box_faces(Point3 lo, Point3 hi) {
    const Vector3 dx{hi.x - lo.x, 0, 0}, dy{0, hi.y - lo.y, 0}, dz{0, 0, hi.z - lo.z};
    return {Quad::make(lo, dz, dy),                       // x = min, facing -x
            Quad::make({hi.x, lo.y, lo.z}, dy, dz),       // x = max, facing +x
            Quad::make(lo, dx, dz),                       // y = min, facing -y
            Quad::make({lo.x, hi.y, lo.z}, dz, dx),       // y = max, facing +y
            Quad::make(lo, dy, dx),                       // z = min, facing -z
            Quad::make({lo.x, lo.y, hi.z}, dx, dy)};      // z = max, facing +z
}

}  // namespace glint::yaml_detail
