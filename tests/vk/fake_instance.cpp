// The fake driver's loader, instance, physical devices and logical device, and
// VK_EXT_debug_utils (fake_vulkan_internal.hpp).
#include "vk/fake_vulkan_internal.hpp"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <string>

namespace vkcollide::test::fake_driver {
namespace {

std::size_t physicalIndex(VkPhysicalDevice p) {
    return static_cast<std::size_t>(reinterpret_cast<char*>(p) - g_physical_objects);
}
const FakePhysicalDevice& physical(VkPhysicalDevice p) { return fake().physical_devices.at(physicalIndex(p)); }

// What vkEnumerate{Instance,Device}ExtensionProperties write: the count, or the names.
VkResult writeExtensions(const std::vector<std::string>& exts, std::uint32_t* count, VkExtensionProperties* out) {
    if (!out) {
        *count = static_cast<std::uint32_t>(exts.size());
        return VK_SUCCESS;
    }
    const std::uint32_t written = std::min(*count, static_cast<std::uint32_t>(exts.size()));
    for (std::uint32_t i = 0; i < written; ++i) {
        out[i] = VkExtensionProperties{};
        std::snprintf(out[i].extensionName, sizeof(out[i].extensionName), "%s", exts[i].c_str());
        out[i].specVersion = 1;
    }
    *count = written;
    return written < exts.size() ? VK_INCOMPLETE : VK_SUCCESS;
}

// ---- global -----------------------------------------------------------------

VKAPI_ATTR VkResult VKAPI_CALL createInstance(const VkInstanceCreateInfo* info, const VkAllocationCallbacks* callbacks, VkInstance* out) {
    if (fake().create_instance_result != VK_SUCCESS) return fake().create_instance_result;
    fake().enabled_instance_extensions.assign(info->ppEnabledExtensionNames,
                                              info->ppEnabledExtensionNames + info->enabledExtensionCount);
    ++fake().instances_alive;
    *out = reinterpret_cast<VkInstance>(&g_instance_object);
    created(&g_instance_object, callbacks);
    return VK_SUCCESS;
}

VKAPI_ATTR VkResult VKAPI_CALL enumerateInstanceExtensionProperties(const char*, std::uint32_t* count, VkExtensionProperties* out) {
    return writeExtensions(fake().instance_extensions, count, out);
}

VKAPI_ATTR VkResult VKAPI_CALL enumerateInstanceLayerProperties(std::uint32_t* count, VkLayerProperties* out) {
    const std::uint32_t n = fake().validation_layer_installed ? 1 : 0;
    if (!out) {
        *count = n;
        return VK_SUCCESS;
    }
    if (n && *count) {
        *out = VkLayerProperties{};
        std::strcpy(out->layerName, "VK_LAYER_KHRONOS_validation");
    }
    *count = std::min(*count, n);
    return VK_SUCCESS;
}

VKAPI_ATTR VkResult VKAPI_CALL enumerateInstanceVersion(std::uint32_t* out) {
    *out = fake().loader_version;
    return VK_SUCCESS;
}

// ---- instance -------------------------------------------------------------------

VKAPI_ATTR void VKAPI_CALL destroyInstance(VkInstance, const VkAllocationCallbacks* callbacks) {
    --fake().instances_alive;
    destroyed("vkDestroyInstance", &g_instance_object, callbacks);
}

VKAPI_ATTR VkResult VKAPI_CALL enumeratePhysicalDevices(VkInstance, std::uint32_t* count, VkPhysicalDevice* out) {
    const auto n = static_cast<std::uint32_t>(fake().physical_devices.size());
    if (!out) {
        *count = n;
        return VK_SUCCESS;
    }
    const std::uint32_t written = std::min(*count, n);
    for (std::uint32_t i = 0; i < written; ++i) out[i] = reinterpret_cast<VkPhysicalDevice>(&g_physical_objects[i]);
    *count = written;
    return written < n ? VK_INCOMPLETE : VK_SUCCESS;
}

void fillProperties(VkPhysicalDevice p, VkPhysicalDeviceProperties& out) {
    const FakePhysicalDevice& d = physical(p);
    out = VkPhysicalDeviceProperties{};
    out.apiVersion = d.api_version;
    out.deviceType = d.type;
    std::snprintf(out.deviceName, sizeof(out.deviceName), "%s", d.name.c_str());
    out.limits.timestampPeriod = 1.0f;
    out.limits.nonCoherentAtomSize = d.non_coherent_atom_size;
    out.limits.maxComputeWorkGroupCount[0] = out.limits.maxComputeWorkGroupCount[1] = out.limits.maxComputeWorkGroupCount[2] = 65535;
    // A desktop GPU's compute limits (Pipeline::createCompute checks shaders against them).
    out.limits.maxComputeSharedMemorySize = 49152;
    out.limits.maxComputeWorkGroupInvocations = 1024;
    out.limits.maxComputeWorkGroupSize[0] = out.limits.maxComputeWorkGroupSize[1] = 1024;
    out.limits.maxComputeWorkGroupSize[2] = 64;
    // The pipeline cache header (FakeVulkan::cacheHeader) repeats these.
    out.vendorID = 0x1234;
    out.deviceID = static_cast<std::uint32_t>(physicalIndex(p) + 1);
    std::memset(out.pipelineCacheUUID, 0x42, VK_UUID_SIZE);
    out.pipelineCacheUUID[0] = static_cast<std::uint8_t>(d.name.size());
}

VKAPI_ATTR void VKAPI_CALL getPhysicalDeviceProperties(VkPhysicalDevice p, VkPhysicalDeviceProperties* out) { fillProperties(p, *out); }

VKAPI_ATTR void VKAPI_CALL getPhysicalDeviceProperties2(VkPhysicalDevice p, VkPhysicalDeviceProperties2* out) {
    fillProperties(p, out->properties);
    for (auto* link = static_cast<VkBaseOutStructure*>(out->pNext); link; link = link->pNext) {
        switch (link->sType) {
            case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES: {
                auto& driver = *reinterpret_cast<VkPhysicalDeviceDriverProperties*>(link);
                std::snprintf(driver.driverName, sizeof(driver.driverName), "fake");
                std::snprintf(driver.driverInfo, sizeof(driver.driverInfo), "tests/vk/fake_vulkan.cpp");
                break;
            }
            case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES:
                reinterpret_cast<VkPhysicalDeviceSubgroupProperties*>(link)->subgroupSize = 32;
                break;
            case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_PROPERTIES:
                reinterpret_cast<VkPhysicalDeviceVulkan11Properties*>(link)->maxMemoryAllocationSize = VkDeviceSize(1) << 32;
                break;
            case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_PROPERTIES:
                reinterpret_cast<VkPhysicalDeviceVulkan13Properties*>(link)->maxBufferSize = VkDeviceSize(1) << 32;
                break;
            default: break;
        }
    }
}

VKAPI_ATTR void VKAPI_CALL getPhysicalDeviceFeatures2(VkPhysicalDevice p, VkPhysicalDeviceFeatures2* out) {
    const vk::FeatureSet& f = physical(p).features;
    using vk::Feature;
    const auto on = [&](Feature x) -> VkBool32 { return f.has(x) ? VK_TRUE : VK_FALSE; };
    out->features = VkPhysicalDeviceFeatures{};
    out->features.shaderInt64 = on(Feature::ShaderInt64);
    out->features.fragmentStoresAndAtomics = on(Feature::FragmentStoresAndAtomics);
    out->features.shaderFloat64 = on(Feature::ShaderFloat64);
    out->features.robustBufferAccess = on(Feature::RobustBufferAccess);
    for (auto* link = static_cast<VkBaseOutStructure*>(out->pNext); link; link = link->pNext) {
        if (link->sType == VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES) {
            auto& v12 = *reinterpret_cast<VkPhysicalDeviceVulkan12Features*>(link);
            v12.bufferDeviceAddress = on(Feature::BufferDeviceAddress);
            v12.scalarBlockLayout = on(Feature::ScalarBlockLayout);
            v12.shaderBufferInt64Atomics = on(Feature::ShaderBufferInt64Atomics);
            v12.hostQueryReset = on(Feature::HostQueryReset);
            v12.timelineSemaphore = on(Feature::TimelineSemaphore);
        } else if (link->sType == VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES) {
            auto& v13 = *reinterpret_cast<VkPhysicalDeviceVulkan13Features*>(link);
            v13.dynamicRendering = on(Feature::DynamicRendering);
            v13.synchronization2 = on(Feature::Synchronization2);
            v13.maintenance4 = on(Feature::Maintenance4);
        } else if (link->sType == VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ROBUSTNESS_2_FEATURES_EXT) {
            reinterpret_cast<VkPhysicalDeviceRobustness2FeaturesEXT*>(link)->robustBufferAccess2 = on(Feature::RobustBufferAccess2);
        }
    }
}

VKAPI_ATTR void VKAPI_CALL getPhysicalDeviceQueueFamilyProperties(VkPhysicalDevice p, std::uint32_t* count,
                                                                   VkQueueFamilyProperties* out) {
    const auto& families = physical(p).queue_families;
    if (!out) {
        *count = static_cast<std::uint32_t>(families.size());
        return;
    }
    *count = std::min(*count, static_cast<std::uint32_t>(families.size()));
    for (std::uint32_t i = 0; i < *count; ++i) out[i] = families[i];
}

VKAPI_ATTR void VKAPI_CALL getPhysicalDeviceMemoryProperties(VkPhysicalDevice p, VkPhysicalDeviceMemoryProperties* out) {
    *out = VkPhysicalDeviceMemoryProperties{};
    out->memoryHeapCount = 1;
    out->memoryHeaps[0] = {VkDeviceSize(1) << 32, VK_MEMORY_HEAP_DEVICE_LOCAL_BIT};
    out->memoryTypeCount = 1;
    out->memoryTypes[0].propertyFlags = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT | VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT |
                                        (physical(p).coherent_memory ? VK_MEMORY_PROPERTY_HOST_COHERENT_BIT : 0);
}

VKAPI_ATTR void VKAPI_CALL getPhysicalDeviceFormatProperties(VkPhysicalDevice, VkFormat, VkFormatProperties* out) {
    *out = VkFormatProperties{};
}

VKAPI_ATTR VkResult VKAPI_CALL enumerateDeviceExtensionProperties(VkPhysicalDevice p, const char*, std::uint32_t* count,
                                                                 VkExtensionProperties* out) {
    return writeExtensions(physical(p).extensions, count, out);
}

VKAPI_ATTR VkResult VKAPI_CALL createDevice(VkPhysicalDevice p, const VkDeviceCreateInfo* info, const VkAllocationCallbacks* callbacks,
                                            VkDevice* out) {
    if (fake().create_device_result != VK_SUCCESS) return fake().create_device_result;
    auto features = vk::readEnabledChain(static_cast<const VkPhysicalDeviceFeatures2*>(info->pNext));
    fake().device_features = features ? *features : vk::FeatureSet{};
    fake().device_extensions.assign(info->ppEnabledExtensionNames, info->ppEnabledExtensionNames + info->enabledExtensionCount);
    g_state->device_physical = physicalIndex(p);
    ++fake().devices_alive;
    *out = reinterpret_cast<VkDevice>(&g_device_object);
    created(&g_device_object, callbacks);
    return VK_SUCCESS;
}

VKAPI_ATTR VkResult VKAPI_CALL createDebugUtilsMessenger(VkInstance, const VkDebugUtilsMessengerCreateInfoEXT*,
                                                         const VkAllocationCallbacks* callbacks, VkDebugUtilsMessengerEXT* out) {
    *out = newHandle<VkDebugUtilsMessengerEXT>();
    created(key(id(*out)), callbacks);
    return VK_SUCCESS;
}
VKAPI_ATTR void VKAPI_CALL destroyDebugUtilsMessenger(VkInstance, VkDebugUtilsMessengerEXT m, const VkAllocationCallbacks* callbacks) {
    destroyed("vkDestroyDebugUtilsMessengerEXT", key(id(m)), callbacks);
}

// VK_EXT_debug_utils' names and labels: recorded, and counted in debug_utils_calls even
// where the instance did not enable the extension (a real loader gives no entry points then;
// the fake gives them, so that a call made anyway is seen, not a crash).
VKAPI_ATTR VkResult VKAPI_CALL setDebugUtilsObjectName(VkDevice, const VkDebugUtilsObjectNameInfoEXT* info) {
    ++fake().debug_utils_calls;
    fake().object_names[info->objectHandle] = info->pObjectName ? info->pObjectName : "";
    return VK_SUCCESS;
}
VKAPI_ATTR void VKAPI_CALL cmdBeginDebugUtilsLabel(VkCommandBuffer, const VkDebugUtilsLabelEXT* label) {
    ++fake().debug_utils_calls;
    fake().labels.push_back(std::string("begin ") + label->pLabelName);
}
VKAPI_ATTR void VKAPI_CALL cmdEndDebugUtilsLabel(VkCommandBuffer) {
    ++fake().debug_utils_calls;
    fake().labels.emplace_back("end");
}
VKAPI_ATTR void VKAPI_CALL cmdInsertDebugUtilsLabel(VkCommandBuffer, const VkDebugUtilsLabelEXT* label) {
    ++fake().debug_utils_calls;
    fake().labels.push_back(std::string("insert ") + label->pLabelName);
}

// ---- device -----------------------------------------------------------------------

VKAPI_ATTR void VKAPI_CALL destroyDevice(VkDevice, const VkAllocationCallbacks* callbacks) {
    --fake().devices_alive;
    destroyed("vkDestroyDevice", &g_device_object, callbacks);
}
VKAPI_ATTR void VKAPI_CALL getDeviceQueue(VkDevice, std::uint32_t, std::uint32_t, VkQueue* out) {
    *out = reinterpret_cast<VkQueue>(&g_queue_object);
}
VKAPI_ATTR VkResult VKAPI_CALL deviceWaitIdle(VkDevice) { return VK_SUCCESS; }

}  // namespace

EntryMap loaderEntries() {
    return {
        entry("vkCreateInstance", createInstance),
        entry("vkEnumerateInstanceExtensionProperties", enumerateInstanceExtensionProperties),
        entry("vkEnumerateInstanceLayerProperties", enumerateInstanceLayerProperties),
        entry("vkEnumerateInstanceVersion", enumerateInstanceVersion),
    };
}

EntryMap instanceEntries() {
    return {
        entry("vkDestroyInstance", destroyInstance),
        entry("vkEnumeratePhysicalDevices", enumeratePhysicalDevices),
        entry("vkGetPhysicalDeviceProperties", getPhysicalDeviceProperties),
        entry("vkGetPhysicalDeviceProperties2", getPhysicalDeviceProperties2),
        entry("vkGetPhysicalDeviceFeatures2", getPhysicalDeviceFeatures2),
        entry("vkGetPhysicalDeviceQueueFamilyProperties", getPhysicalDeviceQueueFamilyProperties),
        entry("vkGetPhysicalDeviceMemoryProperties", getPhysicalDeviceMemoryProperties),
        entry("vkGetPhysicalDeviceFormatProperties", getPhysicalDeviceFormatProperties),
        entry("vkEnumerateDeviceExtensionProperties", enumerateDeviceExtensionProperties),
        entry("vkCreateDevice", createDevice),
        entry("vkGetDeviceProcAddr", getDeviceProcAddr),
        entry("vkCreateDebugUtilsMessengerEXT", createDebugUtilsMessenger),
        entry("vkDestroyDebugUtilsMessengerEXT", destroyDebugUtilsMessenger),
        entry("vkSetDebugUtilsObjectNameEXT", setDebugUtilsObjectName),
        entry("vkCmdBeginDebugUtilsLabelEXT", cmdBeginDebugUtilsLabel),
        entry("vkCmdEndDebugUtilsLabelEXT", cmdEndDebugUtilsLabel),
        entry("vkCmdInsertDebugUtilsLabelEXT", cmdInsertDebugUtilsLabel),
    };
}

EntryMap deviceLifetimeEntries() {
    return {
        entry("vkDestroyDevice", destroyDevice),
        entry("vkGetDeviceQueue", getDeviceQueue),
        entry("vkDeviceWaitIdle", deviceWaitIdle),
    };
}

}  // namespace vkcollide::test::fake_driver

namespace vkcollide::test {

using namespace fake_driver;

vk::FeatureSet FakePhysicalDevice::allFeatures() {
    vk::FeatureSet all;
    for (std::size_t i = 0; i < vk::kFeatureCount; ++i) all.set(static_cast<vk::Feature>(i));
    return all;
}

std::vector<std::byte> FakeVulkan::cacheHeader(const FakePhysicalDevice& device) {
    // The same values fillProperties reports for that device.
    std::size_t index = 0;
    while (index < g_fake->physical_devices.size() && &g_fake->physical_devices[index] != &device) ++index;
    VkPipelineCacheHeaderVersionOne header{};
    header.headerSize = sizeof(header);
    header.headerVersion = VK_PIPELINE_CACHE_HEADER_VERSION_ONE;
    header.vendorID = 0x1234;
    header.deviceID = static_cast<std::uint32_t>(index + 1);
    std::memset(header.pipelineCacheUUID, 0x42, VK_UUID_SIZE);
    header.pipelineCacheUUID[0] = static_cast<std::uint8_t>(device.name.size());
    std::vector<std::byte> out(sizeof(header));
    std::memcpy(out.data(), &header, sizeof(header));
    return out;
}

}  // namespace vkcollide::test
