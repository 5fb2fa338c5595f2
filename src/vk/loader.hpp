// Opening the Vulkan loader and filling the dispatch tables.
#pragma once

#include <memory>
#include <string>

#include "vk/dispatch.hpp"
#include "vkcollide/result.hpp"

namespace vkcollide::vk {

// libvulkan.so.1 opened with dlopen; closed when the last owner goes.
class LoaderLibrary {
public:
    static Result<std::shared_ptr<LoaderLibrary>> open();
    ~LoaderLibrary();
    LoaderLibrary(const LoaderLibrary&) = delete;
    LoaderLibrary& operator=(const LoaderLibrary&) = delete;

    PFN_vkGetInstanceProcAddr getInstanceProcAddr() const noexcept { return get_instance_proc_addr_; }

private:
    LoaderLibrary(void* handle, PFN_vkGetInstanceProcAddr gipa) : handle_(handle), get_instance_proc_addr_(gipa) {}
    void* handle_;
    PFN_vkGetInstanceProcAddr get_instance_proc_addr_;
};

// Global entry points; vkEnumerateInstanceVersion may stay null (Vulkan 1.0 loader).
Result<GlobalFunctions> loadGlobalFunctions(PFN_vkGetInstanceProcAddr gipa);

// Instance entry points. The error names the first required entry point that is missing.
Result<InstanceFunctions> loadInstanceFunctions(PFN_vkGetInstanceProcAddr gipa, VkInstance instance);

// Device entry points through vkGetDeviceProcAddr, so calls skip the loader trampoline.
// push_descriptor: VK_KHR_push_descriptor is enabled, so its entry point is required too.
Result<DeviceFunctions> loadDeviceFunctions(const InstanceFunctions& instance_fns, VkDevice device, bool push_descriptor);

// "VK_ERROR_DEVICE_LOST" etc.
const char* resultName(VkResult result) noexcept;

// Maps a failed VkResult to an Error whose message says which call failed.
Error vulkanError(VkResult result, const std::string& what);

}  // namespace vkcollide::vk
