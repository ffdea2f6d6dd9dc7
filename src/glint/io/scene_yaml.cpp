#include "glint/io/scene_yaml.h"

#include <fmt/core.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <initializer_list>
#include <utility>
#include <limits>
#include <sstream>

#include "glint/io/limits.h"
#include "glint/io/yaml_reader.h"

namespace glint {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

std::string join(const std::vector<std::string>& names) {
    std::string out;
    for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
    return out;
}

template <typename T, typename Read>
void assign(const std::optional<YAML::Node>& node, T& field, Read read) {
    if (!node) return;
    if (auto v = read(*node)) field = static_cast<T>(*v);
}

class SceneParser {
public:
    SceneParser(Diagnostics& diagnostics, const std::string& path)
        : r_(diagnostics, path) {}

    void parse_root(const YAML::Node& root, SceneDescription& scene) {
        if (root.IsNull()) {
            r_.diagnostics().error({scene.path, 0, 0}, "the scene file is empty");
            return;
        }
        MapReader m(r_, root, "scene",
                    {"camera", "film", "sampler", "integrator", "background", "lights",
                     "materials", "objects"});
        if (!m.valid()) return;
        if (auto n = m.get("camera")) scene.camera = camera(*n);
        if (auto n = m.get("film")) film(*n, scene.film);
        if (auto n = m.get("sampler")) sampler(*n, scene.sampler);
        if (auto n = m.get("integrator")) integrator(*n, scene.integrator);
        if (auto n = m.get("background")) {
            if (auto bg = background(*n)) scene.background = *bg;
        }
        if (auto n = m.get("lights")) lights(*n, scene.lights);
        if (auto n = m.get("materials")) materials(*n, scene.materials);
        if (auto n = m.get("objects")) objects(*n, scene.objects);
    }

private:
    // The value of a polymorphic map's `type` key, checked against `types`.
    std::optional<std::string> type_of(const YAML::Node& node, const std::string& context,
                                       const std::vector<std::string>& types,
                                       std::optional<std::string> fallback = std::nullopt) {
        if (!node.IsMap()) {
            r_.error(node, fmt::format("{}: expected a map of keys, got {}", context, describe(node)));
            return std::nullopt;
        }
        const YAML::Node& map = node;
        const YAML::Node t = map["type"];
        if (!t.IsDefined()) {
            if (fallback) return fallback;
            r_.error(node, fmt::format("{}: missing required key 'type' (one of: {})", context,
                                       join(types)));
            return std::nullopt;
        }
        const auto name = r_.string(t);
        if (!name) return std::nullopt;
        if (std::find(types.begin(), types.end(), *name) == types.end()) {
            const std::string guess = closest_match(*name, types);
            r_.error(t, fmt::format("unknown {} type '{}'{} (known: {})", context, *name,
                                    guess.empty() ? "" : fmt::format("; did you mean '{}'?", guess),
                                    join(types)));
            return std::nullopt;
        }
        return name;
    }

    // A name from a fixed list, mapped to its value; otherwise "unknown WHAT 'x' (known: ...)".
    template <typename T>
    std::optional<T> choice(const YAML::Node& node, const char* what,
                            std::initializer_list<std::pair<const char*, T>> options) {
        const auto name = r_.string(node);
        if (!name) return std::nullopt;
        std::string known;
        for (const auto& [key, value] : options) {
            if (*name == key) return value;
            known += (known.empty() ? "" : ", ") + std::string(key);
        }
        r_.error(node, fmt::format("unknown {} '{}' (known: {})", what, *name, known));
        return std::nullopt;
    }

    auto positive(const char* what) {
        return [this, what](const YAML::Node& n) { return r_.number_in(n, what, 0, kInf, true); };
    }
    auto point() {
        return [this](const YAML::Node& n) { return r_.point(n); };
    }
    auto direction(const char* what) {
        return [this, what](const YAML::Node& n) { return r_.direction(n, what); };
    }
    auto color() {
        return [this](const YAML::Node& n) { return r_.color(n); };
    }

