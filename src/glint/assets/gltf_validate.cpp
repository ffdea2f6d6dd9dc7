#include "glint/assets/gltf_validate.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <fmt/format.h>
#include <initializer_list>
#include <vector>

namespace glint {

namespace {

using Json = nlohmann::json;

enum class Type {
    kIndex,    // an integer >= 0 (an index into another array, an offset)
    kCount,    // an integer >= 1
    kInteger,  // an integer (its allowed values listed)
    kNumber,
    kBool,
    kString,
    kObject,
    kNumbers,  // an array of numbers
    kIndices,  // an array of integers >= 0
    kObjects,  // an array of objects
    kStrings,  // an array of strings
};

struct Rule {
    const char* key;
    Type type;
    bool required = false;
    std::vector<long long> allowed_integers{};
    std::vector<const char*> allowed_strings{};
};

const char* type_name(Type t) {
    switch (t) {
        case Type::kIndex: return "an integer of at least 0";
        case Type::kCount: return "an integer of at least 1";
        case Type::kInteger: return "an integer";
        case Type::kNumber: return "a number";
        case Type::kBool: return "true or false";
        case Type::kString: return "a string";
        case Type::kObject: return "an object";
        case Type::kNumbers: return "an array of numbers";
        case Type::kIndices: return "an array of integers of at least 0";
        case Type::kObjects: return "an array of objects";
        case Type::kStrings: return "an array of strings";
    }
    return "";
}

bool integer(const Json& v) {
    if (v.is_number_integer()) return true;
    if (!v.is_number_float()) return false;
    const double x = v.get<double>();
    return std::isfinite(x) && x == std::floor(x) && std::abs(x) < 9.0e15;
}
long long as_integer(const Json& v) { return v.is_number_float() ? static_cast<long long>(v.get<double>()) : v.get<long long>(); }

bool fits(const Json& v, Type t) {
    switch (t) {
        case Type::kIndex: return integer(v) && as_integer(v) >= 0;
        case Type::kCount: return integer(v) && as_integer(v) >= 1;
        case Type::kInteger: return integer(v);
        case Type::kNumber: return v.is_number();
        case Type::kBool: return v.is_boolean();
        case Type::kString: return v.is_string();
        case Type::kObject: return v.is_object();
        case Type::kNumbers:
        case Type::kIndices:
        case Type::kObjects:
        case Type::kStrings: {
            if (!v.is_array()) return false;
            const Type each = t == Type::kNumbers ? Type::kNumber
                              : t == Type::kIndices ? Type::kIndex
                              : t == Type::kObjects ? Type::kObject
                                                    : Type::kString;
            for (const Json& e : v)
                if (!fits(e, each)) return false;
            return true;
        }
    }
    return false;
}

std::string shown(const Json& v) {
    std::string s = v.dump();
    if (s.size() > 40) s = s.substr(0, 37) + "...";
    return s;
}

class Checker {
public:
    std::optional<GltfRuleError> error;

    // Checks the rules on the object at `pointer` (named `name` in messages); false once an error is found.
    bool object(const Json& o, const std::string& pointer, const std::string& name, std::initializer_list<Rule> rules) {
        if (error) return false;
        if (!o.is_object()) return fail(pointer, fmt::format("{}: {} is not an object", name, shown(o)));
        for (const Rule& r : rules) {
            const auto it = o.find(r.key);
            const std::string at = pointer + "/" + r.key, what = name + "." + r.key;
            if (it == o.end()) {
                if (r.required) return fail(pointer, fmt::format("{}: the required property '{}' is missing", name, r.key));
                continue;
            }
            if (!fits(*it, r.type)) return fail(at, fmt::format("{}: {} is not {}", what, shown(*it), type_name(r.type)));
            if (!r.allowed_integers.empty()) {
                bool ok = false;
                for (long long a : r.allowed_integers) ok |= as_integer(*it) == a;
                if (!ok) return fail(at, fmt::format("{}: {} is not one of the values glTF allows", what, shown(*it)));
            }
            if (!r.allowed_strings.empty()) {
                bool ok = false;
                for (const char* a : r.allowed_strings) ok |= it->get<std::string>() == a;
                if (!ok) return fail(at, fmt::format("{}: {} is not one of the values glTF allows", what, shown(*it)));
            }
        }
        return true;
    }
    // Each element of the array `key` of `o` (absent: nothing to check) through `check(element, pointer, name)`.
    template <typename F>
    void each(const Json& o, const std::string& pointer, const char* key, const std::string& name, F&& check) {
        if (error || !o.is_object()) return;
        const auto it = o.find(key);
        if (it == o.end() || !it->is_array()) return;  // types were checked by object()
        for (std::size_t i = 0; i < it->size() && !error; ++i)
            check((*it)[i], fmt::format("{}/{}/{}", pointer, key, i), fmt::format("{}{}[{}]", name, key, i));
    }
    // The member `key` of `o` (if present) through `check`.
    template <typename F>
    void member(const Json& o, const std::string& pointer, const char* key, const std::string& name, F&& check) {
        if (error || !o.is_object()) return;
        if (const auto it = o.find(key); it != o.end()) check(*it, pointer + "/" + key, name + "." + key);
    }

