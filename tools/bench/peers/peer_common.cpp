#include "peer_common.hpp"

#include <algorithm>
#include <string>

#include "narrow/neighbours.hpp"
#include "vkcollide/thread_pool.hpp"
#include "narrow/triangle_intersection.hpp"

namespace vkcollide::bench::detail {
namespace {

// Exact tests cost about a microsecond each; chunks this size amortise the hand-out.
constexpr std::size_t kPairsPerTask = 4096;

}  // namespace

Result<void> validateScene(std::span<const HostMesh> meshes) {
    if (meshes.empty()) return Error(ErrorCode::InvalidArgument, "peer: the scene has no mesh");
    if (meshes.size() > UINT32_MAX) return Error(ErrorCode::InvalidArgument, "peer: more than 2^32 - 1 objects");
    for (const HostMesh& m : meshes) {
        if (Result<void> ok = validateMesh(m); !ok) return ok.error();
    }
    return {};
}

void TopologyCheck::remember(std::span<const HostMesh> meshes) {
    vertex_counts_.clear();
    indices_.clear();
    for (const HostMesh& m : meshes) {
        vertex_counts_.push_back(m.positions.size());
        indices_.push_back(m.indices);
    }
}

Result<void> TopologyCheck::check(std::span<const HostMesh> meshes) const {
    if (meshes.size() != indices_.size()) {
        return Error(ErrorCode::InvalidArgument, "peer: a deforming frame has " + std::to_string(meshes.size()) +
                                                     " objects, the first had " + std::to_string(indices_.size()));
    }
    for (std::size_t o = 0; o < meshes.size(); ++o) {
        if (meshes[o].positions.size() != vertex_counts_[o] || meshes[o].indices != indices_[o]) {
            return Error(ErrorCode::InvalidArgument, "peer: object " + std::to_string(o) + " ('" + meshes[o].name +
                                                         "') changed its vertex count or indices in a deforming frame");
        }
    }
    return {};
}

bool exactTest(const Float3 (&a)[3], const Float3 (&b)[3]) {
    return narrow::trianglesIntersect(std::span<const Float3, 3>(a), std::span<const Float3, 3>(b));
}

std::vector<TrianglePair> exactPairs(std::span<const HostMesh> meshes, std::span<const TrianglePair> candidates,
                                     bool self_collision, const TriangleTest& test, ThreadPool& pool) {
    const std::size_t task_count = (candidates.size() + kPairsPerTask - 1) / kPairsPerTask;
    std::vector<std::vector<TrianglePair>> found(task_count);
    pool.parallelFor(candidates.size(), kPairsPerTask, [&](std::size_t begin, std::size_t end) {
        std::vector<TrianglePair>& out = found[begin / kPairsPerTask];
        for (std::size_t i = begin; i < end; ++i) {
            const TrianglePair& c = candidates[i];
            const HostMesh& ma = meshes[c.object_a];
            const HostMesh& mb = meshes[c.object_b];
            Float3 va[3], vb[3];
            triangleVertices(ma, c.triangle_a, va);
            triangleVertices(mb, c.triangle_b, vb);
            if (c.object_a == c.object_b) {
                if (!self_collision) continue;
                const std::uint32_t ia[3] = {ma.indices[3 * std::size_t{c.triangle_a}],
                                             ma.indices[3 * std::size_t{c.triangle_a} + 1],
                                             ma.indices[3 * std::size_t{c.triangle_a} + 2]};
                const std::uint32_t ib[3] = {mb.indices[3 * std::size_t{c.triangle_b}],
                                             mb.indices[3 * std::size_t{c.triangle_b} + 1],
                                             mb.indices[3 * std::size_t{c.triangle_b} + 2]};
                if (narrow::areNeighbours(ia, va, ib, vb)) continue;
            }
            if (test(va, vb)) out.push_back(c);
        }
    });
    std::vector<TrianglePair> pairs;
    std::size_t total = 0;
    for (const auto& part : found) total += part.size();
    pairs.reserve(total);
    for (const auto& part : found) pairs.insert(pairs.end(), part.begin(), part.end());
    std::sort(pairs.begin(), pairs.end());
    return pairs;
}

}  // namespace vkcollide::bench::detail
