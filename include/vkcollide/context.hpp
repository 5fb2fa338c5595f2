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
//              VK_EXT_conservative_rasterization  DetectSettings::coverage = Conservative/Best
//              VK_KHR_push_descriptor             descriptor-based pipelines (only vkcollide's
//                                                 own tests have any; detection does not)
//              VK_EXT_robustness2                 robustBufferAccess2 (see Robustness)
//  Optional  shaderFloat64: double-precision GPU filters, where the device enables it.
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
//  Sharing   VK_SHARING_MODE_EXCLUSIVE buffers must be owned by the Context's queue family
//            while a detection reads them (or be CONCURRENT across that family).
//  Checks    Vulkan has no query for a buffer's usage, memory flags or binding, so vkcollide
//            can check only what the engine declares (GpuMeshDesc) and bound each declared
//            size by vkGetBufferMemoryRequirements; the rest is the engine's promise, and a
//            broken one is undefined behaviour that the validation layer sees only in part
//            (it cannot follow device-address reads).
//
// Thread safety: a Context and everything made from it is used from one thread at a time.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <vulkan/vulkan_core.h>

#include "vkcollide/result.hpp"

namespace vkcollide {

namespace vk {
struct Device;
}

enum class MessageSeverity { Info, Warning, Error };

// Receives validation-layer and library diagnostics. Called on the thread that made the
// Vulkan call that triggered the message.
using MessageCallback = std::function<void(MessageSeverity severity, std::string_view message)>;

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
};

// Everything an engine lends to adopt(). Every handle must outlive the Context; the queue
// is used only from the thread that uses the Context, so the engine must not submit to it
// concurrently. The device must meet every requirement listed at the top of this file.
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
};

// Sets, in the engine's structs, every feature vkcollide requires (leaves the others as
// they are). Chain them as usual: io_features.pNext -> io_v12 -> io_v13 -> VkDeviceCreateInfo.
void enableRequiredFeatures(VkPhysicalDeviceFeatures2& io_features, VkPhysicalDeviceVulkan12Features& io_v12,
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
    // Empty when the device meets every requirement; otherwise what it lacks.
    std::vector<std::string> missing;
};

const char* toString(VkPhysicalDeviceType type) noexcept;

class Context {
public:
    // Errors: LoaderUnavailable (no libvulkan.so.1 or a required entry point),
    // NoSuitableDevice (no device meets the requirements, or none matches the name; the
    // message lists every device and what it lacks), UnsupportedFeature (validation asked
    // for but not installed), VulkanError / OutOfMemory / DeviceLost (a Vulkan call failed;
    // Error::vkResult() holds its VkResult).
    [[nodiscard]] static Result<std::unique_ptr<Context>> create(const ContextCreateInfo& info = {});
    // Errors: InvalidArgument (a null handle or enabled_features, a queue family that does
    // not exist), UnsupportedFeature (each missing requirement named: version, feature,
    // queue capability), LoaderUnavailable (an entry point the engine's loader lacks).
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
    std::uint64_t deviceMemoryInUse() const noexcept;

    // Internal access for vkcollide's own subsystems.
    vk::Device& device() noexcept { return *device_; }

private:
    explicit Context(std::unique_ptr<vk::Device> device);
    std::unique_ptr<vk::Device> device_;
};

}  // namespace vkcollide
