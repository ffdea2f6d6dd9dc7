#include "glint/formats/pbrt.h"

#include <fmt/core.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>

#include "glint/base/limits.h"
#include "glint/formats/pbrt_parser.h"
#include "glint/math/motion.h"

namespace glint {
namespace pbrt_detail {

constexpr std::array kDirectives{
    "Attribute",      "AttributeBegin",  "AttributeEnd",    "AreaLightSource", "Camera",         "ColorSpace",
    "ConcatTransform", "CoordinateSystem", "CoordSysTransform", "Film",           "Import",         "Include",
    "Integrator",     "LightSource",     "LookAt",          "MakeNamedMaterial", "MakeNamedMedium", "Material",
    "MediumInterface", "NamedMaterial",  "ObjectBegin",     "ObjectEnd",       "ObjectInstance", "Option",
    "PixelFilter",    "ReverseOrientation", "Rotate",       "Sampler",         "Scale",          "Shape",
    "Texture",        "Transform",       "TransformBegin",  "TransformEnd",    "Translate",      "WorldBegin",
    "WorldEnd",       "Accelerator",     "TransformTimes",  "ActiveTransform",
};

void Parser::run_file(const std::string& text, const std::string& path, int depth) {
    if (!dir_set_) {
        dir_ = std::filesystem::path(path).parent_path();
        dir_set_ = true;
    }
    sources_->add(path, text);
    names_.push_back(path);
    // The tokens view into `text`, which outlives this call (parameters keep copies).
    Lexer s(text, &names_.back(), diag_, unescaped_);
    while (!s.done()) {
        const Token t = s.next();
        if (t.kind != Token::Kind::kWord) {
            diag_.error(t.loc(), fmt::format("expected a directive, found '{}'", t.text));
            // Skip to the next word.
            while (!s.done() && s.peek().kind != Token::Kind::kWord) s.next();
            continue;
        }
        directive(s, t, depth);
    }
}

// One directive and its arguments; each step below takes the directives of one kind and says
// whether it took this one.
void Parser::directive(Stream& s, const Token& t, int depth) {
    const std::string name(t.text);
    if (transform_directive(s, t, name) ||
        block_directive(t, name) ||
        include_directive(s, t, name, depth) ||
        typed_directive(s, t, name) ||
        named_directive(s, t, name) ||
        object_directive(s, t, name) ||
        ignored_directive(s, t, name))
        return;
    std::vector<std::string> names(kDirectives.begin(), kDirectives.end());
    const std::string guess = closest_match(name, names);
    diag_.error(t.loc(), fmt::format("unknown directive '{}'{}", name,
                                   guess.empty() ? "" : fmt::format("; did you mean '{}'?", guess)));
    // Skip its arguments.
    while (!s.done() && s.peek().kind != Token::Kind::kWord) s.next();
}

bool Parser::transform_directive(Stream& s, const Token& t, const std::string& name) {
    std::vector<double> v;
    const auto concat = [&](const M4& m) {
        if (gs_.active & 1) gs_.ctm = gs_.ctm * m;
        if (gs_.active & 2) gs_.ctm_end = gs_.ctm_end * m;
    };
    if (name == "Translate") {
        if (numbers(s, t, 3, v)) concat(translate(v[0], v[1], v[2]));
    } else if (name == "Scale") {
        if (numbers(s, t, 3, v)) concat(scale(v[0], v[1], v[2]));
    } else if (name == "Rotate") {
        if (numbers(s, t, 4, v)) {
            if (!(v[1] * v[1] + v[2] * v[2] + v[3] * v[3] > 0))
                diag_.error(t.loc(), "Rotate: the axis is zero");
            else
                concat(rotate(v[0], v[1], v[2], v[3]));
        }
    } else if (name == "LookAt") {
        if (numbers(s, t, 9, v)) {
            const auto m = look_at({v[0], v[1], v[2]}, {v[3], v[4], v[5]}, {v[6], v[7], v[8]});
            if (!m)
                diag_.error(t.loc(), "LookAt: the eye is at the target, or up is parallel to the view direction");
            else
                concat(*m);
        }
    } else if (name == "Transform" || name == "ConcatTransform") {
        bool bracket = !s.done() && s.peek().kind == Token::Kind::kOpen;
        if (bracket) s.next();
        if (numbers(s, t, 16, v)) {
            M4 m;  // pbrt's matrices are given column by column
            for (int i = 0; i < 4; ++i)
                for (int j = 0; j < 4; ++j) m.m[j][i] = v[static_cast<std::size_t>(4 * i + j)];
            if (name == "Transform") {
                if (gs_.active & 1) gs_.ctm = m;
                if (gs_.active & 2) gs_.ctm_end = m;
            } else {
                concat(m);
            }
        }
        if (bracket) {
            if (!s.done() && s.peek().kind == Token::Kind::kClose) s.next();
            else diag_.error(t.loc(), fmt::format("{}: '[' without a matching ']'", name));
        }
    } else if (name == "CoordinateSystem") {
        if (auto n = string_arg(s, t)) coordinate_systems_[*n] = gs_.ctm;
    } else if (name == "CoordSysTransform") {
        if (auto n = string_arg(s, t)) {
            const auto it = coordinate_systems_.find(*n);
            if (it == coordinate_systems_.end())
                diag_.error(t.loc(), fmt::format("CoordSysTransform: no coordinate system \"{}\"", *n));
            else
                gs_.ctm = gs_.ctm_end = it->second;
        }
    } else if (name == "ReverseOrientation") {
        gs_.reverse_orientation = !gs_.reverse_orientation;
    } else {
        return false;
    }
    return true;
}

bool Parser::block_directive(const Token& t, const std::string& name) {
    if (name == "AttributeBegin" || name == "TransformBegin") {
        // Nesting is policy (the nesting limit), not the memory of the state stack.
        const auto nesting = static_cast<long long>(stack_.size() + transform_stack_.size()) + 1;
        if (nesting > limit(Limit::kNesting)) {
            diag_.error(t.loc(), fmt::format("{}: {}", name, over_limit(Limit::kNesting, nesting)));
            diag_.throw_if_errors();
        }
        if (name == "AttributeBegin") stack_.push_back({gs_, t.loc()});
        else transform_stack_.push_back({{gs_.ctm, gs_.ctm_end}, t.loc()});
    } else if (name == "AttributeEnd") {
        if (stack_.empty()) {
            diag_.error(t.loc(), "AttributeEnd without AttributeBegin");
        } else {
            gs_ = stack_.back().first;
            stack_.pop_back();
        }
    } else if (name == "TransformEnd") {
        if (transform_stack_.empty()) {
            diag_.error(t.loc(), "TransformEnd without TransformBegin");
        } else {
            gs_.ctm = transform_stack_.back().first[0];
            gs_.ctm_end = transform_stack_.back().first[1];
            transform_stack_.pop_back();
        }
    } else if (name == "WorldBegin") {
        if (world_) diag_.error(t.loc(), "WorldBegin given twice");
        world_ = true;
        gs_.ctm = gs_.ctm_end = M4{};
        coordinate_systems_["world"] = gs_.ctm;
    } else if (name == "WorldEnd") {
        // pbrt-v3's end of the scene; pbrt-v4 files end without it.
    } else {
        return false;
    }
    return true;
}

bool Parser::include_directive(Stream& s, const Token& t, const std::string& name, int depth) {
    if (name == "Include" || name == "Import") {
        const auto file = string_arg(s, t);
        if (!file) return true;
        if (depth >= limit(Limit::kIncludes)) {
            diag_.error(t.loc(), fmt::format("{}: {}", name, over_limit(Limit::kIncludes, depth + 1)));
            return true;
        }
        const std::filesystem::path p = std::filesystem::path(*file).is_absolute() ? std::filesystem::path(*file) : dir_ / *file;
        if (const std::string why = why_not_readable(p); !why.empty()) {
            diag_.error(t.loc(), fmt::format("{}: cannot read '{}': it {}", name, p.string(), why));
            return true;
        }
        std::ifstream in(p, std::ios::binary);
        if (!in) {
            diag_.error(t.loc(), fmt::format("{}: cannot open '{}': {}", name, p.string(), std::strerror(errno)));
            return true;
        }
        std::ostringstream text;
        text << in.rdbuf();
        run_file(text.str(), p.string(), depth + 1);
    } else {
        return false;
    }
    return true;
}

bool Parser::typed_directive(Stream& s, const Token& t, const std::string& name) {
    if (name == "Camera" || name == "Film" || name == "Sampler" || name == "Integrator" ||
        name == "PixelFilter" || name == "Shape" || name == "LightSource" || name == "AreaLightSource" ||
        name == "Material" || name == "Accelerator") {
        const auto type = string_arg(s, t);
        ParamList pl = params(s);
        if (!type) return true;
        if (name == "Camera") {
            camera(t, *type, std::move(pl));
        } else if (name == "Film") {
            film(t, *type, std::move(pl));
        } else if (name == "Sampler") {
            if (auto n = get_int(pl, "pixelsamples")) {
                if (*n < 1) diag_.error(pl.find("pixelsamples")->loc, "pixelsamples must be at least 1");
                else d_.sampler.spp = {*n, pl.find("pixelsamples")->loc};
            } else {
                d_.sampler.spp.value = 16;  // pbrt's default
            }
            if (*type == "independent") d_.sampler.type = SamplerType::kIndependent;
            else if (*type == "stratified") d_.sampler.type = SamplerType::kStratified;
            else d_.sampler.type = SamplerType::kSobol;
            if (auto seed = get_int(pl, "seed")) d_.sampler.seed = static_cast<std::uint64_t>(std::max(0, *seed));
            ignore_rest(pl, fmt::format("Sampler \"{}\": parameter \"{{}}\" ignored", *type));
            if (*type != "independent" && *type != "stratified" && *type != "sobol" && *type != "zsobol" &&
                *type != "paddedsobol" && *type != "halton" && *type != "pmj02bn")
                diag_.error(t.loc(), fmt::format("unknown sampler \"{}\"", *type));
        } else if (name == "Integrator") {
            d_.integrator.kind = IntegratorKind::kPath;
            d_.integrator.max_depth.value = 5;  // pbrt's default
            if (auto n = get_int(pl, "maxdepth")) {
                if (*n < 0 || *n > 10000) diag_.error(pl.find("maxdepth")->loc, "maxdepth must be in [0, 10000]");
                else d_.integrator.max_depth = {*n, pl.find("maxdepth")->loc};
            }
            if (*type != "path" && *type != "volpath")
                warn(t.loc(), fmt::format("integrator \"{}\" not supported; using path", *type));
            if (const auto ls = get_string(pl, "lightsampler")) {  // pbrt-v4's default is bvh, as glint's
                if (*ls == "power") {
                    d_.integrator.path.light_sampler = LightSamplerKind::kPower;
                } else if (*ls == "uniform") {
                    d_.integrator.path.light_sampler = LightSamplerKind::kPower;
                    warn(pl.find("lightsampler")->loc, "light sampler \"uniform\" not supported; using power");
                } else if (*ls != "bvh") {
                    diag_.error(pl.find("lightsampler")->loc,
                                fmt::format("unknown light sampler \"{}\" (pbrt-v4 knows bvh, power, uniform)", *ls));
                }
            }
            ignore_rest(pl, "Integrator: parameter \"{}\" ignored");
        } else if (name == "PixelFilter") {
            get_floats(pl, "radius", "float", 1);  // pbrt-v3's; the filters below take x/yradius
            const auto xr = get_float(pl, "xradius"), yr = get_float(pl, "yradius");
            if (*type == "box") {
                d_.film.filter = FilterDesc{FilterType::kBox, float(xr.value_or(0.5)), 0.5f};
            } else if (*type == "gaussian") {
                d_.film.filter = FilterDesc{FilterType::kGaussian, float(xr.value_or(1.5)),
                                            float(get_float(pl, "sigma").value_or(0.5))};
            } else if (*type == "triangle") {
                d_.film.filter = FilterDesc{FilterType::kTent, float(xr.value_or(2)), 0.5f};
            } else {
                warn(t.loc(), fmt::format("pixel filter \"{}\" not supported; using gaussian", *type));
                pl.use_all();
                d_.film.filter = FilterDesc{FilterType::kGaussian, 1.5f, 0.5f};
            }
            (void)yr;
            check_unused(pl, "PixelFilter");
        } else if (name == "Shape") {
            shape(t, *type, std::move(pl));
        } else if (name == "LightSource") {
            light(t, *type, std::move(pl));
        } else if (name == "AreaLightSource") {
            area_light(t, *type, std::move(pl));
        } else if (name == "Material") {
            if (auto m = material(t, *type, pl)) {
                const std::string n = fmt::format("pbrt-material-{}", ++material_count_);
                d_.materials.push_back({n, *m, t.loc()});
                gs_.material = n;
            }
            check_unused(pl, "Material \"" + *type + "\"");
        } else {  // Accelerator
            warn(t.loc(), "Accelerator ignored (glint builds its own BVH)");
        }
    } else {
        return false;
    }
    return true;
}

bool Parser::named_directive(Stream& s, const Token& t, const std::string& name) {
    if (name == "MakeNamedMaterial") {
        const auto n = string_arg(s, t);
        ParamList pl = params(s);
        if (!n) return true;
        const auto type = get_string(pl, "type");
        if (!type) {
            diag_.error(t.loc(), fmt::format("MakeNamedMaterial \"{}\": no \"string type\"", *n));
            return true;
        }
        if (auto m = material(t, *type, pl)) {
            // The pbrt name where it is free (a redefinition gets a new one: pbrt's replaces it).
            std::string inner = *n;
            const auto taken = [&](const std::string& x) {
                return std::any_of(d_.materials.begin(), d_.materials.end(), [&](const NamedMaterial& nm) { return nm.name == x; });
            };
            if (taken(inner) || inner.rfind("pbrt-", 0) == 0) inner = fmt::format("pbrt-named-{}-{}", *n, ++material_count_);
            d_.materials.push_back({inner, *m, t.loc()});
            named_materials_[*n] = inner;
        }
        check_unused(pl, "MakeNamedMaterial \"" + *n + "\"");
    } else if (name == "NamedMaterial") {
        if (const auto n = string_arg(s, t)) {
            const auto it = named_materials_.find(*n);
            if (it == named_materials_.end()) {
                std::vector<std::string> names;
                for (const auto& [k, _] : named_materials_) names.push_back(k);
                const std::string guess = closest_match(*n, names);
                diag_.error(t.loc(), fmt::format("unknown named material \"{}\"{}", *n,
                                               guess.empty() ? "" : fmt::format("; did you mean \"{}\"?", guess)));
            } else {
                gs_.material = it->second;
            }
        }
    } else if (name == "Texture") {
        const auto n = string_arg(s, t);
        const auto kind = n ? string_arg(s, t) : std::nullopt;
        const auto type = kind ? string_arg(s, t) : std::nullopt;
        ParamList pl = params(s);
        if (type) texture(t, *n, *kind, *type, std::move(pl));
    } else if (name == "MakeNamedMedium") {
        const auto n = string_arg(s, t);
        ParamList pl = params(s);
        if (n) medium(t, *n, std::move(pl));
    } else if (name == "MediumInterface") {
        const auto inside = string_arg(s, t);
        if (!inside) return true;
        std::string outside = *inside;
        if (!s.done() && s.peek().kind == Token::Kind::kString) outside = std::string(s.next().text);
        for (const std::string& m : {*inside, outside})
            if (!m.empty() && !media_.count(m)) diag_.error(t.loc(), fmt::format("MediumInterface: unknown medium \"{}\"", m));
        gs_.inside = *inside;
        gs_.outside = outside;
    } else {
        return false;
    }
    return true;
}

bool Parser::object_directive(Stream& s, const Token& t, const std::string& name) {
    if (name == "ObjectBegin") {
        if (const auto n = string_arg(s, t)) {
            if (defining_) diag_.error(t.loc(), "ObjectBegin inside another ObjectBegin");
            stack_.push_back({gs_, t.loc()});
            defining_ = {*n, t.loc()};
            instances_[*n];
        }
    } else if (name == "ObjectEnd") {
        if (!defining_) {
            diag_.error(t.loc(), "ObjectEnd without ObjectBegin");
        } else {
            defining_.reset();
            if (!stack_.empty()) {
                gs_ = stack_.back().first;
                stack_.pop_back();
            }
        }
    } else if (name == "ObjectInstance") {
        if (const auto n = string_arg(s, t)) {
            const auto it = instances_.find(*n);
            if (it == instances_.end()) {
                diag_.error(t.loc(), fmt::format("ObjectInstance: no object \"{}\"", *n));
            } else {
                for (const ObjectDesc& o : it->second) {
                    ObjectDesc copy = o;
                    copy.loc = t.loc();
                    M4 inner;
                    if (o.transform)
                        for (int i = 0; i < 3; ++i)
                            for (int j = 0; j < 4; ++j) inner.m[i][j] = o.transform->to_world.m[i][j];
                    add_object(copy, gs_.ctm * inner, gs_.ctm_end * inner);
                }
            }
        }
    } else {
        return false;
    }
    return true;
}

bool Parser::ignored_directive(Stream& s, const Token& t, const std::string& name) {
    std::vector<double> v;
    if (name == "ColorSpace") {
        if (const auto n = string_arg(s, t))
            if (*n != "srgb") warn(t.loc(), fmt::format("color space \"{}\": glint renders in linear sRGB; colours used as given", *n));
    } else if (name == "Option") {
        ParamList pl = params(s);
        for (Param& p : pl.params) warn(p.loc, fmt::format("Option \"{}\" ignored", p.name));
    } else if (name == "Attribute") {
        const auto target = string_arg(s, t);
        ParamList pl = params(s);
        if (target) warn(t.loc(), fmt::format("Attribute \"{}\": default parameters are not supported; ignored", *target));
    } else if (name == "TransformTimes") {
        if (numbers(s, t, 2, v)) {
            if (!(std::isfinite(v[0]) && std::isfinite(v[1]) && v[0] <= v[1]))
                diag_.error(t.loc(), "TransformTimes: expected a start and an end time, start <= end");
            else
                transform_times_ = {v[0], v[1]};
        }
    } else if (name == "ActiveTransform") {
        const std::string which = !s.done() && s.peek().kind == Token::Kind::kWord ? std::string(s.next().text) : "";
        if (which == "StartTime") gs_.active = 1;
        else if (which == "EndTime") gs_.active = 2;
        else if (which == "All") gs_.active = 3;
        else diag_.error(t.loc(), "ActiveTransform: expected StartTime, EndTime or All");
    } else {
        return false;
    }
    return true;
}


void Parser::camera(const Token& t, const std::string& type, ParamList pl) {
    camera_seen_ = true;
    const auto world_from_camera = gs_.ctm.inverse();
    if (!world_from_camera) {
        diag_.error(t.loc(), "Camera: the current transform is singular");
        return;
    }
    coordinate_systems_["camera"] = *world_from_camera;
    const M4& c = *world_from_camera;
    const D3 from = c.point(0, 0, 0), ahead = c.point(0, 0, 1), up = c.vector(0, 1, 0);
    LookAtCameraDesc cam;
    cam.from = {Float(from[0]), Float(from[1]), Float(from[2])};
    cam.to = {Float(ahead[0]), Float(ahead[1]), Float(ahead[2])};
    cam.up = normalize(Vector3{Float(up[0]), Float(up[1]), Float(up[2])});
    // A mirroring camera transform (pbrt scenes often start with Scale -1 1 1) shows the image
    // mirrored in glint's left-handed look-at frame: the camera is right-handed then.
    cam.right_handed = c.det3() < 0;
    const float fov = float(get_float(pl, "fov").value_or(90));
    if (!(fov > 0 && fov < 180)) diag_.error(pl.find("fov") ? pl.find("fov")->loc : t.loc(), "fov must be in (0, 180)");
    cam.fov = fov;  // on the shorter image axis: turned into glint's vertical fov in finish()
    cam.aperture_radius = float(get_float(pl, "lensradius").value_or(0));
    if (auto f = get_float(pl, "focaldistance")) cam.focus_distance = float(*f);
    else if (cam.aperture_radius > 0) cam.focus_distance = 1e6f;  // pbrt's default
    if (const auto* w = get_floats(pl, "screenwindow", "float", 4)) {
        if (w->size() != 4 || !((*w)[1] > (*w)[0] && (*w)[3] > (*w)[2]))
            diag_.error(pl.find("screenwindow")->loc, "screenwindow: expected [x0 x1 y0 y1] with x0 < x1 and y0 < y1");
        else
            cam.window = std::array<Float, 4>{Float((*w)[0]), Float((*w)[1]), Float((*w)[2]), Float((*w)[3])};
    }
    if (get_float(pl, "frameaspectratio"))
        warn(pl.find("frameaspectratio")->loc, "frameaspectratio ignored; the film's resolution decides");
    // The shutter interval is the exposure time of pbrt's imaging ratio, and the interval over
    // which shapes under ActiveTransform move (docs/motion.md).
    const double open = get_float(pl, "shutteropen").value_or(0), close = get_float(pl, "shutterclose").value_or(1);
    if (!(close >= open)) diag_.error(pl.find("shutterclose") ? pl.find("shutterclose")->loc : t.loc(),
                                      "shutterclose must not be before shutteropen");
    exposure_time_ = close - open;
    d_.shutter = {open, close};
    d_.shutter_loc = pl.find("shutteropen") ? pl.find("shutteropen")->loc : t.loc();
    if (type == "orthographic") {
        cam.orthographic = true;
        cam.height = Float(2 * std::sqrt(up[0] * up[0] + up[1] * up[1] + up[2] * up[2]));  // shorter axis [-1, 1]
    } else if (type != "perspective") {
        warn(t.loc(), fmt::format("camera \"{}\" not supported; using perspective", type));
        pl.use_all();
    }
    check_unused(pl, "Camera \"" + type + "\"");
    d_.camera = cam;
    // A moving camera (its start and end transforms differ): its frames at the shutter's open
    // and close, interpolated between the transform times as shapes are (docs/motion.md).
    if (!(gs_.ctm_end.m == gs_.ctm.m)) {
        const auto end_from_camera = gs_.ctm_end.inverse();
        const auto a = c.affine() ? Transform::from(c.to34()) : std::nullopt;
        const auto b = end_from_camera && end_from_camera->affine() ? Transform::from(end_from_camera->to34()) : std::nullopt;
        if (!a || !b) {
            diag_.error(t.loc(), "Camera: the camera transform at the end time is singular or projective");
        } else {
            const Motion between({*a, *b});
            for (const double time : {open, close}) {
                const Transform x = between.at(transform_fraction(time));
                LookAtCameraDesc key = cam;
                key.from = x.point({0, 0, 0});
                key.to = x.point({0, 0, 1});
                key.up = normalize(x.vector({0, 1, 0}));
                d_.camera_motion.push_back(key);
            }
            d_.camera = d_.camera_motion.front();
        }
    }
    if (!gs_.outside.empty()) d_.medium = Located<std::string>{gs_.outside, t.loc()};
}

void Parser::film(const Token& t, const std::string& type, ParamList pl) {
    if (type != "rgb" && type != "gbuffer" && type != "spectral")
        diag_.error(t.loc(), fmt::format("unknown film \"{}\"", type));
    d_.film.width = {1280, t.loc()};
    d_.film.height = {720, t.loc()};
    if (auto x = get_int(pl, "xresolution")) d_.film.width = {*x, pl.find("xresolution")->loc};
    if (auto y = get_int(pl, "yresolution")) d_.film.height = {*y, pl.find("yresolution")->loc};
    if (auto f = get_string(pl, "filename")) d_.film.filename = {*f, pl.find("filename")->loc};
    if (const auto* c = get_floats(pl, "cropwindow", "float", 4)) {
        if (c->size() != 4) diag_.error(pl.find("cropwindow")->loc, "cropwindow: expected 4 values [x0 x1 y0 y1]");
        else d_.film.crop_window = Located<std::array<float, 4>>{
                 {float((*c)[0]), float((*c)[1]), float((*c)[2]), float((*c)[3])}, pl.find("cropwindow")->loc};
    } else if (const auto* b = get_floats(pl, "pixelbounds", "integer", 4)) {
        if (b->size() != 4) diag_.error(pl.find("pixelbounds")->loc, "pixelbounds: expected 4 values [x0 x1 y0 y1]");
        else {
            std::array<int, 4> v{};
            for (std::size_t i = 0; i < 4; ++i) v[i] = int(std::clamp((*b)[i], -1e9, 1e9));
            d_.film.pixel_bounds = Located<std::array<int, 4>>{v, pl.find("pixelbounds")->loc};
        }
    }
    // pbrt-v4's imaging ratio (PixelSensor::Create): exposure time x iso / 100, 1 with its
    // pass-through defaults. (Older pbrt-v4 versions also read fnumber and C; this one does not,
    // and neither does glint: they are ignored with a warning, as any parameter glint skips.)
    const double iso = get_float(pl, "iso").value_or(100);
    if (!(iso > 0))
        diag_.error(pl.find("iso") ? pl.find("iso")->loc : t.loc(), "Film: iso must be positive");
    else
        film_ratio_ = iso / 100;
    if (auto sensor = get_string(pl, "sensor"); sensor && *sensor != "cie1931")
        warn(pl.find("sensor")->loc, fmt::format("sensor \"{}\" not simulated; using cie1931 (plain RGB)", *sensor));
    if (const auto wb = get_float(pl, "whitebalance"); wb && *wb != 0) {
        if (*wb >= 1000 && *wb <= 100000) d_.integrator.path.white_balance = float(*wb);
        else diag_.error(pl.find("whitebalance")->loc, fmt::format("\"whitebalance\": {} K is outside 1000-100000 K", *wb));
    }
    ignore_rest(pl, "Film: parameter \"{}\" ignored (glint writes linear radiance)");
}


void Parser::finish() {
    if (!stack_.empty()) diag_.error(stack_.back().second, "AttributeBegin without AttributeEnd");
    if (!transform_stack_.empty()) diag_.error(transform_stack_.back().second, "TransformBegin without TransformEnd");
    if (defining_) diag_.error(defining_->second, "ObjectBegin without ObjectEnd");
    // pbrt's fov spans the shorter image axis; glint's is vertical.
    // So do its screen window's units and an orthographic camera's extent.
    if (auto* cam = std::get_if<LookAtCameraDesc>(&d_.camera)) {
        const double w = d_.film.width.value, h = d_.film.height.value;
        if (w < h && w > 0) {
            const double half = cam->fov * std::numbers::pi / 360;
            cam->fov = float(2 * std::atan(std::tan(half) * h / w) * 180 / std::numbers::pi);
            cam->height = Float(cam->height * h / w);
            if (cam->window)
                for (Float& v : *cam->window) v = Float(v * w / h);
        }
    }
    const double ratio = exposure_time_ * film_ratio_;
    if (ratio != 1) d_.film.scale = float(ratio);
}

}  // namespace pbrt_detail

using pbrt_detail::Parser;

bool is_pbrt_file(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return ext == ".pbrt";
}

SceneDescription parse_pbrt(const std::string& text, const std::string& path, std::shared_ptr<SourceFiles> sources,
                            const PbrtOptions& options) {
    reset_memory_budget();  // a new scene
    SceneDescription d;
    d.path = path;
    // pbrt's defaults where they differ from glint's: a path tracer of depth 5, 16 spp, a
    // 1280x720 film, a Gaussian filter, a black background, a perspective camera of fov 90.
    d.integrator.kind = IntegratorKind::kPath;
    d.integrator.max_depth.value = 5;
    d.integrator.path.spectral = true;  // pbrt-v4 traces wavelengths; so does glint for its files
    d.sampler.spp.value = 16;
    d.film.width.value = 1280;
    d.film.height.value = 720;
    d.film.filter = FilterDesc{FilterType::kGaussian, 1.5f, 0.5f};
    d.background = ConstantBackground{Color{0}};
    LookAtCameraDesc cam;
    cam.from = {0, 0, 0};
    cam.to = {0, 0, 1};
    cam.fov = 90;
    d.camera = cam;
    Diagnostics diag(sources);
    Parser parser(d, diag, sources, options);
    parser.run_file(text, path, 0);
    parser.finish();
    diag.throw_if_errors();
    return d;
}

SceneDescription load_pbrt_file(const std::string& path, std::shared_ptr<SourceFiles> sources,
                                const PbrtOptions& options) {
    const std::string text = read_scene_text(path, sources);
    return parse_pbrt(text, path, std::move(sources), options);
}

}  // namespace glint
