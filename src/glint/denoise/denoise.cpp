#include "glint/denoise/denoise.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <array>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>

namespace glint {
namespace {

constexpr int kCandidates = 3;
constexpr float kColourK[2] = {0.45f, 1.0f};  // the colour candidates' bandwidths
constexpr float kEpsilon = 1e-10f;             // keeps a noise-free pixel's distances finite
// Feature bandwidths: albedo per channel, normal (unit vectors), depth relative to itself after
// the plane through the pixel (its gradient) is taken away.
constexpr float kAlbedoScale = 0.05f, kNormalScale = 0.2f, kDepthScale = 0.02f;
constexpr int kBand = 16;  // rows per task: fixed, so the work's split never depends on threads

// exp(-x) for x >= 0, to about 6e-6 relative, as a polynomial in plain arithmetic (vectorisable;
// the same bits on every machine and thread count). 0 beyond x = 80.
inline float exp_neg(float x) {
    if (!(x < 80.0f)) return 0.0f;
    const float y = -x * 1.44269504f;  // log2(e)
    const float fl = std::floor(y);
    const float f = y - fl;  // in [0, 1)
    // 2^f on [0, 1): a degree-6 polynomial (Horner), within 5.6e-6 of it.
    float p = 1.535336188319500e-4f;
    p = p * f + 1.339887440266574e-3f;
    p = p * f + 9.618437357674640e-3f;
    p = p * f + 5.550332471162809e-2f;
    p = p * f + 2.402264791363012e-1f;
    p = p * f + 6.931472028550421e-1f;
    p = p * f + 1.0f;
    const int e = static_cast<int>(fl);  // in (-116, 0]
    return p * std::bit_cast<float>(static_cast<std::uint32_t>(e + 127) << 23);
}

std::size_t at(int w, int x, int y) { return static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x); }

// Box mean over (2r+1)^2 pixels, clamped at the borders (the mean of the pixels inside).
template <class T>
std::vector<T> box(const std::vector<T>& in, int w, int h, int r) {
    std::vector<T> rows(in.size()), out(in.size());
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            T s{};
            const int x0 = std::max(0, x - r), x1 = std::min(w - 1, x + r);
            for (int i = x0; i <= x1; ++i) s = s + in[at(w, i, y)];
            rows[at(w, x, y)] = s * (1.0f / static_cast<float>(x1 - x0 + 1));
        }
    }
    for (int y = 0; y < h; ++y) {
        const int y0 = std::max(0, y - r), y1 = std::min(h - 1, y + r);
        for (int x = 0; x < w; ++x) {
            T s{};
            for (int j = y0; j <= y1; ++j) s = s + rows[at(w, x, j)];
            out[at(w, x, y)] = s * (1.0f / static_cast<float>(y1 - y0 + 1));
        }
    }
    return out;
}

void check(const DenoiseInput& in) {
    if (in.width <= 0 || in.height <= 0)
        throw std::invalid_argument("the image is " + std::to_string(in.width) + " x " + std::to_string(in.height) + " pixels");
    if (!in.color) throw std::invalid_argument("the image's colour is missing");
    if (!in.even || !in.odd)
        throw std::invalid_argument("the two half images (even- and odd-numbered samples) are missing: the noise cannot be estimated");
    const int w = in.width;
    const auto where = [w](std::size_t i, const char* plane) {
        return std::string("pixel (") + std::to_string(i % static_cast<std::size_t>(w)) + ", " +
               std::to_string(i / static_cast<std::size_t>(w)) + ") of the " + plane + " is not a finite number";
    };
    const std::size_t n = static_cast<std::size_t>(in.width) * static_cast<std::size_t>(in.height);
    for (std::size_t i = 0; i < n; ++i) {
        if (!is_finite(in.color[i])) throw std::invalid_argument(where(i, "image"));
        if (!is_finite(in.even[i])) throw std::invalid_argument(where(i, "even half"));
        if (!is_finite(in.odd[i])) throw std::invalid_argument(where(i, "odd half"));
        if (in.albedo && !is_finite(in.albedo[i])) throw std::invalid_argument(where(i, "albedo"));
        if (in.normal && !(std::isfinite(in.normal[i].x) && std::isfinite(in.normal[i].y) && std::isfinite(in.normal[i].z)))
            throw std::invalid_argument(where(i, "normal"));
        if (in.depth && std::isnan(in.depth[i])) throw std::invalid_argument(where(i, "depth"));
    }
}

