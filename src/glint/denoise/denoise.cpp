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

// Two sets of weights (strict and loose colour, each also bounded by the features) and five
// candidates from them: the strict weights' mean, the strict weights' plane fit, the loose
// weights' plane fit, and with the albedo's halves the loose weights' mean and plane fit of the
// shading times the pixel's albedo (docs/denoising.md says how these were chosen).
constexpr int kWeightSets = 2;
constexpr int kCandidates = 5;
constexpr int kColumnSums = 9;                 // per set of weights and column of offsets (add_column_*)
constexpr int kShadingColumnSums = 6;          // the shading's set's sums of the shading, per column
constexpr int kMoments = 15;                   // the sums a plane fit needs (fold_*)
constexpr int kShadingMoments = 9;             // and its moments of the shading
constexpr float kShadingFloor = 0.01f;         // added to the albedo the shading is divided by
constexpr int kShadeSet = 1;                   // the weights the shading is filtered with: the loose set
// Where the albedo's noise is large against the albedo (its variance over its square above this),
// the shading candidates' first-order risk estimate does not hold (an emitter's edge, where the
// colour is not albedo times shading): they are not considered there.
constexpr float kShadingMaxRelativeVariance = 0.25f;
constexpr double kRidge = 0.1;                 // on the slopes, times the sum of weights
constexpr float kColourK[kWeightSets] = {1.0f, 2.0f};  // the colour bandwidths
constexpr float kEpsilon = 1e-10f;             // keeps a noise-free pixel's distances finite
// Feature bandwidths: albedo per channel, normal (unit vectors), depth relative to itself after
// the plane through the pixel (its gradient) is taken away.
constexpr float kAlbedoScale = 0.1f, kNormalScale = 0.2f, kDepthScale = 0.02f;
// The loose set's normal distance is this times the strict set's (a bandwidth 4 times as wide):
// its colour term already stops it at an edge the colour shows (docs/denoising.md, step 3).
constexpr float kLooseNormal = 0.0625f;
// The filter's working memory per pixel of a strip at its peak (while the candidates are
// computed): the planes (23 floats and a flag) and five candidates with their error estimates;
// and what a strip may use (docs/denoising.md, "Speed and memory").
constexpr std::size_t kBytesPerPixel = 23 * 4 + 1 + kCandidates * 16;
constexpr std::size_t kStripBytes = std::size_t{256} << 20;
constexpr int kBand = 16;  // rows per task: fixed, so the work's split never depends on threads
// The error maps are smoothed over (2 kSureRadius + 1)^2 pixels and the choice blended over
// (2 kBlendRadius + 1)^2 (docs/denoising.md says how these were chosen).
constexpr int kSureRadius = 3, kBlendRadius = 2;

// Maximum and minimum by value, which the vectoriser turns into selects.
inline float max2(float a, float b) { return a > b ? a : b; }
inline float min2(float a, float b) { return a < b ? a : b; }

// exp(-x) for x >= 0, to 4e-6 relative, in plain arithmetic (vectorisable; the same bits on
// every machine and thread count): 2^y = 2^n 2^f with n = y rounded (by adding 1.5 x 2^23, whose
// low bits then hold n) and f in [-1/2, 1/2], 2^f by its Taylor polynomial of degree 6. x is
// clamped to 80 (exp(-80) = 1.8e-35 is no weight), which also turns NaN and inf into 80.
inline float exp_neg(float x) {
    const float y = -min2(x, 80.0f) * 1.44269504f;  // log2(e); in [-115.5, 0]
    constexpr float kMagic = 12582912.0f;
    const float r = y + kMagic;
    const float f = y - (r - kMagic);
    float p = 1.5403530393381606e-4f;
    p = p * f + 1.3333558146428443e-3f;
    p = p * f + 9.6181291076284772e-3f;
    p = p * f + 5.5504108664821580e-2f;
    p = p * f + 2.4022650695910071e-1f;
    p = p * f + 6.9314718055994531e-1f;
    p = p * f + 1.0f;
    const std::int32_t n = std::bit_cast<std::int32_t>(r) - std::bit_cast<std::int32_t>(kMagic);  // in [-116, 0]
    return p * std::bit_cast<float>(static_cast<std::uint32_t>(n + 127) << 23);
}

std::size_t at(int w, int x, int y) { return static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x); }

// f(y) for every row y in [0, h), rows in parallel: each row's result depends on nothing another
// row writes, so the result is the same for any split.
template <class F>
void for_rows(int h, const F& f) {
    tbb::parallel_for(tbb::blocked_range<int>(0, h, 8), [&](const tbb::blocked_range<int>& b) {
        for (int y = b.begin(); y < b.end(); ++y) f(y);
    });
}

