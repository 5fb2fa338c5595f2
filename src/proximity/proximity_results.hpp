// The proximity pass's records, sorted on the GPU by (kind, object_a, a0, a1, object_b, b0,
// b1), as DetectResult::proximity: each pair once (a pair whose triangles' canonical-cell
// scan ran out of budget comes twice, side by side).
#pragma once

#include <span>
#include <vector>

#include "vkcollide/proximity.hpp"

namespace vkcollide::proximity {

// Fills `out` and the counts of `stats` that the pairs tell (pairs, kinds, in_band,
// duplicates).
void sortedPairs(std::span<const ProximityPair> sorted, std::vector<ProximityPair>& out, ProximityStats& stats);

}  // namespace vkcollide::proximity
