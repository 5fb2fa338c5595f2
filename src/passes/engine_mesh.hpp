// An engine's vertex and index buffers (GpuMeshDesc) as the broad phase reads them: the two
// Vulkan queries the description needs, behind two small functions, so the API holds no
// Vulkan calls. The rules a GpuMeshDesc must meet are checked by the API
// (src/api/validation.cpp); these functions assume them.
#pragma once

#include "passes/broad_phase_types.hpp"
#include "vkcollide/gpu_mesh.hpp"

namespace vkcollide::vk {
struct Device;
}

namespace vkcollide::passes {

// The most bytes `buffer` can hold: its memory requirements' size (at least the size it
// was created with). Precondition: a valid buffer of `device`.
VkDeviceSize engineBufferCapacity(const vk::Device& device, VkBuffer buffer);

// The mesh the broad phase reads: buffer device addresses plus offsets, with the layout of
// `desc` (whose rules the API checked). A buffer without SHADER_DEVICE_ADDRESS usage has
// no address (0): its GpuMesh address is then just the offset.
GpuMesh describeEngineMesh(const vk::Device& device, const GpuMeshDesc& desc, bool open);

}  // namespace vkcollide::passes
