// The padded Sobol sampler's pairs, several dimension pairs of one sample at once: the scalar
// steps of sampler.cpp (get_2d) lane by lane on a GCC/clang vector of unsigned 32-bit integers
// (wrapping multiplies, logical shifts), so every lane gives get_2d's bits. Included by
// sampler.cpp (4 lanes, SSE4.1), sampler_avx2.cpp (8 lanes, AVX2) and sampler_avx512.cpp (16
// lanes, AVX-512) inside their namespaces;
// each includes <bit>, <utility> and the header of Sample2 first. The entry functions are
// always_inline: GCC otherwise kept some of them apart and passed 512-bit vectors between them
// through the stack (19 % slower renders; docs/performance.md, step 15).

// The vector types of N lanes (spelled out per N: GCC ignores vector_size on a dependent type).
template <int N>
struct Lanes;
template <>
struct Lanes<4> {
    using U = std::uint32_t __attribute__((vector_size(16)));
    using I = std::int32_t __attribute__((vector_size(16)));
    using F = float __attribute__((vector_size(16)));
    using Bytes = std::uint8_t __attribute__((vector_size(16)));
};
template <>
struct Lanes<8> {
    using U = std::uint32_t __attribute__((vector_size(32)));
    using I = std::int32_t __attribute__((vector_size(32)));
    using F = float __attribute__((vector_size(32)));
    using Bytes = std::uint8_t __attribute__((vector_size(32)));
};

template <>
struct Lanes<16> {
    using U = std::uint32_t __attribute__((vector_size(64)));
    using I = std::int32_t __attribute__((vector_size(64)));
    using F = float __attribute__((vector_size(64)));
    using Bytes = std::uint8_t __attribute__((vector_size(64)));
};

template <class V>
V lanes_of(std::uint32_t v) {
    return V{} + v;
}

template <class V>
V mix32_lanes(V x) {
    x ^= x >> 16;
    x *= 0x7feb352dU;
    x ^= x >> 15;
    x *= 0x846ca68bU;
    return x ^ (x >> 16);
}

template <class V>
V hash_combine_lanes(V seed, V v) {
    return mix32_lanes(seed ^ (v + 0x9e3779b9U + (seed << 6) + (seed >> 2)));
}

template <class V>
V rotl_lanes(V x, unsigned n) {
    return n == 0 ? x : (x << n) | (x >> (32 - n));
}

template <int N>
typename Lanes<N>::U reverse_bits_lanes(typename Lanes<N>::U v) {
    // The bytes of each lane reversed by one shuffle, then the bits within each byte.
    using V = typename Lanes<N>::U;
    using Bytes = typename Lanes<N>::Bytes;
    const auto b = std::bit_cast<Bytes>(v);
    Bytes r;
    if constexpr (N == 4) {
        r = __builtin_shufflevector(b, b, 3, 2, 1, 0, 7, 6, 5, 4, 11, 10, 9, 8, 15, 14, 13, 12);
    } else if constexpr (N == 8) {
        r = __builtin_shufflevector(b, b, 3, 2, 1, 0, 7, 6, 5, 4, 11, 10, 9, 8, 15, 14, 13, 12, 19, 18, 17, 16, 23, 22,
                                    21, 20, 27, 26, 25, 24, 31, 30, 29, 28);
    } else {
        static_assert(N == 16);
        r = __builtin_shufflevector(b, b, 3, 2, 1, 0, 7, 6, 5, 4, 11, 10, 9, 8, 15, 14, 13, 12, 19, 18, 17, 16, 23, 22,
                                    21, 20, 27, 26, 25, 24, 31, 30, 29, 28, 35, 34, 33, 32, 39, 38, 37, 36, 43, 42, 41,
                                    40, 47, 46, 45, 44, 51, 50, 49, 48, 55, 54, 53, 52, 59, 58, 57, 56, 63, 62, 61, 60);
    }
    v = std::bit_cast<V>(r);
    v = ((v >> 1) & 0x55555555U) | ((v & 0x55555555U) << 1);
    v = ((v >> 2) & 0x33333333U) | ((v & 0x33333333U) << 2);
    return ((v >> 4) & 0x0f0f0f0fU) | ((v & 0x0f0f0f0fU) << 4);
}

