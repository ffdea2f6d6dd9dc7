#include <tiny_gltf.h>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "glint/assets/gltf_importer.h"

namespace glint::gltf_detail {

/// The file's first animation at `time` seconds (held before its first key and after its
/// last): the translation, rotation and scale channels, sampled LINEAR (rotations by slerp),
/// STEP or CUBICSPLINE as the spec defines. Morph target weights are left out with a note.
void Importer::animate(double time) {
    if (model.animations.empty()) return;
    if (model.animations.size() > 1)
        out.notes.push_back(fmt::format("{}: has {} animations; glint plays the first ('{}')", file,
                                        model.animations.size(), model.animations[0].name));
    const tinygltf::Animation& a = model.animations[0];
    bool weights = false;
    for (std::size_t c = 0; c < a.channels.size(); ++c) {
        const tinygltf::AnimationChannel& ch = a.channels[c];
        const std::string at = fmt::format("/animations/0/channels/{}", c);
        const std::string& path = ch.target_path;
        if (path == "weights") {
            weights = true;
            continue;
        }
        const int n = path == "translation" || path == "scale" ? 3 : path == "rotation" ? 4 : 0;
        if (n == 0) fail_at(at + "/target/path", fmt::format("animation target path '{}' (translation, rotation, scale or weights)", path));
        if (ch.target_node < 0 || ch.target_node >= static_cast<int>(model.nodes.size()))
            fail_at(at + "/target/node", fmt::format("animation channel {}: node {} does not exist", c, ch.target_node));
        if (ch.sampler < 0 || ch.sampler >= static_cast<int>(a.samplers.size()))
            fail_at(at + "/sampler", fmt::format("animation channel {}: sampler {} does not exist", c, ch.sampler));
        const tinygltf::AnimationSampler& sm = a.samplers[static_cast<std::size_t>(ch.sampler)];
        const std::string sat = fmt::format("/animations/0/samplers/{}", ch.sampler);
        const std::string what = fmt::format("animation sampler {}", ch.sampler);
        const std::vector<double> t = read(sm.input, 1, what + " input", sat + "/input");
        const std::vector<double> v = read(sm.output, n, what + " output", sat + "/output");
        const bool cubic = sm.interpolation == "CUBICSPLINE";
        if (!cubic && sm.interpolation != "LINEAR" && sm.interpolation != "STEP")
            fail_at(sat + "/interpolation", fmt::format("{}: interpolation '{}' (LINEAR, STEP or CUBICSPLINE)", what, sm.interpolation));
        if (t.empty()) fail_at(sat + "/input", what + ": no keyframe times");
        for (std::size_t k = 0; k < t.size(); ++k)
            if (!std::isfinite(t[k]) || (k > 0 && !(t[k] > t[k - 1])))
                fail_at(sat + "/input", fmt::format("{}: keyframe times must be finite and increase (time {} is {})", what, k, t[k]));
        if (v.size() != t.size() * static_cast<std::size_t>(n) * (cubic ? 3 : 1))
            fail_at(sat + "/output", fmt::format("{}: {} values for {} keyframes{}", what, v.size() / static_cast<std::size_t>(n),
                                                 t.size(), cubic ? " (CUBICSPLINE needs three per keyframe)" : ""));
        for (double x : v)
            if (!std::isfinite(x)) fail_at(sat + "/output", what + ": a value is not a finite number");
        const std::vector<double> x = sample(t, v, n, time, cubic ? 2 : sm.interpolation == "STEP" ? 1 : 0, n == 4);
        Pose& pose = posed[ch.target_node];
        if (n == 4) pose.r = std::array<double, 4>{x[0], x[1], x[2], x[3]};
        else if (path == "translation") pose.t = std::array<double, 3>{x[0], x[1], x[2]};
        else pose.s = std::array<double, 3>{x[0], x[1], x[2]};
    }
    if (weights) out.notes.push_back(fmt::format("{}: animates morph target weights, which glint leaves out", file));
}

/// One channel's value at `time`: keys `t`, values `v` of `n` numbers (for CUBICSPLINE,
/// in-tangent, value, out-tangent per key); curve 0 LINEAR, 1 STEP, 2 CUBICSPLINE. Rotations
/// (`quaternion`) interpolate by slerp along the shorter arc, and come out unit length.
std::vector<double> Importer::sample(const std::vector<double>& t, const std::vector<double>& v, int n, double time,
                                  int curve, bool quaternion) {
    const std::size_t keys = t.size(), stride = static_cast<std::size_t>(n) * (curve == 2 ? 3 : 1);
    const std::size_t value = curve == 2 ? static_cast<std::size_t>(n) : 0;  // offset of the value in a key
    const auto key = [&](std::size_t k) { return std::vector<double>(v.begin() + k * stride + value,
                                                                     v.begin() + k * stride + value + n); };
    std::vector<double> x;
    if (time <= t[0]) x = key(0);
    else if (time >= t[keys - 1]) x = key(keys - 1);
    else {
        std::size_t i = static_cast<std::size_t>(std::upper_bound(t.begin(), t.end(), time) - t.begin()) - 1;
        const double dt = t[i + 1] - t[i], u = (time - t[i]) / dt;
        const std::vector<double> a = key(i), b = key(i + 1);
        x.resize(static_cast<std::size_t>(n));
        if (curve == 1) {
            x = a;
        } else if (curve == 2) {  // Hermite: a's out-tangent, b's in-tangent, scaled by the interval
            const double u2 = u * u, u3 = u2 * u;
            for (int c = 0; c < n; ++c) {
                const double out_a = v[i * stride + 2 * static_cast<std::size_t>(n) + static_cast<std::size_t>(c)];
                const double in_b = v[(i + 1) * stride + static_cast<std::size_t>(c)];
                x[static_cast<std::size_t>(c)] = (2 * u3 - 3 * u2 + 1) * a[static_cast<std::size_t>(c)] + (u3 - 2 * u2 + u) * dt * out_a +
                                                 (-2 * u3 + 3 * u2) * b[static_cast<std::size_t>(c)] + (u3 - u2) * dt * in_b;
            }
        } else if (quaternion) {
            double d = 0;
            for (int c = 0; c < 4; ++c) d += a[static_cast<std::size_t>(c)] * b[static_cast<std::size_t>(c)];
            const double sign = d < 0 ? -1 : 1;
            d = std::min(1.0, std::abs(d));
            const double theta = std::acos(d);
            double wa = 1 - u, wb = u;
            if (theta > 1e-6) wa = std::sin((1 - u) * theta) / std::sin(theta), wb = std::sin(u * theta) / std::sin(theta);
            for (int c = 0; c < 4; ++c)
                x[static_cast<std::size_t>(c)] = wa * a[static_cast<std::size_t>(c)] + sign * wb * b[static_cast<std::size_t>(c)];
        } else {
            for (int c = 0; c < n; ++c)
                x[static_cast<std::size_t>(c)] = a[static_cast<std::size_t>(c)] + u * (b[static_cast<std::size_t>(c)] - a[static_cast<std::size_t>(c)]);
        }
    }
    if (quaternion) {
        const double len = std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2] + x[3] * x[3]);
        if (len > 0) for (double& c : x) c /= len;
        else x = {0, 0, 0, 1};
    }
    return x;
}

