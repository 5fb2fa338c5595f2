#include "proximity/proximity_results.hpp"

#include <algorithm>
#include <cstring>
#include <tuple>

namespace vkcollide::proximity {
namespace {

auto key(const ProximityPair& p) { return std::tie(p.kind, p.object_a, p.a0, p.a1, p.object_b, p.b0, p.b1); }

}  // namespace

void sortedPairs(std::span<const ProximityPair> sorted, std::vector<ProximityPair>& out, ProximityStats& stats) {
    out.assign(sorted.begin(), sorted.end());
    // The GPU sorted them (proximity_sort.comp); a pair found twice lies beside its twin.
    const auto last = std::unique(out.begin(), out.end(), [](const ProximityPair& x, const ProximityPair& y) { return key(x) == key(y); });
    stats.duplicates = static_cast<std::uint64_t>(out.end() - last);
    out.erase(last, out.end());
    stats.pairs = out.size();
    stats.vertex_triangle = stats.edge_edge = stats.in_band = 0;
    for (const ProximityPair& p : out) {
        (p.kind == ProximityKind::VertexTriangle ? stats.vertex_triangle : stats.edge_edge) += 1;
        stats.in_band += (p.flags & kProximityInBand) ? 1 : 0;
    }
}

}  // namespace vkcollide::proximity