    CameraDesc camera(const YAML::Node& node) {
        const auto type = type_of(node, "camera", {"article", "look_at"}, "article");
        if (type == "look_at") {
            LookAtCameraDesc c;
            MapReader m(r_, node, "look_at camera",
                        {"type", "from", "to", "up", "fov", "aperture_radius", "focus_distance"});
            lens(m, c.aperture_radius, c.focus_distance);
            assign(m.require("from"), c.from, point());
            assign(m.require("to"), c.to, point());
            assign(m.get("up"), c.up, direction("up"));
            assign(m.get("fov"), c.fov, [this](const YAML::Node& n) {
                return r_.number_in(n, "fov", 0, 180, true);
            });
            if (c.from == c.to && m.has("from") && m.has("to")) {
                r_.error(*m.get("to"), "look_at camera: 'to' must differ from 'from'");
            }
            return c;
        }
        ArticleCameraDesc c;
        if (!type) return c;
        MapReader m(r_, node, "camera",
                    {"type", "position", "direction", "up", "viewport_width", "viewport_height",
                     "near", "aperture_radius", "focus_distance"});
        lens(m, c.aperture_radius, c.focus_distance);
        assign(m.get("position"), c.position, point());
        assign(m.get("direction"), c.direction, direction("direction"));
        assign(m.get("up"), c.up, direction("up"));
        if (auto n = m.get("viewport_width")) {
            if (auto v = positive("viewport_width")(*n)) c.viewport_width = static_cast<Float>(*v);
        }
        assign(m.get("viewport_height"), c.viewport_height, positive("viewport_height"));
        assign(m.get("near"), c.near, positive("near"));
        return c;
    }

    void lens(MapReader& m, Float& aperture, std::optional<Float>& focus) {
        assign(m.get("aperture_radius"), aperture, [this](const YAML::Node& n) {
            return r_.number_in(n, "aperture_radius", 0, kInf);
        });
        if (auto n = m.get("focus_distance")) {
            if (auto v = positive("focus_distance")(*n)) focus = static_cast<Float>(*v);
        }
    }

    void film(const YAML::Node& node, FilmDesc& f) {
        MapReader m(r_, node, "film",
                    {"width", "height", "encoding", "tonemap", "exposure", "filter", "aovs",
                     "filename"});
        assign(m.get("aovs"), f.aovs, [this](const YAML::Node& v) { return r_.boolean(v); });
        if (auto n = m.get("filter")) f.filter = filter(*n);
        auto size = [this, &m](const char* key, Located<int>& out) {
            if (auto n = m.get(key)) {
                out.loc = r_.loc(*n);
                assign(n, out.value, [this, key](const YAML::Node& v) {
                    return r_.integer_in(v, key, 1, kMaxFilmSide);
                });
            }
        };
        size("width", f.width);
        size("height", f.height);
        if (auto n = m.get("encoding")) {
            if (auto e = choice<Encoding>(*n, "encoding",
                                          {{"srgb", Encoding::kSrgb}, {"raw", Encoding::kRaw}}))
                f.display.encoding = *e;
        }
        if (auto n = m.get("tonemap")) {
            if (auto c = choice<ToneCurve>(*n, "tonemap",
                                           {{"clamp", ToneCurve::kClamp},
                                            {"reinhard", ToneCurve::kReinhard},
                                            {"aces", ToneCurve::kAces}}))
                f.display.curve = *c;
        }
        assign(m.get("exposure"), f.display.exposure, [this](const YAML::Node& v) {
            return r_.number_in(v, "exposure", -64, 64);
        });
        if (auto n = m.get("filename")) {
            f.filename.loc = r_.loc(*n);
            assign(n, f.filename.value, [this](const YAML::Node& v) { return r_.string(v); });
        }
    }

