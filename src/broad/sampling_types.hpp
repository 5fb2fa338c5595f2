// The peeling method's object-sampling knobs (paper §4, pass 1) that BroadPhaseSettings
// carries (BroadPhaseSettings::compute): in the seam, so that the contract
// (broad_phase_types.hpp) includes no method's room.
#pragma once

#include <cstdint>

#include "common/config.h"
#include "vkcollide/types.hpp"

namespace vkcollide::passes {

using vkcollide::SamplingBackend;

// Knobs of the compute backend (peeling/sampling/compute_sampler.hpp); defaults in spirv/common/config.h.
struct ComputeSamplingTuning {
    // Most pixels in the pixel box of a triangle drawn by one invocation; bigger boxes are
    // drawn in tiles. 0 draws every triangle in tiles.
    std::uint32_t small_box = gpu::kCsSmallBox;
    // Fragment lists: the count pass stores the first `list_layers` keys of every ray
    // (N^2 x layers x 8 bytes) and each peeling step picks its keys per pixel, instead of
    // drawing every triangle again per step. A ray with more keys costs one more drawing
    // (gather) in that run, and the next run stores as many layers as this one needed.
    // Lists are used while the buffer needs at most `list_budget_bytes`; 0: never.
    std::uint64_t list_budget_bytes = gpu::kCsListBudgetBytes;
    std::uint32_t list_layers = gpu::kCsListLayers;
    // Without fragment lists (budget 0): the depth-complexity pass also does peeling step 0
    // (the nearest and farthest key of every ray), one drawing of the triangles fewer.
    bool fuse_first_step = true;
    // The depth plane: through the snapped vertices (hardware rasterizers) or the unsnapped
    // ones (llvmpipe's setup); Device picks by vendor (Mesa: unsnapped).
    enum class DepthPlane { Device, Snapped, Unsnapped } depth_plane = DepthPlane::Device;
};

}  // namespace vkcollide::passes
