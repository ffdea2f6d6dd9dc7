#include "glint/math/motion.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace glint {

namespace {

using M3 = std::array<std::array<double, 3>, 3>;

M3 linear_part(const Matrix34& m) {
    M3 a{};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) a[i][j] = m.m[i][j];
    return a;
}

double det3(const M3& a) {
    return a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
           a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
}

// The inverse transpose (a singular matrix is refused before this is reached).
M3 inverse_transpose(const M3& a) {
    const double d = det3(a);
    M3 r{};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            const int i1 = (i + 1) % 3, i2 = (i + 2) % 3, j1 = (j + 1) % 3, j2 = (j + 2) % 3;
            r[i][j] = (a[i1][j1] * a[i2][j2] - a[i1][j2] * a[i2][j1]) / d;  // cofactor / det
        }
    return r;
}

// A = R S with R a rotation and S symmetric (Higham's iteration R <- (R + R^-T) / 2). A mirror
// (det < 0) is decomposed as -A = R S', so that R stays a rotation and S = -S' carries the flip.
void polar(const M3& a, M3& r, M3& s) {
    const double sign = det3(a) < 0 ? -1 : 1;
    M3 x = a;
    for (auto& row : x)
        for (double& v : row) v *= sign;
    for (int it = 0; it < 100; ++it) {
        const M3 y = inverse_transpose(x);
        double change = 0;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) {
                const double next = 0.5 * (x[i][j] + y[i][j]);
                change = std::max(change, std::abs(next - x[i][j]));
                x[i][j] = next;
            }
        if (change < 1e-14) break;
    }
    r = x;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            double v = 0;
            for (int k = 0; k < 3; ++k) v += r[k][i] * a[k][j];  // R^T A
            s[i][j] = v;
        }
}

// The unit quaternion (w, x, y, z) of rotation matrix r (Shepperd's method).
std::array<double, 4> to_quaternion(const M3& r) {
    const double trace = r[0][0] + r[1][1] + r[2][2];
    std::array<double, 4> q{};
    if (trace > 0) {
        const double s = std::sqrt(trace + 1) * 2;
        q = {s / 4, (r[2][1] - r[1][2]) / s, (r[0][2] - r[2][0]) / s, (r[1][0] - r[0][1]) / s};
    } else if (r[0][0] > r[1][1] && r[0][0] > r[2][2]) {
        const double s = std::sqrt(1 + r[0][0] - r[1][1] - r[2][2]) * 2;
        q = {(r[2][1] - r[1][2]) / s, s / 4, (r[0][1] + r[1][0]) / s, (r[0][2] + r[2][0]) / s};
    } else if (r[1][1] > r[2][2]) {
        const double s = std::sqrt(1 + r[1][1] - r[0][0] - r[2][2]) * 2;
        q = {(r[0][2] - r[2][0]) / s, (r[0][1] + r[1][0]) / s, s / 4, (r[1][2] + r[2][1]) / s};
    } else {
        const double s = std::sqrt(1 + r[2][2] - r[0][0] - r[1][1]) * 2;
        q = {(r[1][0] - r[0][1]) / s, (r[0][2] + r[2][0]) / s, (r[1][2] + r[2][1]) / s, s / 4};
    }
    const double n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    for (double& v : q) v /= n;
    return q;
}

M3 to_matrix(const std::array<double, 4>& q) {
    const double w = q[0], x = q[1], y = q[2], z = q[3];
    return {{{1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)},
             {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)},
             {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)}}};
}

std::array<double, 4> slerp(std::array<double, 4> a, std::array<double, 4> b, double u) {
    double c = a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3];
    if (c < 0) {  // the shorter way round
        for (double& v : b) v = -v;
        c = -c;
    }
    std::array<double, 4> q{};
    if (c > 0.9995) {  // nearly the same: blend linearly, then normalise
        for (int i = 0; i < 4; ++i) q[i] = a[i] + (b[i] - a[i]) * u;
    } else {
        const double theta = std::acos(std::min(1.0, c));
        const double wa = std::sin((1 - u) * theta) / std::sin(theta), wb = std::sin(u * theta) / std::sin(theta);
        for (int i = 0; i < 4; ++i) q[i] = wa * a[i] + wb * b[i];
    }
    const double n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    for (double& v : q) v /= n;
    return q;
}

bool same_linear(const Matrix34& a, const Matrix34& b) {
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            if (a.m[i][j] != b.m[i][j]) return false;
    return true;
}

}  // namespace

int shutter_segments(double frames) {
    if (!(frames > 0)) return 1;
    return static_cast<int>(std::clamp(std::ceil(4 * frames), 1.0, 64.0));
}

