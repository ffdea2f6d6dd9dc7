#include "glint/formats/scene_yaml.h"
#include "glint/formats/pbrt.h"

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
#include <numbers>
#include <sstream>

#include "glint/base/limits.h"
#include "glint/formats/yaml_reader.h"
#include "glint/materials/metals.h"

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
                     "materials", "media", "medium", "objects", "animation"});
        if (!m.valid()) return;
        if (auto n = m.get("animation")) {
            MapReader a(r_, *n, "animation", {"fps"});
            if (a.valid())
                if (auto f = a.get("fps")) assign(f, scene.fps, [this](const YAML::Node& v) { return r_.number_in(v, "fps", 0, 1e6, true); });
        }
        // Every keyframed value becomes its value at this frame, then the scene is read as usual.
        for (auto it = root.begin(); it != root.end(); ++it) {
            YAML::Node value = it->second;
            animate(value, scene);
        }
        if (auto n = m.get("camera")) scene.camera = camera(*n);
        if (auto n = m.get("film")) film(*n, scene.film);
        if (auto n = m.get("sampler")) sampler(*n, scene.sampler);
        if (auto n = m.get("integrator")) integrator(*n, scene.integrator);
        if (auto n = m.get("background")) {
            if (auto bg = background(*n, scene.environment)) scene.background = *bg;
        }
        if (auto n = m.get("lights")) lights(*n, scene.lights);
        if (auto n = m.get("materials")) materials(*n, scene.materials);
        if (auto n = m.get("media")) media(*n, scene.media);
        if (auto n = m.get("medium")) scene.medium = located_name(*n);
        if (auto n = m.get("objects")) objects(*n, scene.objects);
    }

