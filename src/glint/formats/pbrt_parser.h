#pragma once
// The pbrt-v4 reader's inside, shared by its files (not part of the library's interface):
// pbrt_params.cpp (tokens and typed parameters), pbrt.cpp (directives, camera, film, the entry
// points), pbrt_shapes.cpp (shapes and area-light power), pbrt_materials.cpp (materials, lights,
// textures, media). pbrt.h is the interface.
#include <fmt/core.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "glint/formats/pbrt.h"
#include "glint/spectra/spectrum.h"

namespace glint::pbrt_detail {

// ---------------------------------------------------------------------------------------------
// Tokens

struct Token {
    enum class Kind { kWord, kNumber, kString, kOpen, kClose };
    Kind kind;
    std::string_view text;  ///< a string's contents, unquoted and unescaped; a view into the file
    double number = 0;
    const std::string* file = nullptr;
    int line = 0, column = 0;
    SourceLoc loc() const { return {*file, line, column}; }
};

// Reads pbrt text a token at a time (views into `text`, which must outlive them); errors (an
// unterminated string, a stray character) go to `diag`. Strings with escapes are unescaped into
// `unescaped`, whose elements do not move. One token of look-ahead: no token array, so a large
// mesh costs no more memory than its numbers.
class Lexer {
public:
    Lexer(const std::string& text, const std::string* file, Diagnostics& diag, std::deque<std::string>& unescaped)
        : base_(text.data()), n_(text.size()), file_(file), diag_(diag), unescaped_(unescaped) {
        advance();
    }
    bool done() const { return !has_; }
    const Token& peek() const { return tok_; }
    Token next() {
        Token t = tok_;
        advance();
        return t;
    }

private:
    void advance();
    const char* base_;
    std::size_t n_, i_ = 0, line_start_ = 0;
    int line_ = 1;
    const std::string* file_;
    Diagnostics& diag_;
    std::deque<std::string>& unescaped_;
    Token tok_{};
    bool has_ = false;
};


// ---------------------------------------------------------------------------------------------
// Transforms, in double (pbrt's own Transform is float; double keeps a LookAt inverted back to
// its exact float inputs).

struct M4 {
    std::array<std::array<double, 4>, 4> m{{{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}}};

    M4 operator*(const M4& b) const {
        M4 r;
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j) {
                double s = 0;
                for (int k = 0; k < 4; ++k) s += m[i][k] * b.m[k][j];
                r.m[i][j] = s;
            }
        return r;
    }
    std::array<double, 3> point(double x, double y, double z) const {
        std::array<double, 3> r;
        for (int i = 0; i < 3; ++i) r[i] = m[i][0] * x + m[i][1] * y + m[i][2] * z + m[i][3];
        const double w = m[3][0] * x + m[3][1] * y + m[3][2] * z + m[3][3];
        if (w != 1 && w != 0)
            for (double& v : r) v /= w;
        return r;
    }
    std::array<double, 3> vector(double x, double y, double z) const {
        std::array<double, 3> r;
        for (int i = 0; i < 3; ++i) r[i] = m[i][0] * x + m[i][1] * y + m[i][2] * z;
        return r;
    }
    double det3() const {
        return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
               m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    }
    bool affine() const { return m[3][0] == 0 && m[3][1] == 0 && m[3][2] == 0 && m[3][3] == 1; }
    /// Gauss-Jordan with partial pivoting; nullopt when singular.
    std::optional<M4> inverse() const {
        std::array<std::array<double, 8>, 4> a;
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 8; ++j) a[i][j] = j < 4 ? m[i][j] : (j - 4 == i ? 1 : 0);
        for (int c = 0; c < 4; ++c) {
            int p = c;
            for (int r = c + 1; r < 4; ++r)
                if (std::abs(a[r][c]) > std::abs(a[p][c])) p = r;
            if (!(std::abs(a[p][c]) > 1e-300)) return std::nullopt;
            std::swap(a[p], a[c]);
            const double inv = 1 / a[c][c];
            for (double& v : a[c]) v *= inv;
            for (int r = 0; r < 4; ++r) {
                if (r == c || a[r][c] == 0) continue;
                const double f = a[r][c];
                for (int j = 0; j < 8; ++j) a[r][j] -= f * a[c][j];
            }
        }
        M4 r;
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j) r.m[i][j] = a[i][j + 4];
        return r;
    }
    Matrix34 to34() const {
        Matrix34 r;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 4; ++j) r.m[i][j] = static_cast<Float>(m[i][j]);
        return r;
    }
    bool identity() const { return *this == M4{}; }
    bool operator==(const M4&) const = default;
};