// Box mean over (2r+1)^2 pixels, clamped at the borders (the mean of the pixels inside).
template <class T>
std::vector<T> box(const std::vector<T>& in, int w, int h, int r) {
    std::vector<T> rows(in.size()), out(in.size());
    for_rows(h, [&](int y) {
        for (int x = 0; x < w; ++x) {
            T s{};
            const int x0 = std::max(0, x - r), x1 = std::min(w - 1, x + r);
            for (int i = x0; i <= x1; ++i) s = s + in[at(w, i, y)];
            rows[at(w, x, y)] = s * (1.0f / static_cast<float>(x1 - x0 + 1));
        }
    });
    for_rows(h, [&](int y) {
        const int y0 = std::max(0, y - r), y1 = std::min(h - 1, y + r);
        for (int x = 0; x < w; ++x) {
            T s{};
            for (int j = y0; j <= y1; ++j) s = s + rows[at(w, x, j)];
            out[at(w, x, y)] = s * (1.0f / static_cast<float>(y1 - y0 + 1));
        }
    });
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
        if (in.even_albedo && !is_finite(in.even_albedo[i])) throw std::invalid_argument(where(i, "albedo's even half"));
        if (in.odd_albedo && !is_finite(in.odd_albedo[i])) throw std::invalid_argument(where(i, "albedo's odd half"));
        if (in.normal && !(std::isfinite(in.normal[i].x) && std::isfinite(in.normal[i].y) && std::isfinite(in.normal[i].z)))
            throw std::invalid_argument(where(i, "normal"));
        if (in.depth && std::isnan(in.depth[i])) throw std::invalid_argument(where(i, "depth"));
    }
}

// The inputs as planes of floats, one per channel (what the loops below vectorise over), the
// features prefiltered: each a 3 x 3 mean weighted by its own differences.
struct Planes {
    int width = 0;
    std::vector<float> c[3], v[3];     // colour, its variance
    std::vector<float> a[3], nrm[3];   // albedo, normal (zero when absent)
    std::vector<float> z, inv_z, hit;  // depth (0 on a miss), 1 / its scale, 1 where hit (all 1 without depth)
    std::vector<float> gx, gy;         // depth gradient (the smaller one-sided difference)
    // With the albedo's halves: the shading s = c / (albedo + floor) (the pixel's own albedo,
    // not prefiltered) and the covariance of the albedo's and the colour's means per channel
    // (from the halves, like the variance).
    bool shading = false;
    std::vector<float> s[3], cov[3];
    std::vector<std::uint8_t> shading_ok;  // 1 where the shading candidates are considered
};

// The albedo the shading is divided by: the pixel's own, not below 0, plus the floor.
inline float shading_albedo(const Color& albedo, int ch) { return std::max(0.0f, albedo[ch]) + kShadingFloor; }

// The covariance of two means per pixel and channel from their halves, (a_e - a_o)(b_e - b_o) / 4,
// smoothed over 5 x 5 pixels: with a = b the variance of the image's mean (the filter's noise
// estimate); with the albedo's and the colour's halves their covariance; with the albedo's
// halves alone the albedo's variance.
std::vector<Color> half_covariance(const DenoiseInput& in, const Color* ae, const Color* ao, const Color* be,
                                   const Color* bo) {
    const std::size_t n = static_cast<std::size_t>(in.width) * static_cast<std::size_t>(in.height);
    std::vector<Color> v(n);
    for (std::size_t i = 0; i < n; ++i) v[i] = (ae[i] - ao[i]) * (be[i] - bo[i]) * 0.25f;
    return box(v, in.width, in.height, 2);
}

