// Sweep-and-prune over screen-space boxes (Cohen et al. 1995), as in section 7 of the
// paper: sort by x0, sweep along x, test y for pairs that overlap in x and the depth
// extent z only for pairs that overlap in x and y. Intervals are closed.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "vkcollide/narrow.hpp"

namespace vkcollide::narrow {

// Indices (i < j) into the candidate span.
struct IndexPair {
    std::uint32_t i = 0, j = 0;
    friend bool operator==(const IndexPair&, const IndexPair&) = default;
    friend auto operator<=>(const IndexPair&, const IndexPair&) = default;
};

// Calls visit(i, j) with i < j for every pair of candidates whose boxes overlap in x and
// y and whose [zmin, zmax] overlap, in a deterministic order (by x0, then index).
// Preconditions: no NaN in box/zmin/zmax; box[0] <= box[2], box[1] <= box[3].
template <typename Visit>
void sweepAndPrune(std::span<const CandidateTriangle> in_candidates, Visit&& visit);

// The pairs sweepAndPrune visits, sorted ascending.
std::vector<IndexPair> sweepAndPrunePairs(std::span<const CandidateTriangle> in_candidates);

// The x0 sweep order: candidate indices sorted by (box[0], index).
std::vector<std::uint32_t> sweepOrder(std::span<const CandidateTriangle> in_candidates);

template <typename Visit>
void sweepAndPrune(std::span<const CandidateTriangle> in_candidates, Visit&& visit) {
    const std::vector<std::uint32_t> order = sweepOrder(in_candidates);
    for (std::size_t s = 0; s < order.size(); ++s) {
        const CandidateTriangle& a = in_candidates[order[s]];
        for (std::size_t t = s + 1; t < order.size(); ++t) {
            const CandidateTriangle& b = in_candidates[order[t]];
            if (b.box[0] > a.box[2]) break;  // sorted by x0: no later box reaches a
            if (b.box[1] > a.box[3] || a.box[1] > b.box[3]) continue;
            // Only now look at depth, as the paper does.
            if (b.zmin > a.zmax || a.zmin > b.zmax) continue;
            const std::uint32_t i = order[s], j = order[t];
            if (i < j) {
                visit(i, j);
            } else {
                visit(j, i);
            }
        }
    }
}

}  // namespace vkcollide::narrow
