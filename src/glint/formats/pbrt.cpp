#include "glint/formats/pbrt.h"

#include "glint/base/limits.h"

#include <fmt/core.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <charconv>
#include <cstring>
#include <deque>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <set>
#include <sstream>

#include "glint/image/image_io.h"
#include "glint/materials/metals.h"
#include "glint/media/medium.h"
#include "glint/shapes/subdivision.h"

namespace glint {

namespace {

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

void Lexer::advance() {
    const char* const base = base_;
    const std::size_t n = n_;
    std::size_t i = i_;
    has_ = false;
    while (i < n) {
        const char c = base[i];
        if (c == '\n') {
            ++line_;
            line_start_ = ++i;
            continue;
        }
        if (c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v') {
            ++i;
            continue;
        }
        if (c == '#') {
            while (i < n && base[i] != '\n') ++i;
            continue;
        }
        Token tok;
        tok.file = file_;
        tok.line = line_;
        tok.column = static_cast<int>(i - line_start_) + 1;
        if (c == '[' || c == ']') {
            tok.kind = c == '[' ? Token::Kind::kOpen : Token::Kind::kClose;
            tok.text = std::string_view(base + i, 1);
            ++i;
        } else if (c == '"') {
            const std::size_t start = ++i;
            bool escaped = false;
            while (i < n && base[i] != '"' && base[i] != '\n') {
                if (base[i] == '\\' && i + 1 < n && base[i + 1] != '\n') {
                    escaped = true;
                    ++i;
                }
                ++i;
            }
            if (i >= n || base[i] != '"') {
                diag_.error(tok.loc(), "unterminated string");
                continue;
            }
            tok.kind = Token::Kind::kString;
            tok.text = std::string_view(base + start, i - start);
            ++i;
            if (escaped) {
                std::string u;
                for (std::size_t k = 0; k < tok.text.size(); ++k) {
                    char e = tok.text[k];
                    if (e == '\\' && k + 1 < tok.text.size()) {
                        e = tok.text[++k];
                        e = e == 'n' ? '\n' : e == 't' ? '\t' : e;
                    }
                    u += e;
                }
                unescaped_.push_back(std::move(u));
                tok.text = unescaped_.back();
            }
        } else {
            std::size_t j = i;
            while (j < n && base[j] != ' ' && base[j] != '\n' && base[j] != '\t' && base[j] != '\r' && base[j] != '"' &&
                   base[j] != '[' && base[j] != ']' && base[j] != '#' && base[j] != '\f' && base[j] != '\v')
                ++j;
            tok.text = std::string_view(base + i, j - i);
            i = j;
            const char first = tok.text[0];
            if ((first >= '0' && first <= '9') || first == '-' || first == '+' || first == '.') {
                const char* b = tok.text.data();
                const char* e = b + tok.text.size();
                if (*b == '+') ++b;  // from_chars takes no plus sign
                double v = 0;
                const auto r = std::from_chars(b, e, v);
                if (r.ec != std::errc() || r.ptr != e || !std::isfinite(v)) {
                    diag_.error(tok.loc(), fmt::format("'{}' is not a number", tok.text));
                    continue;
                }
                tok.kind = Token::Kind::kNumber;
                tok.number = v;
            } else if ((first >= 'a' && first <= 'z') || (first >= 'A' && first <= 'Z')) {
                tok.kind = Token::Kind::kWord;
            } else {
                diag_.error(tok.loc(), fmt::format("unexpected '{}'", tok.text));
                continue;
            }
        }
        tok_ = tok;
        has_ = true;
        break;
    }
    i_ = i;
}

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

M4 translate(double x, double y, double z) {
    M4 t;
    t.m[0][3] = x, t.m[1][3] = y, t.m[2][3] = z;
    return t;
}
M4 scale(double x, double y, double z) {
    M4 t;
    t.m[0][0] = x, t.m[1][1] = y, t.m[2][2] = z;
    return t;
}
// pbrt's Rotate(theta, axis): Rodrigues' rotation about the normalised axis.
M4 rotate(double degrees, double x, double y, double z) {
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
D3 sub(D3 a, D3 b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
D3 cross3(D3 a, D3 b) { return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}; }
double len3(D3 a) { return std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]); }
D3 unit3(D3 a) {
    const double l = len3(a);
    return {a[0] / l, a[1] / l, a[2] / l};
}
// pbrt's LookAt: the world-to-camera transform of a camera at `eye` looking at `look`.
std::optional<M4> look_at(D3 eye, D3 look, D3 up) {
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

constexpr std::array kParamTypes{"integer", "float",  "point2", "vector2", "point3",    "vector3", "normal3",
                                 "normal",  "point",  "vector", "bool",    "string",    "texture", "rgb",
                                 "color",   "spectrum", "blackbody", "point4"};

// Camera, shapes, lights and media that hold a medium or a transform state.
struct GraphicsState {
    M4 ctm;
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
    std::optional<TextureDesc> get_texture(ParamList& pl, const std::string& name, bool is_float, float fallback);

    void camera(const Token& t, const std::string& type, ParamList pl);
    void film(const Token& t, const std::string& type, ParamList pl);
    void shape(const Token& t, const std::string& type, ParamList pl);
    std::optional<MaterialDesc> material(const Token& t, const std::string& type, ParamList& pl);
    void layer(MaterialDesc& m, ParamList& pl);
    void light(const Token& t, const std::string& type, ParamList pl);
    void area_light(const Token& t, const std::string& type, ParamList pl);
    void apply_area_power(const ObjectDesc& o, const std::vector<double>& areas);
    double world_area(Point3 a, Point3 b, Point3 c) const;
    void texture(const Token& t, const std::string& name, const std::string& kind, const std::string& type, ParamList pl);
    void medium(const Token& t, const std::string& name, ParamList pl);
    void add_object(ObjectDesc o, const M4& m);
    std::string material_for_shape();

    SceneDescription& d_;
    Diagnostics& diag_;
    std::shared_ptr<SourceFiles> sources_;
    PbrtOptions options_;
    std::filesystem::path dir_;  ///< of the main file: pbrt resolves every file name against it
    bool dir_set_ = false;
    GraphicsState gs_;
    std::vector<std::pair<GraphicsState, SourceLoc>> stack_;  ///< AttributeBegin/End
    std::vector<std::pair<M4, SourceLoc>> transform_stack_;   ///< TransformBegin/End
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


void Parser::check_unused(ParamList& pl, const std::string& what) {
    for (Param& p : pl.params)
        if (!p.used) diag_.error(p.loc, fmt::format("{}: unknown parameter \"{} {}\"", what, p.type, p.name));
}

std::optional<double> Parser::get_float(ParamList& pl, const std::string& name) {
    Param* p = pl.find(name);
    if (!p) return std::nullopt;
    p->used = true;
    if (p->type == "texture") {  // pbrt allows float textures in many places; glint, constants
        warn(p->loc, fmt::format("\"{}\": float textures are not supported here; using the default", name));
        return std::nullopt;
    }
    if (p->type != "float" && p->type != "integer") {
        diag_.error(p->loc, fmt::format("\"{}\" must be a float, not {}", name, p->type));
        return std::nullopt;
    }
    if (p->numbers.size() != 1) {
        diag_.error(p->loc, fmt::format("\"{}\" takes one value, got {}", name, p->numbers.size()));
        return std::nullopt;
    }
    return p->numbers[0];
}

std::optional<int> Parser::get_int(ParamList& pl, const std::string& name) {
    Param* p = pl.find(name);
    if (!p) return std::nullopt;
    p->used = true;
    if (p->type != "integer" || p->numbers.size() != 1 || p->numbers[0] != std::floor(p->numbers[0]) ||
        std::abs(p->numbers[0]) > 2147483647.0) {
        diag_.error(p->loc, fmt::format("\"{}\" must be one integer", name));
        return std::nullopt;
    }
    return static_cast<int>(p->numbers[0]);
}

std::optional<bool> Parser::get_bool(ParamList& pl, const std::string& name) {
    Param* p = pl.find(name);
    if (!p) return std::nullopt;
    p->used = true;
    if (p->type != "bool" || p->bools.size() != 1) {
        diag_.error(p->loc, fmt::format("\"{}\" must be one bool (true or false)", name));
        return std::nullopt;
    }
    return p->bools[0];
}

std::optional<std::string> Parser::get_string(ParamList& pl, const std::string& name) {
    Param* p = pl.find(name);
    if (!p) return std::nullopt;
    p->used = true;
    if ((p->type != "string" && p->type != "texture") || p->strings.size() != 1) {
        diag_.error(p->loc, fmt::format("\"{}\" must be one string", name));
        return std::nullopt;
    }
    return p->strings[0];
}

const std::vector<double>* Parser::get_floats(ParamList& pl, const std::string& name, const char* type,
                                                      int multiple) {
    Param* p = pl.find(name);
    if (!p) return nullptr;
    p->used = true;
    const std::string t = p->type;
    const bool ok = t == type || (std::strcmp(type, "point3") == 0 && t == "point") ||
                    (std::strcmp(type, "normal3") == 0 && t == "normal") ||
                    (std::strcmp(type, "vector3") == 0 && t == "vector") ||
                    (std::strcmp(type, "float") == 0 && t == "integer");
    if (!ok) {
        diag_.error(p->loc, fmt::format("\"{}\" must be of type {}, not {}", name, type, t));
        return nullptr;
    }
    if (p->numbers.size() % static_cast<std::size_t>(multiple) != 0) {
        diag_.error(p->loc, fmt::format("\"{}\": {} values is not a multiple of {}", name, p->numbers.size(), multiple));
        return nullptr;
    }
    return &p->numbers;
}

// pbrt-v4's named spectra that glint knows as metals (the rest are reported).
struct NamedSpectrum {
    const char* name;
    const char* metal;
    bool k;
};
constexpr std::array kNamedSpectra{
    NamedSpectrum{"metal-Ag-eta", "silver", false}, NamedSpectrum{"metal-Ag-k", "silver", true},
    NamedSpectrum{"metal-Al-eta", "aluminium", false}, NamedSpectrum{"metal-Al-k", "aluminium", true},
    NamedSpectrum{"metal-Au-eta", "gold", false}, NamedSpectrum{"metal-Au-k", "gold", true},
    NamedSpectrum{"metal-Cu-eta", "copper", false}, NamedSpectrum{"metal-Cu-k", "copper", true},
};

float luminance(Color c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; }

// A colour parameter: rgb, blackbody (for lights normalised to luminance 1, as pbrt-v4 normalises
// light spectra photometrically), a named metal spectrum, or a constant spectrum value.
std::optional<Color> Parser::get_color(ParamList& pl, const std::string& name, bool illuminant) {
    Param* p = pl.find(name);
    if (!p) return std::nullopt;
    p->used = true;
    if (p->type == "rgb" || p->type == "color") {
        if (p->numbers.size() != 3) {
            diag_.error(p->loc, fmt::format("\"{}\": rgb takes 3 values, got {}", name, p->numbers.size()));
            return std::nullopt;
        }
        return Color{float(p->numbers[0]), float(p->numbers[1]), float(p->numbers[2])};
    }
    if (p->type == "float" && p->numbers.size() == 1) return Color{float(p->numbers[0])};
    if (p->type == "blackbody") {
        if (p->numbers.size() != 1 || !(p->numbers[0] > 0)) {
            diag_.error(p->loc, fmt::format("\"{}\": blackbody takes one temperature in kelvin", name));
            return std::nullopt;
        }
        Color c = blackbody_rgb(float(p->numbers[0]));
        if (illuminant && luminance(c) > 0) c = c / luminance(c);
        return c;
    }
    if (p->type == "spectrum") {
        if (p->strings.size() == 1) {
            for (const NamedSpectrum& n : kNamedSpectra) {
                if (p->strings[0] != n.name) continue;
                for (const MetalPreset& m : kMetals)
                    if (m.name == n.metal) return n.k ? m.k : m.eta;
            }
            if (p->strings[0].rfind("glass-", 0) == 0) {
                warn(p->loc, fmt::format("spectrum \"{}\": dispersion is not rendered; using 1.5", p->strings[0]));
                return Color{1.5f};
            }
            warn(p->loc, fmt::format("named spectrum \"{}\" not known to glint; using 1", p->strings[0]));
            return Color{1};
        }
        if (p->numbers.size() == 1) return Color{float(p->numbers[0])};
        warn(p->loc, fmt::format("\"{}\": tabulated spectra are not converted; using their mean", name));
        double sum = 0;
        int n = 0;
        for (std::size_t i = 1; i < p->numbers.size(); i += 2) sum += p->numbers[i], ++n;
        return Color{n > 0 ? float(sum / n) : 1.0f};
    }
    diag_.error(p->loc, fmt::format("\"{}\" must be rgb, spectrum or blackbody, not {}", name, p->type));
    return std::nullopt;
}

std::optional<TextureDesc> Parser::get_texture(ParamList& pl, const std::string& name, bool is_float, float fallback) {
    Param* p = pl.find(name);
    if (!p) return std::nullopt;
    if (p->type == "texture") {
        p->used = true;
        if (p->strings.size() != 1) {
            diag_.error(p->loc, fmt::format("\"{}\" must name one texture", name));
            return std::nullopt;
        }
        const auto it = textures_.find(p->strings[0]);
        if (it == textures_.end()) {
            diag_.error(p->loc, fmt::format("unknown texture \"{}\"", p->strings[0]));
            return std::nullopt;
        }
        return it->second.desc;
    }
    std::optional<Color> c;
    if (is_float) {
        if (const auto v = get_float(pl, name)) c = Color{float(*v)};
    } else {
        c = get_color(pl, name, false);
    }
    TextureDesc t;
    t.value = c.value_or(Color{fallback});
    return t;
}

bool Parser::numbers(Stream& s, const Token& at, int n, std::vector<double>& out) {
    out.clear();
    for (int i = 0; i < n; ++i) {
        if (s.done() || s.peek().kind != Token::Kind::kNumber) {
            diag_.error(s.done() ? at.loc() : s.peek().loc(),
                        fmt::format("{} takes {} numbers, found {}", at.text, n, i));
            return false;
        }
        out.push_back(s.next().number);
    }
    return true;
}

std::optional<std::string> Parser::string_arg(Stream& s, const Token& at) {
    if (s.done() || s.peek().kind != Token::Kind::kString) {
        diag_.error(s.done() ? at.loc() : s.peek().loc(), fmt::format("{} needs a quoted string here", at.text));
        return std::nullopt;
    }
    return std::string(s.next().text);
}

ParamList Parser::params(Stream& s) {
    ParamList pl;
    while (!s.done() && s.peek().kind == Token::Kind::kString) {
        const Token decl = s.next();
        std::istringstream words{std::string(decl.text)};
        Param p;
        std::string extra;
        words >> p.type >> p.name >> extra;
        p.loc = decl.loc();
        bool ok = true;
        if (p.name.empty() || !extra.empty()) {
            diag_.error(decl.loc(), fmt::format("a parameter is declared \"type name\", not \"{}\"", decl.text));
            ok = false;
        } else if (std::find(kParamTypes.begin(), kParamTypes.end(), p.type) == kParamTypes.end()) {
            std::vector<std::string> types(kParamTypes.begin(), kParamTypes.end());
            const std::string guess = closest_match(p.type, types);
            diag_.error(decl.loc(), fmt::format("unknown parameter type '{}'{}", p.type,
                                                guess.empty() ? "" : fmt::format("; did you mean '{}'?", guess)));
            ok = false;
        }
        if (s.done()) {
            diag_.error(decl.loc(), fmt::format("parameter \"{}\" has no value", decl.text));
            break;
        }
        // A value is a string for these types (a spectrum: a name, or numbers).
        int count = 0;
        const bool is_bool = p.type == "bool", is_spectrum = p.type == "spectrum";
        bool stringy = p.type == "string" || p.type == "texture" || is_bool;
        const auto take = [&](const Token& v) {
            if (count++ == 0 && is_spectrum) stringy = v.kind == Token::Kind::kString;
            if (!ok) return;
            const bool bare_bool = v.kind == Token::Kind::kWord;  // true / false unquoted
            if (is_bool && bare_bool) {
                p.bools.push_back(v.text == "true");
            } else if (stringy != (v.kind == Token::Kind::kString)) {
                diag_.error(v.loc(), fmt::format("\"{}\": expected {}, got '{}'", decl.text,
                                                 stringy ? "quoted strings" : "numbers", v.text));
                ok = false;
            } else if (is_bool) {
                if (v.text != "true" && v.text != "false") {
                    diag_.error(v.loc(), fmt::format("\"{}\": expected \"true\" or \"false\"", decl.text));
                    ok = false;
                }
                p.bools.push_back(v.text == "true");
            } else if (stringy) {
                p.strings.emplace_back(v.text);
            } else {
                p.numbers.push_back(v.number);
            }
        };
        // pbrt-v4 writes bools bare or quoted: `"bool twosided" true`, `[ "true" ]`.
        const auto is_value = [&](const Token& v) {
            return v.kind == Token::Kind::kNumber || v.kind == Token::Kind::kString ||
                   (is_bool && v.kind == Token::Kind::kWord && (v.text == "true" || v.text == "false"));
        };
        if (s.peek().kind == Token::Kind::kOpen) {
            const Token open = s.next();
            while (!s.done() && is_value(s.peek())) take(s.next());
            if (s.done() || s.peek().kind != Token::Kind::kClose) {
                diag_.error(open.loc(), "'[' without a matching ']'");
                continue;
            }
            s.next();
        } else if (is_value(s.peek())) {
            take(s.next());
        } else {
            diag_.error(s.peek().loc(), fmt::format("parameter \"{}\" has no value", decl.text));
            continue;
        }
        if (count == 0) {
            diag_.error(decl.loc(), fmt::format("parameter \"{}\" has an empty value", decl.text));
            ok = false;
        }
        if (!ok) continue;
        if (pl.find(p.name)) {
            diag_.error(decl.loc(), fmt::format("parameter \"{}\" given twice", p.name));
            continue;
        }
        pl.params.push_back(std::move(p));
    }
    return pl;
}

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

void Parser::directive(Stream& s, const Token& t, int depth) {
    const std::string name(t.text);
    std::vector<double> v;
    const auto concat = [&](const M4& m) { gs_.ctm = gs_.ctm * m; };
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
            if (name == "Transform") gs_.ctm = m; else concat(m);
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
                gs_.ctm = it->second;
        }
    } else if (name == "ReverseOrientation") {
        gs_.reverse_orientation = !gs_.reverse_orientation;
    } else if (name == "AttributeBegin" || name == "TransformBegin") {
        // Nesting is policy (the nesting limit), not the memory of the state stack.
        const auto nesting = static_cast<long long>(stack_.size() + transform_stack_.size()) + 1;
        if (nesting > limit(Limit::kNesting)) {
            diag_.error(t.loc(), fmt::format("{}: {}", name, over_limit(Limit::kNesting, nesting)));
            diag_.throw_if_errors();
        }
        if (name == "AttributeBegin") stack_.push_back({gs_, t.loc()});
        else transform_stack_.push_back({gs_.ctm, t.loc()});
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
            gs_.ctm = transform_stack_.back().first;
            transform_stack_.pop_back();
        }
    } else if (name == "Include" || name == "Import") {
        const auto file = string_arg(s, t);
        if (!file) return;
        if (depth >= limit(Limit::kIncludes)) {
            diag_.error(t.loc(), fmt::format("{}: {}", name, over_limit(Limit::kIncludes, depth + 1)));
            return;
        }
        const std::filesystem::path p = std::filesystem::path(*file).is_absolute() ? std::filesystem::path(*file) : dir_ / *file;
        if (const std::string why = why_not_readable(p); !why.empty()) {
            diag_.error(t.loc(), fmt::format("{}: cannot read '{}': it {}", name, p.string(), why));
            return;
        }
        std::ifstream in(p, std::ios::binary);
        if (!in) {
            diag_.error(t.loc(), fmt::format("{}: cannot open '{}': {}", name, p.string(), std::strerror(errno)));
            return;
        }
        std::ostringstream text;
        text << in.rdbuf();
        run_file(text.str(), p.string(), depth + 1);
    } else if (name == "WorldBegin") {
        if (world_) diag_.error(t.loc(), "WorldBegin given twice");
        world_ = true;
        gs_.ctm = M4{};
        coordinate_systems_["world"] = gs_.ctm;
    } else if (name == "WorldEnd") {
        // pbrt-v3's end of the scene; pbrt-v4 files end without it.
    } else if (name == "Camera" || name == "Film" || name == "Sampler" || name == "Integrator" ||
               name == "PixelFilter" || name == "Shape" || name == "LightSource" || name == "AreaLightSource" ||
               name == "Material" || name == "Accelerator") {
        const auto type = string_arg(s, t);
        ParamList pl = params(s);
        if (!type) return;
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
    } else if (name == "MakeNamedMaterial") {
        const auto n = string_arg(s, t);
        ParamList pl = params(s);
        if (!n) return;
        const auto type = get_string(pl, "type");
        if (!type) {
            diag_.error(t.loc(), fmt::format("MakeNamedMaterial \"{}\": no \"string type\"", *n));
            return;
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
        if (!inside) return;
        std::string outside = *inside;
        if (!s.done() && s.peek().kind == Token::Kind::kString) outside = std::string(s.next().text);
        for (const std::string& m : {*inside, outside})
            if (!m.empty() && !media_.count(m)) diag_.error(t.loc(), fmt::format("MediumInterface: unknown medium \"{}\"", m));
        gs_.inside = *inside;
        gs_.outside = outside;
    } else if (name == "ObjectBegin") {
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
                    M4 place = gs_.ctm;
                    if (o.transform) {
                        M4 inner;
                        for (int i = 0; i < 3; ++i)
                            for (int j = 0; j < 4; ++j) inner.m[i][j] = o.transform->to_world.m[i][j];
                        place = place * inner;
                    }
                    add_object(copy, place);
                }
            }
        }
    } else if (name == "ColorSpace") {
        if (const auto n = string_arg(s, t))
            if (*n != "srgb") warn(t.loc(), fmt::format("color space \"{}\": glint renders in linear sRGB; colours used as given", *n));
    } else if (name == "Option") {
        ParamList pl = params(s);
        for (Param& p : pl.params) warn(p.loc, fmt::format("Option \"{}\" ignored", p.name));
    } else if (name == "Attribute") {
        const auto target = string_arg(s, t);
        ParamList pl = params(s);
        if (target) warn(t.loc(), fmt::format("Attribute \"{}\": default parameters are not supported; ignored", *target));
    } else if (name == "TransformTimes" || name == "ActiveTransform") {
        warn(t.loc(), fmt::format("{}: motion blur is not supported; ignored", name));
        if (name == "TransformTimes") numbers(s, t, 2, v);
        else if (!s.done() && s.peek().kind == Token::Kind::kWord) s.next();
    } else {
        std::vector<std::string> names(kDirectives.begin(), kDirectives.end());
        const std::string guess = closest_match(name, names);
        diag_.error(t.loc(), fmt::format("unknown directive '{}'{}", name,
                                       guess.empty() ? "" : fmt::format("; did you mean '{}'?", guess)));
        // Skip its arguments.
        while (!s.done() && s.peek().kind != Token::Kind::kWord) s.next();
    }
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
    // The shutter interval is the exposure time of pbrt's imaging ratio (no motion blur).
    const double open = get_float(pl, "shutteropen").value_or(0), close = get_float(pl, "shutterclose").value_or(1);
    if (!(close >= open)) diag_.error(pl.find("shutterclose") ? pl.find("shutterclose")->loc : t.loc(),
                                      "shutterclose must not be before shutteropen");
    exposure_time_ = close - open;
    if (type == "orthographic") {
        cam.orthographic = true;
        cam.height = Float(2 * std::sqrt(up[0] * up[0] + up[1] * up[1] + up[2] * up[2]));  // shorter axis [-1, 1]
    } else if (type != "perspective") {
        warn(t.loc(), fmt::format("camera \"{}\" not supported; using perspective", type));
        pl.use_all();
    }
    check_unused(pl, "Camera \"" + type + "\"");
    d_.camera = cam;
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
    if (get_float(pl, "whitebalance").value_or(0) != 0)
        warn(pl.find("whitebalance")->loc, "whitebalance not applied");
    ignore_rest(pl, "Film: parameter \"{}\" ignored (glint writes linear radiance)");
}