Planes planes(const DenoiseInput& in, const std::vector<Color>& var) {
    const int w = in.width, h = in.height;
    const std::size_t n = static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
    Planes pl;
    pl.width = w;
    for (int ch = 0; ch < 3; ++ch) {
        pl.c[ch].resize(n), pl.v[ch].resize(n), pl.a[ch].assign(n, 0.0f), pl.nrm[ch].assign(n, 0.0f);
    }
    pl.z.assign(n, 0.0f), pl.inv_z.assign(n, 0.0f), pl.hit.assign(n, 1.0f), pl.gx.assign(n, 0.0f), pl.gy.assign(n, 0.0f);
    const auto hit = [&](std::size_t i) { return std::isfinite(in.depth[i]); };
    for_rows(h, [&](int y) {
        for (int x = 0; x < w; ++x) {
            const std::size_t p = at(w, x, y);
            for (int ch = 0; ch < 3; ++ch) pl.c[ch][p] = in.color[p][ch], pl.v[ch][p] = var[p][ch];
            Color sa{0};
            Vector3 sn{0, 0, 0};
            float sz = 0, wa = 0, wn = 0, wz = 0;
            for (int j = std::max(0, y - 1); j <= std::min(h - 1, y + 1); ++j) {
                for (int i = std::max(0, x - 1); i <= std::min(w - 1, x + 1); ++i) {
                    const std::size_t q = at(w, i, j);
                    if (in.albedo) {
                        const Color d = in.albedo[q] - in.albedo[p];
                        const float k = exp_neg((d.r * d.r + d.g * d.g + d.b * d.b) / (3 * kAlbedoScale * kAlbedoScale));
                        sa += in.albedo[q] * k, wa += k;
                    }
                    if (in.normal) {
                        const Vector3 d = to_vector(in.normal[q]) - to_vector(in.normal[p]);
                        const float k = exp_neg(dot(d, d) / (kNormalScale * kNormalScale));
                        sn = sn + to_vector(in.normal[q]) * k, wn += k;
                    }
                    if (in.depth && hit(p) && hit(q)) {
                        const float d = (in.depth[q] - in.depth[p]) / (kDepthScale * in.depth[p] + 1e-6f);
                        const float k = exp_neg(d * d);
                        sz += in.depth[q] * k, wz += k;
                    }
                }
            }
            if (in.albedo) {
                const Color a = sa / wa;
                for (int ch = 0; ch < 3; ++ch) pl.a[ch][p] = a[ch];
            }
            if (in.normal) {
                const Vector3 v = sn / wn;
                pl.nrm[0][p] = v.x, pl.nrm[1][p] = v.y, pl.nrm[2][p] = v.z;
            }
            if (in.depth && hit(p)) {
                pl.z[p] = sz / wz;
                pl.inv_z[p] = 1 / (kDepthScale * pl.z[p] + 1e-6f);
            } else if (in.depth) {
                pl.hit[p] = 0;
            }
        }
    });
    if (in.depth) {
        // The gradient: of the two one-sided differences the smaller (an edge is not a slope).
        const auto slope = [](float left, float right) { return std::abs(left) < std::abs(right) ? left : right; };
        for_rows(h, [&](int y) {
            for (int x = 0; x < w; ++x) {
                const std::size_t p = at(w, x, y);
                if (pl.hit[p] == 0) continue;
                const float inf = std::numeric_limits<float>::infinity();
                const auto diff = [&](int i, int j, bool forward) {
                    if (i < 0 || j < 0 || i >= w || j >= h) return inf;
                    const std::size_t q = at(w, i, j);
                    if (pl.hit[q] == 0) return inf;
                    return forward ? pl.z[q] - pl.z[p] : pl.z[p] - pl.z[q];
                };
                const float gx = slope(diff(x - 1, y, false), diff(x + 1, y, true));
                const float gy = slope(diff(x, y - 1, false), diff(x, y + 1, true));
                pl.gx[p] = std::isfinite(gx) ? gx : 0;
                pl.gy[p] = std::isfinite(gy) ? gy : 0;
            }
        });
    }
    pl.shading = in.albedo && in.even_albedo && in.odd_albedo;
    if (pl.shading) {
        const std::vector<Color> cov = half_covariance(in, in.even_albedo, in.odd_albedo, in.even, in.odd),
                                 va = half_covariance(in, in.even_albedo, in.odd_albedo, in.even_albedo, in.odd_albedo);
        pl.shading_ok.resize(n);
        for (int ch = 0; ch < 3; ++ch) pl.s[ch].resize(n), pl.cov[ch].resize(n);
        for_rows(h, [&](int y) {
            for (int x = 0; x < w; ++x) {
                const std::size_t p = at(w, x, y);
                float rel = 0;
                for (int ch = 0; ch < 3; ++ch) {
                    const float a = shading_albedo(in.albedo[p], ch);
                    pl.s[ch][p] = in.color[p][ch] / a, pl.cov[ch][p] = cov[p][ch];
                    rel = std::max(rel, va[p][ch] / (a * a));
                }
                pl.shading_ok[p] = rel <= kShadingMaxRelativeVariance;
            }
        });
    }
    return pl;
}

// A run of n pixels' colour terms of one channel, added to t (set by the first channel), for the
// strict bandwidth; the loose one's terms are these times (k0 / k1)^2 (weight_run).
[[gnu::noinline]] void colour_term_run(const float* __restrict cp, const float* __restrict vp, const float* __restrict cq,
                     const float* __restrict vq, float* __restrict t, int n, bool first) {
    constexpr float k0 = kColourK[0] * kColourK[0];
    for (int x = 0; x < n; ++x) {
        const float a = vp[x], b = vq[x];
        const float d = cp[x] - cq[x];
        const float num = (d * d - (a + min2(a, b))) * (1.0f / 3);
        const float u = num / (kEpsilon + k0 * (a + b));
        t[x] = first ? u : t[x] + u;
    }
}

