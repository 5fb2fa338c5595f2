// A plain CPU implementation of the broad phase's four passes (sampling with the
// hardware coverage rule, ray merging, primitive separation, packing), to check the GPU
// pipeline ray by ray and record by record.
#pragma once

#include <cstdint>
#include <vector>

#include "passes/broad_phase.hpp"
#include "vkcollide/mesh.hpp"
#include "vkcollide/narrow.hpp"

namespace vkcollide::test {

struct ReferenceObject {
    const HostMesh* mesh = nullptr;  // world-space positions (identity transform)
    bool open = false;
};

struct ReferenceResult {
    std::vector<std::uint8_t> rays;       // N*N collision flags
    std::vector<std::uint8_t> ambiguous;  // N*N: a sample within 1e-3 px of an edge or a depth tie
    std::uint32_t depth_complexity = 0;
    std::uint32_t collision_rays = 0;
    std::vector<CandidateTriangle> records;
    std::size_t ambiguousCount() const;
};

// Runs the four passes. `layers` is the number of layers the GPU peeled (min of depth
// complexity and cap). When `gpu_rays` is given, passes 2-4 start from those rays, so
// they are checked exactly even where pass 1 has an ambiguous sample.
ReferenceResult referenceBroadPhase(const std::vector<ReferenceObject>& objects, const passes::BroadPhaseSettings& settings,
                                    std::uint32_t layers, const std::vector<std::uint8_t>* gpu_rays = nullptr);

}  // namespace vkcollide::test
