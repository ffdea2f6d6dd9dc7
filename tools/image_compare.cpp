// glint_image_compare A B [--block N] [--tol T] [--region NAME X0 Y0 X1 Y1]...
//
// Two renders of one scene (any format glint reads: EXR, PFM, HDR, PNG ...) side by side, as
// bench/compare_pbrt.sh uses it against pbrt-v4: the channel means of each and their ratio; the
// mean of every N x N block (N = 16) of A against B's, and the fraction of blocks within T
// (relative, 5 %) with the median and 98th percentile of the relative differences; and the
// relative difference of the means of named regions (an object, the ground beside a light).
// A block darker than a tenth of B's mean is judged against that tenth (its difference relative
// to it), so that the noise of nearly black blocks does not count as disagreement.
// Exit status: 0; 1 when the images cannot be read or differ in size; 2 on a usage error.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <vector>

#include "glint/image/image_io.h"

namespace {

struct Region {
    std::string name;
    int x0, y0, x1, y1;  // pixels [x0, x1) x [y0, y1)
};

double channel(const glint::Color& c, int k) { return k == 0 ? c.r : k == 1 ? c.g : c.b; }

double region_mean(const glint::Image& im, int x0, int y0, int x1, int y1) {
    double sum = 0;
    long n = 0;
    for (int y = std::max(0, y0); y < std::min(im.height, y1); ++y)
        for (int x = std::max(0, x0); x < std::min(im.width, x1); ++x) {
            const glint::Color& c = im.texel(x, y);
            sum += (double(c.r) + c.g + c.b) / 3;
            ++n;
        }
    return n ? sum / double(n) : 0;
}

int usage() {
    std::fprintf(stderr, "usage: glint_image_compare A B [--block N] [--tol T] [--region NAME X0 Y0 X1 Y1]...\n");
    return 2;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 3) return usage();
    int block = 16;
    double tol = 0.05;
    std::vector<Region> regions;
    for (int i = 3; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--block" && i + 1 < argc) block = std::max(1, std::atoi(argv[++i]));
        else if (a == "--tol" && i + 1 < argc) tol = std::atof(argv[++i]);
        else if (a == "--region" && i + 5 < argc) {
            regions.push_back({argv[i + 1], std::atoi(argv[i + 2]), std::atoi(argv[i + 3]), std::atoi(argv[i + 4]),
                               std::atoi(argv[i + 5])});
            i += 5;
        } else return usage();
    }
    glint::Image a, b;
    try {
        a = glint::read_image(argv[1], glint::ImageEncoding::kLinear);
        b = glint::read_image(argv[2], glint::ImageEncoding::kLinear);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "glint_image_compare: %s\n", e.what());
        return 1;
    }
    if (a.width != b.width || a.height != b.height) {
        std::fprintf(stderr, "glint_image_compare: %dx%d against %dx%d\n", a.width, a.height, b.width, b.height);
        return 1;
    }
    double mean_a[3] = {0, 0, 0}, mean_b[3] = {0, 0, 0};
    for (std::size_t i = 0; i < a.texels.size(); ++i)
        for (int k = 0; k < 3; ++k) mean_a[k] += channel(a.texels[i], k), mean_b[k] += channel(b.texels[i], k);
    const double n = double(a.texels.size());
    std::printf("channel means  A %.6g %.6g %.6g  B %.6g %.6g %.6g  A/B %.4f %.4f %.4f\n", mean_a[0] / n,
                mean_a[1] / n, mean_a[2] / n, mean_b[0] / n, mean_b[1] / n, mean_b[2] / n, mean_a[0] / mean_b[0],
                mean_a[1] / mean_b[1], mean_a[2] / mean_b[2]);
    const double floor = 0.1 * (mean_b[0] + mean_b[1] + mean_b[2]) / (3 * n);
    std::vector<double> diffs;
    for (int y = 0; y + block <= a.height; y += block)
        for (int x = 0; x + block <= a.width; x += block) {
            const double ma = region_mean(a, x, y, x + block, y + block), mb = region_mean(b, x, y, x + block, y + block);
            diffs.push_back(std::abs(ma - mb) / std::max(mb, floor));
        }
    std::sort(diffs.begin(), diffs.end());
    const auto within = std::count_if(diffs.begin(), diffs.end(), [tol](double d) { return d <= tol; });
    const auto at = [&](double q) { return diffs.empty() ? 0.0 : diffs[std::size_t(q * double(diffs.size() - 1))]; };
    std::printf("%dx%d blocks    %zu, within %.0f %%: %.1f %%  (median %.2f %%, 98th percentile %.2f %%, worst %.2f %%)\n",
                block, block, diffs.size(), tol * 100, diffs.empty() ? 0.0 : 100.0 * double(within) / double(diffs.size()),
                100 * at(0.5), 100 * at(0.98), 100 * at(1.0));
    for (const Region& r : regions) {
        const double ma = region_mean(a, r.x0, r.y0, r.x1, r.y1), mb = region_mean(b, r.x0, r.y0, r.x1, r.y1);
        std::printf("region %-12s A %.6g  B %.6g  A/B %.4f\n", r.name.c_str(), ma, mb, mb > 0 ? ma / mb : 0.0);
    }
    return 0;
}
