// Two narrow-phase results that must agree to the bit: the same pairs, and responses with
// the same objects, triangles, partner counts and direction bits.
#pragma once

#include <catch2/catch.hpp>

#include <cstring>

#include "vkcollide/narrow.hpp"

namespace vkcollide::test {

inline bool sameBits(const Float3& a, const Float3& b) { return std::memcmp(&a, &b, sizeof(Float3)) == 0; }

inline void requireSamePairsAndResponses(const NarrowResult& a, const NarrowResult& b) {
    REQUIRE(a.pairs == b.pairs);
    REQUIRE(a.responses.size() == b.responses.size());
    for (std::size_t i = 0; i < a.responses.size(); ++i) {
        REQUIRE(a.responses[i].object == b.responses[i].object);
        REQUIRE(a.responses[i].triangle == b.responses[i].triangle);
        REQUIRE(a.responses[i].partner_count == b.responses[i].partner_count);
        REQUIRE(sameBits(a.responses[i].direction, b.responses[i].direction));
    }
}

}  // namespace vkcollide::test