// One row of colour terms for the offset (dx, qy - y): per pixel, the mean over channels of
// ((c_p - c_q)^2 - (v_p + min(v_p, v_q))) / (eps + k0^2 (v_p + v_q)), the strict bandwidth.
void colour_terms(const Planes& pl, int y, int qy, int dx, int w, float* t0) {
    const std::size_t p0 = static_cast<std::size_t>(y) * static_cast<std::size_t>(w),
                      q0 = static_cast<std::size_t>(qy) * static_cast<std::size_t>(w);
    const auto term = [&](int x, int qx, float* o0) {
        *o0 = 0;
        for (int ch = 0; ch < 3; ++ch) {
            const std::size_t i = p0 + static_cast<std::size_t>(x), j = q0 + static_cast<std::size_t>(qx);
            colour_term_run(&pl.c[ch][i], &pl.v[ch][i], &pl.c[ch][j], &pl.v[ch][j], o0, 1, ch == 0);
        }
    };
    const int xa = std::clamp(-dx, 0, w), xb = std::clamp(w - dx, xa, w);
    for (int x = 0; x < xa; ++x) term(x, std::clamp(x + dx, 0, w - 1), &t0[x]);
    // The interior, where p + d is inside: straight loops over the planes.
    const std::size_t xs = static_cast<std::size_t>(xa), qs = q0 + static_cast<std::size_t>(xa + dx);
    for (int ch = 0; ch < 3; ++ch)
        colour_term_run(pl.c[ch].data() + p0 + xs, pl.v[ch].data() + p0 + xs, pl.c[ch].data() + qs, pl.v[ch].data() + qs,
                        t0 + xs, xb - xa, ch == 0);
    for (int x = xb; x < w; ++x) term(x, std::clamp(x + dx, 0, w - 1), &t0[x]);
}

// The sums over one column of offsets (a fixed dx, every dy) of a set of weights, per pixel:
// w, w dy, w dy^2, then w c for r, g and b, then w c dy for r, g and b (kColumnSums planes), and
// for the shading's set of weights the same of the shading s (w s, then w s dy). fold_*() turn them into the moments of a plane
// fit: w, w dx, w dy, w dx^2, w dx dy, w dy^2 and per channel w c, w c dx, w c dy: the dx factors
// are constant over a column, so they are applied once per column, not once per neighbour. Each
// loop's pointers are distinct parameters, so that GCC knows they do not alias and vectorises.
[[gnu::noinline]] void add_column_colour(float* __restrict t0, float* __restrict t1, float* __restrict t2,
                                         float* __restrict r0, float* __restrict g0, float* __restrict b0,
                                         float* __restrict r1, float* __restrict g1, float* __restrict b1,
                                         const float* __restrict wt, const float* __restrict cr,
                                         const float* __restrict cg, const float* __restrict cb, float dy, int n) {
    const float yy = dy * dy;
    for (int x = 0; x < n; ++x) {
        const float v = wt[x], vr = v * cr[x], vg = v * cg[x], vb = v * cb[x];
        t0[x] += v, t1[x] += v * dy, t2[x] += v * yy;
        r0[x] += vr, g0[x] += vg, b0[x] += vb;
        r1[x] += vr * dy, g1[x] += vg * dy, b1[x] += vb * dy;
    }
}
[[gnu::noinline]] void add_column_values(float* __restrict r0, float* __restrict g0, float* __restrict b0,
                                         float* __restrict r1, float* __restrict g1, float* __restrict b1,
                                         const float* __restrict wt, const float* __restrict cr,
                                         const float* __restrict cg, const float* __restrict cb, float dy, int n) {
    for (int x = 0; x < n; ++x) {
        const float v = wt[x], vr = v * cr[x], vg = v * cg[x], vb = v * cb[x];
        r0[x] += vr, g0[x] += vg, b0[x] += vb;
        r1[x] += vr * dy, g1[x] += vg * dy, b1[x] += vb * dy;
    }
}
[[gnu::noinline]] void fold_weights(float* __restrict m0, float* __restrict m1, float* __restrict m2,
                                    float* __restrict m3, float* __restrict m4, float* __restrict m5,
                                    const float* __restrict t0, const float* __restrict t1, const float* __restrict t2,
                                    float dx, int n) {
    const float xx = dx * dx;
    for (int x = 0; x < n; ++x) {
        m0[x] += t0[x], m1[x] += dx * t0[x], m2[x] += t1[x], m3[x] += xx * t0[x], m4[x] += dx * t1[x], m5[x] += t2[x];
    }
}
[[gnu::noinline]] void fold_values(float* __restrict s0, float* __restrict s1, float* __restrict s2,
                                   const float* __restrict t0, const float* __restrict t1, float dx, int n) {
    for (int x = 0; x < n; ++x) s0[x] += t0[x], s1[x] += dx * t0[x], s2[x] += t1[x];
}

// Sums of three along a row, clamped at its ends.
void box3_row(const float* in, float* out, int w) {
    if (w == 1) {
        out[0] = 3 * in[0];
        return;
    }
    out[0] = 2 * in[0] + in[1];
    for (int x = 1; x < w - 1; ++x) out[x] = in[x - 1] + in[x] + in[x + 1];
    out[w - 1] = in[w - 2] + 2 * in[w - 1];
}

// A pixel's features, from a row's start (weights() reads p's and its neighbour q's).
struct FeatureRows {
    const float* a[3];
    const float* n[3];
    const float *z, *inv_z, *hit, *gx, *gy;
};

