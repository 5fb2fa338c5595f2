// The fake driver's command pools and buffers, fences, semaphores and queue, and the
// "GPU" that finishes what was submitted (fake_vulkan_internal.hpp).
#include "vk/fake_vulkan_internal.hpp"

#include <algorithm>

namespace vkcollide::test::fake_driver {
namespace {

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

// ---- commands, fences, semaphores, the queue -------------------------------------------

VKAPI_ATTR VkResult VKAPI_CALL createCommandPool(VkDevice, const VkCommandPoolCreateInfo*, const VkAllocationCallbacks* callbacks,
                                                 VkCommandPool* out) {
    *out = newObject<VkCommandPool>(VK_OBJECT_TYPE_COMMAND_POOL, fake().command_pools_alive, callbacks);
    return VK_SUCCESS;
}
VKAPI_ATTR void VKAPI_CALL destroyCommandPool(VkDevice, VkCommandPool pool, const VkAllocationCallbacks* callbacks) {
    if (pool) endObject("vkDestroyCommandPool", pool, fake().command_pools_alive, callbacks);
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
    *out = newObject<VkFence>(VK_OBJECT_TYPE_FENCE, fake().fences_alive, callbacks);
    g_state->fences[id(*out)] = (info->flags & VK_FENCE_CREATE_SIGNALED_BIT) != 0;
    return VK_SUCCESS;
}
VKAPI_ATTR void VKAPI_CALL destroyFence(VkDevice, VkFence fence, const VkAllocationCallbacks* callbacks) {
    if (fence && g_state->fences.erase(id(fence))) endObject("vkDestroyFence", fence, fake().fences_alive, callbacks);
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
    *out = newObject<VkSemaphore>(VK_OBJECT_TYPE_SEMAPHORE, fake().semaphores_alive, callbacks);
    g_state->semaphores[id(*out)] = sem;
    return VK_SUCCESS;
}
VKAPI_ATTR void VKAPI_CALL destroySemaphore(VkDevice, VkSemaphore semaphore, const VkAllocationCallbacks* callbacks) {
    if (semaphore && g_state->semaphores.erase(id(semaphore)))
        endObject("vkDestroySemaphore", semaphore, fake().semaphores_alive, callbacks);
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

}  // namespace

EntryMap commandEntries() {
    return {
        entry("vkCreateCommandPool", createCommandPool),
        entry("vkDestroyCommandPool", destroyCommandPool),
        entry("vkResetCommandPool", resetCommandPool),
        entry("vkAllocateCommandBuffers", allocateCommandBuffers),
        entry("vkBeginCommandBuffer", beginCommandBuffer),
        entry("vkEndCommandBuffer", endCommandBuffer),
        entry("vkCmdFillBuffer", cmdFillBuffer),
        entry("vkCreateFence", createFence),
        entry("vkDestroyFence", destroyFence),
        entry("vkResetFences", resetFences),
        entry("vkGetFenceStatus", getFenceStatus),
        entry("vkWaitForFences", waitForFences),
        entry("vkCreateSemaphore", createSemaphore),
        entry("vkDestroySemaphore", destroySemaphore),
        entry("vkGetSemaphoreCounterValue", getSemaphoreCounterValue),
        entry("vkSignalSemaphore", signalSemaphore),
        entry("vkWaitSemaphores", waitSemaphores),
        entry("vkQueueSubmit2", queueSubmit2),
    };
}

}  // namespace vkcollide::test::fake_driver

namespace vkcollide::test {

using namespace fake_driver;

void FakeVulkan::finishPending() {
    for (PendingSubmit& p : g_state->pending) p.released = true;
    progress();
}

std::uint64_t FakeVulkan::timelineValue(VkSemaphore semaphore) const {
    auto it = g_state->semaphores.find(id(semaphore));
    return it == g_state->semaphores.end() ? 0 : it->second.value;
}

}  // namespace vkcollide::test