template <class V>
V owen_scramble_reversed_lanes(V v, V seed) {
    v ^= v * 0x3d20adeaU;
    v += seed;
    v *= (seed >> 16) | 1U;
    v ^= v * 0x05526c56U;
    return v ^ (v * 0x53a22864U);
}

// permute_index(i, n, seed) for a power of two n >= 2, where the Feistel network's output is
// always below n and no cycle walk is needed; its round keys are seed and mix32(seed).
template <class V>
V permute_index_pow2_keyed_lanes(V i, std::uint32_t n, V key0, V key1) {
    const auto bits = static_cast<unsigned>(std::bit_width(n - 1));
    const unsigned a = bits / 2, c = bits - a;
    const V keys[2] = {key0, key1};
    V left = i >> c, right = i & ((1U << c) - 1U);
    unsigned left_bits = a, right_bits = c;
    for (unsigned round = 0; round < 4; ++round) {
        const V k = rotl_lanes(keys[round & 1], round * 5);
        const V f = (((right ^ k) * 0x9e3779b1U) ^ k) * 0x85ebca6bU;
        const V t = left_bits == 0 ? left : left ^ (f >> (32 - left_bits));
        left = right;
        right = t;
        std::swap(left_bits, right_bits);
    }
    return (left << right_bits) | right;
}

template <class V>
V permute_index_pow2_lanes(V i, std::uint32_t n, V seed) {
    return permute_index_pow2_keyed_lanes(i, n, seed, mix32_lanes(seed));
}

// The last steps of get_2d in every lane: from the permuted index i, the two Owen-scrambled
// Sobol coordinates (scramble seeds sx and sy) as floats.
template <int N>
[[gnu::always_inline]] inline void sobol_pairs_finish(typename Lanes<N>::U i, std::uint32_t spp,
                                                      typename Lanes<N>::U sx, typename Lanes<N>::U sy,
                                                      Sample2* out) {
    using V = typename Lanes<N>::U;
    // sobol_1_reversed(i): the columns v = 1, 3, 5, 15, ... xored where i has a bit.
    V sobol1{};
    std::uint32_t column = 1;
    for (unsigned b = 0, n = static_cast<unsigned>(std::bit_width(spp - 1)); b < n; ++b, column ^= column << 1)
        sobol1 ^= lanes_of<V>(column) & -((i >> b) & 1U);
    const V xs = reverse_bits_lanes<N>(owen_scramble_reversed_lanes(i, sx));
    const V ys = reverse_bits_lanes<N>(owen_scramble_reversed_lanes(sobol1, sy));
    // The top 24 bits of each, as floats in [0, 1) (exact: below 2^24, so signed conversion).
    using I = typename Lanes<N>::I;
    using F = typename Lanes<N>::F;
    const F x = __builtin_convertvector(std::bit_cast<I>(V(xs >> 8)), F) * (1.0f / 16777216.0f);
    const F y = __builtin_convertvector(std::bit_cast<I>(V(ys >> 8)), F) * (1.0f / 16777216.0f);
    for (int k = 0; k < N; ++k) out[k] = Sample2{x[k], y[k]};
}

// Per lane, get_2d's seed of dimension first_dimension + lane, hash_combine(pixel_seed, dimension),
// and the seed its sample indices are permuted with, hash_combine(seed, 0x5eed).
template <int N>
[[gnu::always_inline]] inline void dimension_seeds_lanes(std::uint32_t pixel_seed, std::uint32_t first_dimension,
                                                         typename Lanes<N>::U& seed, typename Lanes<N>::U& index_seed) {
    using V = typename Lanes<N>::U;
    V dims;
    for (int k = 0; k < N; ++k) dims[k] = first_dimension + static_cast<std::uint32_t>(k);
    seed = hash_combine_lanes(lanes_of<V>(pixel_seed), dims);
    index_seed = hash_combine_lanes(seed, lanes_of<V>(0x5eedU));
}