    FilterDesc filter(const YAML::Node& node) {
        const auto type = type_of(node, "filter", {"box", "tent", "gaussian", "blackman_harris"});
        FilterDesc f;
        if (!type) return f;
        if (*type == "box") f = {FilterType::kBox, 0.5f, 0.5f};
        if (*type == "tent") f = {FilterType::kTent, 1.0f, 0.5f};
        if (*type == "gaussian") f = {FilterType::kGaussian, 1.5f, 0.5f};
        if (*type == "blackman_harris") f = {FilterType::kBlackmanHarris, 1.5f, 0.5f};
        std::vector<std::string> keys{"type", "radius"};
        if (f.type == FilterType::kGaussian) keys.push_back("sigma");
        MapReader m(r_, node, fmt::format("{} filter", *type), keys);
        assign(m.get("radius"), f.radius, [this](const YAML::Node& v) {
            return r_.number_in(v, "radius", 0, 16, true);
        });
        assign(m.get("sigma"), f.sigma, positive("sigma"));
        return f;
    }

    void sampler(const YAML::Node& node, SamplerDesc& s) {
        MapReader m(r_, node, "sampler", {"type", "spp", "seed"});
        if (m.has("type")) {
            const auto type = type_of(node, "sampler", {"sobol", "stratified", "independent"});
            if (type == "sobol") s.type = SamplerType::kSobol;
            if (type == "stratified") s.type = SamplerType::kStratified;
            if (type == "independent") s.type = SamplerType::kIndependent;
        }
        if (auto n = m.get("spp")) {
            s.spp.loc = r_.loc(*n);
            assign(n, s.spp.value,
                   [this](const YAML::Node& v) { return r_.integer_in(v, "spp", 1, kMaxSpp); });
        }
        assign(m.get("seed"), s.seed, [this](const YAML::Node& v) {
            return r_.integer_in(v, "seed", 0, std::numeric_limits<long long>::max());
        });
    }

    void integrator(const YAML::Node& node, IntegratorDesc& d) {
        const auto type = type_of(node, "integrator", {"flat", "normals", "whitted"});
        if (!type) return;
        if (*type != "whitted") {
            d.kind = *type == "flat" ? IntegratorKind::kFlat : IntegratorKind::kNormals;
            MapReader m(r_, node, fmt::format("{} integrator", *type), {"type"});
            return;
        }
        d.kind = IntegratorKind::kWhitted;
        MapReader m(r_, node, "whitted integrator", {"type", "max_depth", "ambient", "shadows"});
        if (auto n = m.get("max_depth")) {
            d.max_depth.loc = r_.loc(*n);
            assign(n, d.max_depth.value, [this](const YAML::Node& v) {
                return r_.integer_in(v, "max_depth", 0, kMaxDepth);
            });
        }
        assign(m.get("ambient"), d.ambient,
               [this](const YAML::Node& v) { return r_.number_in(v, "ambient", 0, 1); });
        assign(m.get("shadows"), d.shadows, [this](const YAML::Node& v) { return r_.boolean(v); });
    }

    std::optional<Background> background(const YAML::Node& node) {
        const auto type = type_of(node, "background", {"sky", "constant"});
        if (!type) return std::nullopt;
        if (*type == "sky") {
            SkyBackground sky;
            MapReader m(r_, node, "sky background", {"type", "horizon", "zenith"});
            assign(m.get("horizon"), sky.horizon, color());
            assign(m.get("zenith"), sky.zenith, color());
            return sky;
        }
        ConstantBackground c;
        MapReader m(r_, node, "constant background", {"type", "color"});
        assign(m.require("color"), c.color, color());
        return c;
    }