Motion::Motion(std::vector<Transform> keys) : keys_(std::move(keys)) {
    if (keys_.empty()) keys_.push_back(Transform{});
    for (const Transform& k : keys_) {
        Parts p;
        for (int i = 0; i < 3; ++i) p.t[i] = k.to_world.m[i][3];
        M3 r, s;
        const M3 a = linear_part(k.to_world);
        if (!(std::abs(det3(a)) > 1e-30) || !std::isfinite(det3(a)))
            throw std::invalid_argument("a motion key is not invertible");
        polar(a, r, s);
        p.q = to_quaternion(r);
        p.s = s;
        parts_.push_back(p);
        translation_only_ = translation_only_ && same_linear(k.to_world, keys_[0].to_world);
    }
    // Keys all alike: the motion is still (one key).
    bool alike = true;
    for (const Transform& k : keys_) alike = alike && k.to_world == keys_[0].to_world;
    if (alike) {
        keys_.resize(1);
        parts_.resize(1);
    }
}

Transform Motion::at(Float time) const {
    if (keys_.size() == 1) return keys_[0];
    const double segments = static_cast<double>(keys_.size() - 1);
    const double x = std::clamp(static_cast<double>(time), 0.0, 1.0) * segments;
    const std::size_t k = std::min(static_cast<std::size_t>(x), keys_.size() - 2);
    const double u = x - static_cast<double>(k);
    const Parts& a = parts_[k];
    const Parts& b = parts_[k + 1];
    Transform out = keys_[0];
    Vector3 t;
    for (int i = 0; i < 3; ++i) t[i] = static_cast<Float>(a.t[i] + (b.t[i] - a.t[i]) * u);
    if (translation_only_) {
        // The linear parts are key 0's; only the translations (and the inverse's) change.
        const Vector3 back = out.to_object.apply(t);
        for (int i = 0; i < 3; ++i) {
            out.to_world.m[i][3] = t[i];
            out.to_object.m[i][3] = -back[i];
        }
        return out;
    }
    const M3 r = to_matrix(slerp(a.q, b.q, u));
    M3 s{};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) s[i][j] = a.s[i][j] + (b.s[i][j] - a.s[i][j]) * u;
    Matrix34 m;
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) {
            double v = 0;
            for (int k2 = 0; k2 < 3; ++k2) v += r[i][k2] * s[k2][j];
            m.m[i][j] = static_cast<Float>(v);
        }
        m.m[i][3] = t[i];
    }
    if (const auto inv = Transform::from(m)) return *inv;
    return out;  // a stretch that passes through zero between keys: the key's own
}

Bounds3 Motion::swept_bounds(const Bounds3& b) const {
    if (b.empty()) return b;
    Bounds3 out;
    const auto unite = [&](const Bounds3& x) {
        out.extend(x.lo);
        out.extend(x.hi);
    };
    if (keys_.size() == 1 || translation_only_) {
        for (const Transform& k : keys_) unite(k.bounds(b));
        return out;
    }
    constexpr int kSteps = 64;
    const int n = static_cast<int>(keys_.size() - 1) * kSteps;
    Float pad = 0;
    std::array<Point3, 8> previous{};
    for (int i = 0; i <= n; ++i) {
        const Transform x = at(static_cast<Float>(i) / static_cast<Float>(n));
        for (int c = 0; c < 8; ++c) {
            const Point3 p = x.point({c & 1 ? b.hi.x : b.lo.x, c & 2 ? b.hi.y : b.lo.y, c & 4 ? b.hi.z : b.lo.z});
            out.extend(p);
            if (i > 0) pad = std::max(pad, length(p - previous[c]));
            previous[c] = p;
        }
    }
    const Vector3 widen{pad, pad, pad};
    out.lo = out.lo - widen;
    out.hi = out.hi + widen;
    return out;
}

Transform rotation_between(Vector3 from, Vector3 to) {
    const Vector3 axis = cross(from, to);
    const Float s = length(axis), c = dot(from, to);
    if (s > 1e-7f) return Transform::rotate(std::atan2(s, c) * Float(180 / std::numbers::pi), axis);
    if (c > 0) return Transform{};
    // Opposite: half a turn about any axis perpendicular to `from`.
    const Vector3 other = std::abs(from.x) < 0.9f ? Vector3{1, 0, 0} : Vector3{0, 1, 0};
    return Transform::rotate(180, cross(from, other));
}

std::vector<Transform> light_keys(const std::vector<Point3>& positions, const std::vector<Vector3>& directions,
                                  Point3 still_at) {
    const std::size_t n = std::max(positions.size(), directions.size());
    std::vector<Transform> keys;
    keys.reserve(n);
    for (std::size_t k = 0; k < n; ++k) {
        const Transform move = Transform::translate(to_vector(positions.empty() ? still_at : positions[k]));
        keys.push_back(directions.empty() ? move
                                          : move * rotation_between(normalize(directions[0]), normalize(directions[k])));
    }
    return keys;
}

}  // namespace glint