void Parser::add_object(ObjectDesc o, const M4& m) {
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
    const auto no_alpha_here = [&] {
        if (alpha) warn(alpha->loc, fmt::format("\"alpha\" on a {}: glint cuts out meshes only; the shape is opaque", type));
    };
    ignore(pl, "emissionfilename", "\"emissionfilename\" not supported; the area light's L is used");
    const std::string what = "Shape \"" + type + "\"";
    if (type == "sphere") {
        const double r = get_float(pl, "radius").value_or(1);
        for (const char* partial : {"zmin", "zmax", "phimax"})
            if (get_float(pl, partial)) warn(pl.find(partial)->loc, fmt::format("\"{}\": partial spheres not supported; a whole sphere", partial));
        if (!(r > 0)) {
            diag_.error(t.loc(), "sphere: radius must be positive");
            return;
        }
        if (gs_.reverse_orientation && gs_.area_light) warn(t.loc(), "ReverseOrientation on an emitting sphere: glint's sphere emits outwards");
        apply_area_power(o, {4 * std::numbers::pi * r * r});
        no_alpha_here();
        o.shape = Sphere{{0, 0, 0}, Float(r)};
        check_unused(pl, what);
        add_object(std::move(o), gs_.ctm);
    } else if (type == "disk") {
        const double h = get_float(pl, "height").value_or(0), r = get_float(pl, "radius").value_or(1);
        if (get_float(pl, "innerradius").value_or(0) != 0) warn(pl.find("innerradius")->loc, "innerradius not supported; a full disk");
        if (get_float(pl, "phimax")) warn(pl.find("phimax")->loc, "phimax not supported; a full disk");
        if (!(r > 0)) {
            diag_.error(t.loc(), "disk: radius must be positive");
            return;
        }
        apply_area_power(o, {std::numbers::pi * r * r});
        no_alpha_here();
        o.shape = Disk{{0, 0, Float(h)}, Normal3{0, 0, gs_.reverse_orientation ? -1.0f : 1.0f}, Float(r)};
        check_unused(pl, what);
        add_object(std::move(o), gs_.ctm);
    } else if (type == "trianglemesh" || type == "bilinearmesh") {
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
    } else if (type == "loopsubdiv") {
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
    } else if (type == "cylinder") {
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
    } else if (type == "plymesh") {
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
    } else {
        warn(t.loc(), fmt::format("shape \"{}\" not supported; left out", type));
        pl.use_all();
    }
}

