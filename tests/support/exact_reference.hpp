// The exact CPU reference for whole scenes: every colliding triangle pair, found by
// world-space AABB sweep-and-prune and the narrow phase's exact triangle test, with the
// same neighbour rule. Used to measure what the GPU pipeline finds or misses.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "vkcollide/mesh.hpp"
#include "vkcollide/narrow.hpp"
#include "vkcollide/result.hpp"

namespace vkcollide::test {

// Row-major 4x4 world transform: world = M * (x, y, z, 1). The last row must be
// (0, 0, 0, 1) (affine transforms only).
using Transform = std::array<float, 16>;

constexpr Transform kIdentityTransform = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};

// A 3x4 row-major matrix [R | t] as a Transform.
Transform transformFrom3x4(const std::array<float, 12>& rows);
Transform translation(float x, float y, float z);

// One object of the scene; its index in the span is its object id.
struct ReferenceObject {
    const HostMesh* mesh = nullptr;  // borrowed; must outlive the call
    Transform transform = kIdentityTransform;
    bool self_collision = true;
};

struct ReferenceOptions {
    // Whether objects a < b may collide; empty: all may. Called concurrently from
    // several threads, so it must be thread safe.
    std::function<bool(std::uint32_t object_a, std::uint32_t object_b)> may_collide;
    unsigned threads = 0;  // 0: hardware concurrency
};

// World-space positions of a mesh: M * p evaluated in double and rounded once to float.
// An exact identity copies the positions bit for bit.
std::vector<Float3> worldPositions(const HostMesh& mesh, const Transform& transform);

// All colliding triangle pairs of the scene, sorted, each ordered (object_a, triangle_a)
// < (object_b, triangle_b). Triangles of one object are tested only when its
// self_collision is on, and never when they are neighbours (shared vertex index or
// bit-identical world position). Errors: ErrorCode::InvalidMesh for a null mesh, an
// index count that is not a multiple of 3, an index out of range or a non-finite
// vertex; ErrorCode::InvalidArgument for a non-finite or non-affine transform.
// Method: a uniform grid of cells about twice the median triangle box; each pair whose
// boxes overlap is tested once, in the cell holding the low corner of the boxes'
// intersection; cells are spread over `threads`. Cost: linear in triangles plus
// box-overlapping pairs per cell (about 0.3 s per million triangles of two deeply
// overlapping meshes on one core); memory about 30 bytes per triangle plus 4 per cell
// (at most 4 cells per triangle).
Result<std::vector<TrianglePair>> computeReferencePairs(std::span<const ReferenceObject> objects,
                                                       const ReferenceOptions& options = {});

// Every triangle of the scene as a narrow-phase candidate, as if seen by an orthographic
// camera looking down -z: box and depth are the world AABB mapped to [0,1] over the scene
// bounds (a monotone mapping, so boxes that touch in world space still touch). Running
// the narrow phase on these must give exactly computeReferencePairs (same filters).
Result<std::vector<CandidateTriangle>> allTrianglesAsCandidates(std::span<const ReferenceObject> objects);

// How a pair list compares with the reference. Pairs are normalised (ordered, sorted,
// deduplicated) first. precision = tp / (tp + fp) and recall = tp / (tp + fn), each 1
// when its denominator is 0.
struct PairComparison {
    std::size_t true_positives = 0, false_positives = 0, false_negatives = 0;
    double precision = 1.0, recall = 1.0;
    std::vector<TrianglePair> missed;    // in reference, not found
    std::vector<TrianglePair> spurious;  // found, not in reference
};
PairComparison comparePairs(std::span<const TrianglePair> found, std::span<const TrianglePair> reference);

// How two intersecting triangles meet. Crossing: each has vertices strictly on both sides
// of the other's plane (the surfaces pass through each other). Touching: anything else
// (a vertex or an edge lying on the other's face, coplanar overlap) — contacts that
// image-space sampling cannot be expected to see and that benchmarks count apart.
// Decided with exact orientation predicates.
enum class Contact { Crossing, Touching };
Contact classifyContact(const std::array<Float3, 3>& a, const std::array<Float3, 3>& b);
// The contact of each pair of `pairs` (world positions of the scene's objects).
Result<std::vector<Contact>> classifyPairs(std::span<const ReferenceObject> objects, std::span<const TrianglePair> pairs);

}  // namespace vkcollide::test
