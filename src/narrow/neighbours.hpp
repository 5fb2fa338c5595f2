// The neighbour rule shared by the narrow phase and the exact reference.
#pragma once

#include <cstdint>
#include <cstring>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "vkcollide/mesh.hpp"

namespace vkcollide::narrow {

// Bitwise equality: -0.0f and 0.0f differ, NaNs with equal bits are equal. Positions that
// a mesh shares are bit-identical copies, and only those should make two triangles
// neighbours, so this deliberately is not operator== on floats.
inline bool bitIdentical(const Float3& a, const Float3& b) noexcept { return std::memcmp(&a, &b, sizeof(Float3)) == 0; }

// Most pairs the sweep reports on self-colliding closed meshes are neighbours, so both
// tests below run for millions of pairs per call: the nine comparisons are made at once
// (SSE2 lanes: b's three values, the third repeated), without branches.

// Whether two triangles share a vertex index (the cheap half of the neighbour rule).
inline bool shareIndex(const std::uint32_t (&index_a)[3], const std::uint32_t (&index_b)[3]) noexcept {
#if defined(__SSE2__)
    const __m128i b = _mm_setr_epi32(static_cast<int>(index_b[0]), static_cast<int>(index_b[1]),
                                     static_cast<int>(index_b[2]), static_cast<int>(index_b[2]));
    const __m128i any = _mm_or_si128(_mm_or_si128(_mm_cmpeq_epi32(_mm_set1_epi32(static_cast<int>(index_a[0])), b),
                                                  _mm_cmpeq_epi32(_mm_set1_epi32(static_cast<int>(index_a[1])), b)),
                                     _mm_cmpeq_epi32(_mm_set1_epi32(static_cast<int>(index_a[2])), b));
    return _mm_movemask_epi8(any) != 0;
#else
    unsigned shared = 0;
    for (int k = 0; k < 3; ++k) {
        for (int l = 0; l < 3; ++l) shared |= static_cast<unsigned>(index_a[k] == index_b[l]);
    }
    return shared != 0;
#endif
}

// Two triangles of the same object are neighbours (touching by construction, not a
// collision) when they share a vertex index or a bit-identical vertex position.
inline bool areNeighbours(const std::uint32_t (&index_a)[3], const Float3 (&pos_a)[3], const std::uint32_t (&index_b)[3],
                          const Float3 (&pos_b)[3]) noexcept {
    std::uint32_t bits_a[3][3], bits_b[3][3];
    static_assert(sizeof(bits_a) == sizeof(pos_a));
    std::memcpy(bits_a, pos_a, sizeof bits_a);
    std::memcpy(bits_b, pos_b, sizeof bits_b);
#if defined(__SSE2__)
    const auto lanes = [](std::uint32_t v0, std::uint32_t v1, std::uint32_t v2) {
        return _mm_setr_epi32(static_cast<int>(v0), static_cast<int>(v1), static_cast<int>(v2), static_cast<int>(v2));
    };
    // b's x, y and z coordinates and indices, one vertex per lane.
    const __m128i bx = lanes(bits_b[0][0], bits_b[1][0], bits_b[2][0]);
    const __m128i by = lanes(bits_b[0][1], bits_b[1][1], bits_b[2][1]);
    const __m128i bz = lanes(bits_b[0][2], bits_b[1][2], bits_b[2][2]);
    const __m128i bi = lanes(index_b[0], index_b[1], index_b[2]);
    __m128i any = _mm_setzero_si128();
    for (int k = 0; k < 3; ++k) {
        const auto splat = [](std::uint32_t v) { return _mm_set1_epi32(static_cast<int>(v)); };
        const __m128i same_position =
            _mm_and_si128(_mm_and_si128(_mm_cmpeq_epi32(splat(bits_a[k][0]), bx), _mm_cmpeq_epi32(splat(bits_a[k][1]), by)),
                          _mm_cmpeq_epi32(splat(bits_a[k][2]), bz));
        any = _mm_or_si128(any, _mm_or_si128(same_position, _mm_cmpeq_epi32(splat(index_a[k]), bi)));
    }
    return _mm_movemask_epi8(any) != 0;
#else
    unsigned shared = 0;
    for (int k = 0; k < 3; ++k) {
        for (int l = 0; l < 3; ++l) {
            const unsigned same_position = (bits_a[k][0] == bits_b[l][0]) & (bits_a[k][1] == bits_b[l][1]) &
                                           (bits_a[k][2] == bits_b[l][2]);
            shared |= static_cast<unsigned>(index_a[k] == index_b[l]) | same_position;
        }
    }
    return shared != 0;
#endif
}

}  // namespace vkcollide::narrow