// The features, prefiltered: each a 3 x 3 mean weighted by its own differences.
struct Features {
    bool albedo = false, normal = false, depth = false;
    std::vector<Color> a;
    std::vector<Vector3> nrm;
    std::vector<float> z;      // finite; `hit` says where something was hit
    std::vector<std::uint8_t> hit;
    std::vector<float> gx, gy;  // depth gradient (the smaller one-sided difference)
};

Features prefilter(const DenoiseInput& in) {
    const int w = in.width, h = in.height;
    const std::size_t n = static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
    Features f;
    f.albedo = in.albedo != nullptr, f.normal = in.normal != nullptr, f.depth = in.depth != nullptr;
    if (f.albedo) f.a.resize(n);
    if (f.normal) f.nrm.resize(n);
    if (f.depth) f.z.resize(n), f.hit.resize(n), f.gx.assign(n, 0), f.gy.assign(n, 0);
    const auto hit = [&](std::size_t i) { return std::isfinite(in.depth[i]); };
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const std::size_t p = at(w, x, y);
            Color sa{0};
            Vector3 sn{0, 0, 0};
            float sz = 0, wa = 0, wn = 0, wz = 0;
            for (int j = std::max(0, y - 1); j <= std::min(h - 1, y + 1); ++j) {
                for (int i = std::max(0, x - 1); i <= std::min(w - 1, x + 1); ++i) {
                    const std::size_t q = at(w, i, j);
                    if (f.albedo) {
                        const Color d = in.albedo[q] - in.albedo[p];
                        const float k = exp_neg((d.r * d.r + d.g * d.g + d.b * d.b) / (3 * kAlbedoScale * kAlbedoScale));
                        sa += in.albedo[q] * k, wa += k;
                    }
                    if (f.normal) {
                        const Vector3 d = to_vector(in.normal[q]) - to_vector(in.normal[p]);
                        const float k = exp_neg(dot(d, d) / (kNormalScale * kNormalScale));
                        sn = sn + to_vector(in.normal[q]) * k, wn += k;
                    }
                    if (f.depth && hit(p) && hit(q)) {
                        const float d = (in.depth[q] - in.depth[p]) / (kDepthScale * in.depth[p] + 1e-6f);
                        const float k = exp_neg(d * d);
                        sz += in.depth[q] * k, wz += k;
                    }
                }
            }
            if (f.albedo) f.a[p] = sa / wa;
            if (f.normal) f.nrm[p] = sn / wn;
            if (f.depth) {
                f.hit[p] = hit(p) ? 1 : 0;
                f.z[p] = hit(p) ? sz / wz : 0;
            }
        }
    }
    if (f.depth) {
        // The gradient: of the two one-sided differences the smaller (an edge is not a slope).
        const auto slope = [](float left, float right) { return std::abs(left) < std::abs(right) ? left : right; };
        for (int y = 0; y < h; ++y) {
            for (int x = 0; x < w; ++x) {
                const std::size_t p = at(w, x, y);
                if (!f.hit[p]) continue;
                const float inf = std::numeric_limits<float>::infinity();
                const auto diff = [&](int i, int j, bool forward) {
                    if (i < 0 || j < 0 || i >= w || j >= h) return inf;
                    const std::size_t q = at(w, i, j);
                    if (!f.hit[q]) return inf;
                    return forward ? f.z[q] - f.z[p] : f.z[p] - f.z[q];
                };
                const float gx = slope(diff(x - 1, y, false), diff(x + 1, y, true));
                const float gy = slope(diff(x, y - 1, false), diff(x, y + 1, true));
                f.gx[p] = std::isfinite(gx) ? gx : 0;
                f.gy[p] = std::isfinite(gy) ? gy : 0;
            }
        }
    }
    return f;
}

