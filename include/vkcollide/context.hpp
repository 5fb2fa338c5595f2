// vkcollide: the Context, a Vulkan device that vkcollide either creates or borrows.
//
// Two ways in:
//  * Context::create(): vkcollide opens libvulkan.so.1 at run time (or uses the
//    vkGetInstanceProcAddr given in ContextCreateInfo), creates its own instance and device
//    and owns them. It prefers a discrete GPU, then an integrated one, then a virtual one,
//    then a CPU driver (lavapipe). ContextCreateInfo::device_name or the environment
//    variable VKCOLLIDE_DEVICE picks one by (case-insensitive) name.
//  * Context::adopt(): an engine hands over its instance, physical device, device and a
//    queue plus its vkGetInstanceProcAddr, and says which features and extensions it
//    enabled. vkcollide borrows them and never destroys them.
//
// ---- What vkcollide needs of a device (the one list; adopt() checks every item) -------
//
//  Version   Vulkan 1.3: the physical device's apiVersion, and the instance created with
//            VkApplicationInfo::apiVersion >= VK_API_VERSION_1_3 (AdoptedDevice::api_version).
//  Features  enabled at vkCreateDevice, in the VkPhysicalDeviceFeatures2 chain
//            (enableRequiredFeatures() below sets exactly these):
//              VkPhysicalDeviceFeatures:          shaderInt64, fragmentStoresAndAtomics
//              VkPhysicalDeviceVulkan12Features:  bufferDeviceAddress, scalarBlockLayout,
//                                                 shaderBufferInt64Atomics, hostQueryReset
//              VkPhysicalDeviceVulkan13Features:  dynamicRendering, synchronization2,
//                                                 maintenance4
//            The single-feature structs of the same names (VkPhysicalDeviceHostQueryReset-
//            Features, ...) count as well. Without hostQueryReset or maintenance4 the device
//            runs, but every detection breaks valid usage (query pools are reset from the
//            host: VUID-vkResetQueryPool-None-02665; the compute shaders use the LocalSizeId
//            execution mode: VUID-RuntimeSpirv-LocalSizeId-06434).
//  Queue     a family with GRAPHICS and COMPUTE and timestampValidBits > 0 (stage timings).
//  Extensions none required. Used where enabled:
//              VK_EXT_conservative_rasterization  DetectSettings::peeling.coverage = Conservative/Best
//              VK_KHR_push_descriptor             descriptor-based pipelines (only vkcollide's
//                                                 own tests have any; detection does not)
//              VK_EXT_robustness2                 robustBufferAccess2 (see Robustness)
//  Optional  shaderFloat64: double-precision GPU filters, where the device enables it.
//            timelineSemaphore: needed only for timeline semaphores in SubmitSync and for
//            EngineCommandBuffer; an engine that created a timeline semaphore has it on.
//            vkcollide's own device enables both where the device has them.
//  Robustness vkcollide's own device enables robustBufferAccess (and robustBufferAccess2
//            where VK_EXT_robustness2 is present) as a second line of defence; an adopted
//            device keeps what the engine chose. Note that no robustness feature covers
//            buffer-device-address accesses, and vkcollide reads meshes and most of its
//            working buffers through device addresses: the first line is that every pass
//            checks its own indices and capacities (docs/stability.md).
//
// ---- What vkcollide needs of an engine's buffers (CollisionWorld::addGpuMesh) ----------
//
//  Usage     created with VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT: vkcollide reads the
//            vertices and indices through buffer device addresses.
//  Memory    bound, before addGpuMesh, completely and contiguously to one VkDeviceMemory
//            allocated with VkMemoryAllocateFlagsInfo::flags containing
//            VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT (with VMA:
//            VMA_ALLOCATOR_CREATE_BUFFER_DEVICE_ADDRESS_BIT on the allocator).
//  Sharing   Ownership is per queue family. vkcollide reads engine buffers only on the
//            Context's queue family (AdoptedDevice::queue_family) and never transfers
//            ownership itself, so for a VK_SHARING_MODE_EXCLUSIVE buffer:
//              * written on a queue of the same family (any queue of it): nothing to do
//                beyond ordering (a semaphore in SubmitSync::wait, or submission order on
//                the same queue);
//              * written on a queue of another family (async compute, transfer): the
//                engine releases the buffer there (a buffer barrier with
//                srcQueueFamilyIndex = its family, dstQueueFamilyIndex = the Context's)
//                and acquires it on the Context's family (the matching barrier, in a
//                command buffer the engine submits to a queue of that family before the
//                detection, or records into its EngineCommandBuffer ahead of vkcollide's
//                commands), with a semaphore from the release to the acquire. To write it
//                on its own family again after the detection, the engine does the reverse
//                pair, after the detection's signal semaphore (or collect()).
//            A buffer created VK_SHARING_MODE_CONCURRENT with both families in
//            pQueueFamilyIndices needs no transfer. The validation layer does not see
//            device-address reads, so it cannot report a missing transfer: on most desktop
//            GPUs nothing visible goes wrong, on others the detection reads stale or
//            compressed data.
//  Checks    Vulkan has no query for a buffer's usage, memory flags or binding, so vkcollide
//            can check only what the engine declares (GpuMeshDesc) and bound each declared
//            size by vkGetBufferMemoryRequirements; the rest is the engine's promise, and a
//            broken one is undefined behaviour that the validation layer sees only in part
//            (it cannot follow device-address reads).
//
// ---- What an engine can lend besides the device (the engine keeps ownership) ------------
//
//  Queue      AdoptedDevice::queue_hooks: every vkQueueSubmit2 vkcollide makes on the
//             engine's queue goes through the engine's lock (and optionally its own submit
//             function). vkcollide makes no other queue call on an adopted device (no
//             vkQueueWaitIdle, no vkDeviceWaitIdle): it waits on its own fences.
//  Memory     DeviceMemoryHooks: every VkDeviceMemory range vkcollide binds comes from the
//             engine's allocator (default: one vkAllocateMemory per buffer or image).
//             Context::deviceMemoryInUse() counts all of it either way.
//  Host memory allocation_callbacks: passed to every Vulkan create/destroy/allocate/free
//             call vkcollide makes (for Context::create also to the instance and device).
//  Pipelines  every pipeline vkcollide creates goes through one VkPipelineCache: the
//             engine's (AdoptedDevice::pipeline_cache) or one the Context creates, filled
//             from pipeline_cache_data and read back by Context::pipelineCacheData().
//             The worlds of a Context share its pipelines, and the Context keeps each one
//             it has made until it is destroyed: a world created later, or a stage a world
//             turns on later (another method, proximity, device pairs), creates none.
//
// ---- Captures (RenderDoc, Nsight Graphics) ----------------------------------------------
//
// Where the instance has VK_EXT_debug_utils enabled (Context::create: wherever the loader
// offers it, ContextCreateInfo::debug_names; adopt(): where
// AdoptedDevice::enabled_instance_extensions lists it), every Vulkan object vkcollide
// creates is named "vkcollide: <what>" (a buffer by its role, "vkcollide: cells-survivors";
// a pipeline by its program), each pass in a command buffer is inside a label
// "vkcollide: <pass>", and each command buffer's work (or a record() into the engine's)
// inside one "vkcollide: detect". Without the extension vkcollide makes none of these calls.
//
// ---- Lifetime -------------------------------------------------------------------------
//
// A Context may be destroyed before the resources made from it: each of them keeps the
// device alive, and the device (with the instance, for Context::create) is destroyed with
// the last of them. Everything the engine lends (adopt()'s handles, the hooks, allocation
// callbacks, pipeline cache and on_message) must stay valid until then, not only until
// ~Context. Destroying the last of them waits for vkcollide's GPU work. A world holds the
// device too: every call of a world whose Context is gone works as before (detections,
// objects added, collect(), destruction).
//
// Thread safety: a Context itself is not changed after creation; the objects made from it
// (worlds) may be used from different threads, each object from one thread at a time.
// The Context serialises what they share: the queue (its own mutex, then the engine's
// QueueHooks), the DeviceMemoryHooks calls and the counters. on_message and
// allocation_callbacks can be called from any of those threads (and from driver threads).
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <vulkan/vulkan_core.h>

