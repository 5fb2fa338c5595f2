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

// Two triangles of the same object are neighbours (touching by construction, not a
// collision) when they share a vertex index or a bit-identical vertex position.
inline bool areNeighbours(const std::uint32_t (&index_a)[3], const Float3 (&pos_a)[3], const std::uint32_t (&index_b)[3],
                          const Float3 (&pos_b)[3]) noexcept {
    for (int k = 0; k < 3; ++k) {
        for (int l = 0; l < 3; ++l) {
            if (index_a[k] == index_b[l] || bitIdentical(pos_a[k], pos_b[l])) return true;
        }
    }
    return false;
}

}  // namespace vkcollide::narrow
