// A fake Vulkan driver behind a vkGetInstanceProcAddr, for contract tests of the device
// layer without a GPU (the role vk-bootstrap's VulkanMock plays): each test describes the
// loader and physical devices it wants, injects getInstanceProcAddr() through
// ContextCreateInfo / AdoptedDevice, and reads back what vkcollide asked for.
//
// It implements the instance queries, device creation and the buffer/memory calls
// vk::Buffer makes; any other entry point is a trap that aborts the test when called, so
// a contract test cannot silently reach code it does not describe.
//
// vkGetInstanceProcAddr carries no user pointer, so the fake is one process-wide object:
// FakeVulkanScope installs a fresh one per test (tests using it must not run in parallel
// threads; Catch runs test cases one after another).
#pragma once

#include <cstdint>
#include <set>
#include <string>
#include <vector>

#include <vulkan/vulkan_core.h>

#include "vk/features.hpp"

namespace vkcollide::test {

struct FakePhysicalDevice {
    std::string name = "Fake GPU";
    VkPhysicalDeviceType type = VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU;
    std::uint32_t api_version = VK_API_VERSION_1_3;
    vk::FeatureSet features = allFeatures();
    std::vector<std::string> extensions;
    std::vector<VkQueueFamilyProperties> queue_families = {
        {VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT | VK_QUEUE_TRANSFER_BIT, 1, 64, {1, 1, 1}}};
    bool coherent_memory = true;
    VkDeviceSize non_coherent_atom_size = 64;

    static vk::FeatureSet allFeatures();
};

struct FakeVulkan {
    // ---- behaviour (set by the test) ----
    std::uint32_t loader_version = VK_API_VERSION_1_3;
    bool validation_layer_installed = false;
    VkResult create_instance_result = VK_SUCCESS;
    VkResult create_device_result = VK_SUCCESS;
    std::set<std::string> missing_entry_points;  // vkGet*ProcAddr returns null for these
    std::vector<FakePhysicalDevice> physical_devices = {FakePhysicalDevice{}};

    // ---- observations (read by the test) ----
    int instances_alive = 0;
    int devices_alive = 0;
    int buffers_alive = 0;
    int allocations_alive = 0;
    vk::FeatureSet device_features;                // what the last vkCreateDevice enabled
    std::vector<std::string> device_extensions;    // ... and which extensions
    std::vector<VkMappedMemoryRange> flushed;      // every range vkFlushMappedMemoryRanges got
    std::vector<VkMappedMemoryRange> invalidated;  // ... and vkInvalidateMappedMemoryRanges

    // Handles of the fake objects, for AdoptedDevice.
    VkInstance instanceHandle() const;
    VkPhysicalDevice physicalHandle(std::size_t index) const;
    VkDevice deviceHandle() const;
    VkQueue queueHandle() const;

    static PFN_vkGetInstanceProcAddr getInstanceProcAddr();
};

// Installs a fresh FakeVulkan for its lifetime; fake() is the installed one.
class FakeVulkanScope {
public:
    FakeVulkanScope();
    ~FakeVulkanScope();
    FakeVulkanScope(const FakeVulkanScope&) = delete;
    FakeVulkanScope& operator=(const FakeVulkanScope&) = delete;
    FakeVulkan& fake();
};

}  // namespace vkcollide::test