    void lights(const YAML::Node& node, std::vector<Light>& out) {
        if (!node.IsSequence()) {
            r_.error(node, fmt::format("lights: expected a list, got {}", describe(node)));
            return;
        }
        for (const YAML::Node& item : node) {
            const auto type = type_of(item, "light", {"directional", "point"});
            if (!type) continue;
            if (*type == "directional") {
                DirectionalLight l{{0, -1, 0}, Color{1}};
                MapReader m(r_, item, "directional light", {"type", "direction", "intensity"});
                assign(m.require("direction"), l.direction, direction("direction"));
                l.direction = normalize(l.direction);
                assign(m.get("intensity"), l.intensity, color());
                out.emplace_back(l);
            } else {
                PointLight l{{0, 0, 0}, Color{1}};
                MapReader m(r_, item, "point light", {"type", "position", "intensity"});
                assign(m.require("position"), l.position, point());
                assign(m.get("intensity"), l.intensity, color());
                out.emplace_back(l);
            }
        }
    }

    // A texture: a number (grey), a colour [r, g, b], or a map with a type.
    std::optional<TextureDesc> texture(const YAML::Node& node) {
        TextureDesc t;
        if (node.IsScalar()) {
            const auto v = r_.number(node);
            if (!v) return std::nullopt;
            if (*v < 0) {
                r_.error(node, "colour components must be >= 0");
                return std::nullopt;
            }
            t.value = Color{static_cast<float>(*v)};
            return t;
        }
        if (node.IsSequence()) {
            const auto c = r_.color(node);
            if (!c) return std::nullopt;
            t.value = *c;
            return t;
        }
        const auto type = type_of(node, "texture", {"constant", "checker", "image", "scale", "mix"});
        if (!type) return std::nullopt;
        if (*type == "constant") {
            MapReader m(r_, node, "constant texture", {"type", "color"});
            assign(m.require("color"), t.value, color());
        } else if (*type == "checker") {
            t.kind = TextureDesc::Kind::kChecker;
            MapReader m(r_, node, "checker texture", {"type", "size", "even", "odd"});
            assign(m.get("size"), t.checker.size, positive("size"));
            assign(m.require("even"), t.checker.even, color());
            assign(m.require("odd"), t.checker.odd, color());
        } else if (*type == "image") {
            t.kind = TextureDesc::Kind::kImage;
            MapReader m(r_, node, "image texture", {"type", "filename", "encoding", "wrap", "size"});
            if (const auto n = m.require("filename")) {
                t.filename.loc = r_.loc(*n);
                assign(n, t.filename.value, [this](const YAML::Node& v) { return r_.string(v); });
            }
            if (const auto n = m.get("encoding")) {
                if (auto e = choice<ImageEncoding>(*n, "encoding",
                                                   {{"auto", ImageEncoding::kAuto},
                                                    {"srgb", ImageEncoding::kSrgb},
                                                    {"linear", ImageEncoding::kLinear}}))
                    t.encoding = *e;
            }
            if (const auto n = m.get("wrap")) {
                if (auto w = choice<WrapMode>(
                        *n, "wrap", {{"repeat", WrapMode::kRepeat}, {"clamp", WrapMode::kClamp}}))
                    t.wrap = *w;
            }
            assign(m.get("size"), t.size, positive("size"));
        } else {
            const bool scale = *type == "scale";
            t.kind = scale ? TextureDesc::Kind::kScale : TextureDesc::Kind::kMix;
            const std::vector<std::string> parts =
                scale ? std::vector<std::string>{"texture", "factor"}
                      : std::vector<std::string>{"a", "b", "amount"};
            std::vector<std::string> keys{"type"};
            keys.insert(keys.end(), parts.begin(), parts.end());
            MapReader m(r_, node, fmt::format("{} texture", *type), keys);
            for (const std::string& part : parts) {
                const auto child_node = m.require(part);
                const auto child = child_node ? texture(*child_node) : std::nullopt;
                t.children.push_back(child.value_or(TextureDesc{}));
            }
        }
        return t;
    }

