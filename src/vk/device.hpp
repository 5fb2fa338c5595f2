// The device every subsystem works on: handles, dispatch tables, properties and the
// ownership flag that says whether vkcollide created them or borrows them.
#pragma once

#include <atomic>
#include <memory>
#include <optional>
#include <span>

#include "vk/dispatch.hpp"
#include "vk/features.hpp"
#include "vk/loader.hpp"
#include "vkcollide/context.hpp"

namespace vkcollide::vk {

struct Device {
    std::shared_ptr<LoaderLibrary> library;  // null when adopted
    GlobalFunctions global{};
    InstanceFunctions instance_fns{};
    DeviceFunctions fns{};

    VkInstance instance = VK_NULL_HANDLE;
    VkPhysicalDevice physical = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    VkQueue queue = VK_NULL_HANDLE;
    std::uint32_t queue_family = 0;
    bool owns_instance = false;
    bool owns_device = false;

    VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
    MessageCallback on_message;
    std::atomic<std::uint64_t> validation_messages{0};
    // Bytes of VkDeviceMemory that vk::Buffer and vk::Image hold on this device right now
    // (every world of the Context): all of vkcollide's device memory goes through them.
    std::atomic<std::uint64_t> memory_in_use{0};

    DeviceInfo info;
    VkPhysicalDeviceProperties properties{};
    VkPhysicalDeviceMemoryProperties memory{};
    std::uint32_t timestamp_valid_bits = 0;
    VkQueueFlags queue_flags = 0;  // of queue_family
    // Largest single buffer and allocation (Vulkan 1.3 maxBufferSize, 1.1 maxMemoryAllocationSize).
    VkDeviceSize max_buffer_size = ~VkDeviceSize(0);
    VkDeviceSize max_allocation_size = ~VkDeviceSize(0);
    // Optional capabilities enabled on this device (context.hpp lists them); each is used
    // only where true. For an adopted device: what the engine enabled and the device has.
    bool conservative_rasterization = false;  // VK_EXT_conservative_rasterization: pipelines may overestimate
    bool push_descriptor = false;             // VK_KHR_push_descriptor: fns.vkCmdPushDescriptorSetKHR is loaded
    bool shader_float64 = false;              // shaderFloat64
    bool robust_buffer_access = false;        // robustBufferAccess (descriptor accesses only)
    bool robust_buffer_access2 = false;       // VK_EXT_robustness2's robustBufferAccess2

    Device() = default;
    ~Device();
    Device(const Device&) = delete;
    Device& operator=(const Device&) = delete;

    // Index of a memory type allowed by type_bits that has all `required` flags, preferring
    // one that also has `preferred`. Empty when none fits.
    std::optional<std::uint32_t> findMemoryType(std::uint32_t type_bits, VkMemoryPropertyFlags required,
                                                VkMemoryPropertyFlags preferred = 0) const;

    void message(MessageSeverity severity, std::string_view text) const;
};

// A physical device's properties, what it supports and what it lacks (see context.hpp).
struct PhysicalDeviceReport {
    DeviceInfo info;                            // info.missing: every requirement it lacks
    FeatureSet supported;                       // empty below Vulkan 1.3 (not queried)
    std::optional<std::uint32_t> queue_family;  // first graphics+compute family with timestamps
};
PhysicalDeviceReport describePhysicalDevice(const InstanceFunctions& fns, VkPhysicalDevice physical);

// Reads the limits and memory properties every subsystem uses; checks the queue family.
Result<void> finishDevice(Device& device);

// True when `name` is in the list of extension names.
bool listsExtension(std::span<const char* const> names, const char* name) noexcept;

}  // namespace vkcollide::vk
