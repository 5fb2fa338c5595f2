// Shared by the peers: input checks, the timer, and the exact test over candidate pairs.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "vkcollide/mesh.hpp"
#include "vkcollide/narrow.hpp"
#include "vkcollide/result.hpp"

namespace vkcollide {
class ThreadPool;
}

namespace vkcollide::bench::detail {

class Stopwatch {
public:
    Stopwatch() : start_(std::chrono::steady_clock::now()) {}
    double ms() const {
        return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_).count();
    }

private:
    std::chrono::steady_clock::time_point start_;
};

// validateMesh on every mesh, at least one mesh, and an object count that fits 32 bits.
Result<void> validateScene(std::span<const HostMesh> meshes);

// What a deforming session remembers of the first frame to check that later frames keep
// the topology (same object count, vertex counts and index lists).
class TopologyCheck {
public:
    void remember(std::span<const HostMesh> meshes);
    Result<void> check(std::span<const HostMesh> meshes) const;

private:
    std::vector<std::size_t> vertex_counts_;
    std::vector<std::vector<std::uint32_t>> indices_;
};

// The three world-space vertices of triangle t of mesh m.
inline void triangleVertices(const HostMesh& m, std::uint32_t t, Float3 (&out)[3]) {
    for (int k = 0; k < 3; ++k) out[k] = m.positions[m.indices[3 * std::size_t{t} + k]];
}

// Decides one pair of triangles; must be a pure function (called from several threads).
using TriangleTest = std::function<bool(const Float3 (&a)[3], const Float3 (&b)[3])>;

// The exact narrow phase over candidate pairs: drops pairs within one object when
// self-collision is off and neighbouring pairs (narrow/neighbours.hpp), runs `test` on the
// rest spread over `pool`, and returns the positive pairs sorted. Candidates must be
// ordered (a < b) and unique.
std::vector<TrianglePair> exactPairs(std::span<const HostMesh> meshes, std::span<const TrianglePair> candidates,
                                     bool self_collision, const TriangleTest& test, ThreadPool& pool);

// narrow::trianglesIntersect as a TriangleTest.
bool exactTest(const Float3 (&a)[3], const Float3 (&b)[3]);

}  // namespace vkcollide::bench::detail