    MaterialDesc material(const YAML::Node& node, const std::string& context) {
        MaterialDesc d;
        MapReader m(r_, node, context, {"color", "shininess"});
        if (auto n = m.get("color")) {
            if (auto t = texture(*n)) d.color = *t;
        }
        assign(m.get("shininess"), d.shininess,
               [this](const YAML::Node& v) { return r_.number_in(v, "shininess", 0, 1); });
        return d;
    }

    void materials(const YAML::Node& node, std::vector<NamedMaterial>& out) {
        if (!node.IsMap()) {
            r_.error(node, fmt::format("materials: expected a map from names to materials, got {}",
                                       describe(node)));
            return;
        }
        for (auto it = node.begin(); it != node.end(); ++it) {
            const auto name = r_.string(it->first);
            if (!name) continue;
            const bool duplicate = std::any_of(out.begin(), out.end(), [&](const NamedMaterial& m) {
                return m.name == *name;
            });
            if (duplicate) {
                r_.error(it->first, fmt::format("materials: duplicate material name '{}'", *name));
                continue;
            }
            out.push_back({*name, material(it->second, fmt::format("material '{}'", *name)),
                           r_.loc(it->first)});
        }
    }

    MaterialRef material_ref(const YAML::Node& node) {
        if (node.IsScalar()) return {node.Scalar(), r_.loc(node)};
        return {material(node, "material"), r_.loc(node)};
    }

