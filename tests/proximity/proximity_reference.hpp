// Brute-force proximity reference for the tests: every vertex-triangle and edge-edge pair
// of the given objects with its distance, in __float128 (113-bit significands: exact to far
// below any band the GPU reports for the float inputs these tests use), under the library's
// rules (ProximityPair's order and canonical form, the neighbour rule within one object).
#pragma once

#include <cstdint>
#include <vector>

#include "vkcollide/mesh.hpp"
#include "vkcollide/proximity.hpp"

namespace vkcollide::test {

struct ProximityObject {
    std::uint32_t id = 0;
    std::vector<Float3> world;  // world vertices as the CPU computes them
    std::vector<std::uint32_t> indices;
    bool self = false;
};

struct ReferenceProximity {
    ProximityKind kind;
    std::uint32_t object_a, a0, a1, object_b, b0, b1;
    long double distance;
};

// Every pair at distance <= limit (pairs of objects a != b always; within an object when
// `self`), sorted like DetectResult::proximity.
std::vector<ReferenceProximity> referenceProximity(const std::vector<ProximityObject>& objects, double limit);

}  // namespace vkcollide::test