Matrix34 Importer::node_matrix(int index) const {
    const tinygltf::Node& n = model.nodes[static_cast<std::size_t>(index)];
    const auto pose = posed.find(index);
    Matrix34 m;
    if (n.matrix.size() == 16 && pose == posed.end()) {  // column-major
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 4; ++c) m.m[r][c] = float(n.matrix[c * 4 + r]);
        return m;
    }
    double t[3] = {0, 0, 0}, q[4] = {0, 0, 0, 1}, s[3] = {1, 1, 1};
    if (n.translation.size() == 3) for (int k = 0; k < 3; ++k) t[k] = n.translation[k];
    if (n.rotation.size() == 4) for (int k = 0; k < 4; ++k) q[k] = n.rotation[k];
    if (n.scale.size() == 3) for (int k = 0; k < 3; ++k) s[k] = n.scale[k];
    if (pose != posed.end()) {
        if (pose->second.t) std::copy_n(pose->second.t->data(), 3, t);
        if (pose->second.r) std::copy_n(pose->second.r->data(), 4, q);
        if (pose->second.s) std::copy_n(pose->second.s->data(), 3, s);
    }
    const double x = q[0], y = q[1], z = q[2], w = q[3];
    const double r[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)},
                            {2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)},
                            {2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)}};
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) m.m[i][j] = float(r[i][j] * s[j]);
        m.m[i][3] = float(t[i]);
    }
    return m;
}

}  // namespace glint::gltf_detail
