// vkcollide: a mesh that lives in an engine's GPU buffers (CollisionWorld::addGpuMesh).
#pragma once

#include <cstdint>

#include <vulkan/vulkan_core.h>

namespace vkcollide {

// Geometry that lives only in the engine's GPU buffers, on the Context's device.
// Both buffers need VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT and
// VK_BUFFER_USAGE_STORAGE_BUFFER_BIT and memory bound before use. The engine must not
// write them while a detection that reads them is in flight (between submit() and
// collect()); writes it submitted earlier to the Context's queue are made visible by a
// barrier at the start of each detection.
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
};

}  // namespace vkcollide