FeatureRows feature_rows(const Planes& pl, std::size_t at) {
    return {{pl.a[0].data() + at, pl.a[1].data() + at, pl.a[2].data() + at},
            {pl.nrm[0].data() + at, pl.nrm[1].data() + at, pl.nrm[2].data() + at},
            pl.z.data() + at, pl.inv_z.data() + at, pl.hit.data() + at, pl.gx.data() + at, pl.gy.data() + at};
}

// The feature distances of a run of pixels (the largest of albedo, normal and depth), into dfo for
// the strict set and into dfl for the loose set (its normal term scaled down).
[[gnu::noinline]] void feature_run(const float* __restrict pa0, const float* __restrict pa1, const float* __restrict pa2,
                                   const float* __restrict qa0, const float* __restrict qa1, const float* __restrict qa2,
                                   const float* __restrict pn0, const float* __restrict pn1, const float* __restrict pn2,
                                   const float* __restrict qn0, const float* __restrict qn1, const float* __restrict qn2,
                                   const float* __restrict pz, const float* __restrict qz, const float* __restrict piz,
                                   const float* __restrict ph, const float* __restrict qh, const float* __restrict pgx,
                                   const float* __restrict pgy, float fdx, float fdy, float* __restrict dfo, float* __restrict dfl, int count) {
    constexpr float ka = 1 / (3 * kAlbedoScale * kAlbedoScale), kn = 1 / (kNormalScale * kNormalScale);
    for (int x = 0; x < count; ++x) {
        const float a0 = qa0[x] - pa0[x], a1 = qa1[x] - pa1[x], a2 = qa2[x] - pa2[x];
        const float n0 = qn0[x] - pn0[x], n1 = qn1[x] - pn1[x], n2 = qn2[x] - pn2[x];
        const float e = (qz[x] - (pz[x] + pgx[x] * fdx + pgy[x] * fdy)) * piz[x];
        const float hd = ph[x] - qh[x];
        const float dz = ph[x] * qh[x] * e * e + hd * hd * 1e30f;
        const float da = max2((a0 * a0 + a1 * a1 + a2 * a2) * ka, dz), dn = (n0 * n0 + n1 * n1 + n2 * n2) * kn;
        dfo[x] = max2(da, dn);
        dfl[x] = max2(da, dn * kLooseNormal);
    }
}

// The weights from the feature distances and the colour terms' row sums. The loose colour
// distance is the strict one times (k0 / k1)^2: the terms differ only in k^2 beside the variance
// (and in where the epsilon for a noise-free pair sits, which leaves such a pair's weight 0 or 1).
[[gnu::noinline]] void weight_run(const float* __restrict dfi, const float* __restrict dfl, const float* __restrict h0a, const float* __restrict h0b,
                                  const float* __restrict h0c, float* __restrict w0, float* __restrict w1,
                                  int count) {
    // exp(-max(a, b)) = min(exp(-a), exp(-b)), and with k1 = 2 k0 the loose colour weight is the
    // strict one's fourth root: two exponentials per neighbour, not three.
    static_assert(kColourK[1] == 2 * kColourK[0], "the loose weight is the strict one's fourth root");
    for (int x = 0; x < count; ++x) {
        const float feature = exp_neg(dfi[x]), loose = exp_neg(dfl[x]);
        const float colour = exp_neg(max2(0.0f, (h0a[x] + h0b[x] + h0c[x]) * (1.0f / 9)));
        w0[x] = min2(colour, feature);
        w1[x] = min2(std::sqrt(std::sqrt(colour)), loose);
    }
}

// The two sets' weights of (p, p + (dx, dy)) for pixels x in [xa, xb) of row y: the least of the
// colour weight (the 3 x 3 patch's mean term, rows a, b, c of the row sums) and the feature
// weight, strict and loose.
void weights(const Planes& pl, int y, int qy, int dx, int dy, int xa, int xb, const float* h0a, const float* h0b,
             const float* h0c, float* df, float* dl, float* w0, float* w1) {
    const std::size_t p = static_cast<std::size_t>(y) * static_cast<std::size_t>(pl.width) + static_cast<std::size_t>(xa);
    const std::size_t q = static_cast<std::size_t>(qy) * static_cast<std::size_t>(pl.width) + static_cast<std::size_t>(xa + dx);
    const auto s = static_cast<std::size_t>(xa);
    const FeatureRows fp = feature_rows(pl, p), fq = feature_rows(pl, q);
    feature_run(fp.a[0], fp.a[1], fp.a[2], fq.a[0], fq.a[1], fq.a[2], fp.n[0], fp.n[1], fp.n[2], fq.n[0], fq.n[1], fq.n[2],
                fp.z, fq.z, fp.inv_z, fp.hit, fq.hit, fp.gx, fp.gy, static_cast<float>(dx), static_cast<float>(dy), df + s, dl + s,
                xb - xa);
    weight_run(df + s, dl + s, h0a + s, h0b + s, h0c + s, w0 + s, w1 + s, xb - xa);
}

}  // namespace

