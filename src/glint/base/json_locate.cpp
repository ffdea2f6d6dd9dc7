#include "glint/base/json_locate.h"

#include <string>
#include <vector>

namespace glint {

namespace {

class Walker {
public:
    Walker(std::string_view text, std::vector<std::string> path) : s_(text), path_(std::move(path)) {}

    // The offset of the value the path names, or npos.
    std::size_t find() { return value(0) ? at_ : std::string_view::npos; }

private:
    static constexpr std::size_t npos = std::string_view::npos;

    void space() {
        while (i_ < s_.size() && (s_[i_] == ' ' || s_[i_] == '\t' || s_[i_] == '\n' || s_[i_] == '\r')) ++i_;
    }
    bool eat(char c) {
        space();
        if (i_ < s_.size() && s_[i_] == c) {
            ++i_;
            return true;
        }
        return false;
    }
    // A string at i_ (after its quote is checked): its text with \" \\ \/ undone; false if unterminated.
    bool string(std::string* out) {
        ++i_;  // the opening quote
        while (i_ < s_.size()) {
            const char c = s_[i_++];
            if (c == '"') return true;
            if (c == '\\') {
                if (i_ >= s_.size()) return false;
                const char e = s_[i_++];
                if (out) out->push_back(e == 'n' ? '\n' : e == 't' ? '\t' : e);
            } else if (out) {
                out->push_back(c);
            }
        }
        return false;
    }
    // Past one value of any kind, nesting counted without recursion.
    bool skip() {
        space();
        if (i_ >= s_.size()) return false;
        if (s_[i_] == '"') return string(nullptr);
        if (s_[i_] == '{' || s_[i_] == '[') {
            std::size_t depth = 0;
            while (i_ < s_.size()) {
                const char c = s_[i_];
                if (c == '"') {
                    if (!string(nullptr)) return false;
                    continue;
                }
                ++i_;
                if (c == '{' || c == '[') ++depth;
                if ((c == '}' || c == ']') && --depth == 0) return true;
            }
            return false;
        }
        const std::size_t start = i_;  // number or literal
        while (i_ < s_.size() && s_[i_] != ',' && s_[i_] != '}' && s_[i_] != ']' && s_[i_] != ' ' &&
               s_[i_] != '\t' && s_[i_] != '\n' && s_[i_] != '\r')
            ++i_;
        return i_ > start;
    }
    // The value at i_, `depth` segments of the path matched so far.
    bool value(std::size_t depth) {
        space();
        if (depth == path_.size()) {
            at_ = i_;
            return i_ < s_.size();
        }
        const std::string& want = path_[depth];
        if (eat('{')) {
            if (eat('}')) return false;
            do {
                space();
                if (i_ >= s_.size() || s_[i_] != '"') return false;
                std::string key;
                if (!string(&key) || !eat(':')) return false;
                if (key == want) return value(depth + 1);
                if (!skip()) return false;
            } while (eat(','));
            return false;
        }
        if (eat('[')) {
            if (want.empty() || want.size() > 9 || want.find_first_not_of("0123456789") != std::string::npos) return false;
            const std::size_t index = std::stoul(want);
            if (eat(']')) return false;
            for (std::size_t k = 0;; ++k) {
                if (k == index) return value(depth + 1);
                if (!skip() || !eat(',')) return false;
            }
        }
        return false;
    }

    std::string_view s_;
    std::vector<std::string> path_;
    std::size_t i_ = 0;
    std::size_t at_ = npos;
};

// RFC 6901: "/a/b~1c" -> {"a", "b/c"}; nullopt if it does not start with '/' (and is not "").
std::optional<std::vector<std::string>> split(std::string_view pointer) {
    std::vector<std::string> out;
    if (pointer.empty()) return out;
    if (pointer[0] != '/') return std::nullopt;
    for (std::size_t k = 1; k <= pointer.size(); ++k) {
        if (k == 1 || pointer[k - 1] == '/') out.emplace_back();
        if (k == pointer.size()) break;
        const char c = pointer[k];
        if (c == '/') continue;
        if (c == '~' && k + 1 < pointer.size() && (pointer[k + 1] == '0' || pointer[k + 1] == '1')) {
            out.back().push_back(pointer[++k] == '0' ? '~' : '/');
        } else {
            out.back().push_back(c);
        }
    }
    return out;
}

}  // namespace

std::optional<TextPosition> json_locate(std::string_view text, std::string_view pointer) {
    auto path = split(pointer);
    if (!path) return std::nullopt;
    const std::size_t at = Walker(text, std::move(*path)).find();
    if (at == std::string_view::npos) return std::nullopt;
    TextPosition p{1, 1};
    for (std::size_t k = 0; k < at; ++k) {
        if (text[k] == '\n') {
            ++p.line;
            p.column = 1;
        } else if ((static_cast<unsigned char>(text[k]) & 0xC0) != 0x80) {
            ++p.column;
        }
    }
    return p;
}

std::optional<TextPosition> json_too_deep(std::string_view text, long long max_depth) {
    long long depth = 0;
    int line = 1, column = 0;
    bool in_string = false, escaped = false;
    for (const char c : text) {
        if ((static_cast<unsigned char>(c) & 0xC0) != 0x80) ++column;  // characters, as json_locate counts
        if (c == '\n') {
            ++line;
            column = 0;
        }
        if (in_string) {
            if (escaped) escaped = false;
            else if (c == '\\') escaped = true;
            else if (c == '"') in_string = false;
        } else if (c == '"') {
            in_string = true;
        } else if (c == '[' || c == '{') {
            if (++depth > max_depth) return TextPosition{line, column};
        } else if ((c == ']' || c == '}') && depth > 0) {
            --depth;
        }
    }
    return std::nullopt;
}

}  // namespace glint
