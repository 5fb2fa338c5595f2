#include "vk/memory.hpp"

#include <algorithm>
#include <exception>

#include "vk/debug_names.hpp"

namespace vkcollide::vk {
namespace {

VkDeviceSize roundUp(VkDeviceSize x, VkDeviceSize to) { return (x + to - 1) / to * to; }

// The hook's block must be usable as vkcollide will use it; the rule it breaks is named.
std::string blockProblem(const DeviceMemoryRequest& request, const DeviceMemoryBlock& block) {
    if (block.memory == VK_NULL_HANDLE) return "returned VK_SUCCESS with a null VkDeviceMemory";
    if (block.offset % std::max<VkDeviceSize>(request.requirements.alignment, 1) != 0)
        return "returned offset " + std::to_string(block.offset) + ", not a multiple of the requested alignment " +
               std::to_string(request.requirements.alignment);
    if (request.host_access && !block.mapped)
        return "returned no host pointer (DeviceMemoryBlock::mapped) though the request has host_access";
    return {};
}

}  // namespace

Result<void> takeHostHooks(Device& device, const VkAllocationCallbacks* callbacks, const DeviceMemoryHooks& memory,
                           const char* what) {
    if (static_cast<bool>(memory.allocate) != static_cast<bool>(memory.free))
        return Error(ErrorCode::InvalidArgument,
                     std::string(what) + "::memory_hooks: allocate and free come as a pair (one of them is empty)");
    if (callbacks) {
        if (!callbacks->pfnAllocation || !callbacks->pfnReallocation || !callbacks->pfnFree)
            return Error(ErrorCode::InvalidArgument, std::string(what) + "::allocation_callbacks: pfnAllocation, pfnReallocation "
                                                                         "and pfnFree must all be set (Vulkan's rule)");
        device.allocation_callbacks = *callbacks;
        device.has_allocator = true;
    }
    device.memory_hooks = memory;
    return {};
}

Result<MemoryBlock> allocateMemory(Device& device, const MemoryNeed& need, const std::string& name) {
    const VkMemoryPropertyFlags props = device.memory.memoryTypes[need.memory_type].propertyFlags;
    const bool host_visible = (props & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT) != 0;
    MemoryBlock block;
    block.coherent = (props & VK_MEMORY_PROPERTY_HOST_COHERENT_BIT) != 0;
    VkMemoryRequirements req = need.requirements;

    if (device.memory_hooks.allocate) {
        // A range of the engine's memory: flush and invalidate work in whole
        // nonCoherentAtomSize blocks that must stay inside the range, so a non-coherent
        // range starts and ends on atom boundaries (VMA does the same).
        if (host_visible && !block.coherent) {
            const VkDeviceSize atom = std::max<VkDeviceSize>(device.properties.limits.nonCoherentAtomSize, 1);
            req.alignment = std::max(req.alignment, atom);
            req.size = roundUp(req.size, atom);
        }
        DeviceMemoryRequest request;
        request.requirements = req;
        request.memory_type = need.memory_type;
        request.properties = props;
        request.device_address = need.device_address;
        request.image = need.image;
        request.host_access = need.map && host_visible;
        request.name = name.c_str();
        DeviceMemoryBlock out;
        VkResult r = VK_ERROR_UNKNOWN;
        std::string problem;
        {
            std::lock_guard<std::mutex> lock(device.memory_hook_mutex);
            try {
                r = device.memory_hooks.allocate(request, out);
            } catch (...) {
                return Error(ErrorCode::VulkanError, "DeviceMemoryHooks::allocate threw for '" + name + "'",
                             static_cast<std::int32_t>(VK_ERROR_UNKNOWN));
            }
            if (r == VK_SUCCESS) {
                problem = blockProblem(request, out);
                if (!problem.empty()) {
                    try {
                        device.memory_hooks.free(out);  // given back before refusing it
                    } catch (...) {
                        device.message(MessageSeverity::Error, "DeviceMemoryHooks::free threw; the block is the engine's to reclaim");
                    }
                }
            }
        }
        if (r != VK_SUCCESS) return vulkanError(r, "DeviceMemoryHooks::allocate of " + std::to_string(req.size) + " bytes for '" + name + "'");
        if (!problem.empty()) return Error(ErrorCode::InvalidArgument, "DeviceMemoryHooks::allocate for '" + name + "' " + problem);
        block.memory = out.memory;
        block.offset = out.offset;
        block.mapped = need.map && host_visible ? out.mapped : nullptr;
        block.user = out.user;
        block.whole_memory = false;
        block.from_hook = true;
    } else {
        VkMemoryAllocateFlagsInfo flags{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_FLAGS_INFO};
        flags.flags = VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT;
        VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
        ai.pNext = need.device_address ? &flags : nullptr;
        ai.allocationSize = req.size;
        ai.memoryTypeIndex = need.memory_type;
        VkResult r = device.fns.vkAllocateMemory(device.device, &ai, device.allocator(), &block.memory);
        if (r != VK_SUCCESS) return vulkanError(r, "vkAllocateMemory of " + std::to_string(req.size) + " bytes for '" + name + "'");
        nameObject(device, block.memory, name, " memory");  // not the engine's memory: that one is the engine's to name
        if (need.map && host_visible) {
            r = device.fns.vkMapMemory(device.device, block.memory, 0, VK_WHOLE_SIZE, 0, &block.mapped);
            if (r != VK_SUCCESS) {
                device.fns.vkFreeMemory(device.device, block.memory, device.allocator());
                return vulkanError(r, "vkMapMemory for '" + name + "'");
            }
        }
    }
    block.size = req.size;
    device.memory_in_use.fetch_add(block.size, std::memory_order_relaxed);
    return block;
}

void freeMemory(Device& device, MemoryBlock& block) {
    if (!block.memory) return;
    if (block.from_hook) {
        DeviceMemoryBlock out;
        out.memory = block.memory;
        out.offset = block.offset;
        out.mapped = block.mapped;
        out.user = block.user;
        std::lock_guard<std::mutex> lock(device.memory_hook_mutex);
        try {
            device.memory_hooks.free(out);
        } catch (...) {
            device.message(MessageSeverity::Error, "DeviceMemoryHooks::free threw; the block is the engine's to reclaim");
        }
    } else {
        device.fns.vkFreeMemory(device.device, block.memory, device.allocator());  // unmaps implicitly
    }
    device.memory_in_use.fetch_sub(block.size, std::memory_order_relaxed);
    block = MemoryBlock{};
}

}  // namespace vkcollide::vk