// The slab of pbrt-v4's coated materials: thickness (0.01), albedo (0) and g (0) of its medium,
// maxdepth (10) and nsamples (1) of the random walks. Constants only (textures are refused by
// the getters, with the spot).
void Parser::layer(MaterialDesc& m, ParamList& pl) {
    const auto check = [&](const char* name, bool ok, const char* what) {
        if (!ok) diag_.error(pl.find(name)->loc, fmt::format("{}: {}", name, what));
        return ok;
    };
    if (auto v = get_float(pl, "thickness"); v && check("thickness", *v > 0 && std::isfinite(*v), "must be positive"))
        m.thickness = float(*v);
    if (auto v = get_color(pl, "albedo", false)) {
        m.layer_albedo = Color{std::clamp(v->r, 0.0f, 1.0f), std::clamp(v->g, 0.0f, 1.0f), std::clamp(v->b, 0.0f, 1.0f)};
    }
    if (auto v = get_float(pl, "g"); v && check("g", std::isfinite(*v), "must be a number"))
        m.g = float(std::clamp(*v, -0.999, 0.999));
    if (auto v = get_int(pl, "maxdepth"); v && check("maxdepth", *v >= 1 && *v <= 1000, "must be in [1, 1000]"))
        m.layer_depth = *v;
    if (auto v = get_int(pl, "nsamples"); v && check("nsamples", *v >= 1 && *v <= 100, "must be in [1, 100]"))
        m.layer_samples = *v;
}

