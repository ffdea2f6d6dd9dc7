#include "glint/formats/scene_yaml.h"
#include "glint/formats/pbrt.h"

#include <fmt/core.h>
#include <yaml-cpp/depthguard.h>
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
#include "glint/description/vocabulary.h"
#include "glint/formats/scene_yaml_parser.h"
#include "glint/formats/spectrum_file.h"
#include "glint/materials/metals.h"

namespace glint {

namespace yaml_detail {

void SceneParser::parse_root(const YAML::Node& root, SceneDescription& scene) {
    if (root.IsNull()) {
        r_.diagnostics().error({scene.path, 0, 0}, "the scene file is empty");
        return;
    }
    MapReader m(r_, root, "scene", vocabulary_keys("scene"));
    if (!m.valid()) return;
    if (auto n = m.get("animation")) {
        MapReader a(r_, *n, "animation", vocabulary_keys("animation"));
        if (a.valid())
            if (auto f = a.get("fps")) assign(f, scene.fps, [this](const YAML::Node& v) { return r_.number_in(v, "fps", 0, 1e6, true); });
    }
    // Every keyframed value becomes its value at this frame, then the scene is read as usual.
    for (auto it = root.begin(); it != root.end(); ++it) {
        YAML::Node value = it->second;
        animate(value, scene);
    }
    if (auto n = m.get("camera")) {
        scene.camera = camera(*n);
        scene.shutter = shutter_;
        scene.shutter_loc = shutter_loc_;
    }
    if (auto n = m.get("film")) film(*n, scene.film);
    if (auto n = m.get("sampler")) sampler(*n, scene.sampler);
    if (auto n = m.get("integrator")) integrator(*n, scene.integrator);
    if (auto n = m.get("background")) {
        if (auto bg = background(*n, scene.environment)) scene.background = *bg;
    }
    if (auto n = m.get("lights")) lights(*n, scene.lights, scene.light_spectra);
    if (auto n = m.get("materials")) materials(*n, scene.materials);
    if (auto n = m.get("media")) media(*n, scene.media);
    if (auto n = m.get("medium")) scene.medium = located_name(*n);
    if (auto n = m.get("objects")) objects(*n, scene.objects);
    scene.warnings.insert(scene.warnings.end(), warnings_.begin(), warnings_.end());
}

// Replaces, in place, every `{keyframes: [[frame, value], ...], interpolation: ...}` under
// `node` with its value at scene.frame (docs/scene-format.md, "Animation").
void SceneParser::animate(YAML::Node& node, SceneDescription& scene) {
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
std::optional<YAML::Node> SceneParser::keyframed(const YAML::Node& node, double frame) {
    MapReader m(r_, node, "keyframed value", vocabulary_keys("keyframes"));
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
std::vector<double> SceneParser::interpolate(const std::vector<double>& t, const std::vector<std::vector<double>>& v,
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
std::optional<std::string> SceneParser::type_of(const YAML::Node& node, const std::string& context,
                                   const std::vector<std::string>& types,
                                   std::optional<std::string> fallback) {
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

CameraDesc SceneParser::camera(const YAML::Node& node) {
    const auto type = type_of(node, "camera", vocabulary_types("camera"), "article");
    if (type == "look_at") {
        LookAtCameraDesc c;
        MapReader m(r_, node, "look_at camera", vocabulary_keys("camera", "look_at"));
        lens(m, c.aperture_radius, c.focus_distance);
        shutter(m);
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
    MapReader m(r_, node, "camera", vocabulary_keys("camera", "article"));
    lens(m, c.aperture_radius, c.focus_distance);
    shutter(m);
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

void SceneParser::film(const YAML::Node& node, FilmDesc& f) {
    MapReader m(r_, node, "film", vocabulary_keys("film"));
    assign(m.get("aovs"), f.aovs, [this](const YAML::Node& v) { return r_.boolean(v); });
    assign(m.get("denoise"), f.denoise, [this](const YAML::Node& v) { return r_.boolean(v); });
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

FilterDesc SceneParser::filter(const YAML::Node& node) {
    const auto type = type_of(node, "filter", vocabulary_types("filter"));
    FilterDesc f;
    if (!type) return f;
    if (*type == "box") f = {FilterType::kBox, 0.5f, 0.5f};
    if (*type == "tent") f = {FilterType::kTent, 1.0f, 0.5f};
    if (*type == "gaussian") f = {FilterType::kGaussian, 1.5f, 0.5f};
    if (*type == "blackman_harris") f = {FilterType::kBlackmanHarris, 1.5f, 0.5f};
    MapReader m(r_, node, fmt::format("{} filter", *type), vocabulary_keys("filter", *type));
    assign(m.get("radius"), f.radius, [this](const YAML::Node& v) {
        return r_.number_in(v, "radius", 0, 16, true);
    });
    assign(m.get("sigma"), f.sigma, positive("sigma"));
    return f;
}

void SceneParser::sampler(const YAML::Node& node, SamplerDesc& s) {
    MapReader m(r_, node, "sampler", vocabulary_keys("sampler"));
    if (m.has("type")) {
        const auto type = type_of(node, "sampler", vocabulary_types("sampler_type"));
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

void SceneParser::integrator(const YAML::Node& node, IntegratorDesc& d) {
    const auto type = type_of(node, "integrator", vocabulary_types("integrator"));
    if (!type) return;
    if (*type == "flat" || *type == "normals") {
        d.kind = *type == "flat" ? IntegratorKind::kFlat : IntegratorKind::kNormals;
        MapReader m(r_, node, fmt::format("{} integrator", *type), vocabulary_keys("integrator", *type));
        return;
    }
    const bool path = *type == "path";
    d.kind = path ? IntegratorKind::kPath : IntegratorKind::kWhitted;
    MapReader m(r_, node, fmt::format("{} integrator", *type), vocabulary_keys("integrator", *type));
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
        if (auto n = m.get("light_sampler")) {
            if (auto k = choice<LightSamplerKind>(*n, "light_sampler",
                                                  {{"bvh", LightSamplerKind::kBvh}, {"power", LightSamplerKind::kPower}}))
                d.path.light_sampler = *k;
        }
        if (auto n = m.get("texture_filter")) {
            if (auto f = choice<TextureFilter>(*n, "texture_filter",
                                               {{"ewa", TextureFilter::kEwa},
                                                {"trilinear", TextureFilter::kTrilinear},
                                                {"none", TextureFilter::kBilinear}}))
                d.path.texture_filter = *f;
        }
        assign(m.get("spectral"), d.path.spectral, [this](const YAML::Node& v) { return r_.boolean(v); });
        assign(m.get("white_balance"), d.path.white_balance,
               [this](const YAML::Node& v) { return r_.number_in(v, "white_balance", 1000, 100000); });
        return;
    }
    assign(m.get("ambient"), d.ambient,
           [this](const YAML::Node& v) { return r_.number_in(v, "ambient", 0, 1); });
    assign(m.get("shadows"), d.shadows, [this](const YAML::Node& v) { return r_.boolean(v); });
}

std::optional<Background> SceneParser::background(const YAML::Node& node,
                                     std::optional<EnvironmentDesc>& environment) {
    const auto type = type_of(node, "background", vocabulary_types("background"));
    if (!type) return std::nullopt;
    if (*type == "sky") {
        SkyBackground sky;
        MapReader m(r_, node, "sky background", vocabulary_keys("background", "sky"));
        assign(m.get("horizon"), sky.horizon, color());
        assign(m.get("zenith"), sky.zenith, color());
        return sky;
    }
    if (*type == "environment") {
        EnvironmentDesc e;
        MapReader m(r_, node, "environment background", vocabulary_keys("background", "environment"));
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
    MapReader m(r_, node, "constant background", vocabulary_keys("background", "constant"));
    assign(m.require("color"), c.color, color());
    if (const auto n = m.get("spectrum")) c.spectrum = emitter_spectrum(*n, c.color);
    return c;
}

std::optional<Spectrum> SceneParser::spectrum(const YAML::Node& n) {
    std::optional<Spectrum> s;
    if (n.IsMap()) {
        MapReader m(r_, n, "spectrum", {"blackbody", "file"});
        if (!m.valid()) return std::nullopt;
        if (const auto f = m.get("file")) {
            // pbrt-v4's .spd format (wavelength-value pairs, '#' comments), relative to this file.
            if (m.has("blackbody")) r_.error(n, "spectrum: give 'blackbody' or 'file', not both");
            const auto name = r_.string(*f);
            if (!name) return std::nullopt;
            std::filesystem::path file = *name;
            if (file.is_relative()) file = std::filesystem::path(r_.file()).parent_path() / file;
            std::string message;
            std::optional<PiecewiseLinearSpectrum> table;
            if (const auto numbers = read_spectrum_file(file, message)) table = spectrum_from_pairs(*numbers, message);
            if (!table) {
                r_.error(*f, fmt::format("spectrum: {}", message));
                return std::nullopt;
            }
            return Spectrum::tabulated(std::move(*table));
        }
        if (const auto k = m.require("blackbody"))
            if (const auto t = r_.number_in(*k, "blackbody", 0, 1e6, true)) s = Spectrum::blackbody(float(*t));
    } else if (n.IsScalar() && !n.Scalar().empty() && std::isalpha(static_cast<unsigned char>(n.Scalar()[0]))) {
        if (const PiecewiseLinearSpectrum* named = named_spectrum(n.Scalar())) {
            s = Spectrum::tabulated(*named);
            s->set_name(n.Scalar());
        } else {
            std::vector<std::string> names;
            for (const std::string_view v : named_spectrum_names()) names.emplace_back(v);
            const std::string guess = closest_match(n.Scalar(), names);
            r_.error(n, fmt::format("spectrum: unknown name '{}'{}", n.Scalar(),
                                    guess.empty() ? "" : fmt::format("; did you mean '{}'?", guess)));
        }
    } else if (n.IsSequence()) {
        if (n.size() < 2 || n.size() % 2 != 0 || n.size() > 100000) {
            r_.error(n, fmt::format("spectrum: expected pairs [nm, value, nm, value, ...], got {} numbers", n.size()));
            return std::nullopt;
        }
        std::vector<float> lambda, value;
        for (std::size_t i = 0; i < n.size(); i += 2) {
            const auto l = r_.number_in(n[i], "spectrum wavelength", 1, 1e5);
            const auto v = r_.number_in(n[i + 1], "spectrum value", 0, 1e30);
            if (!l || !v) return std::nullopt;
            if (!lambda.empty() && !(*l > lambda.back())) {
                r_.error(n[i], fmt::format("spectrum: the wavelengths must increase ({} after {})", *l, lambda.back()));
                return std::nullopt;
            }
            lambda.push_back(float(*l));
            value.push_back(float(*v));
        }
        s = Spectrum::tabulated(PiecewiseLinearSpectrum(std::move(lambda), std::move(value)));
    } else {
        r_.error(n, fmt::format("spectrum: expected {{blackbody: kelvin}}, a name or [nm, value, ...], got {}", describe(n)));
    }
    return s;
}

std::shared_ptr<const Spectrum> SceneParser::emitter_spectrum(const YAML::Node& n, Color& rgb) {
    const std::optional<Spectrum> s = spectrum(n);
    if (!s) return nullptr;
    const Spectrum e = s->normalised_emission();
    if (!(spectrum_to_xyz(e).y > 0)) {
        r_.error(n, "spectrum: it emits nothing visible (360-830 nm)");
        return nullptr;
    }
    rgb = e.emission_rgb() * luminance(rgb);
    return std::make_shared<const Spectrum>(e);
}

void SceneParser::lights(const YAML::Node& node, std::vector<Light>& out,
                         std::vector<std::shared_ptr<const Spectrum>>& spectra) {
    if (!node.IsSequence()) {
        r_.error(node, fmt::format("lights: expected a list, got {}", describe(node)));
        return;
    }
    const auto degrees = [this](const char* what, double hi) {
        return [this, what, hi](const YAML::Node& n) { return r_.number_in(n, what, 0, hi); };
    };
    // A light's `spectrum` (spectral mode), at the index the light is about to take.
    const auto with_spectrum = [&](const MapReader& m, Color& intensity) {
        if (const auto n = m.get("spectrum")) {
            if (auto s = emitter_spectrum(*n, intensity)) {
                spectra.resize(out.size() + 1);
                spectra.back() = std::move(s);
            }
        }
    };
    for (const YAML::Node& item : node) {
        const auto type = type_of(item, "light", vocabulary_types("light"));
        if (!type) continue;
        if (*type == "directional") {
            DirectionalLight l{{0, -1, 0}, Color{1}};
            MapReader m(r_, item, "directional light", vocabulary_keys("light", "directional"));
            assign(m.require("direction"), l.direction, direction("direction"));
            l.direction = normalize(l.direction);
            assign(m.get("intensity"), l.intensity, color());
            float diameter = 0;
            assign(m.get("angular_diameter"), diameter, degrees("angular_diameter", 179));
            const float s = std::sin(diameter * std::numbers::pi_v<float> / 720);  // sin(d/4)
            l.one_minus_cos = 2 * s * s;
            with_spectrum(m, l.intensity);
            out.emplace_back(l);
        } else if (*type == "point") {
            PointLight l{{0, 0, 0}, Color{1}};
            MapReader m(r_, item, "point light", vocabulary_keys("light", "point"));
            assign(m.require("position"), l.position, point());
            assign(m.get("intensity"), l.intensity, color());
            with_spectrum(m, l.intensity);
            out.emplace_back(l);
        } else {
            SpotLight l{{0, 0, 0}, {0, -1, 0}, Color{1}, 1, 0};
            MapReader m(r_, item, "spot light", vocabulary_keys("light", "spot"));
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
            with_spectrum(m, l.intensity);
            out.emplace_back(l);
        }
    }
}

}  // namespace yaml_detail

using yaml_detail::SceneParser;


SceneDescription parse_scene(const std::string& text, const std::string& path,
                             std::shared_ptr<SourceFiles> sources, double frame, const InlineArrays* arrays) {
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
    } catch (const YAML::DeepRecursion& e) {  // block nesting past yaml-cpp's own guard, which says only "bad file"
        diagnostics.error({path, e.mark.is_null() ? 0 : e.mark.line + 1, e.mark.is_null() ? 0 : e.mark.column + 1},
                          over_limit(Limit::kNesting, std::max<long long>(e.depth(), limit(Limit::kNesting) + 1)));
        diagnostics.throw_if_errors();
    } catch (const YAML::Exception& e) {
        diagnostics.error({path, e.mark.is_null() ? 0 : e.mark.line + 1,
                           e.mark.is_null() ? 0 : e.mark.column + 1},
                          fmt::format("invalid YAML: {}", e.msg));
        diagnostics.throw_if_errors();
    }
    {
        YamlReader reader(diagnostics, path);
        check_expanded_size(reader, root);
        diagnostics.throw_if_errors();
    }
    SceneParser(diagnostics, path, arrays).parse_root(root, scene);
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
    return parse_scene_over_shutter(text, path, std::move(sources), frame);
}

}  // namespace glint
