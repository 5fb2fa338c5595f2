#include "narrow/sweep_and_prune.hpp"

#include <algorithm>
#include <numeric>

namespace vkcollide::narrow {

std::vector<std::uint32_t> sweepOrder(std::span<const CandidateTriangle> in_candidates) {
    std::vector<std::uint32_t> order(in_candidates.size());
    std::iota(order.begin(), order.end(), 0u);
    // Ties broken by index so the visit order never depends on the sort implementation.
    std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
        const float xa = in_candidates[a].box[0], xb = in_candidates[b].box[0];
        return xa != xb ? xa < xb : a < b;
    });
    return order;
}

std::vector<IndexPair> sweepAndPrunePairs(std::span<const CandidateTriangle> in_candidates) {
    std::vector<IndexPair> pairs;
    sweepAndPrune(in_candidates, [&](std::uint32_t i, std::uint32_t j) { pairs.push_back({i, j}); });
    std::sort(pairs.begin(), pairs.end());
    return pairs;
}

}  // namespace vkcollide::narrow