#include "vkcollide/export.hpp"
#include "vkcollide/result.hpp"

namespace vkcollide {

namespace vk {
struct Device;
}

enum class MessageSeverity { Info, Warning, Error };

// Receives validation-layer and library diagnostics. Called on the thread that made the
// Vulkan call that triggered the message.
using MessageCallback = std::function<void(MessageSeverity severity, std::string_view message)>;

// ---- Synchronisation with the engine's GPU work -----------------------------------------

// One semaphore operation of a detection's GPU work (CollisionWorld::submit). A wait keeps
// the detection from starting until the engine's work that writes its meshes is done (for
// instance a deformation on another queue); a signal tells the engine's later work (its
// next frame, a queue that consumes the results) that the detection has finished, without
// a CPU wait. Semaphores belong to the engine; vkcollide only names them in its submission.
struct SemaphoreSubmit {
    // Binary or timeline, created on the Context's device. Binary: Vulkan's rules hold (a
    // wait needs a signal already submitted; a signal needs the semaphore unsignalled).
    VkSemaphore semaphore = VK_NULL_HANDLE;
    // Timeline: wait until the counter is >= value, or set it to value (greater than its
    // current value and every value already pending). Binary: ignored.
    std::uint64_t value = 0;
    // Wait: the stages of vkcollide's work that wait (ALL_COMMANDS: all of it). Signal: the
    // stages that finish before the signal (ALL_COMMANDS: all of it). Never 0.
    VkPipelineStageFlags2 stages = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
};

// The waits and signals of one submission; the spans are read only during the call.
// A detection that takes several queue submissions waits in the first and signals in the
// last (Vulkan orders the rest: signals cover all earlier work on the queue, waits all
// later work).
struct SubmitSync {
    std::span<const SemaphoreSubmit> wait;
    std::span<const SemaphoreSubmit> signal;
};

// Records a detection's GPU work into the engine's command buffer instead of submitting it.
// The engine submits the command buffer to a queue of the Context's queue family (the
// buffers vkcollide reads and writes are EXCLUSIVE to it) in a batch that signals
// `timeline` to `value` or more; vkcollide learns that its work is done from that timeline
// (needs the timelineSemaphore feature, which every timeline semaphore implies).
// The command buffer: primary, in the recording state, outside a render pass; vkcollide
// binds its own pipelines and push constants there, so the engine re-binds its state
// afterwards. It must be submitted before anyone waits for the result (collect(), the
// world's destruction): those waits have no time limit, since freeing what the command
// buffer uses before it ran would be worse.
struct EngineCommandBuffer {
    VkCommandBuffer command_buffer = VK_NULL_HANDLE;
    VkSemaphore timeline = VK_NULL_HANDLE;
    std::uint64_t value = 0;
};

// ---- What an engine lends: queue access and memory ----------------------------------------

// How vkcollide reaches an adopted queue. The engine usually owns its queue on one thread;
// these let it keep that ownership. Called on the thread that called into vkcollide, always
// under the Context's own queue mutex (so never twice at once, even with several worlds).
// They must not call into vkcollide, and must not throw (an exception is caught and the
// submission fails with VulkanError).
struct QueueHooks {
    // Both or neither: lock() before each vkQueueSubmit2 vkcollide makes, unlock() after it.
    std::function<void()> lock;
    std::function<void()> unlock;
    // Optional: makes the submission in vkcollide's place (between lock and unlock when
    // both are set), e.g. through the engine's own submission path. The pointers are valid
    // only during the call; the batches must have been submitted to `queue`, unchanged,
    // before it returns (later work and vkcollide's fence wait depend on it). Returns the
    // VkResult of the submission.
    std::function<VkResult(VkQueue queue, std::span<const VkSubmitInfo2> submits, VkFence fence)> submit;
};

// One buffer's or image's memory, as vkcollide asks the engine's allocator for it.
struct DeviceMemoryRequest {
    // From vkGet*MemoryRequirements; alignment is already raised to nonCoherentAtomSize
    // and size rounded up to it where the memory type is host-visible but not coherent.
    VkMemoryRequirements requirements{};
    // The memory type vkcollide chose (a bit of requirements.memoryTypeBits): allocate
    // from exactly this one. `properties` are its flags.
    std::uint32_t memory_type = 0;
    VkMemoryPropertyFlags properties = 0;
    // Allocate with VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT (every buffer; with VMA, an
    // allocator created with VMA_ALLOCATOR_CREATE_BUFFER_DEVICE_ADDRESS_BIT).
    bool device_address = false;
    // An optimally tiled image (bufferImageGranularity applies), not a buffer.
    bool image = false;
    // vkcollide reads or writes the memory from the host (upload and readback buffers):
    // DeviceMemoryBlock::mapped is required. Only for host-visible types.
    bool host_access = false;
    // vkcollide's name for the resource (valid during the call), for the engine's tools.
    const char* name = "";
};

// What the engine's allocator hands back: a range of one VkDeviceMemory.
struct DeviceMemoryBlock {
    VkDeviceMemory memory = VK_NULL_HANDLE;
    VkDeviceSize offset = 0;  // a multiple of requirements.alignment; size bytes from here are vkcollide's
    void* mapped = nullptr;   // request.host_access: the host address of byte `offset` (persistently
                              // mapped by the engine: vkcollide never maps engine memory); else ignored
    std::uint64_t user = 0;   // the engine's own handle (e.g. its VmaAllocation), given back to free
};

// Routes vkcollide's device memory to the engine's allocator. Both or neither. Called one at
// a time (under a Context mutex), from whichever thread creates or destroys the resource.
struct DeviceMemoryHooks {
    // Returns VK_SUCCESS and fills out_block, or the VkResult of the failure (the resource's
    // creation then fails with it: VK_ERROR_OUT_OF_DEVICE_MEMORY gives OutOfMemory).
    std::function<VkResult(const DeviceMemoryRequest& request, DeviceMemoryBlock& out_block)> allocate;
    // Called once per successful allocate(), after the buffer or image bound to the block
    // is destroyed (so after the GPU work that used it has finished).
    std::function<void(const DeviceMemoryBlock& block)> free;
};

struct ContextCreateInfo {
    // Substring of the device name to use (case-insensitive). Empty: VKCOLLIDE_DEVICE if
    // set, else the preferred device type.
    std::string device_name;
    // Turn on VK_LAYER_KHRONOS_validation (with synchronization validation) and route its
    // messages to on_message. Creation fails if the layer is not installed.
    bool validation = false;
    // Default: warnings and errors are printed to stderr.
    MessageCallback on_message;
    // Enable robustBufferAccess (and robustBufferAccess2) where the device has them: a
    // second line of defence (see Robustness above). Off only to measure what it costs.
    bool robust_buffer_access = true;
    // Optional: the loader entry point to use instead of opening libvulkan.so.1 (an engine
    // that links or wraps the loader; a test's fake driver). Must stay callable for the
    // Context's lifetime.
    PFN_vkGetInstanceProcAddr get_instance_proc_addr = nullptr;
    // Optional: host allocation callbacks for every Vulkan object vkcollide creates (the
    // instance and device included). Copied; what they point to must outlive the device.
    const VkAllocationCallbacks* allocation_callbacks = nullptr;
    // Optional: where vkcollide's device memory comes from (see DeviceMemoryHooks).
    DeviceMemoryHooks memory_hooks;
    // Optional: what Context::pipelineCacheData() returned in an earlier run; read only
    // during create(). Data for another device or driver (its header says so) is ignored.
    std::span<const std::byte> pipeline_cache_data;
    // Name objects and label passes for capture tools (see Captures above): VK_EXT_debug_utils
    // is enabled on vkcollide's instance wherever the loader offers it (always with
    // validation, which needs it for its messages). false: no names or labels, and the
    // extension only where validation needs it.
    bool debug_names = true;
    // Keep every pipeline's compiler statistics (VK_KHR_pipeline_executable_properties:
    // registers, spills, shared memory, instructions: whatever the driver reports), read
    // with Context::pipelineStatistics(): for tuning the passes, where the driver offers
    // the extension (NVIDIA's does; lavapipe's does not: pipelineStatistics() then says so).
    // Pipelines take longer to create with it.
    bool pipeline_statistics = false;
};

// One pipeline's compiler statistics (ContextCreateInfo::pipeline_statistics): one entry
// per executable the driver made of it (a compute pipeline has one).
struct PipelineStatistic {
    std::string name;         // the driver's, e.g. "Register Count"
    std::string description;  // the driver's
    double value = 0;         // booleans as 0 / 1, integers exactly below 2^53
};
struct PipelineStatistics {
    std::string pipeline;    // vkcollide's name for the pass's program
    std::string executable;  // the driver's name for what it compiled (a stage)
    std::vector<PipelineStatistic> statistics;
};

// Everything an engine lends to adopt(). Every handle must outlive the Context and every
// world made from it (see Lifetime). The queue: vkcollide submits to it from the threads
// its worlds are used on, under the Context's mutex; unless queue_hooks lock it, the engine
// must not use the queue at the same time (Vulkan requires external synchronisation).
// The device must meet every requirement listed at the top of this file.
struct AdoptedDevice {
    PFN_vkGetInstanceProcAddr get_instance_proc_addr = nullptr;
    VkInstance instance = VK_NULL_HANDLE;
    VkPhysicalDevice physical_device = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    std::uint32_t queue_family = 0;
    VkQueue queue = VK_NULL_HANDLE;
    // The Vulkan API version the engine created its instance with (>= 1.3).
    std::uint32_t api_version = VK_API_VERSION_1_3;
    // Required: the features the engine enabled, as it passed them to vkCreateDevice: a
    // VkPhysicalDeviceFeatures2 whose pNext chain holds VkPhysicalDeviceVulkan11/12/13Features
    // and/or single-feature structs (others are skipped). An engine that used
    // VkDeviceCreateInfo::pEnabledFeatures copies them into VkPhysicalDeviceFeatures2::features.
    // Read only during adopt(), which refuses the device naming each missing feature.
    const VkPhysicalDeviceFeatures2* enabled_features = nullptr;
    // The device extensions the engine enabled (VkDeviceCreateInfo::ppEnabledExtensionNames);
    // read only during adopt(). None is required; the optional ones above are used where
    // listed (and where the physical device has them).
    std::span<const char* const> enabled_extensions;
    // The instance extensions the engine enabled (VkInstanceCreateInfo::ppEnabledExtensionNames);
    // read only during adopt(). None is required. VK_EXT_debug_utils listed: vkcollide names
    // its objects and labels its passes (see Captures above); not listed: it makes no
    // debug-utils call. Vulkan cannot tell vkcollide what an instance enabled, so only this
    // list counts.
    std::span<const char* const> enabled_instance_extensions;
    // Optional: the engine's lock around (or its own path for) vkcollide's submissions.
    QueueHooks queue_hooks;
    // Optional: as ContextCreateInfo's (the callbacks vkcollide's own objects are created
    // and destroyed with; the engine's objects are none of vkcollide's business).
    const VkAllocationCallbacks* allocation_callbacks = nullptr;
    DeviceMemoryHooks memory_hooks;
    // Optional: the engine's pipeline cache, used for every pipeline vkcollide creates
    // (borrowed, never destroyed). One created with
    // VK_PIPELINE_CACHE_CREATE_EXTERNALLY_SYNCHRONIZED_BIT must not be used by the engine
    // while vkcollide creates pipelines (a world's first detections with a method or stage).
    // VK_NULL_HANDLE: the Context creates its own, from pipeline_cache_data.
    VkPipelineCache pipeline_cache = VK_NULL_HANDLE;
    std::span<const std::byte> pipeline_cache_data;
};

// Sets, in the engine's structs, every feature vkcollide requires (leaves the others as
// they are). Chain them as usual: io_features.pNext -> io_v12 -> io_v13 -> VkDeviceCreateInfo.
VKCOLLIDE_API void enableRequiredFeatures(VkPhysicalDeviceFeatures2& io_features, VkPhysicalDeviceVulkan12Features& io_v12,
                            VkPhysicalDeviceVulkan13Features& io_v13) noexcept;

struct DeviceInfo {
    std::string name;
    VkPhysicalDeviceType type = VK_PHYSICAL_DEVICE_TYPE_OTHER;
    std::uint32_t api_version = 0;
    std::string driver;           // driverName and driverInfo
    double timestamp_period_ns = 1.0;
    std::uint32_t subgroup_size = 0;
    // Optional capabilities the physical device offers (see the list at the top).
    bool conservative_rasterization = false;  // VK_EXT_conservative_rasterization
    bool push_descriptor = false;             // VK_KHR_push_descriptor
    bool robustness2 = false;                 // VK_EXT_robustness2 with robustBufferAccess2
    bool shader_float64 = false;              // shaderFloat64
    bool timeline_semaphore = false;          // timelineSemaphore
    // Loop iterations one shader invocation runs before the driver ends its loops without an
    // error (0: no such limit known). llvmpipe (lavapipe): 65,535, all loops of an
    // invocation together. vkcollide's long loops count against it and fail by name there
    // (docs/reliable.md, "Huge cells"); Auto pair sorting stays on the host.
    std::uint32_t loop_iteration_limit = 0;
    // Empty when the device meets every requirement; otherwise what it lacks.
    std::vector<std::string> missing;
};

VKCOLLIDE_API const char* toString(VkPhysicalDeviceType type) noexcept;

class VKCOLLIDE_API Context {
public:
    // Errors: LoaderUnavailable (no libvulkan.so.1 or a required entry point),
    // NoSuitableDevice (no device meets the requirements, or none matches the name; the
    // message lists every device and what it lacks), UnsupportedFeature (validation asked
    // for but not installed), InvalidArgument (allocate without free or the reverse,
    // allocation callbacks without pfnAllocation, pfnReallocation and pfnFree),
    // VulkanError / OutOfMemory / DeviceLost (a Vulkan call failed; Error::vkResult()
    // holds its VkResult).
    [[nodiscard]] static Result<std::unique_ptr<Context>> create(const ContextCreateInfo& info = {});
    // Errors: InvalidArgument (a null handle or enabled_features, a queue family that does
    // not exist, only one of a lock/unlock or allocate/free pair, incomplete allocation
    // callbacks), UnsupportedFeature (each
    // missing requirement named: version, feature, queue capability), LoaderUnavailable
    // (an entry point the engine's loader lacks), VulkanError / OutOfMemory (creating the
    // pipeline cache).
    [[nodiscard]] static Result<std::unique_ptr<Context>> adopt(const AdoptedDevice& device,
                                                                MessageCallback on_message = {});
    // Every physical device the loader reports, with what each one lacks.
    // get_instance_proc_addr: as ContextCreateInfo's (null: open libvulkan.so.1).
    [[nodiscard]] static Result<std::vector<DeviceInfo>> listDevices(PFN_vkGetInstanceProcAddr get_instance_proc_addr = nullptr);

