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
struct FakeSemaphore {
    bool timeline = false;
    std::uint64_t value = 0;  // timeline counter; binary: 1 when signalled
};
struct PendingSubmit {
    FakeVulkan::Submit submit;
    bool released = false;  // finishPending() let it finish (or the GPU finishes at once)
};
struct HostAllocation {
    VkAllocationCallbacks callbacks;
    void* memory;
};
struct FakeState {
    std::uint64_t next_handle = 1;
    std::map<std::uint64_t, FakeBuffer> buffers;
    std::map<std::uint64_t, VkDeviceSize> images;  // bytes
    std::map<std::uint64_t, std::unique_ptr<std::byte[]>> memory;
    std::map<std::uint64_t, bool> fences;  // signalled?
    std::map<std::uint64_t, FakeSemaphore> semaphores;
    std::vector<PendingSubmit> pending;
    std::map<const void*, HostAllocation> host_allocations;  // objects created with callbacks
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

// ---- allocation callbacks: one host allocation per object created with them ----------

const void* key(std::uint64_t handle) { return reinterpret_cast<const void*>(static_cast<std::uintptr_t>(handle)); }

void created(const void* object, const VkAllocationCallbacks* callbacks) {
    if (!callbacks) return;
    void* memory = callbacks->pfnAllocation(callbacks->pUserData, 64, 8, VK_SYSTEM_ALLOCATION_SCOPE_OBJECT);
    g_state->host_allocations[object] = {*callbacks, memory};
}

void destroyed(const char* what, const void* object, const VkAllocationCallbacks* callbacks) {
    auto it = g_state->host_allocations.find(object);
    const bool with = it != g_state->host_allocations.end();
    if (with != (callbacks != nullptr))
        fake().allocator_mismatches.push_back(std::string(what) + (with ? ": created with allocation callbacks, destroyed without"
                                                                         : ": created without allocation callbacks, destroyed with"));
    else if (with && (callbacks->pfnFree != it->second.callbacks.pfnFree || callbacks->pUserData != it->second.callbacks.pUserData))
        fake().allocator_mismatches.push_back(std::string(what) + ": destroyed with other allocation callbacks");
    if (with) {
        it->second.callbacks.pfnFree(it->second.callbacks.pUserData, it->second.memory);
        g_state->host_allocations.erase(it);
    }
}

// Every object the device layer creates, for the tests of its names.
void made(VkObjectType type, std::uint64_t handle) { fake().created_objects.push_back({type, handle}); }

// ---- the "GPU": batches finish in submission order once released and their waits hold ---

bool waitsHold(const FakeVulkan::Submit& s) {
    for (const VkSemaphoreSubmitInfo& w : s.waits) {
        const FakeSemaphore& sem = g_state->semaphores.at(id(w.semaphore));
        if (sem.timeline ? sem.value < w.value : sem.value == 0) return false;
    }
    return true;
}

void progress() {
    auto& pending = g_state->pending;
    while (!pending.empty()) {
        PendingSubmit& p = pending.front();
        if (!(p.released || fake().gpu_finishes_at_once) || !waitsHold(p.submit)) return;
        for (const VkSemaphoreSubmitInfo& w : p.submit.waits) {
            FakeSemaphore& sem = g_state->semaphores.at(id(w.semaphore));
            if (!sem.timeline) sem.value = 0;  // a binary wait unsignals
        }
        for (const VkSemaphoreSubmitInfo& sig : p.submit.signals) {
            FakeSemaphore& sem = g_state->semaphores.at(id(sig.semaphore));
            sem.value = sem.timeline ? std::max(sem.value, sig.value) : 1;
        }
        if (p.submit.fence) g_state->fences[id(p.submit.fence)] = true;
        pending.erase(pending.begin());
    }
}

// An unbounded wait on work the test has not released: the real GPU would finish it some
// time; the fake finishes everything now (so reset() paths can be observed, not hang).
void finishForUnboundedWait(std::uint64_t timeout) {
    if (timeout != UINT64_MAX) return;
    ++fake().unbounded_waits;
    fake().finishPending();
}

[[noreturn]] VKAPI_ATTR void VKAPI_CALL trap() {
    std::fprintf(stderr, "fake Vulkan: an entry point the fake does not implement was called\n");
    std::abort();
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
    const auto& exts = fake().instance_extensions;
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

VKAPI_ATTR VkResult VKAPI_CALL createBuffer(VkDevice, const VkBufferCreateInfo* info, const VkAllocationCallbacks* callbacks, VkBuffer* out) {
    *out = newHandle<VkBuffer>();
    g_state->buffers[id(*out)] = FakeBuffer{info->size};
    ++fake().buffers_alive;
    made(VK_OBJECT_TYPE_BUFFER, id(*out));
    created(key(id(*out)), callbacks);
    return VK_SUCCESS;
}
VKAPI_ATTR void VKAPI_CALL destroyBuffer(VkDevice, VkBuffer buffer, const VkAllocationCallbacks* callbacks) {
    if (buffer && g_state->buffers.erase(id(buffer))) {
        --fake().buffers_alive;
        destroyed("vkDestroyBuffer", key(id(buffer)), callbacks);
    }
}
VKAPI_ATTR void VKAPI_CALL getBufferMemoryRequirements(VkDevice, VkBuffer buffer, VkMemoryRequirements* out) {
    const VkDeviceSize size = g_state->buffers.at(id(buffer)).size;
    *out = VkMemoryRequirements{(size + 255) / 256 * 256, 256, 1u};
}
VKAPI_ATTR VkResult VKAPI_CALL allocateMemory(VkDevice, const VkMemoryAllocateInfo* info, const VkAllocationCallbacks* callbacks,
                                              VkDeviceMemory* out) {
    *out = newHandle<VkDeviceMemory>();
    g_state->memory[id(*out)] = std::make_unique<std::byte[]>(info->allocationSize);
    ++fake().allocations_alive;
    made(VK_OBJECT_TYPE_DEVICE_MEMORY, id(*out));
    created(key(id(*out)), callbacks);
    return VK_SUCCESS;
}
VKAPI_ATTR void VKAPI_CALL freeMemory(VkDevice, VkDeviceMemory memory, const VkAllocationCallbacks* callbacks) {
    if (memory && g_state->memory.erase(id(memory))) {
        --fake().allocations_alive;
        destroyed("vkFreeMemory", key(id(memory)), callbacks);
    }
}
VKAPI_ATTR VkResult VKAPI_CALL bindBufferMemory(VkDevice, VkBuffer, VkDeviceMemory, VkDeviceSize offset) {
    fake().bind_offsets.push_back(offset);
    return VK_SUCCESS;
}
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

// ---- images -------------------------------------------------------------------------

VKAPI_ATTR VkResult VKAPI_CALL createImage(VkDevice, const VkImageCreateInfo* info, const VkAllocationCallbacks* callbacks, VkImage* out) {
    *out = newHandle<VkImage>();
    g_state->images[id(*out)] = VkDeviceSize(info->extent.width) * info->extent.height * 4 * 2;
    ++fake().images_alive;
    made(VK_OBJECT_TYPE_IMAGE, id(*out));
    created(key(id(*out)), callbacks);
    return VK_SUCCESS;
}
VKAPI_ATTR void VKAPI_CALL destroyImage(VkDevice, VkImage image, const VkAllocationCallbacks* callbacks) {
    if (image && g_state->images.erase(id(image))) {
        --fake().images_alive;
        destroyed("vkDestroyImage", key(id(image)), callbacks);
    }
}
VKAPI_ATTR void VKAPI_CALL getImageMemoryRequirements(VkDevice, VkImage image, VkMemoryRequirements* out) {
    *out = VkMemoryRequirements{(g_state->images.at(id(image)) + 1023) / 1024 * 1024, 1024, 1u};
}
VKAPI_ATTR VkResult VKAPI_CALL bindImageMemory(VkDevice, VkImage, VkDeviceMemory, VkDeviceSize offset) {
    fake().bind_offsets.push_back(offset);
    return VK_SUCCESS;
}
VKAPI_ATTR VkResult VKAPI_CALL createImageView(VkDevice, const VkImageViewCreateInfo*, const VkAllocationCallbacks* callbacks,
                                               VkImageView* out) {
    *out = newHandle<VkImageView>();
    ++fake().image_views_alive;
    made(VK_OBJECT_TYPE_IMAGE_VIEW, id(*out));
    created(key(id(*out)), callbacks);
    return VK_SUCCESS;
}
VKAPI_ATTR void VKAPI_CALL destroyImageView(VkDevice, VkImageView view, const VkAllocationCallbacks* callbacks) {
    if (!view) return;
    --fake().image_views_alive;
    destroyed("vkDestroyImageView", key(id(view)), callbacks);
}

// ---- pipelines and their cache -------------------------------------------------------

VKAPI_ATTR VkResult VKAPI_CALL createPipelineCache(VkDevice, const VkPipelineCacheCreateInfo* info, const VkAllocationCallbacks* callbacks,
                                                   VkPipelineCache* out) {
    *out = newHandle<VkPipelineCache>();
    fake().last_pipeline_cache_initial_size = info->initialDataSize;
    ++fake().pipeline_caches_alive;
    made(VK_OBJECT_TYPE_PIPELINE_CACHE, id(*out));
    created(key(id(*out)), callbacks);
    return VK_SUCCESS;
}
VKAPI_ATTR void VKAPI_CALL destroyPipelineCache(VkDevice, VkPipelineCache cache, const VkAllocationCallbacks* callbacks) {
    if (!cache) return;
    --fake().pipeline_caches_alive;
    destroyed("vkDestroyPipelineCache", key(id(cache)), callbacks);
}
VKAPI_ATTR VkResult VKAPI_CALL getPipelineCacheData(VkDevice, VkPipelineCache, std::size_t* size, void* data) {
    // The header, then one byte per pipeline created so far (a cache that fills up).
    std::vector<std::byte> all = FakeVulkan::cacheHeader(fake().physical_devices.at(g_state->device_physical));
    all.resize(all.size() + fake().pipelines_cache_used.size(), std::byte{7});
    if (!data) {
        *size = all.size();
        return VK_SUCCESS;
    }
    const std::size_t n = std::min(*size, all.size());
    std::memcpy(data, all.data(), n);
    *size = n;
    return n < all.size() ? VK_INCOMPLETE : VK_SUCCESS;
}
VKAPI_ATTR VkResult VKAPI_CALL createShaderModule(VkDevice, const VkShaderModuleCreateInfo*, const VkAllocationCallbacks* callbacks,
                                                  VkShaderModule* out) {
    *out = newHandle<VkShaderModule>();
    ++fake().shader_modules_alive;
    made(VK_OBJECT_TYPE_SHADER_MODULE, id(*out));
    created(key(id(*out)), callbacks);
    return VK_SUCCESS;
}
VKAPI_ATTR void VKAPI_CALL destroyShaderModule(VkDevice, VkShaderModule module, const VkAllocationCallbacks* callbacks) {
    if (!module) return;
    --fake().shader_modules_alive;
    destroyed("vkDestroyShaderModule", key(id(module)), callbacks);
}
VKAPI_ATTR VkResult VKAPI_CALL createPipelineLayout(VkDevice, const VkPipelineLayoutCreateInfo*, const VkAllocationCallbacks* callbacks,
                                                    VkPipelineLayout* out) {
    *out = newHandle<VkPipelineLayout>();
    ++fake().pipeline_layouts_alive;
    made(VK_OBJECT_TYPE_PIPELINE_LAYOUT, id(*out));
    created(key(id(*out)), callbacks);
    return VK_SUCCESS;
}
VKAPI_ATTR void VKAPI_CALL destroyPipelineLayout(VkDevice, VkPipelineLayout layout, const VkAllocationCallbacks* callbacks) {
    if (!layout) return;
    --fake().pipeline_layouts_alive;
    destroyed("vkDestroyPipelineLayout", key(id(layout)), callbacks);
}
VKAPI_ATTR VkResult VKAPI_CALL createComputePipelines(VkDevice, VkPipelineCache cache, std::uint32_t count,
                                                      const VkComputePipelineCreateInfo*, const VkAllocationCallbacks* callbacks,
                                                      VkPipeline* out) {
    for (std::uint32_t i = 0; i < count; ++i) {
        out[i] = newHandle<VkPipeline>();
        fake().pipelines_cache_used.push_back(cache);
        made(VK_OBJECT_TYPE_PIPELINE, id(out[i]));
        ++fake().pipelines_alive;
        created(key(id(out[i])), callbacks);
    }
    return VK_SUCCESS;
}
VKAPI_ATTR void VKAPI_CALL destroyPipeline(VkDevice, VkPipeline pipeline, const VkAllocationCallbacks* callbacks) {
    if (!pipeline) return;
    --fake().pipelines_alive;
    destroyed("vkDestroyPipeline", key(id(pipeline)), callbacks);
}

// ---- commands, fences, semaphores, the queue -------------------------------------------

VKAPI_ATTR VkResult VKAPI_CALL createCommandPool(VkDevice, const VkCommandPoolCreateInfo*, const VkAllocationCallbacks* callbacks,
                                                 VkCommandPool* out) {
    *out = newHandle<VkCommandPool>();
    ++fake().command_pools_alive;
    made(VK_OBJECT_TYPE_COMMAND_POOL, id(*out));
    created(key(id(*out)), callbacks);
    return VK_SUCCESS;
}
VKAPI_ATTR void VKAPI_CALL destroyCommandPool(VkDevice, VkCommandPool pool, const VkAllocationCallbacks* callbacks) {
    if (!pool) return;
    --fake().command_pools_alive;
    destroyed("vkDestroyCommandPool", key(id(pool)), callbacks);
}
VKAPI_ATTR VkResult VKAPI_CALL resetCommandPool(VkDevice, VkCommandPool, VkCommandPoolResetFlags) { return VK_SUCCESS; }
VKAPI_ATTR VkResult VKAPI_CALL allocateCommandBuffers(VkDevice, const VkCommandBufferAllocateInfo* info, VkCommandBuffer* out) {
    for (std::uint32_t i = 0; i < info->commandBufferCount; ++i) {
        out[i] = newHandle<VkCommandBuffer>();
        made(VK_OBJECT_TYPE_COMMAND_BUFFER, id(out[i]));
    }
    return VK_SUCCESS;
}
VKAPI_ATTR VkResult VKAPI_CALL beginCommandBuffer(VkCommandBuffer, const VkCommandBufferBeginInfo*) { return VK_SUCCESS; }
VKAPI_ATTR VkResult VKAPI_CALL endCommandBuffer(VkCommandBuffer) { return VK_SUCCESS; }
VKAPI_ATTR void VKAPI_CALL cmdFillBuffer(VkCommandBuffer, VkBuffer, VkDeviceSize, VkDeviceSize, std::uint32_t) {}

VKAPI_ATTR VkResult VKAPI_CALL createFence(VkDevice, const VkFenceCreateInfo* info, const VkAllocationCallbacks* callbacks, VkFence* out) {
    *out = newHandle<VkFence>();
    g_state->fences[id(*out)] = (info->flags & VK_FENCE_CREATE_SIGNALED_BIT) != 0;
    ++fake().fences_alive;
    made(VK_OBJECT_TYPE_FENCE, id(*out));
    created(key(id(*out)), callbacks);
    return VK_SUCCESS;
}
VKAPI_ATTR void VKAPI_CALL destroyFence(VkDevice, VkFence fence, const VkAllocationCallbacks* callbacks) {
    if (fence && g_state->fences.erase(id(fence))) {
        --fake().fences_alive;
        destroyed("vkDestroyFence", key(id(fence)), callbacks);
    }
}
VKAPI_ATTR VkResult VKAPI_CALL resetFences(VkDevice, std::uint32_t count, const VkFence* fences) {
    for (std::uint32_t i = 0; i < count; ++i) g_state->fences.at(id(fences[i])) = false;
    return VK_SUCCESS;
}
VKAPI_ATTR VkResult VKAPI_CALL getFenceStatus(VkDevice, VkFence fence) {
    if (fake().device_status != VK_SUCCESS) return fake().device_status;
    return g_state->fences.at(id(fence)) ? VK_SUCCESS : VK_NOT_READY;
}
VKAPI_ATTR VkResult VKAPI_CALL waitForFences(VkDevice, std::uint32_t count, const VkFence* fences, VkBool32, std::uint64_t timeout) {
    if (fake().device_status != VK_SUCCESS) return fake().device_status;
    finishForUnboundedWait(timeout);
    for (std::uint32_t i = 0; i < count; ++i)
        if (!g_state->fences.at(id(fences[i]))) return VK_TIMEOUT;
    return VK_SUCCESS;
}

VKAPI_ATTR VkResult VKAPI_CALL createSemaphore(VkDevice, const VkSemaphoreCreateInfo* info, const VkAllocationCallbacks* callbacks,
                                               VkSemaphore* out) {
    FakeSemaphore sem;
    for (auto* link = static_cast<const VkBaseInStructure*>(info->pNext); link; link = link->pNext)
        if (link->sType == VK_STRUCTURE_TYPE_SEMAPHORE_TYPE_CREATE_INFO) {
            const auto& type = *reinterpret_cast<const VkSemaphoreTypeCreateInfo*>(link);
            sem.timeline = type.semaphoreType == VK_SEMAPHORE_TYPE_TIMELINE;
            sem.value = sem.timeline ? type.initialValue : 0;
        }
    *out = newHandle<VkSemaphore>();
    g_state->semaphores[id(*out)] = sem;
    ++fake().semaphores_alive;
    made(VK_OBJECT_TYPE_SEMAPHORE, id(*out));
    created(key(id(*out)), callbacks);
    return VK_SUCCESS;
}
VKAPI_ATTR void VKAPI_CALL destroySemaphore(VkDevice, VkSemaphore semaphore, const VkAllocationCallbacks* callbacks) {
    if (semaphore && g_state->semaphores.erase(id(semaphore))) {
        --fake().semaphores_alive;
        destroyed("vkDestroySemaphore", key(id(semaphore)), callbacks);
    }
}
VKAPI_ATTR VkResult VKAPI_CALL getSemaphoreCounterValue(VkDevice, VkSemaphore semaphore, std::uint64_t* out) {
    if (fake().device_status != VK_SUCCESS) return fake().device_status;
    *out = g_state->semaphores.at(id(semaphore)).value;
    return VK_SUCCESS;
}
VKAPI_ATTR VkResult VKAPI_CALL signalSemaphore(VkDevice, const VkSemaphoreSignalInfo* info) {
    FakeSemaphore& sem = g_state->semaphores.at(id(info->semaphore));
    sem.value = std::max(sem.value, info->value);
    progress();
    return VK_SUCCESS;
}
VKAPI_ATTR VkResult VKAPI_CALL waitSemaphores(VkDevice, const VkSemaphoreWaitInfo* info, std::uint64_t timeout) {
    if (fake().device_status != VK_SUCCESS) return fake().device_status;
    finishForUnboundedWait(timeout);
    for (std::uint32_t i = 0; i < info->semaphoreCount; ++i)
        if (g_state->semaphores.at(id(info->pSemaphores[i])).value < info->pValues[i]) return VK_TIMEOUT;
    return VK_SUCCESS;
}

VKAPI_ATTR VkResult VKAPI_CALL queueSubmit2(VkQueue, std::uint32_t count, const VkSubmitInfo2* submits, VkFence fence) {
    if (fake().submit_result != VK_SUCCESS) return fake().submit_result;
    for (std::uint32_t i = 0; i < count; ++i) {
        FakeVulkan::Submit s;
        s.waits.assign(submits[i].pWaitSemaphoreInfos, submits[i].pWaitSemaphoreInfos + submits[i].waitSemaphoreInfoCount);
        s.signals.assign(submits[i].pSignalSemaphoreInfos, submits[i].pSignalSemaphoreInfos + submits[i].signalSemaphoreInfoCount);
        s.fence = i + 1 == count ? fence : VK_NULL_HANDLE;
        fake().submits.push_back(s);
        g_state->pending.push_back({s, false});
    }
    progress();
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
        FAKE_ENTRY("vkCreateImage", createImage),
        FAKE_ENTRY("vkDestroyImage", destroyImage),
        FAKE_ENTRY("vkGetImageMemoryRequirements", getImageMemoryRequirements),
        FAKE_ENTRY("vkBindImageMemory", bindImageMemory),
        FAKE_ENTRY("vkCreateImageView", createImageView),
        FAKE_ENTRY("vkDestroyImageView", destroyImageView),
        FAKE_ENTRY("vkCreatePipelineCache", createPipelineCache),
        FAKE_ENTRY("vkDestroyPipelineCache", destroyPipelineCache),
        FAKE_ENTRY("vkGetPipelineCacheData", getPipelineCacheData),
        FAKE_ENTRY("vkCreateShaderModule", createShaderModule),
        FAKE_ENTRY("vkDestroyShaderModule", destroyShaderModule),
        FAKE_ENTRY("vkCreatePipelineLayout", createPipelineLayout),
        FAKE_ENTRY("vkDestroyPipelineLayout", destroyPipelineLayout),
        FAKE_ENTRY("vkCreateComputePipelines", createComputePipelines),
        FAKE_ENTRY("vkDestroyPipeline", destroyPipeline),
        FAKE_ENTRY("vkCreateCommandPool", createCommandPool),
        FAKE_ENTRY("vkDestroyCommandPool", destroyCommandPool),
        FAKE_ENTRY("vkResetCommandPool", resetCommandPool),
        FAKE_ENTRY("vkAllocateCommandBuffers", allocateCommandBuffers),
        FAKE_ENTRY("vkBeginCommandBuffer", beginCommandBuffer),
        FAKE_ENTRY("vkEndCommandBuffer", endCommandBuffer),
        FAKE_ENTRY("vkCmdFillBuffer", cmdFillBuffer),
        FAKE_ENTRY("vkCreateFence", createFence),
        FAKE_ENTRY("vkDestroyFence", destroyFence),
        FAKE_ENTRY("vkResetFences", resetFences),
        FAKE_ENTRY("vkGetFenceStatus", getFenceStatus),
        FAKE_ENTRY("vkWaitForFences", waitForFences),
        FAKE_ENTRY("vkCreateSemaphore", createSemaphore),
        FAKE_ENTRY("vkDestroySemaphore", destroySemaphore),
        FAKE_ENTRY("vkGetSemaphoreCounterValue", getSemaphoreCounterValue),
        FAKE_ENTRY("vkSignalSemaphore", signalSemaphore),
        FAKE_ENTRY("vkWaitSemaphores", waitSemaphores),
        FAKE_ENTRY("vkQueueSubmit2", queueSubmit2),
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
        FAKE_ENTRY("vkSetDebugUtilsObjectNameEXT", setDebugUtilsObjectName),
        FAKE_ENTRY("vkCmdBeginDebugUtilsLabelEXT", cmdBeginDebugUtilsLabel),
        FAKE_ENTRY("vkCmdEndDebugUtilsLabelEXT", cmdEndDebugUtilsLabel),
        FAKE_ENTRY("vkCmdInsertDebugUtilsLabelEXT", cmdInsertDebugUtilsLabel),
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

void FakeVulkan::finishPending() {
    for (PendingSubmit& p : g_state->pending) p.released = true;
    progress();
}

std::uint64_t FakeVulkan::timelineValue(VkSemaphore semaphore) const {
    auto it = g_state->semaphores.find(id(semaphore));
    return it == g_state->semaphores.end() ? 0 : it->second.value;
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
