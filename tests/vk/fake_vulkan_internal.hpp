// What the fake driver's files share (fake_vulkan.cpp: the installed fake, host allocations
// and entry-point lookup; fake_instance.cpp: loader, instance, physical and logical device;
// fake_resources.cpp: memory, buffers, images and pipelines; fake_commands.cpp: command
// buffers, fences, semaphores and the queue): the fake's hidden state, its handles and the
// bookkeeping every created object goes through.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <string_view>
#include <vector>

#include <vulkan/vulkan_core.h>

#include "vk/fake_vulkan.hpp"

namespace vkcollide::test::fake_driver {

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

// Installed by FakeVulkanScope, null outside one.
extern FakeVulkan* g_fake;
extern FakeState* g_state;

// Dispatchable handles point at these; their addresses are all the fake needs.
extern char g_instance_object;
extern char g_physical_objects[8];
extern char g_device_object;
extern char g_queue_object;

// The installed fake; aborts outside a FakeVulkanScope.
FakeVulkan& fake();

template <typename Handle>
Handle newHandle() {
    return reinterpret_cast<Handle>(static_cast<std::uintptr_t>(g_state->next_handle++));
}
template <typename Handle>
std::uint64_t id(Handle h) {
    return static_cast<std::uint64_t>(reinterpret_cast<std::uintptr_t>(h));
}
inline const void* key(std::uint64_t handle) { return reinterpret_cast<const void*>(static_cast<std::uintptr_t>(handle)); }

// One host allocation per object created with allocation callbacks; `what` names the
// destroying call in allocator_mismatches.
void created(const void* object, const VkAllocationCallbacks* callbacks);
void destroyed(const char* what, const void* object, const VkAllocationCallbacks* callbacks);
// Every object the device layer creates, for the tests of its names.
void made(VkObjectType type, std::uint64_t handle);

// A new object of the device layer: a fresh handle, counted in `alive`, listed in
// created_objects, with its host allocation when made with callbacks.
template <typename Handle>
Handle newObject(VkObjectType type, int& alive, const VkAllocationCallbacks* callbacks) {
    const Handle handle = newHandle<Handle>();
    ++alive;
    made(type, id(handle));
    created(key(id(handle)), callbacks);
    return handle;
}
// Its destruction by `call` (vkDestroyBuffer, ...).
template <typename Handle>
void endObject(const char* call, Handle handle, int& alive, const VkAllocationCallbacks* callbacks) {
    --alive;
    destroyed(call, key(id(handle)), callbacks);
}

// Entry points by name.
using EntryMap = std::map<std::string_view, PFN_vkVoidFunction>;
template <typename Function>
EntryMap::value_type entry(std::string_view name, Function* function) {
    return {name, reinterpret_cast<PFN_vkVoidFunction>(function)};
}
// vkGetDeviceProcAddr (fake_vulkan.cpp), which the instance hands out too.
VKAPI_ATTR PFN_vkVoidFunction VKAPI_CALL getDeviceProcAddr(VkDevice device, const char* name);

// Each file's own entry points. The loader's are found before there is an instance
// (vkGetInstanceProcAddr(NULL, ...)); the device's own are its destruction, queue and idle.
EntryMap loaderEntries();
EntryMap instanceEntries();
EntryMap deviceLifetimeEntries();
EntryMap resourceEntries();
EntryMap commandEntries();

}  // namespace vkcollide::test::fake_driver
