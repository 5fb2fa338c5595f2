// Names and labels for capture tools (RenderDoc, Nsight Graphics) and the validation layer's
// messages, through VK_EXT_debug_utils: every Vulkan object vkcollide creates is named
// "vkcollide: <what>" by the code that creates it (one call, next to the vkCreate*), and
// every recorded pass is labelled "vkcollide: <pass>" (graph/executor.cpp). Only where the
// instance enabled the extension (Device::debug_utils); without it each call here is one
// test of that flag: no Vulkan call, no string built.
#pragma once

#include <cstdint>
#include <string_view>
#include <type_traits>

#include "vk/device.hpp"

namespace vkcollide::vk {

// What every name and label starts with, so that vkcollide's work stands out in a capture
// of an engine's frame.
inline constexpr std::string_view kDebugPrefix = "vkcollide: ";

// Loads VKC_DEBUG_LABEL_FUNCTIONS into io_fns through vkGetInstanceProcAddr (the instance
// must have enabled VK_EXT_debug_utils). True when all of them are there; otherwise all are
// left null, so that names and labels are all or nothing.
bool loadDebugLabelFunctions(PFN_vkGetInstanceProcAddr gipa, VkInstance instance, DeviceFunctions& io_fns) noexcept;

// Names an object "vkcollide: <what><suffix>" (the suffix joined here, after the flag's test,
// so that a device without names builds no string). A failure is ignored: a name is a
// diagnostic, never a reason for the object's creation to fail.
void nameObject(const Device& device, VkObjectType type, std::uint64_t handle, std::string_view what,
                std::string_view suffix = {});

template <class Handle>
constexpr VkObjectType objectTypeOf() noexcept {
    if constexpr (std::is_same_v<Handle, VkBuffer>) return VK_OBJECT_TYPE_BUFFER;
    else if constexpr (std::is_same_v<Handle, VkDeviceMemory>) return VK_OBJECT_TYPE_DEVICE_MEMORY;
    else if constexpr (std::is_same_v<Handle, VkImage>) return VK_OBJECT_TYPE_IMAGE;
    else if constexpr (std::is_same_v<Handle, VkImageView>) return VK_OBJECT_TYPE_IMAGE_VIEW;
    else if constexpr (std::is_same_v<Handle, VkShaderModule>) return VK_OBJECT_TYPE_SHADER_MODULE;
    else if constexpr (std::is_same_v<Handle, VkDescriptorSetLayout>) return VK_OBJECT_TYPE_DESCRIPTOR_SET_LAYOUT;
    else if constexpr (std::is_same_v<Handle, VkPipelineLayout>) return VK_OBJECT_TYPE_PIPELINE_LAYOUT;
    else if constexpr (std::is_same_v<Handle, VkPipeline>) return VK_OBJECT_TYPE_PIPELINE;
    else if constexpr (std::is_same_v<Handle, VkPipelineCache>) return VK_OBJECT_TYPE_PIPELINE_CACHE;
    else if constexpr (std::is_same_v<Handle, VkCommandPool>) return VK_OBJECT_TYPE_COMMAND_POOL;
    else if constexpr (std::is_same_v<Handle, VkCommandBuffer>) return VK_OBJECT_TYPE_COMMAND_BUFFER;
    else if constexpr (std::is_same_v<Handle, VkFence>) return VK_OBJECT_TYPE_FENCE;
    else if constexpr (std::is_same_v<Handle, VkSemaphore>) return VK_OBJECT_TYPE_SEMAPHORE;
    else if constexpr (std::is_same_v<Handle, VkQueryPool>) return VK_OBJECT_TYPE_QUERY_POOL;
    else if constexpr (std::is_same_v<Handle, VkEvent>) return VK_OBJECT_TYPE_EVENT;
    else static_assert(!sizeof(Handle), "a handle type vkcollide does not name yet");
}

template <class Handle>
void nameObject(const Device& device, Handle handle, std::string_view what, std::string_view suffix = {}) {
    if (!device.debug_utils) return;
    std::uint64_t bits;
    if constexpr (std::is_pointer_v<Handle>) bits = reinterpret_cast<std::uintptr_t>(handle);
    else bits = static_cast<std::uint64_t>(handle);  // non-dispatchable handles on 32-bit targets
    nameObject(device, objectTypeOf<Handle>(), bits, what, suffix);
}

// A label around commands recorded straight into a command buffer (not through a command
// tape): begin/end must pair in the same command buffer.
void beginLabel(const Device& device, VkCommandBuffer cmd, std::string_view what);
void endLabel(const Device& device, VkCommandBuffer cmd);

}  // namespace vkcollide::vk
