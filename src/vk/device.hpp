// The device every subsystem works on: handles, dispatch tables, properties and the
// ownership flag that says whether vkcollide created them or borrows them.
#pragma once

#include <atomic>
#include <memory>
#include <optional>

#include "vk/dispatch.hpp"
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

    DeviceInfo info;
    VkPhysicalDeviceProperties properties{};
    VkPhysicalDeviceMemoryProperties memory{};
    std::uint32_t timestamp_valid_bits = 0;
    // Largest single buffer and allocation (Vulkan 1.3 maxBufferSize, 1.1 maxMemoryAllocationSize).
    VkDeviceSize max_buffer_size = ~VkDeviceSize(0);
    VkDeviceSize max_allocation_size = ~VkDeviceSize(0);
    // VK_EXT_conservative_rasterization is enabled on this device (pipelines may overestimate).
    bool conservative_rasterization = false;

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

// Reads properties and checks every requirement of a physical device (see context.hpp).
DeviceInfo describePhysicalDevice(const InstanceFunctions& fns, VkPhysicalDevice physical,
                                  std::optional<std::uint32_t>* out_queue_family = nullptr);

}  // namespace vkcollide::vk