// d(p, q) of the features (the largest of the three), with q = p + (dx, dy).
inline float feature_distance(const Features& f, std::size_t p, std::size_t q, int dx, int dy) {
    float d = 0;
    if (f.albedo) {
        const Color a = f.a[q] - f.a[p];
        d = std::max(d, (a.r * a.r + a.g * a.g + a.b * a.b) * (1 / (3 * kAlbedoScale * kAlbedoScale)));
    }
    if (f.normal) {
        const Vector3 v = f.nrm[q] - f.nrm[p];
        d = std::max(d, dot(v, v) * (1 / (kNormalScale * kNormalScale)));
    }
    if (f.depth) {
        if (f.hit[p] != f.hit[q]) return std::numeric_limits<float>::infinity();
        if (f.hit[p]) {
            const float predicted = f.z[p] + f.gx[p] * static_cast<float>(dx) + f.gy[p] * static_cast<float>(dy);
            const float e = (f.z[q] - predicted) / (kDepthScale * f.z[p] + 1e-6f);
            d = std::max(d, e * e);
        }
    }
    return d;
}

struct Sums {
    float r, g, b, w;
};

}  // namespace

std::vector<Color> denoise_variance(const DenoiseInput& in) {
    check(in);
    const std::size_t n = static_cast<std::size_t>(in.width) * static_cast<std::size_t>(in.height);
    std::vector<Color> v(n);
    for (std::size_t i = 0; i < n; ++i) {
        const Color d = in.even[i] - in.odd[i];
        v[i] = d * d * 0.25f;
    }
    return box(v, in.width, in.height, 2);
}