inline M4 translate(double x, double y, double z) {
    M4 t;
    t.m[0][3] = x, t.m[1][3] = y, t.m[2][3] = z;
    return t;
}
inline M4 scale(double x, double y, double z) {
    M4 t;
    t.m[0][0] = x, t.m[1][1] = y, t.m[2][2] = z;
    return t;
}
// pbrt's Rotate(theta, axis): Rodrigues' rotation about the normalised axis.
inline M4 rotate(double degrees, double x, double y, double z) {
    const double len = std::sqrt(x * x + y * y + z * z);
    x /= len, y /= len, z /= len;
    const double th = degrees * std::numbers::pi / 180, s = std::sin(th), c = std::cos(th);
    M4 r;
    r.m[0] = {x * x + (1 - x * x) * c, x * y * (1 - c) - z * s, x * z * (1 - c) + y * s, 0};
    r.m[1] = {x * y * (1 - c) + z * s, y * y + (1 - y * y) * c, y * z * (1 - c) - x * s, 0};
    r.m[2] = {x * z * (1 - c) - y * s, y * z * (1 - c) + x * s, z * z + (1 - z * z) * c, 0};
    return r;
}
using D3 = std::array<double, 3>;
inline D3 sub(D3 a, D3 b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
inline D3 cross3(D3 a, D3 b) { return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}; }
inline double len3(D3 a) { return std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]); }
inline D3 unit3(D3 a) {
    const double l = len3(a);
    return {a[0] / l, a[1] / l, a[2] / l};
}
// pbrt's LookAt: the world-to-camera transform of a camera at `eye` looking at `look`.
inline std::optional<M4> look_at(D3 eye, D3 look, D3 up) {
    const D3 dir = sub(look, eye);
    if (!(len3(dir) > 0)) return std::nullopt;
    const D3 d = unit3(dir);
    const D3 right0 = cross3(unit3(up), d);
    if (!(len3(right0) > 0)) return std::nullopt;
    const D3 right = unit3(right0);
    const D3 new_up = cross3(d, right);
    M4 camera_to_world;
    for (int i = 0; i < 3; ++i) {
        camera_to_world.m[i][0] = right[i];
        camera_to_world.m[i][1] = new_up[i];
        camera_to_world.m[i][2] = d[i];
        camera_to_world.m[i][3] = eye[i];
    }
    return camera_to_world.inverse();
}

// ---------------------------------------------------------------------------------------------
// Parameters: "type name" followed by a value or [ values ].

struct Param {
    std::string type, name;
    std::vector<double> numbers;
    std::vector<std::string> strings;
    std::vector<bool> bools;
    SourceLoc loc;
    bool used = false;
};

struct ParamList {
    std::vector<Param> params;
    /// Marks every parameter read: the directive was replaced as a whole (and warned about).
    void use_all() {
        for (Param& p : params) p.used = true;
    }
    Param* find(const std::string& name) {
        for (Param& p : params)
            if (p.name == name) return &p;
        return nullptr;
    }
};

inline constexpr std::array kParamTypes{"integer", "float",  "point2", "vector2", "point3",    "vector3", "normal3",
                                 "normal",  "point",  "vector", "bool",    "string",    "texture", "rgb",
                                 "color",   "spectrum", "blackbody", "point4"};