std::optional<MaterialDesc> Parser::material(const Token& t, const std::string& type, ParamList& pl) {
    using K = MaterialDesc::Kind;
    MaterialDesc m;
    // pbrt's roughness: alpha = sqrt(r) when remapped (the default), r otherwise; glint's
    // roughness is sqrt(alpha).
    const auto roughness = [&](double fallback, const std::string& prefix = "") {
        const bool remap = get_bool(pl, "remaproughness").value_or(true);
        double r = fallback;
        if (auto v = get_float(pl, prefix + "roughness")) r = *v;
        const auto u = get_float(pl, prefix + "uroughness"), v = get_float(pl, prefix + "vroughness");
        if (u || v) {
            if (u && v && *u != *v) warn(pl.find(prefix + "uroughness")->loc, "anisotropic roughness not supported; using the mean");
            r = ((u ? *u : r) + (v ? *v : r)) / 2;
        }
        const double alpha = remap ? std::sqrt(std::max(0.0, r)) : std::max(0.0, r);
        return float(std::sqrt(alpha));
    };
    ignore(pl, {"displacement", "normalmap"}, "ignored (no bump or normal maps from pbrt files yet)");
    if (type == "diffuse") {
        m.kind = K::kDiffuse;
        m.color = get_texture(pl, "reflectance", false, 0.5f).value_or(TextureDesc{});
        if (!pl.find("reflectance")) m.color.value = Color{0.5f};
    } else if (type == "coateddiffuse") {
        m.kind = K::kCoated;  // pbrt-v4's layered BSDF: a diffuse base under a dielectric coat
        m.color = get_texture(pl, "reflectance", false, 0.5f).value_or(TextureDesc{});
        if (!pl.find("reflectance")) m.color.value = Color{0.5f};
        m.coat_roughness = roughness(0);
        if (auto eta = get_float(pl, "eta")) m.ior = float(*eta);
        layer(m, pl);
    } else if (type == "conductor" || type == "coatedconductor") {
        m.kind = K::kConductor;
        const std::string prefix = type == "coatedconductor" ? "conductor." : "";
        if (type == "coatedconductor") {
            m.kind = K::kCoated;  // a conductor base under a dielectric coat
            m.coated_conductor = true;
            m.coat_roughness = roughness(0, "interface.");
            if (auto eta = get_float(pl, "interface.eta")) m.ior = float(*eta);
            layer(m, pl);
        }
        if (pl.find("reflectance")) {
            m.reflectance = get_texture(pl, "reflectance", false, 1);
        } else {
            for (const MetalPreset& p : kMetals)
                if (p.name == "copper") m.eta = p.eta, m.k = p.k;  // pbrt's default conductor is copper
            if (const auto eta = get_color(pl, prefix + "eta", false)) m.eta = *eta;
            if (const auto k = get_color(pl, prefix + "k", false)) m.k = *k;
        }
        m.roughness = roughness(0, prefix);
    } else if (type == "dielectric" || type == "thindielectric") {
        m.kind = K::kDielectric;
        m.thin = type == "thindielectric";
        if (pl.find("eta")) {
            const auto c = get_color(pl, "eta", false);
            m.ior = c ? c->g : 1.5f;
        }
        m.roughness = roughness(0);
    } else if (type == "interface") {
        m.kind = K::kInterface;
    } else if (type == "diffusetransmission") {
        m.kind = K::kDiffuseTransmission;
        const double scale = get_float(pl, "scale").value_or(1);
        const auto scaled = [&](const char* name) {
            TextureDesc d = get_texture(pl, name, false, 0.25f).value_or(TextureDesc{});
            if (!pl.find(name)) d.value = Color{0.25f};
            if (scale == 1) return d;
            if (d.kind == TextureDesc::Kind::kConstant) {
                d.value = d.value * float(scale);
                return d;
            }
            TextureDesc f, product;
            f.value = Color{float(scale)};
            product.kind = TextureDesc::Kind::kScale;
            product.children = {d, f};
            return product;
        };
        m.color = scaled("reflectance");
        m.transmittance = scaled("transmittance");
    } else if (type == "mix") {
        m.kind = K::kMix;
        Param* mats = pl.find("materials");
        if (!mats || mats->type != "string" || mats->strings.size() != 2) {
            diag_.error(mats ? mats->loc : t.loc(), "mix: needs \"string materials\" [ \"a\" \"b\" ]");
            if (mats) mats->used = true;
            return std::nullopt;
        }
        mats->used = true;
        for (const std::string& name : mats->strings) {
            const auto it = named_materials_.find(name);
            if (it == named_materials_.end()) {
                diag_.error(mats->loc, fmt::format("mix: unknown material \"{}\"", name));
                return std::nullopt;
            }
            m.mix.push_back({it->second, mats->loc});
        }
        if (pl.find("amount")) m.amount = get_texture(pl, "amount", true, 0.5f);
    } else {
        warn(t.loc(), fmt::format("material \"{}\" not supported; using diffuse 0.5", type));
        pl.use_all();
        m.kind = K::kDiffuse;
        m.color.value = Color{0.5f};
    }
    if (Param* p = pl.find("type")) p->used = true;  // MakeNamedMaterial's
    return m;
}

