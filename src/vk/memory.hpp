// Device memory for one buffer or image: from vkAllocateMemory (one VkDeviceMemory per
// resource, the default) or from the engine's DeviceMemoryHooks (a range of the engine's
// memory). Both paths count into Device::memory_in_use, so Context::deviceMemoryInUse()
// is everything vkcollide holds whichever path it took.
#pragma once

#include <string>

#include "vk/device.hpp"

namespace vkcollide::vk {

struct MemoryBlock {
    VkDeviceMemory memory = VK_NULL_HANDLE;
    VkDeviceSize offset = 0;  // where the resource is bound in `memory`
    VkDeviceSize size = 0;    // bytes counted (requirements.size, rounded as DeviceMemoryRequest says)
    void* mapped = nullptr;   // host address of byte `offset` (host-visible and asked for), else null
    bool coherent = true;     // HOST_COHERENT (flush/invalidate not needed)
    // The VkDeviceMemory is this block alone (vkAllocateMemory): a flush may run to its end
    // with VK_WHOLE_SIZE. False for a range of the engine's memory.
    bool whole_memory = true;
    bool from_hook = false;
    std::uint64_t user = 0;  // DeviceMemoryBlock::user, for the free hook
};

struct MemoryNeed {
    VkMemoryRequirements requirements{};
    std::uint32_t memory_type = 0;
    bool device_address = false;  // VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT
    bool image = false;
    bool map = false;             // host-visible types: give a host pointer
};

// Allocates (and, on the default path, maps when asked) and counts. `name` names the
// resource in errors. Errors: OutOfMemory / VulkanError from vkAllocateMemory, vkMapMemory
// or the hook's VkResult; InvalidArgument when the hook's block breaks a rule (null
// memory, misaligned offset, no host pointer for a host-visible type): the block is given
// back to the free hook first.
Result<MemoryBlock> allocateMemory(Device& device, const MemoryNeed& need, const std::string& name);
// Frees (or hands back to the hook) and uncounts; leaves `block` empty. After the resource
// bound to it is destroyed.
void freeMemory(Device& device, MemoryBlock& block);

}  // namespace vkcollide::vk
