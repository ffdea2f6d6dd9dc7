#include "glint/samplers/stratified.h"

#include <algorithm>
#include <cmath>

#include "glint/samplers/hash.h"

namespace glint {

std::uint32_t permute_index(std::uint32_t i, std::uint32_t n, std::uint32_t seed) {
    if (n <= 1) return 0;
    std::uint32_t mask = n - 1;
    mask |= mask >> 1;
    mask |= mask >> 2;
    mask |= mask >> 4;
    mask |= mask >> 8;
    mask |= mask >> 16;
    const std::uint32_t s1 = mix32(seed), s2 = mix32(s1), s3 = mix32(s2);
    // Each step is a bijection on [0, mask]: xor with a constant, multiplication by an odd
    // number and addition modulo 2^bits, and x ^= x >> k.
    do {
        i = (i ^ s1) & mask;
        i = (i * 0x9e3779b1U) & mask;
        i ^= i >> 3;
        i = (i + s2) & mask;
        i = (i * (s3 | 1U)) & mask;
        i ^= i >> 5;
        i = (i * 0x85ebca6bU) & mask;
        i ^= i >> 1;
    } while (i >= n);
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
