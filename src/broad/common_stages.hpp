// The stages every method shares: the front of a run and the header readback.
//
// Front ("prepare/validate/fit", Stage::Prepare):
//   "clear"    makes the engine's earlier writes visible, resets the header (counters 0,
//              bound minima +inf) and zeroes the table's `cleared` rows;
//   "validate" engine meshes only (check_on_gpu): indices < vertex count, finite positions,
//              findings in the header (BroadPhase reads them as ObjectFaults);
//   "bounds", "fit" without a caller's region: the scene's extent in the projection basis,
//              then the projection (fit.comp.glsl; projection.hpp repeats it on the host).
// Readback ("readback-header", Stage::Readback): the header into host-visible memory.
#pragma once

#include <memory>
#include <utility>
#include <vector>

#include "broad/method.hpp"

namespace vkcollide::passes {

class CommonStages {
public:
    static Result<std::unique_ptr<CommonStages>> create(vk::Device& device);
    // `cleared`: the table's rows zeroed every run, with their sizes.
    void recordFront(graph::Graph& g, const RunView& run, const GraphBuffers& buffers, const CoreBuffers& core,
                     const std::vector<std::pair<BufferId, VkDeviceSize>>& cleared) const;
    void recordReadback(graph::Graph& g, const GraphBuffers& buffers, const CoreBuffers& core) const;

private:
    CommonStages() = default;
    vk::Pipeline validate_, bounds_, fit_;
};

}  // namespace vkcollide::passes
