// The neighbour rule shared by the narrow phase and the exact reference.
#pragma once

#include <cstdint>
#include <cstring>

#include "vkcollide/mesh.hpp"

namespace vkcollide::narrow {

// Bitwise equality: -0.0f and 0.0f differ, NaNs with equal bits are equal. Positions that
// a mesh shares are bit-identical copies, and only those should make two triangles
// neighbours, so this deliberately is not operator== on floats.
inline bool bitIdentical(const Float3& a, const Float3& b) noexcept { return std::memcmp(&a, &b, sizeof(Float3)) == 0; }

// Whether two triangles share a vertex index (the cheap half of the neighbour rule).
inline bool shareIndex(const std::uint32_t (&index_a)[3], const std::uint32_t (&index_b)[3]) noexcept {
    unsigned shared = 0;
    for (int k = 0; k < 3; ++k) {
        for (int l = 0; l < 3; ++l) shared |= static_cast<unsigned>(index_a[k] == index_b[l]);
    }
    return shared != 0;
}

// Two triangles of the same object are neighbours (touching by construction, not a
// collision) when they share a vertex index or a bit-identical vertex position.
//
// Most pairs the sweep reports on closed meshes are neighbours, so this runs for every
// one of them: the nine index and nine position comparisons are made without branches.
inline bool areNeighbours(const std::uint32_t (&index_a)[3], const Float3 (&pos_a)[3], const std::uint32_t (&index_b)[3],
                          const Float3 (&pos_b)[3]) noexcept {
    std::uint32_t bits_a[3][3], bits_b[3][3];
    static_assert(sizeof(bits_a) == sizeof(pos_a));
    std::memcpy(bits_a, pos_a, sizeof bits_a);
    std::memcpy(bits_b, pos_b, sizeof bits_b);
    unsigned shared = 0;
    for (int k = 0; k < 3; ++k) {
        for (int l = 0; l < 3; ++l) {
            const unsigned same_position = (bits_a[k][0] == bits_b[l][0]) & (bits_a[k][1] == bits_b[l][1]) &
                                           (bits_a[k][2] == bits_b[l][2]);
            shared |= static_cast<unsigned>(index_a[k] == index_b[l]) | same_position;
        }
    }
    return shared != 0;
}

}  // namespace vkcollide::narrow
