#include "glint/samplers/stratified.h"

#include <algorithm>
#include <bit>
#include <cmath>

#include "glint/samplers/hash.h"

namespace glint {

std::uint32_t permute_index(std::uint32_t i, std::uint32_t n, std::uint32_t seed) {
    if (n <= 1) return 0;
    // A four-round Feistel network on the bits of n - 1 (a pseudo-random permutation: Luby and
    // Rackoff), the halves a and c bits wide, each round's function a keyed multiply-shift hash
    // of the other half. The mix-and-multiply bijection used before was a weak family (over
    // seeds, the images of 0 and 1 fixed that of 2: n^2 of the n(n-1)(n-2) triples occurred), so
    // the dimension pairs the padded Sobol sampler permutes with it stayed correlated: a third
    // more variance on Figure 14 soft at 64 spp (docs/denoising.md, "Half buffers").
    const auto bits = static_cast<unsigned>(std::bit_width(n - 1));
    const unsigned a = bits / 2, c = bits - a;
    const std::uint32_t keys[2] = {seed, mix32(seed)};
    do {
        std::uint32_t left = i >> c, right = i & ((1U << c) - 1U);
        unsigned left_bits = a, right_bits = c;
        for (unsigned round = 0; round < 4; ++round) {
            const std::uint32_t k = std::rotl(keys[round & 1], static_cast<int>(round * 5));
            const std::uint32_t f = (((right ^ k) * 0x9e3779b1U) ^ k) * 0x85ebca6bU;
            const std::uint32_t t = left_bits == 0 ? left : left ^ (f >> (32 - left_bits));
            left = right;
            right = t;
            std::swap(left_bits, right_bits);
        }
        i = (left << right_bits) | right;
    } while (i >= n);  // walks the cycle until it lands below n: fewer than 2 steps on average
    return i;
}

Sample2 stratified_sample(std::uint32_t index, std::uint32_t count, std::uint32_t seed) {
    const auto m = std::max<std::uint32_t>(
        1, static_cast<std::uint32_t>(std::sqrt(static_cast<double>(count))));
    const std::uint32_t k = (count + m - 1) / m;
    const std::uint32_t cell = permute_index(index, count, hash_combine(seed, 0x51633e2dU));
    const std::uint32_t cx = cell % m, cy = cell / m;
    const std::uint32_t sub_x = permute_index(cy, k, hash_combine(seed, 0x68bc21ebU));
    const std::uint32_t sub_y = permute_index(cx, m, hash_combine(seed, 0x02e5be93U));
    const float jx = to_unit_float(hash_combine(hash_combine(seed, 0xa399d265U), index));
    const float jy = to_unit_float(hash_combine(hash_combine(seed, 0x711ad6a5U), index));
    const float x = (static_cast<float>(cx) + (static_cast<float>(sub_x) + jx) / k) / m;
    const float y = (static_cast<float>(cy) + (static_cast<float>(sub_y) + jy) / m) / k;
    // Guard against rounding up to exactly 1.
    return {std::min(x, 0x1.fffffep-1f), std::min(y, 0x1.fffffep-1f)};
}

std::uint32_t pixel_seed(std::uint64_t scene_seed, std::uint32_t x, std::uint32_t y) {
    std::uint32_t h = mix32(static_cast<std::uint32_t>(scene_seed));
    h = hash_combine(h, static_cast<std::uint32_t>(scene_seed >> 32));
    h = hash_combine(h, x);
    return hash_combine(h, y);
}

}  // namespace glint
