// An engine's vertex and index buffers (GpuMeshDesc) as the broad phase reads them. The
// rules a GpuMeshDesc must meet are checked by the API (src/api/validation.cpp for the
// layout, vk::checkEngineBuffer for each buffer, which also gives its device address);
// this assumes them.
#pragma once

#include "broad/broad_phase_types.hpp"
#include "vkcollide/gpu_mesh.hpp"

namespace vkcollide::passes {

// The mesh the broad phase reads, with the layout of `desc`: `vertices` is the device
// address of vertex 0's position, `indices` that of the first index (offsets included).
GpuMesh describeEngineMesh(const GpuMeshDesc& desc, VkDeviceAddress vertices, VkDeviceAddress indices, bool open);

}  // namespace vkcollide::passes