std::vector<Color> denoise_variance(const DenoiseInput& in) {
    check(in);
    return half_covariance(in, in.even, in.odd, in.even, in.odd);
}

namespace {

// The filter on a whole image `in` (or a strip of rows of one, with its halo), of which the rows
// [keep0, keep1) are written to `out` (row keep0 first) and their choices counted into `chosen`.
void denoise_rows(const DenoiseInput& in, const DenoiseOptions& options, int keep0, int keep1, Color* out,
                  double* chosen) {
    // The variance lives on in the planes (pl.v); the planes go once the candidates are computed:
    // the working memory peaks at kBytesPerPixel (docs/denoising.md, "Speed and memory").
    // (denoise() has checked the whole image; a strip is not checked again.)
    Planes pl = planes(in, half_covariance(in, in.even, in.odd, in.even, in.odd));
    const int w = in.width, h = in.height, r = std::max(0, options.radius);
    const std::size_t n = static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
    const Color* c = in.color;
    const bool shade = pl.shading;

    // Each candidate's image and its SURE error map, filled band by band.
    std::vector<Color> filtered[kCandidates];
    std::vector<float> sure[kCandidates];
    for (int k = 0; k < kCandidates; ++k) filtered[k].resize(n), sure[k].resize(n);
    const int bands = (h + kBand - 1) / kBand;
    const auto run_band = [&](int band) {
        const int y0 = band * kBand, y1 = std::min(h, y0 + kBand);
        const int ty0 = std::max(0, y0 - 1), ty1 = std::min(h, y1 + 1);  // with the patches' halo
        const auto row_size = static_cast<std::size_t>(w);
        std::vector<float> t0(static_cast<std::size_t>(ty1 - ty0) * row_size), h0(t0.size());
        std::vector<float> wk0(row_size), wk1(row_size), dfr(row_size), dlr(row_size);
        // The band's sums, plane by plane: per column of offsets (cols) and over the window
        // (moments); the strict set's first, then the loose set's.
        const std::size_t band_pixels = static_cast<std::size_t>(y1 - y0) * row_size;
        int ncol[kWeightSets] = {kColumnSums, kColumnSums};
        int nmom[kWeightSets] = {kMoments, kMoments};
        if (shade) ncol[kShadeSet] += kShadingColumnSums, nmom[kShadeSet] += kShadingMoments;
        // Planes one cache line further apart than their size: a loop over a dozen planes whose
        // addresses agree modulo 4 KiB would evict its own lines from the 8-way L1 cache (a band
        // of 1920-pixel rows is exactly 30 pages; with the padding the column sums went from 27 %
        // of `glint denoise`'s time at 1080p to 7 %).
        const std::size_t stride = band_pixels + 16;
        std::vector<float> cols(static_cast<std::size_t>(ncol[0] + ncol[1]) * stride);
        std::vector<float> moments(static_cast<std::size_t>(nmom[0] + nmom[1]) * stride, 0.0f);
        float* col[kWeightSets][kColumnSums + kShadingColumnSums];
        float* mom[kWeightSets][kMoments + kShadingMoments];
        for (int k = 0, ci = 0, mi = 0; k < kWeightSets; ++k) {
            for (int j = 0; j < ncol[k]; ++j) col[k][j] = cols.data() + static_cast<std::size_t>(ci++) * stride;
            for (int j = 0; j < nmom[k]; ++j) mom[k][j] = moments.data() + static_cast<std::size_t>(mi++) * stride;
        }
        for (int dx = -r; dx <= r; ++dx) {
            const int xa = std::max(0, -dx), xb = std::min(w, w - dx);
            if (xa >= xb) continue;
            std::fill(cols.begin(), cols.end(), 0.0f);
            for (int dy = -r; dy <= r; ++dy) {
                // Per-pixel colour terms of (p, p + d), neighbours clamped to the image.
                for (int y = ty0; y < ty1; ++y) {
                    const std::size_t row = static_cast<std::size_t>(y - ty0) * row_size;
                    colour_terms(pl, y, std::clamp(y + dy, 0, h - 1), dx, w, &t0[row]);
                    box3_row(&t0[row], &h0[row], w);
                }
                const auto fy = static_cast<float>(dy);
                for (int y = y0; y < y1; ++y) {
                    const int qy = y + dy;
                    if (qy < 0 || qy >= h) continue;
                    const std::size_t ra = static_cast<std::size_t>(std::max(ty0, y - 1) - ty0) * row_size,
                                      rb = static_cast<std::size_t>(y - ty0) * row_size,
                                      rc = static_cast<std::size_t>(std::min(ty1 - 1, y + 1) - ty0) * row_size;
                    weights(pl, y, qy, dx, dy, xa, xb, &h0[ra], &h0[rb], &h0[rc],
                            dfr.data(), dlr.data(), wk0.data(), wk1.data());
                    const std::size_t p0 = static_cast<std::size_t>(y - y0) * row_size, q0 = static_cast<std::size_t>(qy) * row_size;
                    const float* wk[kWeightSets] = {wk0.data(), wk1.data()};
                    const std::size_t xs = static_cast<std::size_t>(xa), qs = q0 + static_cast<std::size_t>(xa + dx);
                    const std::size_t o = p0 + xs;
                    const int count = xb - xa;
                    for (int k = 0; k < kWeightSets; ++k) {
                        // Column planes: w, w dy, w dy^2, then w c for r, g, b, then w c dy (and
                        // for the shading set the same of s).
                        const float* wt = wk[k] + xs;
                        float* const* t = col[k];
                        add_column_colour(t[0] + o, t[1] + o, t[2] + o, t[3] + o, t[4] + o, t[5] + o, t[6] + o, t[7] + o,
                                          t[8] + o, wt, pl.c[0].data() + qs, pl.c[1].data() + qs, pl.c[2].data() + qs, fy,
                                          count);
                        if (k == kShadeSet && shade)
                            add_column_values(t[9] + o, t[10] + o, t[11] + o, t[12] + o, t[13] + o, t[14] + o, wt,
                                              pl.s[0].data() + qs, pl.s[1].data() + qs, pl.s[2].data() + qs, fy, count);
                    }
                }
            }
            const auto fx = static_cast<float>(dx);
            const auto bp = static_cast<int>(band_pixels);
            for (int k = 0; k < kWeightSets; ++k) {
                float* const* t = col[k];
                float* const* m = mom[k];
                fold_weights(m[0], m[1], m[2], m[3], m[4], m[5], t[0], t[1], t[2], fx, bp);
                for (int ch = 0; ch < 3; ++ch) fold_values(m[6 + 3 * ch], m[7 + 3 * ch], m[8 + 3 * ch], t[3 + ch], t[6 + ch], fx, bp);
                if (k == kShadeSet && shade)
                    for (int ch = 0; ch < 3; ++ch)
                        fold_values(m[15 + 3 * ch], m[16 + 3 * ch], m[17 + 3 * ch], t[9 + ch], t[12 + ch], fx, bp);
            }
        }
        for (std::size_t i = 0; i < band_pixels; ++i) {
            const std::size_t p = static_cast<std::size_t>(y0) * row_size + i;
            const float v = pl.v[0][p] + pl.v[1][p] + pl.v[2][p];
            // SURE of an output f whose derivative by the pixel's own colour is df.
            const auto risk = [&](const Color& f, float df) {
                const Color d = f - c[p];
                return d.r * d.r + d.g * d.g + d.b * d.b + v * (2 * df - 1);
            };
            // A shading candidate's: the output a f, with a the pixel's albedo (plus the floor)
            // and f the filtered shading, moves with the pixel's colour through f (derivative
            // df) and with its albedo, whose noise goes with the colour's: the risk gains
            // 2 cov(a, c) (f - df s_p) per channel (docs/denoising.md derives it).
            const auto shading_risk = [&](const float* f, float df, Color* value) {
                float e = 0, g[3];
                for (int ch = 0; ch < 3; ++ch) {
                    g[ch] = shading_albedo(in.albedo[p], ch) * f[ch];
                    const float d = g[ch] - c[p][ch];
                    e += d * d + pl.v[ch][p] * (2 * df - 1) + 2 * pl.cov[ch][p] * (f[ch] - df * pl.s[ch][p]);
                }
                *value = Color{g[0], g[1], g[2]};
                return e;
            };
            // The strict weights' mean. The pixel weighs itself by 1, so the sum of weights is at least 1.
            float* const* m = mom[0];
            const float sw = m[0][i];
            filtered[0][p] = Color{m[6][i] / sw, m[9][i] / sw, m[12][i] / sw};
            sure[0][p] = risk(filtered[0][p], 1 / sw);
            if (shade) {
                float* const* ms = mom[kShadeSet];
                const float sws = ms[0][i];
                const float f[3] = {ms[15][i] / sws, ms[18][i] / sws, ms[21][i] / sws};
                sure[3][p] = shading_risk(f, 1 / sws, &filtered[3][p]);
                if (!pl.shading_ok[p]) sure[3][p] = std::numeric_limits<float>::infinity();
            } else {
                sure[3][p] = sure[4][p] = std::numeric_limits<float>::infinity();
            }
            for (std::size_t k = 0; k < kWeightSets; ++k) {
                // The plane's value at the pixel: the first row of the moments' inverse times the
                // colour sums (a ridge on the slopes keeps a fit along a line, or of the pixel
                // alone, from dividing by zero). Its derivative by the pixel's colour is the
                // inverse's corner: the pixel sits at (0, 0) with weight 1.
                m = mom[k];
                const double s0 = m[0][i], sx = m[1][i], sy = m[2][i];
                const double sxx = m[3][i] + kRidge * s0, sxy = m[4][i], syy = m[5][i] + kRidge * s0;
                const double c0 = syy * sxx - sxy * sxy, c1 = sy * sxy - sx * syy, c2 = sx * sxy - sy * sxx;
                const double det = s0 * c0 + sx * c1 + sy * c2;
                const double i0 = c0 / det, i1 = c1 / det, i2 = c2 / det;
                const auto fit = [&](int first) {
                    return static_cast<float>(i0 * m[first][i] + i1 * m[first + 1][i] + i2 * m[first + 2][i]);
                };
                filtered[1 + k][p] = Color{fit(6), fit(9), fit(12)};
                sure[1 + k][p] = risk(filtered[1 + k][p], static_cast<float>(i0));
                if (k == kShadeSet && shade) {
                    const float f[3] = {fit(15), fit(18), fit(21)};
                    sure[4][p] = shading_risk(f, static_cast<float>(i0), &filtered[4][p]);
                    if (!pl.shading_ok[p]) sure[4][p] = std::numeric_limits<float>::infinity();
                }
            }
        }
    };
    tbb::parallel_for(tbb::blocked_range<int>(0, bands, 1), [&](const tbb::blocked_range<int>& b) {
        for (int band = b.begin(); band < b.end(); ++band) run_band(band);
    });

    pl = Planes{};
    for (int k = 0; k < kCandidates; ++k) sure[k] = box(sure[k], w, h, kSureRadius);
    // The choice, one-hot, then blended over 5 x 5.
    struct Shares {
        std::array<float, kCandidates> v{};
        Shares operator+(const Shares& o) const {
            Shares r;
            for (std::size_t k = 0; k < kCandidates; ++k) r.v[k] = v[k] + o.v[k];
            return r;
        }
        Shares operator*(float s) const {
            Shares r;
            for (std::size_t k = 0; k < kCandidates; ++k) r.v[k] = v[k] * s;
            return r;
        }
    };
    std::vector<Shares> hot(n);
    const std::size_t kept0 = at(w, 0, keep0), kept1 = at(w, 0, keep1);
    for (std::size_t p = 0; p < n; ++p) {
        std::size_t best = 0;
        for (std::size_t k = 1; k < kCandidates; ++k)
            if (sure[k][p] < sure[best][p]) best = k;
        hot[p].v[best] = 1;
        if (p >= kept0 && p < kept1) chosen[best] += 1;
    }
    for (auto& s : sure) s = {};
    hot = box(hot, w, h, kBlendRadius);
    for (std::size_t p = kept0; p < kept1; ++p) {
        Color o{0};
        float total = 0;
        for (std::size_t k = 0; k < kCandidates; ++k) total += hot[p].v[k];
        for (std::size_t k = 0; k < kCandidates; ++k) o += filtered[k][p] * (hot[p].v[k] / total);
        out[p - kept0] = o;
    }
}

// The rows a strip's result depends on beyond it, on each side: the output blends the choice
// over +-kBlendRadius rows, the choice compares error maps smoothed over +-kSureRadius, the candidates at a pixel read
// neighbours +-r away and their 3 x 3 patches (+-1), whose variance is smoothed over +-2, and
// each computation clamps at its input's edge. A strip filtered with this many rows of the image
// on each side gives the bits the whole image would (test Denoise.StripsGiveTheWholeImagesBits).
int halo(int radius) { return kBlendRadius + kSureRadius + radius + 1 + 2; }

}  // namespace

