// Vulkan entry points loaded at run time into per-instance and per-device tables
// (the job Volk does elsewhere). Nothing here is global: every Context owns its tables.
#pragma once

#include <vulkan/vulkan_core.h>

namespace vkcollide::vk {

// Entry points fetched with vkGetInstanceProcAddr(nullptr, ...).
#define VKC_GLOBAL_FUNCTIONS(X)              \
    X(vkCreateInstance)                      \
    X(vkEnumerateInstanceExtensionProperties) \
    X(vkEnumerateInstanceLayerProperties)    \
    X(vkEnumerateInstanceVersion)

#define VKC_INSTANCE_FUNCTIONS(X)                   \
    X(vkDestroyInstance)                            \
    X(vkEnumeratePhysicalDevices)                   \
    X(vkGetPhysicalDeviceProperties)                \
    X(vkGetPhysicalDeviceProperties2)               \
    X(vkGetPhysicalDeviceFeatures2)                 \
    X(vkGetPhysicalDeviceQueueFamilyProperties)     \
    X(vkGetPhysicalDeviceMemoryProperties)          \
    X(vkGetPhysicalDeviceFormatProperties)          \
    X(vkEnumerateDeviceExtensionProperties)         \
    X(vkCreateDevice)                               \
    X(vkGetDeviceProcAddr)

// Present only when VK_EXT_debug_utils is enabled on the instance.
#define VKC_DEBUG_FUNCTIONS(X)          \
    X(vkCreateDebugUtilsMessengerEXT)   \
    X(vkDestroyDebugUtilsMessengerEXT)

#define VKC_DEVICE_FUNCTIONS(X)             \
    X(vkDestroyDevice)                      \
    X(vkGetDeviceQueue)                     \
    X(vkDeviceWaitIdle)                     \
    X(vkQueueSubmit2)                       \
    X(vkQueueWaitIdle)                      \
    X(vkAllocateMemory)                     \
    X(vkFreeMemory)                         \
    X(vkMapMemory)                          \
    X(vkUnmapMemory)                        \
    X(vkInvalidateMappedMemoryRanges)       \
    X(vkFlushMappedMemoryRanges)            \
    X(vkCreateBuffer)                       \
    X(vkDestroyBuffer)                      \
    X(vkGetBufferMemoryRequirements)        \
    X(vkBindBufferMemory)                   \
    X(vkGetBufferDeviceAddress)             \
    X(vkCreateImage)                        \
    X(vkDestroyImage)                       \
    X(vkGetImageMemoryRequirements)         \
    X(vkBindImageMemory)                    \
    X(vkCreateImageView)                    \
    X(vkDestroyImageView)                   \
    X(vkCreateShaderModule)                 \
    X(vkDestroyShaderModule)                \
    X(vkCreateDescriptorSetLayout)          \
    X(vkDestroyDescriptorSetLayout)         \
    X(vkCreatePipelineLayout)               \
    X(vkDestroyPipelineLayout)              \
    X(vkCreateComputePipelines)             \
    X(vkCreateGraphicsPipelines)            \
    X(vkDestroyPipeline)                    \
    X(vkCreateCommandPool)                  \
    X(vkDestroyCommandPool)                 \
    X(vkResetCommandPool)                   \
    X(vkAllocateCommandBuffers)             \
    X(vkFreeCommandBuffers)                 \
    X(vkBeginCommandBuffer)                 \
    X(vkEndCommandBuffer)                   \
    X(vkCreateFence)                        \
    X(vkDestroyFence)                       \
    X(vkWaitForFences)                      \
    X(vkResetFences)                        \
    X(vkGetFenceStatus)                     \
    X(vkCreateSemaphore)                    \
    X(vkDestroySemaphore)                   \
    X(vkGetSemaphoreCounterValue)           \
    X(vkWaitSemaphores)                     \
    X(vkSignalSemaphore)                    \
    X(vkCreateEvent)                        \
    X(vkDestroyEvent)                       \
    X(vkGetEventStatus)                     \
    X(vkResetEvent)                         \
    X(vkCreatePipelineCache)                \
    X(vkDestroyPipelineCache)               \
    X(vkGetPipelineCacheData)               \
    X(vkCreateQueryPool)                    \
    X(vkDestroyQueryPool)                   \
    X(vkResetQueryPool)                     \
    X(vkGetQueryPoolResults)                \
    X(vkCmdPipelineBarrier2)                \
    X(vkCmdSetEvent2)                       \
    X(vkCmdBeginRendering)                  \
    X(vkCmdEndRendering)                    \
    X(vkCmdBindPipeline)                    \
    X(vkCmdPushConstants)                   \
    X(vkCmdDispatch)                        \
    X(vkCmdDispatchIndirect)                \
    X(vkCmdDraw)                            \
    X(vkCmdDrawIndirect)                    \
    X(vkCmdSetViewport)                     \
    X(vkCmdSetScissor)                      \
    X(vkCmdFillBuffer)                      \
    X(vkCmdCopyBuffer)                      \
    X(vkCmdCopyImageToBuffer)               \
    X(vkCmdClearColorImage)                 \
    X(vkCmdResetQueryPool)                  \
    X(vkCmdWriteTimestamp2)

// VK_KHR_push_descriptor (optional): loaded only where the device enables it, else null.
#define VKC_PUSH_DESCRIPTOR_FUNCTIONS(X) \
    X(vkCmdPushDescriptorSetKHR)

// VK_EXT_debug_utils' names and labels (optional): loaded only where the instance enabled the
// extension (vk/debug_names.hpp), else null. Commands of an instance extension, so they come
// from vkGetInstanceProcAddr (not every loader and driver returns them from
// vkGetDeviceProcAddr); they live in the device table because command tapes replay them.
#define VKC_DEBUG_LABEL_FUNCTIONS(X)    \
    X(vkSetDebugUtilsObjectNameEXT)     \
    X(vkCmdBeginDebugUtilsLabelEXT)     \
    X(vkCmdEndDebugUtilsLabelEXT)       \
    X(vkCmdInsertDebugUtilsLabelEXT)

#define VKC_DECLARE_PFN(name) PFN_##name name = nullptr;

struct GlobalFunctions {
    PFN_vkGetInstanceProcAddr vkGetInstanceProcAddr = nullptr;
    VKC_GLOBAL_FUNCTIONS(VKC_DECLARE_PFN)
};

struct InstanceFunctions {
    VKC_INSTANCE_FUNCTIONS(VKC_DECLARE_PFN)
    VKC_DEBUG_FUNCTIONS(VKC_DECLARE_PFN)
};

struct DeviceFunctions {
    VKC_DEVICE_FUNCTIONS(VKC_DECLARE_PFN)
    VKC_PUSH_DESCRIPTOR_FUNCTIONS(VKC_DECLARE_PFN)
    VKC_DEBUG_LABEL_FUNCTIONS(VKC_DECLARE_PFN)
};

#undef VKC_DECLARE_PFN

}  // namespace vkcollide::vk