std::vector<Color> denoise(const DenoiseInput& in, const DenoiseOptions& options, DenoiseStats* stats) {
    const auto start = std::chrono::steady_clock::now();
    const std::vector<Color> var = denoise_variance(in);  // checks `in`
    const Features feat = prefilter(in);
    const int w = in.width, h = in.height, r = std::max(0, options.radius);
    const std::size_t n = static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
    const Color* c = in.color;

    // The candidates' sums, per pixel.
    std::vector<std::array<Sums, kCandidates>> sums(n);
    const int bands = (h + kBand - 1) / kBand;
    const auto run_band = [&](int band) {
        const int y0 = band * kBand, y1 = std::min(h, y0 + kBand);
        const int ty0 = std::max(0, y0 - 1), ty1 = std::min(h, y1 + 1);  // with the patches' halo
        const int rows = ty1 - ty0;
        std::vector<float> t[2], hsum[2];
        for (int k = 0; k < 2; ++k) t[k].resize(static_cast<std::size_t>(rows) * w), hsum[k].resize(t[k].size());
        for (int dy = -r; dy <= r; ++dy) {
            for (int dx = -r; dx <= r; ++dx) {
                // Per-pixel colour terms of (p, p + d), neighbours clamped to the image.
                for (int y = ty0; y < ty1; ++y) {
                    const int qy = std::clamp(y + dy, 0, h - 1);
                    float* t0 = &t[0][static_cast<std::size_t>(y - ty0) * w];
                    float* t1 = &t[1][static_cast<std::size_t>(y - ty0) * w];
                    for (int x = 0; x < w; ++x) {
                        const std::size_t p = at(w, x, y), q = at(w, std::clamp(x + dx, 0, w - 1), qy);
                        float s0 = 0, s1 = 0;
                        for (int ch = 0; ch < 3; ++ch) {
                            const float vp = var[p][ch], vq = var[q][ch];
                            const float d = c[p][ch] - c[q][ch];
                            const float num = d * d - (vp + std::min(vp, vq));
                            const float s = vp + vq;
                            s0 += num / (kEpsilon + kColourK[0] * kColourK[0] * s);
                            s1 += num / (kEpsilon + kColourK[1] * kColourK[1] * s);
                        }
                        t0[x] = s0 * (1.0f / 3), t1[x] = s1 * (1.0f / 3);
                    }
                }
                // 3 x 3 patch means: along rows, then down columns.
                for (int k = 0; k < 2; ++k) {
                    for (int y = 0; y < rows; ++y) {
                        const float* row = &t[k][static_cast<std::size_t>(y) * w];
                        float* out = &hsum[k][static_cast<std::size_t>(y) * w];
                        for (int x = 0; x < w; ++x)
                            out[x] = row[std::max(0, x - 1)] + row[x] + row[std::min(w - 1, x + 1)];
                    }
                }
                for (int y = y0; y < y1; ++y) {
                    const int qy = y + dy;
                    if (qy < 0 || qy >= h) continue;
                    const int ya = std::max(ty0, y - 1) - ty0, yb = y - ty0, yc = std::min(ty1 - 1, y + 1) - ty0;
                    for (int x = std::max(0, -dx); x < std::min(w, w - dx); ++x) {
                        const std::size_t p = at(w, x, y), q = at(w, x + dx, qy);
                        const float df = feature_distance(feat, p, q, dx, dy);
                        const float wf = exp_neg(df);
                        float wk[kCandidates];
                        for (int k = 0; k < 2; ++k) {
                            const float* hs = hsum[k].data();
                            const float dc = (hs[static_cast<std::size_t>(ya) * w + x] + hs[static_cast<std::size_t>(yb) * w + x] +
                                              hs[static_cast<std::size_t>(yc) * w + x]) * (1.0f / 9);
                            wk[k] = exp_neg(std::max({0.0f, dc, df}));
                        }
                        wk[2] = wf;
                        const Color cq = c[q];
                        for (int k = 0; k < kCandidates; ++k) {
                            Sums& s = sums[p][static_cast<std::size_t>(k)];
                            s.r += wk[k] * cq.r, s.g += wk[k] * cq.g, s.b += wk[k] * cq.b, s.w += wk[k];
                        }
                    }
                }
            }
        }
    };
    tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic);
    arena.execute([&] {
        tbb::parallel_for(tbb::blocked_range<int>(0, bands, 1), [&](const tbb::blocked_range<int>& b) {
            for (int band = b.begin(); band < b.end(); ++band) run_band(band);
        });
    });

    // Each candidate's image and its SURE error map.
    std::vector<Color> filtered[kCandidates];
    std::vector<float> sure[kCandidates];
    for (int k = 0; k < kCandidates; ++k) {
        filtered[k].resize(n), sure[k].resize(n);
        for (std::size_t p = 0; p < n; ++p) {
            const Sums& s = sums[p][static_cast<std::size_t>(k)];
            // The pixel weighs itself by 1, so the sum of weights is at least 1.
            const Color f{s.r / s.w, s.g / s.w, s.b / s.w};
            filtered[k][p] = f;
            const Color d = f - c[p];
            const float self = 2 / s.w - 1;
            sure[k][p] = d.r * d.r + d.g * d.g + d.b * d.b + (var[p].r + var[p].g + var[p].b) * self;
        }
        sure[k] = box(sure[k], w, h, 3);
    }
    // The choice, one-hot, then blended over 5 x 5.
    std::vector<std::array<float, kCandidates>> choice(n);
    for (std::size_t p = 0; p < n; ++p) {
        int best = 0;
        for (int k = 1; k < kCandidates; ++k)
            if (sure[k][p] < sure[best][p]) best = k;
        choice[p] = {0, 0, 0};
        choice[p][static_cast<std::size_t>(best)] = 1;
    }
    struct Triple {
        std::array<float, kCandidates> v{};
        Triple operator+(const Triple& o) const { return {{v[0] + o.v[0], v[1] + o.v[1], v[2] + o.v[2]}}; }
        Triple operator*(float s) const { return {{v[0] * s, v[1] * s, v[2] * s}}; }
    };
    std::vector<Triple> hot(n);
    for (std::size_t p = 0; p < n; ++p) hot[p].v = choice[p];
    hot = box(hot, w, h, 2);
    std::vector<Color> out(n);
    double chosen[kCandidates] = {0, 0, 0};
    for (std::size_t p = 0; p < n; ++p) {
        Color o{0};
        float total = 0;
        for (int k = 0; k < kCandidates; ++k) total += hot[p].v[static_cast<std::size_t>(k)];
        for (int k = 0; k < kCandidates; ++k) {
            const float s = hot[p].v[static_cast<std::size_t>(k)] / total;
            o += filtered[k][p] * s;
            chosen[k] += choice[p][static_cast<std::size_t>(k)];
        }
        out[p] = o;
    }
    if (stats) {
        for (int k = 0; k < kCandidates; ++k) stats->chosen[k] = chosen[k] / static_cast<double>(n);
        stats->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
    return out;
}

}  // namespace glint