std::vector<Color> denoise(const DenoiseInput& in, const DenoiseOptions& options, DenoiseStats* stats) {
    const auto start = std::chrono::steady_clock::now();
    check(in);
    const int w = in.width, h = in.height, r = std::max(0, options.radius);
    // Strips of rows, each with its halo, so that the working memory stays near kStripBytes
    // whatever the image's size (a 4K image in six strips, 1080p in two).
    const int rows = options.strip_rows > 0 ? options.strip_rows
                                            : std::max(64, static_cast<int>(kStripBytes / (kBytesPerPixel * static_cast<std::size_t>(w))));
    std::vector<Color> out(static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
    double chosen[kCandidates] = {};
    tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic);
    arena.execute([&] {
        for (int y0 = 0; y0 < h; y0 += rows) {
            const int y1 = std::min(h, y0 + rows), s0 = std::max(0, y0 - halo(r)), s1 = std::min(h, y1 + halo(r));
            const std::size_t o = at(w, 0, s0);
            const auto shift = [o](const auto* plane) { return plane ? plane + o : nullptr; };
            const DenoiseInput strip{w,
                                     s1 - s0,
                                     shift(in.color),
                                     shift(in.even),
                                     shift(in.odd),
                                     shift(in.albedo),
                                     shift(in.normal),
                                     shift(in.depth),
                                     shift(in.even_albedo),
                                     shift(in.odd_albedo)};
            denoise_rows(strip, options, y0 - s0, y1 - s0, out.data() + at(w, 0, y0), chosen);
        }
    });
    if (stats) {
        for (int k = 0; k < kCandidates; ++k) stats->chosen[k] = chosen[k] / static_cast<double>(out.size());
        stats->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
    return out;
}

}  // namespace glint
