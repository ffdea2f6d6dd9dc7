// PNG encoder settings on a real render: for each zlib level / strategy / filter, the median time
// of encode_png over several runs (on the machine's threads) and the file size; and the same with
// libspng's own encoder (one thread) for comparison. Results in docs/benchmarks.md.
//
//   glint_png_options IMAGE.ppm [RUNS]    (an 8-bit binary PPM, e.g. from glint render -o x.ppm)
#include <spng.h>
#include <zlib.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include "glint/image/image_formats.h"

namespace {

template <typename F>
double median_ms(int runs, F&& f) {
    std::vector<double> t;
    for (int i = 0; i < runs; ++i) {
        const auto a = std::chrono::steady_clock::now();
        f();
        t.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - a).count());
    }
    std::sort(t.begin(), t.end());
    return t[t.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: %s IMAGE.ppm [RUNS]\n", argv[0]);
        return 2;
    }
    const int runs = argc > 2 ? std::max(1, std::atoi(argv[2])) : 7;
    std::ifstream in(argv[1], std::ios::binary);
    std::string magic;
    int w = 0, h = 0, maxval = 0;
    in >> magic >> w >> h >> maxval;
    in.get();
    std::vector<std::uint8_t> rgb(static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 3);
    in.read(reinterpret_cast<char*>(rgb.data()), static_cast<std::streamsize>(rgb.size()));
    if (magic != "P6" || maxval != 255 || !in) {
        std::fprintf(stderr, "%s: expected an 8-bit binary PPM\n", argv[1]);
        return 1;
    }
    std::printf("%dx%d, median of %d runs\n\n| encoder | level | strategy | filter | ms | bytes |\n|---|---|---|---|---|---|\n",
                w, h, runs);
    const char* strategies[] = {"default", "filtered", "huffman", "rle"};
    const char* filters[] = {"none", "sub", "up", "average", "paeth"};
    for (int level : {1, 3, 6}) {
        for (int strategy : {0, 3}) {
            for (int filter : {0, 1, 2, 4}) {
                if (strategy == 3 && level != 1) continue;  // zlib's RLE ignores the level
                glint::PngOptions o{level, strategy, filter};
                std::size_t size = 0;
                const double ms = median_ms(runs, [&] { size = glint::encode_png(rgb.data(), w, h, false, {}, o).size(); });
                std::printf("| glint | %d | %s | %s | %.1f | %zu |\n", level, strategies[strategy], filters[filter], ms, size);
            }
        }
    }
    for (int level : {1, 6}) {
        std::size_t size = 0;
        const double ms = median_ms(runs, [&] {
            spng_ctx* ctx = spng_ctx_new(SPNG_CTX_ENCODER);
            spng_set_option(ctx, SPNG_ENCODE_TO_BUFFER, 1);
            spng_set_option(ctx, SPNG_IMG_COMPRESSION_LEVEL, level);
            spng_ihdr ihdr{static_cast<std::uint32_t>(w), static_cast<std::uint32_t>(h), 8, SPNG_COLOR_TYPE_TRUECOLOR, 0, 0, 0};
            spng_set_ihdr(ctx, &ihdr);
            spng_encode_image(ctx, rgb.data(), rgb.size(), SPNG_FMT_PNG, SPNG_ENCODE_FINALIZE);
            int error = 0;
            void* png = spng_get_png_buffer(ctx, &size, &error);
            std::free(png);
            spng_ctx_free(ctx);
        });
        std::printf("| libspng | %d | default | adaptive | %.1f | %zu |\n", level, ms, size);
    }
    return 0;
}
