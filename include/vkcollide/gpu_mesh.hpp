// vkcollide: a mesh that lives in an engine's GPU buffers (CollisionWorld::addGpuMesh).
#pragma once

#include <cstdint>

#include <vulkan/vulkan_core.h>

namespace vkcollide {

// The usage GpuMeshDesc::vertex_usage and index_usage assume when the engine does not
// state its own: what vkcollide needs (context.hpp, "What vkcollide needs of an engine's
// buffers"), VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT only: it reads the buffers through
// their device addresses, never as descriptors or transfer sources.
inline constexpr VkBufferUsageFlags kGpuMeshBufferUsage = VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT;

// Geometry that lives only in the engine's GPU buffers, on the Context's device.
// Both buffers need VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT usage and memory bound
// (allocated with VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT) before use. The engine must not
// write them while a detection that reads them is in flight (between submit() and
// collect(), or until submit()'s signal semaphores: world.hpp); writes it submitted
// earlier to the Context's queue are made visible by a barrier at the start of each
// detection, writes on other queues by submit()'s wait semaphores.
struct GpuMeshDesc {
    VkBuffer vertex_buffer = VK_NULL_HANDLE;
    VkDeviceSize vertex_buffer_size = 0;  // size the buffer was created with
    VkDeviceSize vertex_offset = 0;       // byte offset of vertex 0's position; multiple of 4
    std::uint32_t vertex_stride = 12;     // bytes between positions; multiple of 4
    std::uint32_t vertex_count = 0;
    VkFormat position_format = VK_FORMAT_R32G32B32_SFLOAT;  // or R32G32B32A32_SFLOAT (w ignored)

    VkBuffer index_buffer = VK_NULL_HANDLE;
    VkDeviceSize index_buffer_size = 0;
    VkDeviceSize index_offset = 0;  // multiple of 4
    VkIndexType index_type = VK_INDEX_TYPE_UINT32;  // or VK_INDEX_TYPE_UINT16
    std::uint32_t index_count = 0;  // 3 per triangle

    // The usage flags each buffer was created with (VkBufferCreateInfo::usage), which Vulkan
    // cannot be asked for. A buffer declared without VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT
    // is refused by name (asking for its address would itself be invalid). The default
    // states that the buffers have what vkcollide needs; state the real flags to have them
    // checked.
    VkBufferUsageFlags vertex_usage = kGpuMeshBufferUsage;
    VkBufferUsageFlags index_usage = kGpuMeshBufferUsage;
};

}  // namespace vkcollide
