// Which triangle owns each vertex and edge (src/proximity/ownership.hpp): the lowest that
// has it, so that every primitive pair comes from one candidate triangle pair. Host only.
#include <catch2/catch.hpp>

#include <cstdint>
#include <vector>

#include "proximity/ownership.hpp"

using vkcollide::proximity::ownedPrimitives;

TEST_CASE("proximity ownership: the lowest triangle owns each vertex and edge once", "[host][proximity]") {
    // A quad of two triangles sharing the edge 0-2, and a triangle repeating vertex 3.
    const std::vector<std::uint32_t> indices = {0, 1, 2, 0, 2, 3, 3, 3, 4};
    const std::vector<std::uint8_t> owned = ownedPrimitives(indices, 5);
    REQUIRE(owned.size() == 3);
    CHECK(owned[0] == (1 | 2 | 4 | 8 | 16 | 32));  // its three vertices and edges 0-1, 1-2, 2-0
    CHECK(owned[1] == (4 | 16 | 32));              // vertex 3, edges 2-3 and 3-0 (0-2 is triangle 0's)
    CHECK(owned[2] == (4 | 8 | 16));               // vertex 4; edges 3-3 (its first), 3-4 (4-3 repeats 3-4)
    // Every vertex and edge owned exactly once.
    int vertices = 0, edges = 0;
    for (std::uint8_t m : owned)
        for (int k = 0; k < 3; ++k) vertices += (m >> k) & 1, edges += (m >> (3 + k)) & 1;
    CHECK(vertices == 5);
    CHECK(edges == 7);  // 0-1, 1-2, 0-2, 2-3, 0-3, 3-3, 3-4
}