    void objects(const YAML::Node& node, std::vector<ObjectDesc>& out) {
        if (!node.IsSequence()) {
            r_.error(node, fmt::format("objects: expected a list, got {}", describe(node)));
            return;
        }
        for (const YAML::Node& item : node) {
            const auto type =
                type_of(item, "object", {"sphere", "plane", "quad", "disk", "triangle", "box"});
            if (!type) continue;
            const std::size_t first = out.size();
            std::optional<YAML::Node> mat;
            if (*type == "sphere") {
                Sphere s{{0, 0, 0}, 1};
                MapReader m(r_, item, "sphere", {"type", "center", "radius", "material"});
                assign(m.require("center"), s.center, point());
                assign(m.require("radius"), s.radius, positive("radius"));
                out.push_back({s, {}, {}});
                mat = m.get("material");
            } else if (*type == "plane") {
                Plane p{{0, 0, 0}, {0, 1, 0}};
                MapReader m(r_, item, "plane", {"type", "point", "normal", "material"});
                assign(m.require("point"), p.point, point());
                Vector3 n{0, 1, 0};
                assign(m.require("normal"), n, direction("normal"));
                p.normal = Normal3(normalize(n));
                out.push_back({p, {}, {}});
                mat = m.get("material");
            } else if (*type == "quad") {
                Point3 corner{0, 0, 0};
                Vector3 e1{1, 0, 0}, e2{0, 1, 0};
                MapReader m(r_, item, "quad", {"type", "corner", "edge1", "edge2", "material"});
                assign(m.require("corner"), corner, point());
                assign(m.require("edge1"), e1, direction("edge1"));
                const auto edge2 = m.require("edge2");
                assign(edge2, e2, direction("edge2"));
                if (edge2 && !(length(cross(e1, e2)) > 0)) {
                    r_.error(*edge2, "quad: edge1 and edge2 must not be parallel");
                }
                out.push_back({Quad::make(corner, e1, e2), {}, {}});
                mat = m.get("material");
            } else if (*type == "disk") {
                Disk d{{0, 0, 0}, {0, 1, 0}, 1};
                MapReader m(r_, item, "disk", {"type", "center", "normal", "radius", "material"});
                assign(m.require("center"), d.center, point());
                Vector3 n{0, 1, 0};
                assign(m.require("normal"), n, direction("normal"));
                d.normal = Normal3(normalize(n));
                assign(m.require("radius"), d.radius, positive("radius"));
                out.push_back({d, {}, {}});
                mat = m.get("material");
            } else if (*type == "triangle") {
                Triangle t{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
                MapReader m(r_, item, "triangle", {"type", "vertices", "material"});
                if (const auto v = m.require("vertices")) {
                    if (!v->IsSequence() || v->size() != 3) {
                        r_.error(*v, fmt::format("triangle: expected a list of 3 vertices, got {}",
                                                 v->IsSequence() ? fmt::format("a list of {}", v->size())
                                                                 : describe(*v)));
                    } else {
                        const auto a = r_.point((*v)[0]), b = r_.point((*v)[1]), c = r_.point((*v)[2]);
                        if (a && b && c) {
                            t = Triangle{*a, *b, *c};
                            if (!(length(cross(*b - *a, *c - *a)) > 0)) {
                                r_.error(*v, "triangle: the vertices are collinear (zero area)");
                            }
                        }
                    }
                }
                out.push_back({t, {}, {}});
                mat = m.get("material");
            } else {
                Point3 lo{0, 0, 0}, hi{1, 1, 1};
                MapReader m(r_, item, "box", {"type", "min", "max", "material"});
                assign(m.require("min"), lo, point());
                const auto max_node = m.require("max");
                assign(max_node, hi, point());
                if (max_node && !(hi.x > lo.x && hi.y > lo.y && hi.z > lo.z)) {
                    r_.error(*max_node, "box: max must exceed min on every axis");
                }
                for (const Quad& q : box_faces(lo, hi)) out.push_back({q, {}, {}});
                mat = m.get("material");
            }
            const MaterialRef ref = mat ? material_ref(*mat) : MaterialRef{MaterialDesc{}, r_.loc(item)};
            for (std::size_t i = first; i < out.size(); ++i) {
                out[i].material = ref;
                out[i].loc = r_.loc(item);
            }
        }
    }

    // The six faces of an axis-aligned box as quads whose normals (edge1 x edge2) point outward.
    static std::array<Quad, 6> box_faces(Point3 lo, Point3 hi) {
        const Vector3 dx{hi.x - lo.x, 0, 0}, dy{0, hi.y - lo.y, 0}, dz{0, 0, hi.z - lo.z};
        return {Quad::make(lo, dz, dy),                       // x = min, facing -x
                Quad::make({hi.x, lo.y, lo.z}, dy, dz),       // x = max, facing +x
                Quad::make(lo, dx, dz),                       // y = min, facing -y
                Quad::make({lo.x, hi.y, lo.z}, dz, dx),       // y = max, facing +y
                Quad::make(lo, dy, dx),                       // z = min, facing -z
                Quad::make({lo.x, lo.y, hi.z}, dx, dy)};      // z = max, facing +z
    }

    YamlReader r_;
};

}  // namespace

SceneDescription parse_scene(const std::string& text, const std::string& path,
                             std::shared_ptr<SourceFiles> sources) {
    sources->add(path, text);
    Diagnostics diagnostics(sources);
    SceneDescription scene;
    scene.path = path;
    YAML::Node root;
    try {
        root = YAML::Load(text);
    } catch (const YAML::Exception& e) {
        diagnostics.error({path, e.mark.is_null() ? 0 : e.mark.line + 1,
                           e.mark.is_null() ? 0 : e.mark.column + 1},
                          fmt::format("invalid YAML: {}", e.msg));
        diagnostics.throw_if_errors();
    }
    SceneParser(diagnostics, path).parse_root(root, scene);
    diagnostics.throw_if_errors();
    return scene;
}

SceneDescription load_scene_file(const std::string& path, std::shared_ptr<SourceFiles> sources) {
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        Diagnostics d(sources);
        d.error({path, 0, 0}, fmt::format("cannot open scene file: {}", std::strerror(errno)));
        d.throw_if_errors();
    }
    std::ostringstream text;
    text << in.rdbuf();
    if (in.bad()) {
        Diagnostics d(sources);
        d.error({path, 0, 0}, "cannot read scene file");
        d.throw_if_errors();
    }
    return parse_scene(text.str(), path, std::move(sources));
}

}  // namespace glint