// The pairs first_dimension .. first_dimension + lanes - 1 of sample `index` of a pixel, for a
// power-of-two spp >= 4: get_2d's steps (sobol_index, the Owen scrambles, sobol_1) in every lane.
template <int N>
[[gnu::always_inline]] inline void sobol_pairs_lanes(std::uint32_t pixel_seed, std::uint32_t spp, std::uint32_t index,
                                                     std::uint32_t first_dimension, Sample2* out) {
    using V = typename Lanes<N>::U;
    V seed, index_seed;
    dimension_seeds_lanes<N>(pixel_seed, first_dimension, seed, index_seed);
    // sobol_index(index, spp, index_seed), lane by lane.
    const V side = (lanes_of<V>(index) ^ (index_seed >> 31)) & 1U;
    const std::uint32_t half = spp / 2;
    const V i = side * half + permute_index_pow2_lanes(lanes_of<V>(index >> 1), half, hash_combine_lanes(index_seed, side));
    sobol_pairs_finish<N>(i, spp, hash_combine_lanes(seed, lanes_of<V>(1U)), hash_combine_lanes(seed, lanes_of<V>(2U)),
                          out);
}

// What sobol_pairs_lanes computes from the pixel and the dimensions alone, kept to serve every
// sample of a pixel: per lane, the index seed's top bit (which half the even samples take), the
// permutation's two round keys for either half, and the two scramble seeds: seven rows of N
// lanes, in that order (the even half's keys before the odd half's).
template <int N>
[[gnu::always_inline]] inline void sobol_keys_lanes(std::uint32_t pixel_seed, std::uint32_t first_dimension,
                                                    std::uint32_t* keys) {
    using V = typename Lanes<N>::U;
    V seed, index_seed;
    dimension_seeds_lanes<N>(pixel_seed, first_dimension, seed, index_seed);
    const V key0_even = hash_combine_lanes(index_seed, lanes_of<V>(0U));
    const V key0_odd = hash_combine_lanes(index_seed, lanes_of<V>(1U));
    const V rows[7] = {index_seed >> 31,
                       key0_even,
                       mix32_lanes(key0_even),
                       key0_odd,
                       mix32_lanes(key0_odd),
                       hash_combine_lanes(seed, lanes_of<V>(1U)),
                       hash_combine_lanes(seed, lanes_of<V>(2U))};
    for (int r = 0; r < 7; ++r) __builtin_memcpy(keys + r * N, &rows[r], sizeof(V));
}

// sobol_pairs_lanes from kept keys (sobol_keys_lanes): the same bits, with only the steps that
// depend on the sample index left.
template <int N>
[[gnu::always_inline]] inline void sobol_pairs_keyed_lanes(const std::uint32_t* keys, std::uint32_t spp,
                                                           std::uint32_t index, Sample2* out) {
    using V = typename Lanes<N>::U;
    V rows[7];
    for (int r = 0; r < 7; ++r) __builtin_memcpy(&rows[r], keys + r * N, sizeof(V));
    const V side = (lanes_of<V>(index) ^ rows[0]) & 1U;
    const V odd = -side;  // all ones where the half is the other one
    const V key0 = (rows[1] & ~odd) | (rows[3] & odd), key1 = (rows[2] & ~odd) | (rows[4] & odd);
    const V i = side * (spp / 2) + permute_index_pow2_keyed_lanes(lanes_of<V>(index >> 1), spp / 2, key0, key1);
    sobol_pairs_finish<N>(i, spp, rows[5], rows[6], out);
}
