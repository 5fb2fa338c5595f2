// The installed fake, host allocations and entry-point lookup; the entry points themselves
// live in fake_instance.cpp, fake_resources.cpp and fake_commands.cpp.
#include "vk/fake_vulkan.hpp"

#include "vk/fake_vulkan_internal.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace vkcollide::test::fake_driver {

FakeVulkan* g_fake = nullptr;
FakeState* g_state = nullptr;
char g_instance_object;
char g_physical_objects[8];
char g_device_object;
char g_queue_object;

FakeVulkan& fake() {
    if (!g_fake) {
        std::fprintf(stderr, "fake Vulkan called outside a FakeVulkanScope\n");
        std::abort();
    }
    return *g_fake;
}

// ---- allocation callbacks: one host allocation per object created with them ----------

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

void made(VkObjectType type, std::uint64_t handle) { fake().created_objects.push_back({type, handle}); }

namespace {

[[noreturn]] VKAPI_ATTR void VKAPI_CALL trap() {
    std::fprintf(stderr, "fake Vulkan: an entry point the fake does not implement was called\n");
    std::abort();
}

const EntryMap& deviceEntries() {
    static const EntryMap entries = [] {
        EntryMap all = deviceLifetimeEntries();
        for (EntryMap part : {resourceEntries(), commandEntries()}) all.merge(part);
        return all;
    }();
    return entries;
}

}  // namespace

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

namespace {

VKAPI_ATTR PFN_vkVoidFunction VKAPI_CALL fakeGetInstanceProcAddr(VkInstance instance, const char* name) {
    if (fake().missing_entry_points.count(name)) return nullptr;
    static const EntryMap global = loaderEntries();
    static const EntryMap per_instance = instanceEntries();
    if (std::string_view(name) == "vkGetInstanceProcAddr") return reinterpret_cast<PFN_vkVoidFunction>(fakeGetInstanceProcAddr);
    if (auto it = global.find(name); it != global.end()) return it->second;
    if (!instance) return nullptr;
    if (auto it = per_instance.find(name); it != per_instance.end()) return it->second;
    return getDeviceProcAddr(VK_NULL_HANDLE, name);
}

}  // namespace

}  // namespace vkcollide::test::fake_driver

namespace vkcollide::test {

using namespace fake_driver;

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
