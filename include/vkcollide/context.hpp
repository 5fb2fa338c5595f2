// vkcollide: the Context, a Vulkan device that vkcollide either creates or borrows.
//
// Two ways in:
//  * Context::create(): vkcollide opens libvulkan.so.1 at run time, creates its own
//    instance and device and owns them. It prefers a discrete GPU, then an integrated
//    one, then a virtual one, then a CPU driver (lavapipe). ContextCreateInfo::device_name
//    or the environment variable VKCOLLIDE_DEVICE picks one by (case-insensitive) name.
//  * Context::adopt(): an engine hands over its instance, physical device, device and a
//    queue plus its vkGetInstanceProcAddr. vkcollide borrows them and never destroys them.
//
// Required of a device (checked up front; the error names what is missing): Vulkan 1.3
// with dynamicRendering and synchronization2, bufferDeviceAddress, scalarBlockLayout,
// shaderInt64, shaderBufferInt64Atomics, fragmentStoresAndAtomics, VK_KHR_push_descriptor
// and timestamp queries on a graphics+compute queue.
//
// Thread safety: a Context and everything made from it is used from one thread at a time.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
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
};

// Everything an engine lends to adopt(). Every handle must outlive the Context; the queue
// is used only from the thread that uses the Context, so the engine must not submit to it
// concurrently. The device must have been created with the features listed above enabled.
struct AdoptedDevice {
    PFN_vkGetInstanceProcAddr get_instance_proc_addr = nullptr;
    VkInstance instance = VK_NULL_HANDLE;
    VkPhysicalDevice physical_device = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    std::uint32_t queue_family = 0;
    VkQueue queue = VK_NULL_HANDLE;
    // The Vulkan API version the engine created its instance with (>= 1.3).
    std::uint32_t api_version = VK_API_VERSION_1_3;
    // Optional: the engine enabled VK_EXT_conservative_rasterization on the device, so
    // DetectSettings::coverage may use it (ignored when the device lacks it).
    bool conservative_rasterization = false;
};

struct DeviceInfo {
    std::string name;
    VkPhysicalDeviceType type = VK_PHYSICAL_DEVICE_TYPE_OTHER;
    std::uint32_t api_version = 0;
    std::string driver;           // driverName and driverInfo
    double timestamp_period_ns = 1.0;
    std::uint32_t subgroup_size = 0;
    bool conservative_rasterization = false;  // VK_EXT_conservative_rasterization is available
    // Empty when the device meets every requirement; otherwise what it lacks.
    std::vector<std::string> missing;
};

const char* toString(VkPhysicalDeviceType type) noexcept;

class Context {
public:
    [[nodiscard]] static Result<std::unique_ptr<Context>> create(const ContextCreateInfo& info = {});
    [[nodiscard]] static Result<std::unique_ptr<Context>> adopt(const AdoptedDevice& device,
                                                                MessageCallback on_message = {});
    // Every physical device the loader reports, with what each one lacks.
    [[nodiscard]] static Result<std::vector<DeviceInfo>> listDevices();

    ~Context();
    Context(const Context&) = delete;
    Context& operator=(const Context&) = delete;

    const DeviceInfo& deviceInfo() const noexcept;
    bool ownsDevice() const noexcept;
    // Validation warnings and errors seen since creation (0 when validation is off).
    std::uint64_t validationMessageCount() const noexcept;

    // Internal access for vkcollide's own subsystems.
    vk::Device& device() noexcept { return *device_; }

private:
    explicit Context(std::unique_ptr<vk::Device> device);
    std::unique_ptr<vk::Device> device_;
};

}  // namespace vkcollide