    ~Context();
    Context(const Context&) = delete;
    Context& operator=(const Context&) = delete;

    const DeviceInfo& deviceInfo() const noexcept;
    bool ownsDevice() const noexcept;
    // Validation warnings and errors seen since creation (0 when validation is off).
    std::uint64_t validationMessageCount() const noexcept;
    // Bytes of device memory vkcollide holds on this device now, over all its worlds
    // (every buffer and image it allocated; the engine's own buffers are not counted).
    // Through DeviceMemoryHooks or not, this is the one counter to trust: the bytes of every
    // VkMemoryRequirements::size vkcollide bound (rounded up as DeviceMemoryRequest says).
    std::uint64_t deviceMemoryInUse() const noexcept;
    // The contents of the pipeline cache every vkcollide pipeline goes through (the
    // engine's, for an adopted device given one), to save and pass back as
    // pipeline_cache_data next run. Errors: VulkanError / OutOfMemory.
    [[nodiscard]] Result<std::vector<std::byte>> pipelineCacheData() const;
    // The statistics of every pipeline created so far, in creation order (pipelines are
    // made when a world first records a pass that needs them). Errors: UnsupportedFeature
    // (ContextCreateInfo::pipeline_statistics was off, the device is adopted, or its driver
    // does not offer VK_KHR_pipeline_executable_properties: the message says which).
    [[nodiscard]] Result<std::vector<PipelineStatistics>> pipelineStatistics() const;

private:
    // vkcollide's own subsystems reach the device through ContextAccess
    // (src/api/context_access.hpp); a world holds a reference to keep it alive (Lifetime).
    friend struct ContextAccess;
    explicit Context(std::shared_ptr<vk::Device> device);
    std::shared_ptr<vk::Device> device_;
};

}  // namespace vkcollide