    bool fail(const std::string& pointer, std::string message) {
        if (!error) error = GltfRuleError{pointer, std::move(message)};
        return false;
    }
};

const std::vector<long long> kComponentTypes{5120, 5121, 5122, 5123, 5125, 5126};

void texture_info(Checker& c, const Json& v, const std::string& at, const std::string& name) {
    c.object(v, at, name, {{"index", Type::kIndex, true}, {"texCoord", Type::kIndex}, {"scale", Type::kNumber},
                           {"strength", Type::kNumber}, {"extensions", Type::kObject}});
}

}  // namespace

std::optional<GltfRuleError> gltf_rule_error(std::string_view text) {
    const Json root = Json::parse(text.begin(), text.end(), nullptr, false);
    if (root.is_discarded()) return std::nullopt;
    Checker c;
    const Type A = Type::kObjects;
    if (!c.object(root, "", "the file",
                  {{"asset", Type::kObject, true}, {"scene", Type::kIndex}, {"extensionsUsed", Type::kStrings},
                   {"extensionsRequired", Type::kStrings}, {"accessors", A}, {"animations", A}, {"buffers", A},
                   {"bufferViews", A}, {"cameras", A}, {"images", A}, {"materials", A}, {"meshes", A}, {"nodes", A},
                   {"samplers", A}, {"scenes", A}, {"skins", A}, {"textures", A}, {"extensions", Type::kObject}}))
        return c.error;
    // The version: glint reads glTF 2.0 and what 2.x files a 2.0 reader may read.
    const Json& asset = root["asset"];
    if (!c.object(asset, "/asset", "asset",
                  {{"version", Type::kString, true}, {"minVersion", Type::kString}, {"generator", Type::kString},
                   {"copyright", Type::kString}}))
        return c.error;
    for (const char* key : {"version", "minVersion"}) {
        if (!asset.contains(key)) continue;
        const std::string v = asset[key].get<std::string>();
        int major = -1, minor = -1;
        char rest = 0;
        if (std::sscanf(v.c_str(), "%d.%d%c", &major, &minor, &rest) != 2 || major < 0 || minor < 0)
            return GltfRuleError{std::string("/asset/") + key,
                                 fmt::format("asset.{}: '{}' is not a version of the form MAJOR.MINOR", key, v)};
        const bool too_new = std::string(key) == "version" ? major != 2 : major != 2 || minor > 0;
        if (too_new)
            return GltfRuleError{std::string("/asset/") + key,
                                 fmt::format("asset.{}: the file needs glTF {}; glint reads glTF 2.0", key, v)};
    }
    c.each(root, "", "accessors", "", [&](const Json& a, const std::string& at, const std::string& name) {
        c.object(a, at, name,
                 {{"bufferView", Type::kIndex}, {"byteOffset", Type::kIndex},
                  {"componentType", Type::kInteger, true, kComponentTypes}, {"normalized", Type::kBool},
                  {"count", Type::kCount, true},
                  {"type", Type::kString, true, {}, {"SCALAR", "VEC2", "VEC3", "VEC4", "MAT2", "MAT3", "MAT4"}},
                  {"max", Type::kNumbers}, {"min", Type::kNumbers}, {"sparse", Type::kObject}, {"name", Type::kString}});
        c.member(a, at, "sparse", name, [&](const Json& s, const std::string& sat, const std::string& sname) {
            c.object(s, sat, sname, {{"count", Type::kCount, true}, {"indices", Type::kObject, true}, {"values", Type::kObject, true}});
            c.member(s, sat, "indices", sname, [&](const Json& i, const std::string& iat, const std::string& iname) {
                c.object(i, iat, iname, {{"bufferView", Type::kIndex, true}, {"byteOffset", Type::kIndex},
                                         {"componentType", Type::kInteger, true, {5121, 5123, 5125}}});
            });
            c.member(s, sat, "values", sname, [&](const Json& v, const std::string& vat, const std::string& vname) {
                c.object(v, vat, vname, {{"bufferView", Type::kIndex, true}, {"byteOffset", Type::kIndex}});
            });
        });
    });
    c.each(root, "", "bufferViews", "", [&](const Json& v, const std::string& at, const std::string& name) {
        c.object(v, at, name, {{"buffer", Type::kIndex, true}, {"byteOffset", Type::kIndex}, {"byteLength", Type::kCount, true},
                               {"byteStride", Type::kCount}, {"target", Type::kInteger, false, {34962, 34963}},
                               {"name", Type::kString}});
        if (!c.error && v.contains("byteStride")) {
            const long long s = as_integer(v["byteStride"]);
            if (s < 4 || s > 252 || s % 4 != 0)
                c.fail(at + "/byteStride", fmt::format("{}.byteStride: {} is not a multiple of 4 from 4 to 252", name, s));
        }
    });
    c.each(root, "", "buffers", "", [&](const Json& b, const std::string& at, const std::string& name) {
        c.object(b, at, name, {{"uri", Type::kString}, {"byteLength", Type::kCount, true}, {"name", Type::kString}});
    });
    c.each(root, "", "images", "", [&](const Json& i, const std::string& at, const std::string& name) {
        c.object(i, at, name, {{"uri", Type::kString}, {"mimeType", Type::kString}, {"bufferView", Type::kIndex}, {"name", Type::kString}});
    });
    c.each(root, "", "textures", "", [&](const Json& t, const std::string& at, const std::string& name) {
        c.object(t, at, name, {{"sampler", Type::kIndex}, {"source", Type::kIndex}, {"name", Type::kString}});
    });
    c.each(root, "", "samplers", "", [&](const Json& s, const std::string& at, const std::string& name) {
        c.object(s, at, name, {{"magFilter", Type::kInteger, false, {9728, 9729}},
                               {"minFilter", Type::kInteger, false, {9728, 9729, 9984, 9985, 9986, 9987}},
                               {"wrapS", Type::kInteger, false, {33071, 33648, 10497}},
                               {"wrapT", Type::kInteger, false, {33071, 33648, 10497}}, {"name", Type::kString}});
    });
    c.each(root, "", "materials", "", [&](const Json& m, const std::string& at, const std::string& name) {
        c.object(m, at, name, {{"name", Type::kString}, {"pbrMetallicRoughness", Type::kObject}, {"normalTexture", Type::kObject},
                               {"occlusionTexture", Type::kObject}, {"emissiveTexture", Type::kObject},
                               {"emissiveFactor", Type::kNumbers}, {"alphaMode", Type::kString, false, {}, {"OPAQUE", "MASK", "BLEND"}},
                               {"alphaCutoff", Type::kNumber}, {"doubleSided", Type::kBool}, {"extensions", Type::kObject}});
        c.member(m, at, "pbrMetallicRoughness", name, [&](const Json& p, const std::string& pat, const std::string& pname) {
            c.object(p, pat, pname, {{"baseColorFactor", Type::kNumbers}, {"baseColorTexture", Type::kObject},
                                     {"metallicFactor", Type::kNumber}, {"roughnessFactor", Type::kNumber},
                                     {"metallicRoughnessTexture", Type::kObject}});
            c.member(p, pat, "baseColorTexture", pname, [&](const auto& v, const auto& a, const auto& n) { texture_info(c, v, a, n); });
            c.member(p, pat, "metallicRoughnessTexture", pname, [&](const auto& v, const auto& a, const auto& n) { texture_info(c, v, a, n); });
        });
        for (const char* key : {"normalTexture", "occlusionTexture", "emissiveTexture"})
            c.member(m, at, key, name, [&](const auto& v, const auto& a, const auto& n) { texture_info(c, v, a, n); });
    });
    c.each(root, "", "meshes", "", [&](const Json& m, const std::string& at, const std::string& name) {
        c.object(m, at, name, {{"primitives", Type::kObjects, true}, {"weights", Type::kNumbers}, {"name", Type::kString}});
        c.each(m, at, "primitives", name + ".", [&](const Json& p, const std::string& pat, const std::string& pname) {
            c.object(p, pat, pname, {{"attributes", Type::kObject, true}, {"indices", Type::kIndex}, {"material", Type::kIndex},
                                     {"mode", Type::kInteger, false, {0, 1, 2, 3, 4, 5, 6}}, {"targets", Type::kObjects},
                                     {"extensions", Type::kObject}});
            if (!c.error)
                for (const auto& [key, value] : p["attributes"].items())
                    if (!fits(value, Type::kIndex)) {
                        c.fail(pat + "/attributes/" + key, fmt::format("{}.attributes.{}: {} is not {}", pname, key,
                                                                     shown(value), type_name(Type::kIndex)));
                        break;
                    }
        });
    });
    c.each(root, "", "nodes", "", [&](const Json& n, const std::string& at, const std::string& name) {
        c.object(n, at, name, {{"camera", Type::kIndex}, {"children", Type::kIndices}, {"skin", Type::kIndex},
                               {"matrix", Type::kNumbers}, {"mesh", Type::kIndex}, {"rotation", Type::kNumbers},
                               {"scale", Type::kNumbers}, {"translation", Type::kNumbers}, {"weights", Type::kNumbers},
                               {"name", Type::kString}, {"extensions", Type::kObject}});
        for (const auto& [key, size] : {std::pair{"matrix", 16u}, {"rotation", 4u}, {"scale", 3u}, {"translation", 3u}})
            if (!c.error && n.contains(key) && n[key].size() != size)
                c.fail(at + "/" + key, fmt::format("{}.{}: {} numbers; it needs {}", name, key, n[key].size(), size));
    });
    c.each(root, "", "scenes", "", [&](const Json& s, const std::string& at, const std::string& name) {
        c.object(s, at, name, {{"nodes", Type::kIndices}, {"name", Type::kString}});
    });
    c.each(root, "", "cameras", "", [&](const Json& cam, const std::string& at, const std::string& name) {
        c.object(cam, at, name, {{"type", Type::kString, true, {}, {"perspective", "orthographic"}},
                                 {"perspective", Type::kObject}, {"orthographic", Type::kObject}, {"name", Type::kString}});
        c.member(cam, at, "perspective", name, [&](const Json& p, const std::string& pat, const std::string& pname) {
            c.object(p, pat, pname, {{"aspectRatio", Type::kNumber}, {"yfov", Type::kNumber, true}, {"zfar", Type::kNumber},
                                     {"znear", Type::kNumber, true}});
        });
        c.member(cam, at, "orthographic", name, [&](const Json& o, const std::string& oat, const std::string& oname) {
            c.object(o, oat, oname, {{"xmag", Type::kNumber, true}, {"ymag", Type::kNumber, true}, {"zfar", Type::kNumber, true},
                                     {"znear", Type::kNumber, true}});
        });
    });
    c.each(root, "", "skins", "", [&](const Json& s, const std::string& at, const std::string& name) {
        c.object(s, at, name, {{"inverseBindMatrices", Type::kIndex}, {"skeleton", Type::kIndex}, {"joints", Type::kIndices, true}});
    });
    c.each(root, "", "animations", "", [&](const Json& a, const std::string& at, const std::string& name) {
        c.object(a, at, name, {{"channels", Type::kObjects, true}, {"samplers", Type::kObjects, true}, {"name", Type::kString}});
        c.each(a, at, "channels", name + ".", [&](const Json& ch, const std::string& cat, const std::string& cname) {
            c.object(ch, cat, cname, {{"sampler", Type::kIndex, true}, {"target", Type::kObject, true}});
            c.member(ch, cat, "target", cname, [&](const Json& t, const std::string& tat, const std::string& tname) {
                c.object(t, tat, tname, {{"node", Type::kIndex}, {"path", Type::kString, true}});
            });
        });
        c.each(a, at, "samplers", name + ".", [&](const Json& s, const std::string& sat, const std::string& sname) {
            c.object(s, sat, sname, {{"input", Type::kIndex, true}, {"output", Type::kIndex, true},
                                     {"interpolation", Type::kString, false, {}, {"LINEAR", "STEP", "CUBICSPLINE"}}});
        });
    });
    return c.error;
}

}  // namespace glint