void Parser::light(const Token& t, const std::string& type, ParamList pl) {
    float s = float(get_float(pl, "scale").value_or(1));
    // pbrt-v4's "power" (point, spot) and "illuminance" (distant, infinite) scale the given
    // colour so that the light emits that power or gives that illuminance (RGB colours keep
    // their own magnitude: pbrt normalises only the illuminant's spectrum).
    const auto target = [&](const char* name) -> std::optional<double> {
        const auto v = get_float(pl, name);
        if (v && !(*v > 0)) return std::nullopt;  // pbrt: non-positive means "not given"
        return v;
    };    const auto pt = [&](const char* name, D3 fallback) {
        const auto v = get_floats(pl, name, "point3", 3);
        return v && v->size() == 3 ? D3{(*v)[0], (*v)[1], (*v)[2]} : fallback;
    };
    const auto to_point = [](D3 p) { return Point3{Float(p[0]), Float(p[1]), Float(p[2])}; };
    if (type == "point") {
        if (const auto p = target("power")) s *= float(*p / (4 * std::numbers::pi));
        const Color I = get_color(pl, "I", true).value_or(Color{1}) * s;
        const D3 f = pt("from", {0, 0, 0});
        d_.lights.push_back(PointLight{to_point(gs_.ctm.point(f[0], f[1], f[2])), I});
    } else if (type == "spot") {
        const D3 f = pt("from", {0, 0, 0}), to = pt("to", {0, 0, 1});
        const double cone = get_float(pl, "coneangle").value_or(30), delta = get_float(pl, "conedeltaangle").value_or(5);
        if (const auto p = target("power")) {  // the cone's solid angle, the falloff counted half
            const double to_rad = std::numbers::pi / 180, c_end = std::cos(cone * to_rad),
                         c_start = std::cos((cone - delta) * to_rad);
            s *= float(*p / (2 * std::numbers::pi * ((1 - c_start) + (c_start - c_end) / 2)));
        }
        const Color I = get_color(pl, "I", true).value_or(Color{1}) * s;
        const D3 wf = gs_.ctm.point(f[0], f[1], f[2]), wt = gs_.ctm.point(to[0], to[1], to[2]);
        const D3 dir = sub(wt, wf);
        if (!(len3(dir) > 0)) {
            diag_.error(t.loc(), "spot light: from and to are the same point");
            return;
        }
        const D3 u = unit3(dir);
        const double to_rad = std::numbers::pi / 180;
        SpotLight l{to_point(wf), Vector3{Float(u[0]), Float(u[1]), Float(u[2])}, I,
                    Float(std::cos(std::max(0.0, cone - delta) * to_rad)), Float(std::cos(cone * to_rad))};
        d_.lights.push_back(l);
    } else if (type == "distant") {
        if (const auto e = target("illuminance")) s *= float(*e);
        const Color L = get_color(pl, "L", true).value_or(Color{1}) * s;
        const D3 f = pt("from", {0, 0, 0}), to = pt("to", {0, 0, 1});
        const D3 dir = gs_.ctm.vector(to[0] - f[0], to[1] - f[1], to[2] - f[2]);
        if (!(len3(dir) > 0)) {
            diag_.error(t.loc(), "distant light: from and to are the same point");
            return;
        }
        const D3 u = unit3(dir);
        d_.lights.push_back(DirectionalLight{Vector3{Float(u[0]), Float(u[1]), Float(u[2])}, L});
    } else if (type == "infinite") {
        if (auto file = get_string(pl, "filename")) {
            // pbrt-v4's environment maps are square, equal-area octahedral images with +z at
            // their centre, oriented by the light's transform: resampled at load. (A 2:1 map
            // would be a pbrt-v3 lat-long one, which pbrt-v4 refuses; build says so.)
            EnvironmentDesc e;
            e.filename = {*file, pl.find("filename")->loc};  // build resolves it against the scene's folder
            e.scale = s;
            e.equal_area = true;
            const auto inv = gs_.ctm.inverse();
            if (inv) e.world_to_light = inv->to34();
            if (const auto illuminance = target("illuminance")) {  // computed from the map by build
                const D3 up = unit3(gs_.ctm.vector(0, 0, 1));
                e.illuminance = float(*illuminance);
                e.up = Vector3{Float(up[0]), Float(up[1]), Float(up[2])};
            }
            d_.environment = e;
        } else {
            if (const auto e = target("illuminance")) s *= float(*e / std::numbers::pi);  // E = pi L
            const Color L = get_color(pl, "L", true).value_or(Color{1}) * s;
            d_.background = ConstantBackground{L};
        }
        ignore(pl, "portal", "\"portal\" ignored");
    } else {
        warn(t.loc(), fmt::format("light \"{}\" not supported; left out", type));
        pl.use_all();
    }
    check_unused(pl, "LightSource \"" + type + "\"");
}

