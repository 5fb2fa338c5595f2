// A plain CPU implementation of the broad phase's four passes (sampling with the
// hardware coverage rule, ray merging, primitive separation, packing), to check the GPU
// pipeline ray by ray and record by record; with settings.depth_aware, depth-aware
// separation's rules as well (near pairs, (x, y, depth) bundles, kept depth ranges).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "broad/broad_phase.hpp"
#include "vkcollide/mesh.hpp"
#include "vkcollide/narrow.hpp"

namespace vkcollide::test {

// Not named ReferenceObject: exact_reference.hpp has one, and two classes of one name in
// one program break the one-definition rule (ASan saw std::vector code of one run on the other).
struct BroadPhaseObject {
    const HostMesh* mesh = nullptr;  // world-space positions (identity transform)
    bool open = false;
    bool self_collision = true;      // as passes::GpuMesh::self_collision
};

struct ReferenceResult {
    std::vector<std::uint8_t> rays;       // N*N collision flags
    // N*N: a sample within 1e-3 px of an edge or a depth tie, or (depth-aware) a near test
    // or silhouette test within rounding of its threshold.
    std::vector<std::uint8_t> ambiguous;
    // Depth-aware: each ray's depth interval as its bundle gets it (lo > hi: none).
    std::vector<std::array<float, 2>> ray_depth;
    std::uint32_t depth_complexity = 0;
    std::uint32_t collision_rays = 0;
    std::vector<CandidateTriangle> records;
    std::size_t ambiguousCount() const;
};

// The GPU's pass-1 output, to run passes 2-4 from: its collision rays and (depth-aware)
// its rays' depth intervals (BroadPhaseResult::ray_image and ray_depth).
struct GpuRays {
    const std::vector<std::uint8_t>* rays = nullptr;
    const std::vector<std::array<float, 2>>* depth = nullptr;
};

// Runs the four passes. `layers` is the number of layers the GPU peeled (min of depth
// complexity and cap). When `gpu` is given, passes 2-4 start from its rays, so they are
// checked exactly even where pass 1 has an ambiguous sample.
ReferenceResult referenceBroadPhase(const std::vector<BroadPhaseObject>& objects, const passes::BroadPhaseSettings& settings,
                                    std::uint32_t layers, const GpuRays& gpu = {});

}  // namespace vkcollide::test
