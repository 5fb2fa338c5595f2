#include "proximity/ownership.hpp"

#include <algorithm>
#include <cassert>
#include <limits>

namespace vkcollide::proximity {

std::vector<std::uint8_t> ownedPrimitives(std::span<const std::uint32_t> indices, std::uint32_t vertex_count) {
    const std::size_t triangles = indices.size() / 3;
    std::vector<std::uint8_t> owned(triangles, 0);
    constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
    // Vertices: the first triangle (in order) that names one owns it.
    std::vector<std::uint32_t> vertex_owner(vertex_count, kNone);
    for (std::size_t t = 0; t < triangles; ++t)
        for (unsigned k = 0; k < 3; ++k) {
            const std::uint32_t v = indices[3 * t + k];
            assert(v < vertex_count);
            if (vertex_owner[v] == kNone) {
                vertex_owner[v] = static_cast<std::uint32_t>(t);
                owned[t] |= std::uint8_t(1u << k);
            }
        }
    // Edges: sorted (lower, higher, triangle, local edge); the first of each run owns it.
    struct Edge {
        std::uint32_t lo, hi, triangle, k;
    };
    std::vector<Edge> edges;
    edges.reserve(3 * triangles);
    for (std::size_t t = 0; t < triangles; ++t)
        for (unsigned k = 0; k < 3; ++k) {
            const std::uint32_t a = indices[3 * t + k], b = indices[3 * t + (k + 1) % 3];
            edges.push_back({std::min(a, b), std::max(a, b), static_cast<std::uint32_t>(t), k});
        }
    std::sort(edges.begin(), edges.end(), [](const Edge& x, const Edge& y) {
        if (x.lo != y.lo) return x.lo < y.lo;
        if (x.hi != y.hi) return x.hi < y.hi;
        if (x.triangle != y.triangle) return x.triangle < y.triangle;
        return x.k < y.k;
    });
    for (std::size_t i = 0; i < edges.size(); ++i)
        if (i == 0 || edges[i].lo != edges[i - 1].lo || edges[i].hi != edges[i - 1].hi)
            owned[edges[i].triangle] |= std::uint8_t(8u << edges[i].k);
    return owned;
}

}  // namespace vkcollide::proximity
