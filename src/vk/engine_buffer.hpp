// Buffers vkcollide did not create (the engine's, for CollisionWorld::addGpuMesh): what
// Vulkan lets a library check about them, in one place (context.hpp, "What vkcollide
// needs of an engine's buffers").
//
// Vulkan has no query for a buffer's usage flags, its memory's allocate flags, whether
// memory is bound or its sharing mode, and calling vkGetBufferDeviceAddress on a buffer
// without SHADER_DEVICE_ADDRESS usage is itself invalid. So the engine declares the usage
// its buffer was created with and its size; this checks the declaration, bounds the size
// by vkGetBufferMemoryRequirements (which any buffer answers), and only then asks for the
// device address.
#pragma once

#include <string>

#include "vk/device.hpp"

namespace vkcollide::vk {

// One engine buffer and the bytes a detection will read from it.
struct EngineBufferUse {
    VkBuffer buffer = VK_NULL_HANDLE;
    VkBufferUsageFlags declared_usage = 0;  // the flags the engine created it with
    VkDeviceSize declared_size = 0;         // VkBufferCreateInfo::size
    VkDeviceSize offset = 0;                // first byte read; a multiple of `alignment`
    VkDeviceSize bytes = 0;                 // bytes read from `offset` on (> 0)
    VkDeviceSize alignment = 4;             // what the shaders' loads need of offset
};

// Returns the device address of byte `offset` of the buffer.
// `what` names the buffer in errors ("object 3 ('cloth'): vertex buffer").
// Errors, checked in this order, each naming the broken rule:
//   InvalidArgument  null buffer; declared_usage lacks VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT;
//                    offset not a multiple of alignment; bytes == 0
//   BufferTooSmall   offset + bytes > declared_size; declared_size larger than the buffer
//                    can be (vkGetBufferMemoryRequirements' size)
//   InvalidArgument  vkGetBufferDeviceAddress returned 0 (memory not bound, or not
//                    allocated with VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT on some drivers)
Result<VkDeviceAddress> checkEngineBuffer(const Device& device, const EngineBufferUse& use, const std::string& what);

}  // namespace vkcollide::vk