// Camera, shapes, lights and media that hold a medium or a transform state.
struct GraphicsState {
    M4 ctm;
    /// pbrt's second transform, at the end time (TransformTimes): it differs from ctm where an
    /// ActiveTransform StartTime / EndTime block moved one of them; then shapes move.
    M4 ctm_end;
    int active = 3;  ///< which transforms directives change: 1 the start's, 2 the end's
    bool reverse_orientation = false;
    std::string material;  ///< the name of a SceneDescription material ("" before any)
    std::optional<Emission> area_light;
    SourceLoc area_light_loc;
    std::optional<Located<double>> area_power;  ///< the area light's "power": per shape, as pbrt
    std::string inside, outside;  ///< named media; "" = none
};

struct TextureEntry {
    TextureDesc desc;
    bool is_float = false;
};

class Parser {
public:
    Parser(SceneDescription& d, Diagnostics& diag, std::shared_ptr<SourceFiles> sources, const PbrtOptions& options)
        : d_(d), diag_(diag), sources_(std::move(sources)), options_(options) {}

    void run_file(const std::string& text, const std::string& path, int depth);
    void finish();

private:
    // token stream of one file
    using Stream = Lexer;

    void warn(const SourceLoc& loc, std::string message) {
        if (options_.strict) {
            diag_.error(loc, message + " (--strict)");
        } else {
            d_.warnings.push_back({loc, std::move(message)});
        }
    }
    void directive(Stream& s, const Token& t, int depth);
    bool transform_directive(Stream& s, const Token& t, const std::string& name);
    bool block_directive(const Token& t, const std::string& name);
    bool include_directive(Stream& s, const Token& t, const std::string& name, int depth);
    bool typed_directive(Stream& s, const Token& t, const std::string& name);
    bool named_directive(Stream& s, const Token& t, const std::string& name);
    bool object_directive(Stream& s, const Token& t, const std::string& name);
    bool ignored_directive(Stream& s, const Token& t, const std::string& name);
    bool numbers(Stream& s, const Token& at, int n, std::vector<double>& out);
    std::optional<std::string> string_arg(Stream& s, const Token& at);
    ParamList params(Stream& s);
    void check_unused(ParamList& pl, const std::string& what);
    /// A parameter glint accepts but does not apply: read, and warned about with `message`.
    void ignore(ParamList& pl, const std::string& name, const std::string& message) {
        if (Param* p = pl.find(name)) {
            p->used = true;
            warn(p->loc, message);
        }
    }
    /// The same for several parameters, each warned about as "name" `why`.
    void ignore(ParamList& pl, std::initializer_list<const char*> names, const char* why) {
        for (const char* n : names) ignore(pl, n, fmt::format("\"{}\" {}", n, why));
    }
    /// Every parameter not read yet: warned about, `message` formatted with its name.
    void ignore_rest(ParamList& pl, const std::string& message) {
        for (Param& p : pl.params)
            if (!p.used) ignore(pl, p.name, fmt::format(fmt::runtime(message), p.name));
    }

    // typed parameter access (marks used; wrong types are errors)
    std::optional<double> get_float(ParamList& pl, const std::string& name);
    std::optional<int> get_int(ParamList& pl, const std::string& name);
    std::optional<bool> get_bool(ParamList& pl, const std::string& name);
    std::optional<std::string> get_string(ParamList& pl, const std::string& name);
    /// The values (in the ParamList, not copied: meshes are large), or null.
    const std::vector<double>* get_floats(ParamList& pl, const std::string& name, const char* type, int multiple);
    std::optional<Color> get_color(ParamList& pl, const std::string& name, bool illuminant);
    /// A "spectrum" parameter as a spectrum (a named one, or inline wavelength-value pairs) for
    /// spectral mode; null when the parameter is absent or not a spectrum.
    std::shared_ptr<const Spectrum> get_spectrum(ParamList& pl, const std::string& name);
    std::shared_ptr<const Spectrum> emission_spectrum(ParamList& pl, const std::string& name);
    void light_spectrum(ParamList& pl, const std::string& name);
    std::optional<PiecewiseLinearSpectrum> spectrum_values(const Param& p, const std::string& name, bool report = true);
    std::optional<TextureDesc> get_texture(ParamList& pl, const std::string& name, bool is_float, float fallback);

