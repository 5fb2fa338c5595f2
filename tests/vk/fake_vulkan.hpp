// A fake Vulkan driver behind a vkGetInstanceProcAddr, for contract tests of the device
// layer without a GPU (the role vk-bootstrap's VulkanMock plays): each test describes the
// loader and physical devices it wants, injects getInstanceProcAddr() through
// ContextCreateInfo / AdoptedDevice, and reads back what vkcollide asked for.
//
// It implements the instance queries, device creation, the buffer/image/memory calls of
// vk::Buffer and vk::Image, pipeline caches, shader modules, compute pipelines, command
// pools, fences, semaphores (binary and timeline), vkQueueSubmit2 (recorded; the "GPU"
// finishes submitted work at once, or when the test says) and VK_EXT_debug_utils' names and
// labels (recorded); any other entry point is a trap
// that aborts the test when called, so a contract test cannot silently reach code it does
// not describe. Objects created with VkAllocationCallbacks get one host allocation from
// them, freed at destruction; a destruction without the callbacks the object was created
// with (or with different ones) is recorded in allocator_mismatches.
//
// vkGetInstanceProcAddr carries no user pointer, so the fake is one process-wide object:
// FakeVulkanScope installs a fresh one per test (tests using it must not run in parallel
// threads; Catch runs test cases one after another).
#pragma once

#include <cstdint>
#include <map>
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
    std::vector<std::string> instance_extensions;  // what the loader offers (VK_EXT_debug_utils, ...)
    std::vector<FakePhysicalDevice> physical_devices = {FakePhysicalDevice{}};
    // false: submitted work stays pending (fences unsignalled, semaphore signals not
    // applied, timeline waits time out) until finishPending().
    bool gpu_finishes_at_once = true;
    // Not VK_SUCCESS (VK_ERROR_DEVICE_LOST): every fence/semaphore status and wait returns it.
    VkResult device_status = VK_SUCCESS;
    // What vkQueueSubmit2 returns (the submission is recorded only on VK_SUCCESS).
    VkResult submit_result = VK_SUCCESS;

    // ---- observations (read by the test) ----
    int instances_alive = 0;
    int devices_alive = 0;
    int buffers_alive = 0;
    int allocations_alive = 0;
    vk::FeatureSet device_features;                // what the last vkCreateDevice enabled
    std::vector<std::string> device_extensions;    // ... and which extensions
    std::vector<VkMappedMemoryRange> flushed;      // every range vkFlushMappedMemoryRanges got
    std::vector<VkMappedMemoryRange> invalidated;  // ... and vkInvalidateMappedMemoryRanges
    int images_alive = 0;
    int image_views_alive = 0;
    int pipelines_alive = 0;
    int pipeline_layouts_alive = 0;
    int shader_modules_alive = 0;
    int pipeline_caches_alive = 0;
    int command_pools_alive = 0;
    int fences_alive = 0;
    int semaphores_alive = 0;
    std::size_t last_pipeline_cache_initial_size = 0;   // pInitialDataSize of the last vkCreatePipelineCache
    std::vector<VkPipelineCache> pipelines_cache_used;  // the cache each vkCreate*Pipelines got
    std::vector<VkDeviceSize> bind_offsets;             // memoryOffset of every vkBind*Memory
    std::vector<std::string> allocator_mismatches;      // "vkDestroyBuffer: ..." per mismatch
    int unbounded_waits = 0;                            // fence/semaphore waits with timeout UINT64_MAX
    struct Submit {
        std::vector<VkSemaphoreSubmitInfo> waits, signals;
        VkFence fence = VK_NULL_HANDLE;
    };
    std::vector<Submit> submits;  // every successful vkQueueSubmit2 batch, in order
    std::vector<std::string> enabled_instance_extensions;  // what the last vkCreateInstance enabled
    // Every buffer, memory, image, view, shader module, pipeline layout, pipeline, pipeline
    // cache, command pool, command buffer, fence and semaphore created, in order.
    struct Created {
        VkObjectType type;
        std::uint64_t handle;
    };
    std::vector<Created> created_objects;
    std::map<std::uint64_t, std::string> object_names;  // the last vkSetDebugUtilsObjectNameEXT per handle
    std::vector<std::string> labels;                    // "begin <name>", "end", "insert <name>", in call order
    int debug_utils_calls = 0;                          // of those four entry points, with the extension or not

    // Completes every submitted batch: signals its fence and applies its semaphore signals.
    void finishPending();
    // A timeline semaphore's counter (0 for unknown handles).
    std::uint64_t timelineValue(VkSemaphore semaphore) const;
    // The header Context::pipelineCacheData() gets back: matches physical device `index`.
    static std::vector<std::byte> cacheHeader(const FakePhysicalDevice& device);

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