void Parser::area_light(const Token& t, const std::string& type, ParamList pl) {
    if (type != "diffuse") {
        warn(t.loc(), fmt::format("area light \"{}\" not supported; the shapes do not emit", type));
        pl.use_all();
        return;
    }
    Emission e;
    e.radiance = get_color(pl, "L", true).value_or(Color{1}) * float(get_float(pl, "scale").value_or(1));
    e.two_sided = get_bool(pl, "twosided").value_or(false);
    gs_.area_power.reset();
    if (const auto p = get_float(pl, "power"); p && *p > 0) gs_.area_power = Located<double>{*p, pl.find("power")->loc};
    ignore(pl, "filename", "image area lights not supported; using L");
    check_unused(pl, "AreaLightSource");
    gs_.area_light = e;
    gs_.area_light_loc = t.loc();
}

void Parser::texture(const Token& t, const std::string& name, const std::string& kind, const std::string& type,
                     ParamList pl) {
    if (kind != "spectrum" && kind != "float" && kind != "color" && kind != "rgb") {
        diag_.error(t.loc(), fmt::format("Texture \"{}\": the kind is \"spectrum\" or \"float\", not \"{}\"", name, kind));
        return;
    }
    const bool is_float = kind == "float";
    TextureEntry e;
    e.is_float = is_float;
    using K = TextureDesc::Kind;
    // pbrt-v4 reads a 2D mapping's parameters (uscale, vscale, udelta, vdelta, mapping) only
    // for textures looked up by (u, v): an image and a 2D checkerboard; elsewhere they are
    // unknown, as in pbrt-v4.
    double us = 1, vs = 1;
    const auto uv_mapping = [&] {
        for (const char* n : {"mapping", "udelta", "vdelta"})
            ignore(pl, n, fmt::format("texture \"{}\": \"{}\" ignored", name, n));
        us = get_float(pl, "uscale").value_or(1);
        vs = get_float(pl, "vscale").value_or(1);
    };
    if (type == "imagemap") {
        uv_mapping();
        for (const char* quiet : {"filter", "maxanisotropy"})  // filtering is glint's own choice
            if (Param* p = pl.find(quiet)) p->used = true;
        ignore(pl, "invert", fmt::format("texture \"{}\": \"invert\" ignored", name));
        e.desc.kind = K::kImage;
        const auto file = get_string(pl, "filename");
        if (!file) {
            diag_.error(t.loc(), fmt::format("Texture \"{}\": imagemap needs \"string filename\"", name));
            return;
        }
        e.desc.filename = {*file, pl.find("filename")->loc};
        if (auto enc = get_string(pl, "encoding")) {
            if (*enc == "sRGB") e.desc.encoding = ImageEncoding::kSrgb;
            else if (*enc == "linear") e.desc.encoding = ImageEncoding::kLinear;
            else warn(pl.find("encoding")->loc, fmt::format("encoding \"{}\" not supported; using the file's", *enc));
        }
        if (auto wrap = get_string(pl, "wrap")) {
            if (*wrap == "clamp") e.desc.wrap = WrapMode::kClamp;
            else if (*wrap != "repeat") warn(pl.find("wrap")->loc, fmt::format("wrap \"{}\": using repeat", *wrap));
        }
        if (get_float(pl, "scale")) warn(pl.find("scale")->loc, "imagemap \"scale\" ignored");
        if (us != 1 || vs != 1) e.desc.uv_transform = {Float(us), 0, 0, 0, Float(vs), 0};
    } else if (type == "constant") {
        e.desc.kind = K::kConstant;
        e.desc = get_texture(pl, "value", is_float, 1).value_or(TextureDesc{});
    } else if (type == "scale") {
        e.desc.kind = K::kScale;
        e.desc.children.push_back(get_texture(pl, "tex", is_float, 1).value_or(TextureDesc{}));
        e.desc.children.push_back(get_texture(pl, "scale", true, 1).value_or(TextureDesc{}));
        if (!pl.find("tex")) e.desc.children[0].value = Color{1};
        if (!pl.find("scale")) e.desc.children[1].value = Color{1};
    } else if (type == "mix") {
        e.desc.kind = K::kMix;
        TextureDesc a = get_texture(pl, "tex1", is_float, 0).value_or(TextureDesc{});
        TextureDesc b = get_texture(pl, "tex2", is_float, 1).value_or(TextureDesc{});
        if (!pl.find("tex1")) a.value = Color{0};
        if (!pl.find("tex2")) b.value = Color{1};
        TextureDesc amount = get_texture(pl, "amount", true, 0.5f).value_or(TextureDesc{});
        if (!pl.find("amount")) amount.value = Color{0.5f};
        e.desc.children = {a, b, amount};
    } else if (type == "checkerboard") {
        e.desc.kind = K::kChecker;
        const auto constant = [&](const char* n, float fallback) {
            const auto tx = get_texture(pl, n, is_float, fallback);
            if (tx && tx->kind != K::kConstant) warn(pl.find(n)->loc, "checkerboard of textures: using constant colours");
            return tx && tx->kind == K::kConstant ? tx->value : Color{fallback};
        };
        const auto dim = get_int(pl, "dimension");
        double size = 1;
        if (dim && *dim == 3) {
            // pbrt-v4's 3D checker has cells of 1 in the texture's space, placed by the
            // transform at the Texture directive: a uniform scale s gives cells of s.
            const auto x = gs_.ctm.vector(1, 0, 0), y = gs_.ctm.vector(0, 1, 0), z = gs_.ctm.vector(0, 0, 1);
            size = len3(x);
            const bool uniform = std::abs(len3(y) - size) <= 1e-6 * size && std::abs(len3(z) - size) <= 1e-6 * size &&
                                 std::abs(x[0] * y[0] + x[1] * y[1] + x[2] * y[2]) <= 1e-6 * size * size;
            const auto o = gs_.ctm.point(0, 0, 0);
            if (!uniform || o[0] != 0 || o[1] != 0 || o[2] != 0 || !(size > 0))
                warn(t.loc(), "3D checkerboard: only a uniform scale of its space is applied");
            if (!(size > 0) || !std::isfinite(size)) size = 1;
        } else {
            uv_mapping();
            size = 1 / std::max(us, 1e-6);
            warn(dim ? pl.find("dimension")->loc : t.loc(), "2D checkerboard rendered as glint's 3D checker");
        }
        e.desc.checker = CheckerTexture{Float(size), constant("tex1", 1), constant("tex2", 0)};
    } else {
        warn(t.loc(), fmt::format("texture \"{}\" not supported; using a constant 0.5", type));
        pl.use_all();
        e.desc.kind = K::kConstant;
        e.desc.value = Color{0.5f};
    }
    check_unused(pl, "Texture \"" + name + "\"");
    textures_[name] = e;
}

