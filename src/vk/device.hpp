// The device every subsystem works on: handles, dispatch tables, properties and the
// ownership flag that says whether vkcollide created them or borrows them; what the engine
// lends besides (queue hooks, memory hooks, allocation callbacks, pipeline cache) and the
// locks that make sharing one device between worlds on several threads safe.
//
// Lifetime: a Device is always owned by shared_ptr (Context::create/adopt make it so).
// Every resource made on it (Buffer, Image, Pipeline, Submission, Semaphore) holds a
// DeviceRef, so the Device and its VkDevice live until the Context and the last resource
// are gone, whichever order they go in (context.hpp, Lifetime).
#pragma once

#include <atomic>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "vk/dispatch.hpp"
#include "vk/features.hpp"
#include "vk/loader.hpp"
#include "vkcollide/context.hpp"

namespace vkcollide::vk {

struct Device;
using DeviceRef = std::shared_ptr<Device>;
struct PipelineHandles;  // vk/pipeline.hpp

struct Device : std::enable_shared_from_this<Device> {
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
    // Bytes of device memory that vk::Buffer and vk::Image hold on this device right now
    // (every world of the Context): all of vkcollide's device memory goes through them
    // (src/vk/memory.cpp), from vkAllocateMemory or from the engine's DeviceMemoryHooks.
    std::atomic<std::uint64_t> memory_in_use{0};
    // Counts the destructions of vk::Buffer, vk::Image and vk::Pipeline objects on this
    // device (every world of the Context). A command buffer names such objects by handle,
    // and Vulkan invalidates it when one is destroyed, even if a new object gets the same
    // handle value later: graph::Executor submits a recorded command buffer again only
    // while this count is what it was when the buffer was recorded.
    std::atomic<std::uint64_t> resource_generation{0};

    // What the engine lent (context.hpp). The callbacks are a copy (has_allocator says
    // whether there are any): allocator() is what every create/destroy call passes.
    VkAllocationCallbacks allocation_callbacks{};
    bool has_allocator = false;
    QueueHooks queue_hooks;        // adopted devices only
    DeviceMemoryHooks memory_hooks;
    // The pipeline cache every Pipeline is created through: the engine's (borrowed) or
    // vkcollide's own (owns_pipeline_cache), created by setUpPipelineCache().
    VkPipelineCache pipeline_cache = VK_NULL_HANDLE;
    bool owns_pipeline_cache = false;
    // Every pipeline alive on this device, by what it was made from (Pipeline::createCompute
    // and createRaster): the worlds of one Context share one set instead of building their own
    // 12-24 each. Weak: a pipeline dies with the last holder; while the Context lives it is
    // one (kept_pipelines), so that a world created later, or a stage a world turns on
    // later, finds its pipelines made. Creation is the expensive part of a first detection
    // (a driver compiles each program: about 0.6 s for one method's set on lavapipe).
    // ~Context turns keeping off and drops the kept ones, which breaks the cycle (each
    // pipeline holds a DeviceRef); a Device without a Context keeps nothing.
    std::mutex pipelines_mutex;
    std::map<std::string, std::weak_ptr<const PipelineHandles>> pipelines;
    std::vector<std::shared_ptr<const PipelineHandles>> kept_pipelines;  // under pipelines_mutex
    bool keep_pipelines = false;                                         // under pipelines_mutex
    std::uint64_t pipelines_created = 0;  // under pipelines_mutex; for tests
    // Serialise what several worlds on several threads share: the queue (every submission
    // goes through queueSubmit) and the engine's memory hooks.
    std::mutex queue_mutex;
    std::mutex memory_hook_mutex;

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
    bool timeline_semaphore = false;          // timelineSemaphore (engine timelines only)
    // VK_EXT_debug_utils on the instance, and fns' VKC_DEBUG_LABEL_FUNCTIONS loaded: objects
    // get names and passes labels (vk/debug_names.hpp).
    bool debug_utils = false;
    // ContextCreateInfo::pipeline_statistics: VK_KHR_pipeline_executable_properties enabled,
    // its two queries loaded, every pipeline created capturing its statistics, which
    // finishPipeline appends to pipeline_statistics (under pipelines_mutex). Where it was
    // asked for and cannot be had, why (Context::pipelineStatistics returns it).
    bool capture_statistics = false;
    PFN_vkGetPipelineExecutablePropertiesKHR get_executable_properties = nullptr;
    PFN_vkGetPipelineExecutableStatisticsKHR get_executable_statistics = nullptr;
    std::vector<PipelineStatistics> pipeline_statistics;
    std::string statistics_unavailable = "ContextCreateInfo::pipeline_statistics was off";

    Device() = default;
    ~Device();
    Device(const Device&) = delete;
    Device& operator=(const Device&) = delete;

    // Index of a memory type allowed by type_bits that has all `required` flags, preferring
    // one that also has `preferred`. Empty when none fits.
    std::optional<std::uint32_t> findMemoryType(std::uint32_t type_bits, VkMemoryPropertyFlags required,
                                                VkMemoryPropertyFlags preferred = 0) const;

    void message(MessageSeverity severity, std::string_view text) const;

    const VkAllocationCallbacks* allocator() const noexcept { return has_allocator ? &allocation_callbacks : nullptr; }
    // A DeviceRef to this device (every Device is owned by shared_ptr).
    DeviceRef ref() { return shared_from_this(); }

    // The one way vkcollide submits to the queue: under queue_mutex, inside the engine's
    // QueueHooks lock, through its submit hook when it has one. A hook that throws gives
    // VK_ERROR_UNKNOWN (and a message).
    VkResult queueSubmit(std::span<const VkSubmitInfo2> submits, VkFence fence);
    // vkDeviceWaitIdle under queue_mutex (it touches every queue of the device); only for a
    // device vkcollide owns.
    VkResult waitIdle();
};

// A physical device's properties, what it supports and what it lacks (see context.hpp).
struct PhysicalDeviceReport {
    DeviceInfo info;                            // info.missing: every requirement it lacks
    FeatureSet supported;                       // empty below Vulkan 1.3 (not queried)
    std::optional<std::uint32_t> queue_family;  // first graphics+compute family with timestamps
    bool executable_properties = false;         // VK_KHR_pipeline_executable_properties listed
};
PhysicalDeviceReport describePhysicalDevice(const InstanceFunctions& fns, VkPhysicalDevice physical);

// Reads the limits and memory properties every subsystem uses; checks the queue family.
Result<void> finishDevice(Device& device);

// Copies what the engine lends (allocation callbacks, memory hooks); refuses half a pair.
// `what` names the struct in errors ("ContextCreateInfo").
Result<void> takeHostHooks(Device& device, const VkAllocationCallbacks* callbacks, const DeviceMemoryHooks& memory,
                           const char* what);

// Sets device.pipeline_cache: `borrowed` when given, else a new cache from `initial_data`
// (ignored, with an Info message, when its header names another device or driver).
Result<void> setUpPipelineCache(Device& device, VkPipelineCache borrowed, std::span<const std::byte> initial_data);
// Whether `data` starts with a VkPipelineCacheHeaderVersionOne matching this device.
bool pipelineCacheDataMatches(const Device& device, std::span<const std::byte> data) noexcept;

// True when `name` is in the list of extension names.
bool listsExtension(std::span<const char* const> names, const char* name) noexcept;

// How an error names a device that ends long shader loops silently
// (DeviceInfo::loop_iteration_limit): "<device> <does> in one shader invocation (it ends
// loops past N iterations without an error)".
std::string loopLimitPhrase(const Device& device, std::string_view does);

}  // namespace vkcollide::vk
