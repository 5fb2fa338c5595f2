#include "vk/fake_vulkan.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <memory>
#include <string_view>

namespace vkcollide::test {
namespace {

FakeVulkan* g_fake = nullptr;

// Dispatchable handles point at these; their addresses are all the fake needs.
char g_instance_object;
char g_physical_objects[8];
char g_device_object;
char g_queue_object;

struct FakeBuffer {
    VkDeviceSize size = 0;
};
struct FakeState {
    std::uint64_t next_handle = 1;
    std::map<std::uint64_t, FakeBuffer> buffers;
    std::map<std::uint64_t, std::unique_ptr<std::byte[]>> memory;
    std::size_t device_physical = 0;
};
FakeState* g_state = nullptr;

FakeVulkan& fake() {
    if (!g_fake) {
        std::fprintf(stderr, "fake Vulkan called outside a FakeVulkanScope\n");
        std::abort();
    }
    return *g_fake;
}

std::size_t physicalIndex(VkPhysicalDevice p) {
    return static_cast<std::size_t>(reinterpret_cast<char*>(p) - g_physical_objects);
}
const FakePhysicalDevice& physical(VkPhysicalDevice p) { return fake().physical_devices.at(physicalIndex(p)); }

template <typename Handle>
Handle newHandle() {
    return reinterpret_cast<Handle>(static_cast<std::uintptr_t>(g_state->next_handle++));
}
template <typename Handle>
std::uint64_t id(Handle h) {
    return static_cast<std::uint64_t>(reinterpret_cast<std::uintptr_t>(h));
}

[[noreturn]] VKAPI_ATTR void VKAPI_CALL trap() {
    std::fprintf(stderr, "fake Vulkan: an entry point the fake does not implement was called\n");
    std::abort();
}

// ---- global -----------------------------------------------------------------

VKAPI_ATTR VkResult VKAPI_CALL createInstance(const VkInstanceCreateInfo*, const VkAllocationCallbacks*, VkInstance* out) {
    if (fake().create_instance_result != VK_SUCCESS) return fake().create_instance_result;
    ++fake().instances_alive;
    *out = reinterpret_cast<VkInstance>(&g_instance_object);
    return VK_SUCCESS;
}

VKAPI_ATTR VkResult VKAPI_CALL enumerateInstanceExtensionProperties(const char*, std::uint32_t* count, VkExtensionProperties*) {
    *count = 0;
    return VK_SUCCESS;
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

VKAPI_ATTR void VKAPI_CALL destroyInstance(VkInstance, const VkAllocationCallbacks*) { --fake().instances_alive; }

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
    const auto& exts = physical(p).extensions;
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

VKAPI_ATTR VkResult VKAPI_CALL createDevice(VkPhysicalDevice p, const VkDeviceCreateInfo* info, const VkAllocationCallbacks*,
                                            VkDevice* out) {
    if (fake().create_device_result != VK_SUCCESS) return fake().create_device_result;
    auto features = vk::readEnabledChain(static_cast<const VkPhysicalDeviceFeatures2*>(info->pNext));
    fake().device_features = features ? *features : vk::FeatureSet{};
    fake().device_extensions.assign(info->ppEnabledExtensionNames, info->ppEnabledExtensionNames + info->enabledExtensionCount);
    g_state->device_physical = physicalIndex(p);
    ++fake().devices_alive;
    *out = reinterpret_cast<VkDevice>(&g_device_object);
    return VK_SUCCESS;
}

VKAPI_ATTR VkResult VKAPI_CALL createDebugUtilsMessenger(VkInstance, const VkDebugUtilsMessengerCreateInfoEXT*,
                                                         const VkAllocationCallbacks*, VkDebugUtilsMessengerEXT* out) {
    *out = newHandle<VkDebugUtilsMessengerEXT>();
    return VK_SUCCESS;
}
VKAPI_ATTR void VKAPI_CALL destroyDebugUtilsMessenger(VkInstance, VkDebugUtilsMessengerEXT, const VkAllocationCallbacks*) {}

// ---- device -----------------------------------------------------------------------

VKAPI_ATTR void VKAPI_CALL destroyDevice(VkDevice, const VkAllocationCallbacks*) { --fake().devices_alive; }
VKAPI_ATTR void VKAPI_CALL getDeviceQueue(VkDevice, std::uint32_t, std::uint32_t, VkQueue* out) {
    *out = reinterpret_cast<VkQueue>(&g_queue_object);
}
VKAPI_ATTR VkResult VKAPI_CALL deviceWaitIdle(VkDevice) { return VK_SUCCESS; }

VKAPI_ATTR VkResult VKAPI_CALL createBuffer(VkDevice, const VkBufferCreateInfo* info, const VkAllocationCallbacks*, VkBuffer* out) {
    *out = newHandle<VkBuffer>();
    g_state->buffers[id(*out)] = FakeBuffer{info->size};
    ++fake().buffers_alive;
    return VK_SUCCESS;
}
VKAPI_ATTR void VKAPI_CALL destroyBuffer(VkDevice, VkBuffer buffer, const VkAllocationCallbacks*) {
    if (buffer && g_state->buffers.erase(id(buffer))) --fake().buffers_alive;
}
VKAPI_ATTR void VKAPI_CALL getBufferMemoryRequirements(VkDevice, VkBuffer buffer, VkMemoryRequirements* out) {
    const VkDeviceSize size = g_state->buffers.at(id(buffer)).size;
    *out = VkMemoryRequirements{(size + 255) / 256 * 256, 256, 1u};
}
VKAPI_ATTR VkResult VKAPI_CALL allocateMemory(VkDevice, const VkMemoryAllocateInfo* info, const VkAllocationCallbacks*,
                                              VkDeviceMemory* out) {
    *out = newHandle<VkDeviceMemory>();
    g_state->memory[id(*out)] = std::make_unique<std::byte[]>(info->allocationSize);
    ++fake().allocations_alive;
    return VK_SUCCESS;
}
VKAPI_ATTR void VKAPI_CALL freeMemory(VkDevice, VkDeviceMemory memory, const VkAllocationCallbacks*) {
    if (memory && g_state->memory.erase(id(memory))) --fake().allocations_alive;
}
VKAPI_ATTR VkResult VKAPI_CALL bindBufferMemory(VkDevice, VkBuffer, VkDeviceMemory, VkDeviceSize) { return VK_SUCCESS; }
VKAPI_ATTR VkResult VKAPI_CALL mapMemory(VkDevice, VkDeviceMemory memory, VkDeviceSize offset, VkDeviceSize, VkMemoryMapFlags,
                                         void** out) {
    *out = g_state->memory.at(id(memory)).get() + offset;
    return VK_SUCCESS;
}
VKAPI_ATTR void VKAPI_CALL unmapMemory(VkDevice, VkDeviceMemory) {}
VKAPI_ATTR VkDeviceAddress VKAPI_CALL getBufferDeviceAddress(VkDevice, const VkBufferDeviceAddressInfo* info) {
    return id(info->buffer) << 20;
}
VKAPI_ATTR VkResult VKAPI_CALL flushMappedMemoryRanges(VkDevice, std::uint32_t count, const VkMappedMemoryRange* ranges) {
    fake().flushed.insert(fake().flushed.end(), ranges, ranges + count);
    return VK_SUCCESS;
}
VKAPI_ATTR VkResult VKAPI_CALL invalidateMappedMemoryRanges(VkDevice, std::uint32_t count, const VkMappedMemoryRange* ranges) {
    fake().invalidated.insert(fake().invalidated.end(), ranges, ranges + count);
    return VK_SUCCESS;
}

#define FAKE_ENTRY(name, fn) {name, reinterpret_cast<PFN_vkVoidFunction>(fn)}

const std::map<std::string_view, PFN_vkVoidFunction>& deviceEntries() {
    static const std::map<std::string_view, PFN_vkVoidFunction> entries = {
        FAKE_ENTRY("vkDestroyDevice", destroyDevice),
        FAKE_ENTRY("vkGetDeviceQueue", getDeviceQueue),
        FAKE_ENTRY("vkDeviceWaitIdle", deviceWaitIdle),
        FAKE_ENTRY("vkCreateBuffer", createBuffer),
        FAKE_ENTRY("vkDestroyBuffer", destroyBuffer),
        FAKE_ENTRY("vkGetBufferMemoryRequirements", getBufferMemoryRequirements),
        FAKE_ENTRY("vkAllocateMemory", allocateMemory),
        FAKE_ENTRY("vkFreeMemory", freeMemory),
        FAKE_ENTRY("vkBindBufferMemory", bindBufferMemory),
        FAKE_ENTRY("vkMapMemory", mapMemory),
        FAKE_ENTRY("vkUnmapMemory", unmapMemory),
        FAKE_ENTRY("vkGetBufferDeviceAddress", getBufferDeviceAddress),
        FAKE_ENTRY("vkFlushMappedMemoryRanges", flushMappedMemoryRanges),
        FAKE_ENTRY("vkInvalidateMappedMemoryRanges", invalidateMappedMemoryRanges),
    };
    return entries;
}

VKAPI_ATTR PFN_vkVoidFunction VKAPI_CALL getDeviceProcAddr(VkDevice, const char* name) {
    if (fake().missing_entry_points.count(name)) return nullptr;
    const auto& entries = deviceEntries();
    if (auto it = entries.find(name); it != entries.end()) return it->second;
    // Extension entry points exist only where the extension is enabled, as on a driver.
    if (std::string_view(name) == "vkCmdPushDescriptorSetKHR") {
        const auto& exts = fake().device_extensions;
        if (std::find(exts.begin(), exts.end(), VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME) == exts.end()) return nullptr;
    }
    return reinterpret_cast<PFN_vkVoidFunction>(trap);
}

VKAPI_ATTR PFN_vkVoidFunction VKAPI_CALL fakeGetInstanceProcAddr(VkInstance instance, const char* name) {
    if (fake().missing_entry_points.count(name)) return nullptr;
    static const std::map<std::string_view, PFN_vkVoidFunction> global = {
        FAKE_ENTRY("vkCreateInstance", createInstance),
        FAKE_ENTRY("vkEnumerateInstanceExtensionProperties", enumerateInstanceExtensionProperties),
        FAKE_ENTRY("vkEnumerateInstanceLayerProperties", enumerateInstanceLayerProperties),
        FAKE_ENTRY("vkEnumerateInstanceVersion", enumerateInstanceVersion),
    };
    static const std::map<std::string_view, PFN_vkVoidFunction> per_instance = {
        FAKE_ENTRY("vkDestroyInstance", destroyInstance),
        FAKE_ENTRY("vkEnumeratePhysicalDevices", enumeratePhysicalDevices),
        FAKE_ENTRY("vkGetPhysicalDeviceProperties", getPhysicalDeviceProperties),
        FAKE_ENTRY("vkGetPhysicalDeviceProperties2", getPhysicalDeviceProperties2),
        FAKE_ENTRY("vkGetPhysicalDeviceFeatures2", getPhysicalDeviceFeatures2),
        FAKE_ENTRY("vkGetPhysicalDeviceQueueFamilyProperties", getPhysicalDeviceQueueFamilyProperties),
        FAKE_ENTRY("vkGetPhysicalDeviceMemoryProperties", getPhysicalDeviceMemoryProperties),
        FAKE_ENTRY("vkGetPhysicalDeviceFormatProperties", getPhysicalDeviceFormatProperties),
        FAKE_ENTRY("vkEnumerateDeviceExtensionProperties", enumerateDeviceExtensionProperties),
        FAKE_ENTRY("vkCreateDevice", createDevice),
        FAKE_ENTRY("vkGetDeviceProcAddr", getDeviceProcAddr),
        FAKE_ENTRY("vkCreateDebugUtilsMessengerEXT", createDebugUtilsMessenger),
        FAKE_ENTRY("vkDestroyDebugUtilsMessengerEXT", destroyDebugUtilsMessenger),
    };
    if (std::string_view(name) == "vkGetInstanceProcAddr") return reinterpret_cast<PFN_vkVoidFunction>(fakeGetInstanceProcAddr);
    if (auto it = global.find(name); it != global.end()) return it->second;
    if (!instance) return nullptr;
    if (auto it = per_instance.find(name); it != per_instance.end()) return it->second;
    return getDeviceProcAddr(VK_NULL_HANDLE, name);
}

#undef FAKE_ENTRY

}  // namespace

vk::FeatureSet FakePhysicalDevice::allFeatures() {
    vk::FeatureSet all;
    for (std::size_t i = 0; i < vk::kFeatureCount; ++i) all.set(static_cast<vk::Feature>(i));
    return all;
}

VkInstance FakeVulkan::instanceHandle() const { return reinterpret_cast<VkInstance>(&g_instance_object); }
VkPhysicalDevice FakeVulkan::physicalHandle(std::size_t index) const {
    return reinterpret_cast<VkPhysicalDevice>(&g_physical_objects[index]);
}
VkDevice FakeVulkan::deviceHandle() const { return reinterpret_cast<VkDevice>(&g_device_object); }
VkQueue FakeVulkan::queueHandle() const { return reinterpret_cast<VkQueue>(&g_queue_object); }
PFN_vkGetInstanceProcAddr FakeVulkan::getInstanceProcAddr() { return &fakeGetInstanceProcAddr; }

FakeVulkanScope::FakeVulkanScope() {
    g_fake = new FakeVulkan();
    g_state = new FakeState();
}
FakeVulkanScope::~FakeVulkanScope() {
    delete g_state;
    delete g_fake;
    g_state = nullptr;
    g_fake = nullptr;
}
FakeVulkan& FakeVulkanScope::fake() { return *g_fake; }

}  // namespace vkcollide::test
