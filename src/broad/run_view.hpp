// The run a broad-phase stage records: the broad phase's copy of the run's inputs and its
// buffers as resources of the graph being recorded.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "broad/broad_phase_types.hpp"
#include "common/broadphase.h"
#include "graph/graph.hpp"

namespace vkcollide::passes {

// Index of a buffer in the broad phase's BufferTable.
using BufferId = std::uint32_t;

// Vertices per dispatch of the bounds pass at most (gpu::ObjectGpu::vertex_base counts
// within a batch and is 32-bit): one batch unless a scene has more.
inline constexpr std::uint64_t kBoundsBatchVertices = std::uint64_t{1} << 31;

// The run being recorded. Refers to the broad phase's own copy of the run's inputs, which
// lives until the next prepare(), so record callbacks (run at submission, after the
// recording functions returned) may capture it by value.
struct RunView {
    const BroadPhaseSettings& settings;
    std::span<const GpuMesh> meshes;
    const gpu::Frame& frame;  // as uploaded
    VkDeviceAddress frame_address = 0;
    bool any_gpu_check = false;  // some mesh has check_on_gpu
    std::span<const gpu::ObjectGpu> objects;  // the meshes as uploaded (triangle bases, transforms)
    VkDeviceAddress objects_address = 0;      // where the GPU reads them (gpu::Frame::objects)
};

// The table's buffers as resources of one graph (BufferTable::import); invalid ids for
// buffers this run does not use.
struct GraphBuffers {
    std::vector<graph::ResourceId> ids;
    graph::ResourceId operator[](BufferId b) const { return ids.at(b); }
};

}  // namespace vkcollide::passes
