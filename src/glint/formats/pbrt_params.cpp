#include <fmt/core.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>

#include "glint/base/limits.h"
#include "glint/formats/pbrt_parser.h"
#include "glint/formats/spectrum_file.h"
#include "glint/materials/metals.h"
#include "glint/spectra/spectrum.h"

namespace glint::pbrt_detail {

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

// A "spectrum" parameter's values: a name pbrt-v4 knows, a file of wavelength-value pairs (pbrt's
// .spd files, relative to the main file, '#' comments), or the pairs inline. Located errors for a
// missing file, an odd count, wavelengths that do not increase and negative values.
std::optional<PiecewiseLinearSpectrum> Parser::spectrum_values(const Param& p, const std::string& name, bool report) {
    std::string message;
    std::optional<PiecewiseLinearSpectrum> s;
    if (p.strings.size() == 1) {
        if (const PiecewiseLinearSpectrum* named = named_spectrum(p.strings[0])) return *named;
        std::filesystem::path file = p.strings[0];
        if (file.is_relative()) file = dir_ / file;
        if (!std::ifstream(file)) {
            message = fmt::format("\"{}\" is neither a spectrum pbrt-v4 names nor a file that can be read ({})",
                                  p.strings[0], file.string());
        } else if (const auto numbers = read_spectrum_file(file, message)) {
            s = spectrum_from_pairs(*numbers, message);
        }
    } else {
        s = spectrum_from_pairs(p.numbers, message);
    }
    if (!s && report) diag_.error(p.loc, fmt::format("\"{}\": {}", name, message));
    return s;
}

std::shared_ptr<const Spectrum> Parser::get_spectrum(ParamList& pl, const std::string& name) {
    Param* p = pl.find(name);
    if (!p || p->type != "spectrum" || p->numbers.size() == 1) return nullptr;
    auto values = spectrum_values(*p, name, false);  // get_color, read first, reported any error
    if (!values) return nullptr;
    Spectrum t = Spectrum::tabulated(std::move(*values));
    if (p->strings.size() == 1) t.set_name(p->strings[0]);
    return std::make_shared<const Spectrum>(std::move(t));
}

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
        // A light's: the colour of its spectrum at luminance 1 (spectral mode uses the spectrum).
        if (illuminant) return Spectrum::blackbody(float(p->numbers[0])).emission_rgb();
        return blackbody_rgb(float(p->numbers[0]));
    }
    if (p->type == "spectrum") {
        if (p->strings.size() == 1)
            if (const Color* rgb = named_metal_rgb(p->strings[0])) return *rgb;
        if (p->numbers.size() == 1) return Color{float(p->numbers[0])};
        // RGB mode's stand-in for a spectrum: an illuminant by its colour (luminance 1), a glass
        // by its index at 587.56 nm, a reflectance (values in [0, 1]) by its colour under D65,
        // anything else (a metal's eta or k) by its values at 650, 550 and 450 nm. Spectral mode
        // reads the spectrum itself where it can (get_spectrum).
        const auto s = spectrum_values(*p, name);
        if (!s) return std::nullopt;
        const std::string named = p->strings.size() == 1 ? p->strings[0] : "";
        if (named.rfind("glass-", 0) == 0) return Color{(*s)(587.56f)};
        // A light's colour: luminance 1, clipped to the gamut (Spectrum::emission_rgb).
        if (illuminant) return Spectrum::tabulated(*s).emission_rgb();
        if (named.rfind("stdillum-", 0) == 0) return xyz_to_linear_srgb(spectrum_to_xyz(*s));
        if (std::all_of(s->value().begin(), s->value().end(), [](float v) { return v <= 1; }))
            return reflectance_rgb(*s);
        return Color{(*s)(650), (*s)(550), (*s)(450)};
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
    // A reflectance given as a spectrum (values in [0, 1], not a metal's, a glass's or an
    // illuminant's): spectral mode reads the spectrum itself, RGB mode its colour under D65.
    if (c && !is_float && p->type == "spectrum") {
        const std::string named = p->strings.size() == 1 ? p->strings[0] : "";
        const bool other = named.rfind("metal-", 0) == 0 || named.rfind("glass-", 0) == 0 || named.rfind("stdillum-", 0) == 0;
        if (auto s = other ? nullptr : get_spectrum(pl, name)) {
            const auto& v = s->table().value();
            if (std::all_of(v.begin(), v.end(), [](float x) { return x <= 1; })) t.spectrum = std::move(s);
        }
    }
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

}  // namespace glint::pbrt_detail
