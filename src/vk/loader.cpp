#include "vk/loader.hpp"

#include <dlfcn.h>

namespace vkcollide::vk {

Result<std::shared_ptr<LoaderLibrary>> LoaderLibrary::open() {
    void* handle = dlopen("libvulkan.so.1", RTLD_NOW | RTLD_LOCAL);
    if (!handle) handle = dlopen("libvulkan.so", RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
        const char* why = dlerror();
        return Error(ErrorCode::LoaderUnavailable,
                     std::string("cannot open the Vulkan loader libvulkan.so.1: ") + (why ? why : "unknown reason") +
                         " (install libvulkan1)");
    }
    auto gipa = reinterpret_cast<PFN_vkGetInstanceProcAddr>(dlsym(handle, "vkGetInstanceProcAddr"));
    if (!gipa) {
        dlclose(handle);
        return Error(ErrorCode::LoaderUnavailable, "libvulkan.so.1 has no vkGetInstanceProcAddr");
    }
    return std::shared_ptr<LoaderLibrary>(new LoaderLibrary(handle, gipa));
}

LoaderLibrary::~LoaderLibrary() {
    if (handle_) dlclose(handle_);
}

Result<GlobalFunctions> loadGlobalFunctions(PFN_vkGetInstanceProcAddr gipa) {
    if (!gipa) return Error(ErrorCode::InvalidArgument, "vkGetInstanceProcAddr is null");
    GlobalFunctions fns;
    fns.vkGetInstanceProcAddr = gipa;
#define VKC_LOAD(name) fns.name = reinterpret_cast<PFN_##name>(gipa(VK_NULL_HANDLE, #name));
    VKC_GLOBAL_FUNCTIONS(VKC_LOAD)
#undef VKC_LOAD
    if (!fns.vkCreateInstance || !fns.vkEnumerateInstanceExtensionProperties || !fns.vkEnumerateInstanceLayerProperties)
        return Error(ErrorCode::LoaderUnavailable, "the Vulkan loader lacks vkCreateInstance or instance enumeration");
    return fns;
}

Result<InstanceFunctions> loadInstanceFunctions(PFN_vkGetInstanceProcAddr gipa, VkInstance instance) {
    InstanceFunctions fns;
#define VKC_LOAD(name)                                                                              \
    fns.name = reinterpret_cast<PFN_##name>(gipa(instance, #name));                                \
    if (!fns.name)                                                                                  \
        return Error(ErrorCode::LoaderUnavailable, "instance entry point " #name " is unavailable");
    VKC_INSTANCE_FUNCTIONS(VKC_LOAD)
#undef VKC_LOAD
    // Optional: only there when the instance enabled VK_EXT_debug_utils.
#define VKC_LOAD_OPTIONAL(name) fns.name = reinterpret_cast<PFN_##name>(gipa(instance, #name));
    VKC_DEBUG_FUNCTIONS(VKC_LOAD_OPTIONAL)
#undef VKC_LOAD_OPTIONAL
    return fns;
}

Result<DeviceFunctions> loadDeviceFunctions(const InstanceFunctions& instance_fns, VkDevice device, bool push_descriptor) {
    DeviceFunctions fns;
#define VKC_LOAD(name)                                                                                  \
    fns.name = reinterpret_cast<PFN_##name>(instance_fns.vkGetDeviceProcAddr(device, #name));           \
    if (!fns.name)                                                                                      \
        return Error(ErrorCode::UnsupportedFeature,                                                     \
                     "device entry point " #name " is unavailable (is the extension or Vulkan 1.3 core enabled?)");
    VKC_DEVICE_FUNCTIONS(VKC_LOAD)
    if (push_descriptor) {
        VKC_PUSH_DESCRIPTOR_FUNCTIONS(VKC_LOAD)
    }
#undef VKC_LOAD
    return fns;
}

const char* resultName(VkResult result) noexcept {
    switch (result) {
#define VKC_CASE(r) \
    case r:         \
        return #r;
        VKC_CASE(VK_SUCCESS)
        VKC_CASE(VK_NOT_READY)
        VKC_CASE(VK_TIMEOUT)
        VKC_CASE(VK_INCOMPLETE)
        VKC_CASE(VK_ERROR_OUT_OF_HOST_MEMORY)
        VKC_CASE(VK_ERROR_OUT_OF_DEVICE_MEMORY)
        VKC_CASE(VK_ERROR_INITIALIZATION_FAILED)
        VKC_CASE(VK_ERROR_DEVICE_LOST)
        VKC_CASE(VK_ERROR_MEMORY_MAP_FAILED)
        VKC_CASE(VK_ERROR_LAYER_NOT_PRESENT)
        VKC_CASE(VK_ERROR_EXTENSION_NOT_PRESENT)
        VKC_CASE(VK_ERROR_FEATURE_NOT_PRESENT)
        VKC_CASE(VK_ERROR_INCOMPATIBLE_DRIVER)
        VKC_CASE(VK_ERROR_TOO_MANY_OBJECTS)
        VKC_CASE(VK_ERROR_FORMAT_NOT_SUPPORTED)
        VKC_CASE(VK_ERROR_UNKNOWN)
#undef VKC_CASE
        default:
            return "VK_ERROR_(other)";
    }
}

Error vulkanError(VkResult result, const std::string& what) {
    ErrorCode code = ErrorCode::VulkanError;
    if (result == VK_ERROR_DEVICE_LOST) code = ErrorCode::DeviceLost;
    if (result == VK_ERROR_OUT_OF_HOST_MEMORY || result == VK_ERROR_OUT_OF_DEVICE_MEMORY) code = ErrorCode::OutOfMemory;
    return Error(code, what + " failed with " + resultName(result), static_cast<std::int32_t>(result));
}

}  // namespace vkcollide::vk