void Parser::medium(const Token& t, const std::string& name, ParamList pl) {
    const auto type = get_string(pl, "type");
    if (!type) {
        diag_.error(t.loc(), fmt::format("MakeNamedMedium \"{}\": no \"string type\"", name));
        return;
    }
    media_.insert(name);
    if (*type == "uniformgrid") {
        // pbrt-v4's grid medium: nx x ny x nz density samples (x fastest) over the box [p0, p1]
        // of the medium's space, sample (i, j, k) at p0 + (p1 - p0) (i + 0.5, j + 0.5, k + 0.5) / n,
        // trilinear between samples: glint's voxel grid with that index-to-world transform.
        MediumDesc m;
        m.kind = MediumDesc::Kind::kGrid;
        const float sc = float(get_float(pl, "scale").value_or(1));
        m.sigma_a = get_color(pl, "sigma_a", false).value_or(Color{1}) * sc;
        m.sigma_s = get_color(pl, "sigma_s", false).value_or(Color{1}) * sc;
        m.g = float(get_float(pl, "g").value_or(0));
        if (!(std::abs(m.g) < 1)) diag_.error(pl.find("g")->loc, "g must be in (-1, 1)");
        const long long nx = get_int(pl, "nx").value_or(1), ny = get_int(pl, "ny").value_or(1),
                        nz = get_int(pl, "nz").value_or(1);
        const auto* density = get_floats(pl, "density", "float", 1);
        const auto pt = [&](const char* n, D3 fallback) {
            const auto v = get_floats(pl, n, "point3", 3);
            return v && v->size() == 3 ? D3{(*v)[0], (*v)[1], (*v)[2]} : fallback;
        };
        const D3 p0 = pt("p0", {0, 0, 0}), p1 = pt("p1", {1, 1, 1});
        for (const char* n : {"Le", "Lescale", "temperature", "temperaturecutoff", "temperaturescale"})
            ignore(pl, n, fmt::format("uniformgrid \"{}\": grid emission from pbrt files not supported; ignored", n));
        check_unused(pl, "MakeNamedMedium \"" + name + "\"");
        const SourceLoc at = pl.find("density") ? pl.find("density")->loc : t.loc();
        if (!density) {
            diag_.error(t.loc(), "uniformgrid: needs \"float density\"");
        } else if (nx < 1 || ny < 1 || nz < 1) {
            diag_.error(at, "uniformgrid: nx, ny, nz must be at least 1");
        } else if (double(nx) * double(ny) * double(nz) > double(limit(Limit::kGridVoxels))) {
            diag_.error(at, fmt::format("uniformgrid: {}", over_limit(Limit::kGridVoxels, static_cast<long long>(double(nx) * double(ny) * double(nz)))));
        } else if (static_cast<long long>(density->size()) != nx * ny * nz) {
            diag_.error(at, fmt::format("uniformgrid: {} density values for nx x ny x nz = {}", density->size(), nx * ny * nz));
        } else if (!(p1[0] > p0[0] && p1[1] > p0[1] && p1[2] > p0[2])) {
            diag_.error(pl.find("p1") ? pl.find("p1")->loc : t.loc(), "uniformgrid: p1 must exceed p0 on every axis");
        } else if (std::any_of(density->begin(), density->end(), [](double v) { return !(v >= 0) || !std::isfinite(v); })) {
            diag_.error(at, "uniformgrid: density values must be finite and non-negative");
        } else {
            const int ix = int(nx), iy = int(ny), iz = int(nz);
            m.inline_density = std::make_shared<const VoxelGrid>(VoxelGrid::from_function(
                {0, 0, 0}, {ix, iy, iz}, [&](int i, int j, int k) {
                    return float((*density)[(std::size_t(k) * std::size_t(iy) + std::size_t(j)) * std::size_t(ix) + std::size_t(i)]);
                }));
            // medium space -> world, then the box, then the half-voxel offset.
            M4 box;
            const double n3[3] = {double(nx), double(ny), double(nz)};
            for (int a = 0; a < 3; ++a) {
                const double step = (p1[a] - p0[a]) / n3[a];
                box.m[a][a] = step;
                box.m[a][3] = p0[a] + 0.5 * step;
            }
            const M4 to_world = gs_.ctm * box;
            if (const auto tr = to_world.affine() ? Transform::from(to_world.to34()) : std::nullopt) m.transform = *tr;
            else diag_.error(t.loc(), "uniformgrid: the medium's transform is singular or projective");
        }
        d_.media.push_back({name, m, t.loc()});
        return;
    }
    if (*type != "homogeneous") {
        warn(t.loc(), fmt::format("medium \"{}\" of type \"{}\" not supported; treated as empty", name, *type));
        pl.use_all();
        d_.media.push_back({name, MediumDesc{}, t.loc()});
        return;
    }
    MediumDesc m;
    const float sc = float(get_float(pl, "scale").value_or(1));
    m.sigma_a = get_color(pl, "sigma_a", false).value_or(Color{0.0011f, 0.0024f, 0.014f}) * sc;
    m.sigma_s = get_color(pl, "sigma_s", false).value_or(Color{2.55f, 3.21f, 3.77f}) * sc;
    m.emission = get_color(pl, "Le", true).value_or(Color{0}) * float(get_float(pl, "Lescale").value_or(1));
    m.g = float(get_float(pl, "g").value_or(0));
    if (!(std::abs(m.g) < 1)) diag_.error(pl.find("g")->loc, "g must be in (-1, 1)");
    ignore(pl, "preset", "named scattering presets are not known to glint; using sigma_a and sigma_s");
    check_unused(pl, "MakeNamedMedium \"" + name + "\"");
    d_.media.push_back({name, m, t.loc()});
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

}  // namespace

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