private:
    // Replaces, in place, every `{keyframes: [[frame, value], ...], interpolation: ...}` under
    // `node` with its value at scene.frame (docs/scene-format.md, "Animation").
    void animate(YAML::Node& node, SceneDescription& scene) {
        if (node.IsMap() && std::as_const(node)["keyframes"].IsDefined()) {  // const: no key made
            scene.animated = true;
            if (auto v = keyframed(node, scene.frame)) node = *v;
            return;
        }
        if (node.IsMap()) {
            for (auto it = node.begin(); it != node.end(); ++it) {
                YAML::Node value = it->second;
                animate(value, scene);
            }
        } else if (node.IsSequence()) {
            for (auto it = node.begin(); it != node.end(); ++it) {
                YAML::Node value = *it;
                animate(value, scene);
            }
        }
    }

    // A keyframed value at `frame`: a number, or a list of numbers, as a node made here (errors
    // about it are located at the keyframes map).
    std::optional<YAML::Node> keyframed(const YAML::Node& node, double frame) {
        MapReader m(r_, node, "keyframed value", {"keyframes", "interpolation"});
        if (!m.valid()) return std::nullopt;
        enum class Curve { kLinear, kStep, kSmooth } curve = Curve::kLinear;
        if (auto n = m.get("interpolation")) {
            auto c = choice<Curve>(*n, "interpolation", {{"linear", Curve::kLinear}, {"step", Curve::kStep},
                                                         {"smooth", Curve::kSmooth}});
            if (!c) return std::nullopt;
            curve = *c;
        }
        const YAML::Node keys = *m.get("keyframes");
        if (!keys.IsSequence() || keys.size() == 0) {
            r_.error(keys, fmt::format("keyframes: expected a list of [frame, value] pairs, got {}", describe(keys)));
            return std::nullopt;
        }
        std::vector<double> t;
        std::vector<std::vector<double>> v;
        bool scalar = false;
        for (std::size_t i = 0; i < keys.size(); ++i) {
            const YAML::Node k = keys[i];
            if (!k.IsSequence() || k.size() != 2) {
                r_.error(k, fmt::format("keyframe: expected [frame, value], got {}", describe(k)));
                return std::nullopt;
            }
            const auto f = r_.number(k[0]);
            if (!f) return std::nullopt;
            if (!t.empty() && !(*f > t.back())) {
                r_.error(k[0], fmt::format("keyframe at frame {}: frames must increase (the one before is {})", *f, t.back()));
                return std::nullopt;
            }
            const YAML::Node value = k[1];
            std::vector<double> x;
            if (value.IsScalar()) {
                const auto n = r_.number(value);
                if (!n) return std::nullopt;
                x.push_back(*n);
            } else if (value.IsSequence() && value.size() > 0) {
                for (std::size_t j = 0; j < value.size(); ++j) {
                    const auto n = r_.number(value[j]);
                    if (!n) return std::nullopt;
                    x.push_back(*n);
                }
            } else {
                r_.error(value, fmt::format("keyframe value: expected a number or a list of numbers, got {}", describe(value)));
                return std::nullopt;
            }
            if (i == 0) scalar = value.IsScalar();
            else if (value.IsScalar() != scalar || x.size() != v[0].size()) {
                r_.error(value, fmt::format("keyframe value: every key must have the shape of the first ({})",
                                            scalar ? "a number" : fmt::format("a list of {}", v[0].size())));
                return std::nullopt;
            }
            t.push_back(*f);
            v.push_back(std::move(x));
        }
        const std::vector<double> at = interpolate(t, v, frame, static_cast<int>(curve));
        YAML::Node out;
        const auto number = [&](double x) {
            YAML::Node n(fmt::format("{:.17g}", x));
            r_.locate_as(n, r_.loc(node));
            return n;
        };
        if (scalar) {
            out = number(at[0]);
        } else {
            out = YAML::Node(YAML::NodeType::Sequence);
            for (double x : at) out.push_back(number(x));
        }
        r_.locate_as(out, r_.loc(node));
        return out;
    }

    // The value at `f` of keys (t[i], v[i]), t increasing: held before the first and after the
    // last; between keys linear (0), the earlier key's (1), or smooth (2): a cubic Hermite
    // through the keys whose slopes are the central differences (Catmull-Rom, non-uniform), one-sided at the ends.
    static std::vector<double> interpolate(const std::vector<double>& t, const std::vector<std::vector<double>>& v,
                                           double f, int curve) {
        const std::size_t n = t.size();
        if (f <= t[0]) return v[0];
        if (f >= t[n - 1]) return v[n - 1];
        std::size_t i = 0;
        while (!(f < t[i + 1])) ++i;
        if (curve == 1) return v[i];
        const double dt = t[i + 1] - t[i], u = (f - t[i]) / dt;
        std::vector<double> out(v[i].size());
        for (std::size_t c = 0; c < out.size(); ++c) {
            if (curve == 0) {
                out[c] = v[i][c] + u * (v[i + 1][c] - v[i][c]);
                continue;
            }
            const auto slope = [&](std::size_t k) {
                const std::size_t a = k == 0 ? 0 : k - 1, b = k + 1 == n ? k : k + 1;
                return (v[b][c] - v[a][c]) / (t[b] - t[a]);
            };
            const double u2 = u * u, u3 = u2 * u;
            out[c] = (2 * u3 - 3 * u2 + 1) * v[i][c] + (u3 - 2 * u2 + u) * dt * slope(i) +
                     (-2 * u3 + 3 * u2) * v[i + 1][c] + (u3 - u2) * dt * slope(i + 1);
        }
        return out;
    }

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
                        {"type", "from", "to", "up", "fov", "aperture_radius", "focus_distance",
                         "handedness", "projection", "height", "window"});
            lens(m, c.aperture_radius, c.focus_distance);
            handedness(m, c.right_handed);
            if (auto n = m.get("projection")) {
                if (auto o = choice<bool>(*n, "projection",
                                          {{"perspective", false}, {"orthographic", true}}))
                    c.orthographic = *o;
            }
            if (auto n = m.get("height")) {
                if (!c.orthographic) r_.error(*n, "look_at camera: 'height' is for projection: orthographic (a perspective camera has 'fov')");
                if (auto v = positive("height")(*n)) c.height = static_cast<Float>(*v);
            }
            if (auto n = m.get("window")) {
                if (auto w = r_.bounds(*n, "window"))
                    c.window = std::array<Float, 4>{Float((*w)[0]), Float((*w)[1]), Float((*w)[2]), Float((*w)[3])};
            }
            assign(m.require("from"), c.from, point());
            assign(m.require("to"), c.to, point());
            assign(m.get("up"), c.up, direction("up"));
            assign(m.get("fov"), c.fov, [this](const YAML::Node& n) {
                return r_.number_in(n, "fov", 0, 180, true, true);
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
                     "near", "aperture_radius", "focus_distance", "handedness"});
        lens(m, c.aperture_radius, c.focus_distance);
        handedness(m, c.right_handed);
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

    void handedness(MapReader& m, bool& right) {
        if (auto n = m.get("handedness")) {
            if (auto h = choice<bool>(*n, "handedness", {{"left", false}, {"right", true}}))
                right = *h;
        }
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
                     "filename", "crop", "crop_pixels", "scale"});
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
        if (auto n = m.get("crop")) {
            if (auto c = r_.bounds(*n, "crop")) {
                if ((*c)[0] < 0 || (*c)[1] > 1 || (*c)[2] < 0 || (*c)[3] > 1)
                    r_.error(*n, "crop: fractions of the frame, in [0, 1]");
                else
                    f.crop_window = Located<std::array<float, 4>>{
                        {float((*c)[0]), float((*c)[1]), float((*c)[2]), float((*c)[3])}, r_.loc(*n)};
            }
        }
        if (auto n = m.get("crop_pixels")) {
            if (auto c = r_.bounds(*n, "crop_pixels")) {
                const auto& b = *c;
                if (b[0] < 0 || b[2] < 0 || b[1] > kMaxFilmSide || b[3] > kMaxFilmSide ||
                    b[0] != std::floor(b[0]) || b[1] != std::floor(b[1]) || b[2] != std::floor(b[2]) ||
                    b[3] != std::floor(b[3]))
                    r_.error(*n, "crop_pixels: whole pixel numbers within the frame");
                else
                    f.pixel_bounds = Located<std::array<int, 4>>{
                        {int(b[0]), int(b[1]), int(b[2]), int(b[3])}, r_.loc(*n)};
            }
        }
        if (f.crop_window && f.pixel_bounds) r_.error(node, "film: give 'crop' or 'crop_pixels', not both");
        assign(m.get("scale"), f.scale, [this](const YAML::Node& v) {
            return r_.number_in(v, "scale", 0, 1e30, true);
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
        MapReader m(r_, node, "sampler", {"type", "spp", "seed", "noise_threshold", "min_spp"});
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
        assign(m.get("noise_threshold"), s.noise_threshold, [this](const YAML::Node& v) {
            return r_.number_in(v, "noise_threshold", 0, 1);
        });
        assign(m.get("min_spp"), s.min_spp, [this](const YAML::Node& v) {
            return r_.integer_in(v, "min_spp", 0, kMaxSpp);
        });
    }

    void integrator(const YAML::Node& node, IntegratorDesc& d) {
        const auto type = type_of(node, "integrator", {"flat", "normals", "whitted", "path"});
        if (!type) return;
        if (*type == "flat" || *type == "normals") {
            d.kind = *type == "flat" ? IntegratorKind::kFlat : IntegratorKind::kNormals;
            MapReader m(r_, node, fmt::format("{} integrator", *type), {"type"});
            return;
        }
        const bool path = *type == "path";
        d.kind = path ? IntegratorKind::kPath : IntegratorKind::kWhitted;
        MapReader m(r_, node, fmt::format("{} integrator", *type),
                    path ? std::vector<std::string>{"type", "max_depth", "rr_depth", "clamp",
                                                    "strategy"}
                         : std::vector<std::string>{"type", "max_depth", "ambient", "shadows"});
        if (path) d.max_depth.value = d.path.max_depth;
        if (auto n = m.get("max_depth")) {
            d.max_depth.loc = r_.loc(*n);
            assign(n, d.max_depth.value, [this](const YAML::Node& v) {
                return r_.integer_in(v, "max_depth", 0, kMaxDepth);
            });
        }
        if (path) {
            assign(m.get("rr_depth"), d.path.rr_depth, [this](const YAML::Node& v) {
                return r_.integer_in(v, "rr_depth", 0, kMaxDepth);
            });
            assign(m.get("clamp"), d.path.clamp, positive("clamp"));
            if (auto n = m.get("strategy")) {
                if (auto st = choice<LightStrategy>(*n, "strategy",
                                                    {{"mis", LightStrategy::kMis},
                                                     {"light", LightStrategy::kLight},
                                                     {"bsdf", LightStrategy::kBsdf}}))
                    d.path.strategy = *st;
            }
            return;
        }
        assign(m.get("ambient"), d.ambient,
               [this](const YAML::Node& v) { return r_.number_in(v, "ambient", 0, 1); });
        assign(m.get("shadows"), d.shadows, [this](const YAML::Node& v) { return r_.boolean(v); });
    }

    std::optional<Background> background(const YAML::Node& node,
                                         std::optional<EnvironmentDesc>& environment) {
        const auto type = type_of(node, "background", {"sky", "constant", "environment"});
        if (!type) return std::nullopt;
        if (*type == "sky") {
            SkyBackground sky;
            MapReader m(r_, node, "sky background", {"type", "horizon", "zenith"});
            assign(m.get("horizon"), sky.horizon, color());
            assign(m.get("zenith"), sky.zenith, color());
            return sky;
        }
        if (*type == "environment") {
            EnvironmentDesc e;
            MapReader m(r_, node, "environment background", {"type", "filename", "scale"});
            if (const auto n = m.require("filename")) {
                e.filename.loc = r_.loc(*n);
                assign(n, e.filename.value, [this](const YAML::Node& v) { return r_.string(v); });
            }
            assign(m.get("scale"), e.scale,
                   [this](const YAML::Node& v) { return r_.number_in(v, "scale", 0, kInf); });
            environment = e;
            return std::nullopt;
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
        const auto degrees = [this](const char* what, double hi) {
            return [this, what, hi](const YAML::Node& n) { return r_.number_in(n, what, 0, hi); };
        };
        for (const YAML::Node& item : node) {
            const auto type = type_of(item, "light", {"directional", "point", "spot"});
            if (!type) continue;
            if (*type == "directional") {
                DirectionalLight l{{0, -1, 0}, Color{1}};
                MapReader m(r_, item, "directional light",
                            {"type", "direction", "intensity", "angular_diameter"});
                assign(m.require("direction"), l.direction, direction("direction"));
                l.direction = normalize(l.direction);
                assign(m.get("intensity"), l.intensity, color());
                float diameter = 0;
                assign(m.get("angular_diameter"), diameter, degrees("angular_diameter", 179));
                const float s = std::sin(diameter * std::numbers::pi_v<float> / 720);  // sin(d/4)
                l.one_minus_cos = 2 * s * s;
                out.emplace_back(l);
            } else if (*type == "point") {
                PointLight l{{0, 0, 0}, Color{1}};
                MapReader m(r_, item, "point light", {"type", "position", "intensity"});
                assign(m.require("position"), l.position, point());
                assign(m.get("intensity"), l.intensity, color());
                out.emplace_back(l);
            } else {
                SpotLight l{{0, 0, 0}, {0, -1, 0}, Color{1}, 1, 0};
                MapReader m(r_, item, "spot light",
                            {"type", "position", "direction", "intensity", "cone_angle",
                             "falloff_start"});
                assign(m.require("position"), l.position, point());
                assign(m.require("direction"), l.direction, direction("direction"));
                l.direction = normalize(l.direction);
                assign(m.get("intensity"), l.intensity, color());
                float cone = 30, start = 25;
                assign(m.get("cone_angle"), cone, degrees("cone_angle", 180));
                const auto start_node = m.get("falloff_start");
                assign(start_node, start, degrees("falloff_start", 180));
                if (!start_node) start = cone * 5 / 6;
                if (start > cone && start_node) {
                    r_.error(*start_node, "spot light: falloff_start must not exceed cone_angle");
                }
                const float to_rad = std::numbers::pi_v<float> / 180;
                l.cos_outer = std::cos(cone * to_rad);
                l.cos_inner = std::cos(std::min(start, cone) * to_rad);
                if (l.cos_inner <= l.cos_outer) l.cos_inner = l.cos_outer + 1e-6f;
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
        const auto type =
            type_of(node, "texture", {"constant", "checker", "image", "scale", "mix", "vertex_color"});
        if (!type) return std::nullopt;
        if (*type == "vertex_color") {
            MapReader m(r_, node, "vertex_color texture", {"type"});
            t.kind = TextureDesc::Kind::kVertexColor;
        } else if (*type == "constant") {
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
                        *n, "wrap", {{"repeat", WrapMode::kRepeat}, {"clamp", WrapMode::kClamp}, {"mirror", WrapMode::kMirror}}))
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
        if (!node.IsMap()) {
            r_.error(node, fmt::format("{}: expected a map of keys, got {}", context, describe(node)));
            return d;
        }
        const auto type = type_of(node, "material",
                                  {"article", "diffuse", "conductor", "dielectric", "plastic", "pbr",
                                   "interface", "diffuse_transmission", "mix", "coated_diffuse", "coated_conductor"},
                                  "article");
        if (!type) return d;
        if (*type == "interface") {
            d.kind = MaterialDesc::Kind::kInterface;
            MapReader m(r_, node, context, {"type"});
            return d;
        }
        std::vector<std::string> keys{"type", "emission", "two_sided"};
        const auto add = [&keys](std::initializer_list<const char*> more) {
            keys.insert(keys.end(), more.begin(), more.end());
        };
        using K = MaterialDesc::Kind;
        if (*type == "article") d.kind = K::kArticle, add({"color", "shininess"});
        if (*type == "diffuse") d.kind = K::kDiffuse, add({"albedo"});
        if (*type == "conductor") d.kind = K::kConductor, add({"metal", "eta", "k", "reflectance", "roughness"});
        if (*type == "dielectric") d.kind = K::kDielectric, add({"ior", "roughness", "thin", "tint"});
        if (*type == "plastic") d.kind = K::kPlastic, add({"albedo", "ior", "roughness"});
        if (*type == "diffuse_transmission") d.kind = K::kDiffuseTransmission, add({"reflectance", "transmittance"});
        if (*type == "mix") d.kind = K::kMix, add({"materials", "amount"});
        if (*type == "coated_diffuse" || *type == "coated_conductor") {
            d.kind = K::kCoated;
            d.coated_conductor = *type == "coated_conductor";
            d.color.value = Color{0.5f};  // pbrt-v4's coateddiffuse reflectance
            add({"ior", "thickness", "layer_albedo", "g", "max_depth", "samples"});
            if (d.coated_conductor) add({"metal", "eta", "k", "reflectance", "roughness", "coat_roughness"});
            else add({"albedo", "roughness"});
        }
        if (*type == "pbr") {
            d.kind = K::kPbr;
            d.roughness = 0.5f;
            add({"base_color", "metallic", "roughness", "transmission", "ior", "clearcoat", "clearcoat_roughness", "sheen",
                 "sheen_roughness", "specular", "specular_color"});
        }
        MapReader m(r_, node, context, keys);
        const auto tex = [&](const char* key) {
            if (auto n = m.get(key)) {
                if (auto t = texture(*n)) d.color = *t;
            }
        };
        const auto unit = [this](const char* what) {
            return [this, what](const YAML::Node& v) { return r_.number_in(v, what, 0, 1); };
        };
        tex("color");
        tex("albedo");
        tex("base_color");
        if (d.kind == K::kDiffuseTransmission) {
            d.color.value = Color{0.25f};
            d.transmittance = TextureDesc{};
            d.transmittance->value = Color{0.25f};
            if (auto n = m.get("reflectance"))
                if (auto t = texture(*n)) d.color = *t;
            if (auto n = m.get("transmittance"))
                if (auto t = texture(*n)) d.transmittance = *t;
        }
        if (d.kind == K::kMix) {
            if (auto n = m.require("materials")) {
                if (!n->IsSequence() || n->size() != 2) {
                    r_.error(*n, fmt::format("{}: 'materials' is a list of two material names", context));
                } else {
                    for (std::size_t i = 0; i < 2; ++i)
                        if (auto name = r_.string((*n)[i])) d.mix.push_back({*name, r_.loc((*n)[i])});
                }
            }
            if (auto n = m.get("amount"))
                if (auto t = texture(*n)) d.amount = *t;
        }
        if (d.kind == K::kPbr) {  // glTF's clear coat, sheen and specular: numbers, colours or textures
            for (auto [key, slot] : {std::pair{"clearcoat", &d.clearcoat}, {"clearcoat_roughness", &d.clearcoat_roughness},
                                     {"sheen", &d.sheen}, {"sheen_roughness", &d.sheen_roughness},
                                     {"specular", &d.specular}, {"specular_color", &d.specular_color}})
                if (auto n = m.get(key))
                    if (auto t = texture(*n)) *slot = *t;
        }
        assign(m.get("shininess"), d.shininess, unit("shininess"));
        assign(m.get("roughness"), d.roughness, unit("roughness"));
        if (d.kind == K::kCoated) {
            // A coated diffuse's roughness is its coat's; a coated conductor's is the metal's.
            if (!d.coated_conductor) std::swap(d.roughness, d.coat_roughness);
            assign(m.get("coat_roughness"), d.coat_roughness, unit("coat_roughness"));
            assign(m.get("thickness"), d.thickness, [this](const YAML::Node& v) {
                return r_.number_in(v, "thickness", 0, 1e30, true);
            });
            assign(m.get("layer_albedo"), d.layer_albedo, color());
            assign(m.get("g"), d.g, [this](const YAML::Node& v) { return r_.number_in(v, "g", -0.999, 0.999); });
            assign(m.get("max_depth"), d.layer_depth, [this](const YAML::Node& v) { return r_.integer_in(v, "max_depth", 1, 1000); });
            assign(m.get("samples"), d.layer_samples, [this](const YAML::Node& v) { return r_.integer_in(v, "samples", 1, 100); });
        }
        assign(m.get("metallic"), d.metallic, unit("metallic"));
        assign(m.get("transmission"), d.transmission, unit("transmission"));
        assign(m.get("ior"), d.ior, [this](const YAML::Node& v) {
            return r_.number_in(v, "ior", 0, 10, true);
        });
        assign(m.get("thin"), d.thin, [this](const YAML::Node& v) { return r_.boolean(v); });
        assign(m.get("tint"), d.tint, color());
        assign(m.get("emission"), d.emission.radiance, color());
        assign(m.get("two_sided"), d.emission.two_sided,
               [this](const YAML::Node& v) { return r_.boolean(v); });
        if (d.kind == K::kConductor || (d.kind == K::kCoated && d.coated_conductor)) {
            const auto metal = m.get("metal");
            const auto eta = m.get("eta"), k = m.get("k"), reflectance = m.get("reflectance");
            const int forms = (metal ? 1 : 0) + (eta || k ? 1 : 0) + (reflectance ? 1 : 0);
            if (forms > 1) {
                r_.error(node, fmt::format("{}: give one of 'metal', 'eta' and 'k', or "
                                           "'reflectance'", context));
            }
            if (metal) {
                if (const auto name = r_.string(*metal)) {
                    const auto it = std::find_if(kMetals.begin(), kMetals.end(),
                                                 [&](const MetalPreset& p) { return p.name == *name; });
                    if (it == kMetals.end()) {
                        std::vector<std::string> names;
                        for (const auto& p : kMetals) names.emplace_back(p.name);
                        const std::string guess = closest_match(*name, names);
                        r_.error(*metal, fmt::format("unknown metal '{}'{} (known: {})", *name,
                                                     guess.empty() ? "" : fmt::format("; did you mean '{}'?", guess),
                                                     join(names)));
                    } else {
                        d.eta = it->eta;
                        d.k = it->k;
                    }
                }
            } else if (eta || k) {
                if (!(eta && k)) r_.error(node, fmt::format("{}: 'eta' and 'k' go together", context));
                assign(eta, d.eta, color());
                assign(k, d.k, color());
            } else if (reflectance) {
                if (auto t = texture(*reflectance)) d.reflectance = *t;
            } else {
                TextureDesc white;  // no form given: a perfect mirror-white metal
                white.value = Color{1};
                d.reflectance = white;
            }
        }
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
            if (*name == "interface") {
                r_.error(it->first, "materials: 'interface' is the built-in material of surfaces that "
                                    "only bound a medium; choose another name");
                continue;
            }
            out.push_back({*name, material(it->second, fmt::format("material '{}'", *name)),
                           r_.loc(it->first)});
        }
    }

    MaterialRef material_ref(const YAML::Node& node) {
        if (node.IsScalar() && node.Scalar() == "interface") {
            MaterialDesc d;
            d.kind = MaterialDesc::Kind::kInterface;
            return {d, r_.loc(node)};
        }
        if (node.IsScalar()) return {node.Scalar(), r_.loc(node)};
        return {material(node, "material"), r_.loc(node)};
    }

    Located<std::string> located_name(const YAML::Node& node) {
        Located<std::string> l{"", r_.loc(node)};
        if (const auto v = r_.string(node)) l.value = *v;
        return l;
    }

    // The coefficients of a medium: sigma_a and sigma_s, or the artist's albedo, density and
    // scale (sigma_s = albedo density scale, sigma_a = (1 - albedo) density scale).
    void coefficients(MapReader& m, const YAML::Node& node, const std::string& context, MediumDesc& d) {
        const auto sa = m.get("sigma_a"), ss = m.get("sigma_s");
        const auto albedo = m.get("albedo"), density = m.get("density"), scale = m.get("scale");
        const bool physical = sa || ss, artist = albedo || density || scale;
        if (physical && artist) {
            r_.error(node, fmt::format("{}: give 'sigma_a' and 'sigma_s', or 'albedo', 'density' and "
                                       "'scale', not both", context));
            return;
        }
        if (physical) {
            assign(sa, d.sigma_a, color());
            assign(ss, d.sigma_s, color());
            return;
        }
        Color a{1};
        double k = 1, f = 1;
        if (albedo) {
            std::optional<Color> c;
            if (!albedo->IsScalar()) c = r_.color(*albedo);
            else if (const auto v = r_.number(*albedo)) c = Color{static_cast<float>(*v)};
            if (c) {
                if (!(c->max_component() <= 1 && c->r >= 0 && c->g >= 0 && c->b >= 0))
                    r_.error(*albedo, fmt::format("{}: albedo must be in [0, 1]", context));
                else a = *c;
            }
        }
        assign(density, k, [this](const YAML::Node& v) { return r_.number_in(v, "density", 0, kInf); });
        assign(scale, f, [this](const YAML::Node& v) { return r_.number_in(v, "scale", 0, kInf); });
        const float sigma_t = static_cast<float>(k * f);
        d.sigma_s = a * sigma_t;
        d.sigma_a = (Color{1} - a) * sigma_t;
    }

    MediumDesc medium(const YAML::Node& node, const std::string& context) {
        MediumDesc d;
        const auto type = type_of(node, "medium", {"homogeneous", "grid"});
        if (!type) return d;
        std::vector<std::string> keys{"type", "sigma_a", "sigma_s", "albedo", "density", "scale", "g"};
        if (*type == "homogeneous") {
            keys.push_back("emission");
        } else {
            d.kind = MediumDesc::Kind::kGrid;
            keys.insert(keys.end(), {"file", "grid", "emission_grid", "emission", "temperature_grid",
                                     "temperature_scale", "emission_scale", "transform"});
        }
        MapReader m(r_, node, context, keys);
        coefficients(m, node, context, d);
        if (const auto g = m.get("g")) {
            if (const auto v = r_.number(*g)) {
                if (!(std::abs(*v) < 1)) r_.error(*g, fmt::format("{}: g must lie in (-1, 1), got {}", context, *v));
                else d.g = static_cast<float>(*v);
            }
        }
        assign(m.get("emission"), d.emission, color());
        if (d.kind == MediumDesc::Kind::kGrid) {
            if (const auto f = m.require("file")) d.file = located_name(*f);
            if (const auto g = m.get("grid")) d.density_grid = located_name(*g);
            const auto eg = m.get("emission_grid"), tg = m.get("temperature_grid");
            if (eg && tg) {
                r_.error(*tg, fmt::format("{}: give 'emission_grid' or 'temperature_grid', not both", context));
            } else if (eg) {
                d.emission_kind = MediumDesc::Emission::kGrid;
                d.emission_grid = located_name(*eg);
                if (!m.has("emission")) d.emission = Color{1};
            } else if (tg) {
                d.emission_kind = MediumDesc::Emission::kTemperature;
                d.emission_grid = located_name(*tg);
            }
            if (m.has("emission") && !eg) {
                r_.error(*m.get("emission"), fmt::format("{}: 'emission' is the colour of an 'emission_grid', "
                                                         "which is not given", context));
            }
            assign(m.get("emission_scale"), d.emission_scale, [this](const YAML::Node& v) {
                return r_.number_in(v, "emission_scale", 0, kInf);
            });
            assign(m.get("temperature_scale"), d.temperature_scale, [this](const YAML::Node& v) {
                return r_.number_in(v, "temperature_scale", 0, kInf);
            });
            if (const auto t = m.get("transform")) d.transform = transform(*t);
        }
        return d;
    }

    void media(const YAML::Node& node, std::vector<NamedMedium>& out) {
        if (!node.IsMap()) {
            r_.error(node, fmt::format("media: expected a map from names to media, got {}", describe(node)));
            return;
        }
        for (auto it = node.begin(); it != node.end(); ++it) {
            const auto name = r_.string(it->first);
            if (!name) continue;
            if (*name == "none") {
                r_.error(it->first, "media: 'none' means vacuum; choose another name");
                continue;
            }
            if (std::any_of(out.begin(), out.end(), [&](const NamedMedium& m) { return m.name == *name; })) {
                r_.error(it->first, fmt::format("media: duplicate medium name '{}'", *name));
                continue;
            }
            out.push_back({*name, medium(it->second, fmt::format("medium '{}'", *name)), r_.loc(it->first)});
        }
    }

    void objects(const YAML::Node& node, std::vector<ObjectDesc>& out) {
        if (!node.IsSequence()) {
            r_.error(node, fmt::format("objects: expected a list, got {}", describe(node)));
            return;
        }
        for (const YAML::Node& item : node) {
            const auto type =
                type_of(item, "object",
                        {"sphere", "plane", "quad", "disk", "triangle", "polygon", "box", "mesh"});
            if (!type) continue;
            const std::size_t first = out.size();
            std::optional<YAML::Node> mat;
            if (*type == "sphere") {
                Sphere s{{0, 0, 0}, 1};
                MapReader m(r_, item, "sphere", {"type", "center", "radius", "material", "transform", "interior", "exterior"});
                assign(m.require("center"), s.center, point());
                assign(m.require("radius"), s.radius, positive("radius"));
                out.push_back(object_of(s));
                mat = m.get("material");
            } else if (*type == "plane") {
                Plane p{{0, 0, 0}, {0, 1, 0}};
                MapReader m(r_, item, "plane", {"type", "point", "normal", "material", "transform", "interior", "exterior"});
                assign(m.require("point"), p.point, point());
                Vector3 n{0, 1, 0};
                assign(m.require("normal"), n, direction("normal"));
                p.normal = Normal3(normalize(n));
                out.push_back(object_of(p));
                mat = m.get("material");
            } else if (*type == "quad") {
                Point3 corner{0, 0, 0};
                Vector3 e1{1, 0, 0}, e2{0, 1, 0};
                MapReader m(r_, item, "quad", {"type", "corner", "edge1", "edge2", "material", "transform", "interior", "exterior"});
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
                MapReader m(r_, item, "disk", {"type", "center", "normal", "radius", "material", "transform", "interior", "exterior"});
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
                MapReader m(r_, item, *type, {"type", "vertices", "material", "transform", "interior", "exterior"});
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
                MapReader m(r_, item, "mesh", {"type", "file", "material", "transform", "interior", "exterior",
                                               "alpha", "alpha_mode", "alpha_cutoff"});
                MeshFileDesc f;
                if (const auto n = m.require("file")) {
                    f.file.loc = r_.loc(*n);
                    assign(n, f.file.value, [this](const YAML::Node& v) { return r_.string(v); });
                }
                out.push_back(object_of(f));
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
                MapReader m(r_, item, "box", {"type", "min", "max", "material", "transform", "interior", "exterior"});
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
    std::optional<Transform> transform(const YAML::Node& node) {
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
                MapReader m(r_, v, "rotate", {"angle", "axis"});
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
                MapReader m(r_, v, "look_at", {"from", "to", "up"});
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

    // An object of this shape; material, placement and location are filled in after.
    template <typename Shape>
    static ObjectDesc object_of(const Shape& shape) {
        ObjectDesc o;
        o.shape = shape;
        return o;
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
                             std::shared_ptr<SourceFiles> sources, double frame) {
    reset_memory_budget();  // a new scene
    sources->add(path, text);
    Diagnostics diagnostics(sources);
    SceneDescription scene;
    scene.path = path;
    scene.frame = frame;
    // Flow collections nested deeper than the nesting limit, found before yaml-cpp recurses
    // into them (its own guard, at 2000 levels, reports only "bad file").
    {
        int line = 1, column = 0;
        long long depth = 0;
        char quote = 0;
        bool comment = false;
        for (const char c : text) {
            ++column;
            if (c == '\n') {
                ++line, column = 0, comment = false;
                if (quote == '\'') quote = 0;  // plain YAML allows multi-line quotes; good enough for a bound
                continue;
            }
            if (comment) continue;
            if (quote) {
                if (c == quote) quote = 0;
                continue;
            }
            if (c == '"' || c == '\'') quote = c;
            else if (c == '#') comment = true;
            else if (c == ']' || c == '}') depth = std::max(0LL, depth - 1);
            else if ((c == '[' || c == '{') && ++depth > limit(Limit::kNesting)) {
                diagnostics.error({path, line, column}, over_limit(Limit::kNesting, depth));
                diagnostics.throw_if_errors();
            }
        }
    }
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

SceneDescription load_scene_file(const std::string& path, std::shared_ptr<SourceFiles> sources, double frame) {
    if (is_pbrt_file(path)) {
        SceneDescription d = load_pbrt_file(path, std::move(sources));
        d.frame = frame;
        return d;
    }
    const std::string text = read_scene_text(path, sources);
    return parse_scene(text, path, std::move(sources), frame);
}

}  // namespace glint