    void camera(const Token& t, const std::string& type, ParamList pl);
    void film(const Token& t, const std::string& type, ParamList pl);
    void shape(const Token& t, const std::string& type, ParamList pl);
    void sphere_shape(const Token& t, const std::string& type, ParamList& pl, ObjectDesc o,
                      const std::optional<AlphaDesc>& alpha);
    void disk_shape(const Token& t, const std::string& type, ParamList& pl, ObjectDesc o,
                      const std::optional<AlphaDesc>& alpha);
    void triangle_mesh_shape(const Token& t, const std::string& type, ParamList& pl, ObjectDesc o,
                      const std::optional<AlphaDesc>& alpha);
    void loop_subdiv_shape(const Token& t, const std::string& type, ParamList& pl, ObjectDesc o,
                      const std::optional<AlphaDesc>& alpha);
    void cylinder_shape(const Token& t, const std::string& type, ParamList& pl, ObjectDesc o,
                      const std::optional<AlphaDesc>& alpha);
    void ply_mesh_shape(const Token& t, const std::string& type, ParamList& pl, ObjectDesc o,
                      const std::optional<AlphaDesc>& alpha);
    void no_alpha_here(const std::optional<AlphaDesc>& alpha, const std::string& type);
    std::optional<MaterialDesc> material(const Token& t, const std::string& type, ParamList& pl);
    void layer(MaterialDesc& m, ParamList& pl);
    void light(const Token& t, const std::string& type, ParamList pl);
    void area_light(const Token& t, const std::string& type, ParamList pl);
    void apply_area_power(const ObjectDesc& o, const std::vector<double>& areas);
    double world_area(Point3 a, Point3 b, Point3 c) const;
    void texture(const Token& t, const std::string& name, const std::string& kind, const std::string& type, ParamList pl);
    void medium(const Token& t, const std::string& name, ParamList pl);
    /// `end`: the placement at the end time (default: the current end-time transform).
    void add_object(ObjectDesc o, const M4& m, std::optional<M4> end = std::nullopt);
    std::string material_for_shape();

    SceneDescription& d_;
    Diagnostics& diag_;
    std::shared_ptr<SourceFiles> sources_;
    PbrtOptions options_;
    std::filesystem::path dir_;  ///< of the main file: pbrt resolves every file name against it
    bool dir_set_ = false;
    GraphicsState gs_;
    std::vector<std::pair<GraphicsState, SourceLoc>> stack_;  ///< AttributeBegin/End
    std::vector<std::pair<std::array<M4, 2>, SourceLoc>> transform_stack_;   ///< TransformBegin/End
    std::array<double, 2> transform_times_{0, 1};             ///< TransformTimes
    /// Where `time` falls between the transform times, in [0, 1]: pbrt holds the start's
    /// transform before them and the end's after.
    Float transform_fraction(double time) const {
        const double t0 = transform_times_[0], t1 = transform_times_[1];
        return static_cast<Float>(t1 > t0 ? std::clamp((time - t0) / (t1 - t0), 0.0, 1.0) : (time < t0 ? 0.0 : 1.0));
    }
    /// The object's placement over the shutter from its transforms at the start and end times
    /// (empty when they are equal).
    std::vector<Transform> motion_keys(const M4& start, const M4& end, const SourceLoc& loc);
    std::map<std::string, M4> coordinate_systems_;
    std::map<std::string, TextureEntry> textures_;
    std::map<std::string, std::string> named_materials_;  ///< pbrt name -> SceneDescription name
    std::set<std::string> media_;
    int material_count_ = 0;
    bool world_ = false;
    bool camera_seen_ = false;
    double exposure_time_ = 1;  ///< the camera's shutter interval
    double film_ratio_ = 1;     ///< the film's part of the imaging ratio
    // ObjectBegin .. ObjectEnd: the objects recorded (their transforms relative to the world)
    std::map<std::string, std::vector<ObjectDesc>> instances_;
    std::optional<std::pair<std::string, SourceLoc>> defining_;
    std::deque<std::string> names_;      ///< file names the tokens point to (a deque: they do not move)
    std::deque<std::string> unescaped_;  ///< strings with escapes, unescaped
};


}  // namespace glint::pbrt_detail
