// The one path to the queue (src/vk/device.hpp, Device::queueSubmit): the Context's own
// mutex, then the engine's QueueHooks (context.hpp).
//
// Why both locks: two worlds on one Context used from two threads share the VkQueue, which
// Vulkan requires to be externally synchronised; the Context's mutex makes that safe with
// no help from the engine. The engine's lock is for the engine's own use of the queue
// (its render thread), which vkcollide cannot see.
#include <exception>
#include <string>

#include "vk/device.hpp"

namespace vkcollide::vk {
namespace {

// Calls one engine hook; an exception must not cross vkcollide (the API promises none).
template <typename F>
bool callHook(const Device& device, const char* which, F&& f) {
    try {
        f();
        return true;
    } catch (const std::exception& e) {
        device.message(MessageSeverity::Error, std::string("QueueHooks::") + which + " threw: " + e.what());
    } catch (...) {
        device.message(MessageSeverity::Error, std::string("QueueHooks::") + which + " threw");
    }
    return false;
}

}  // namespace

VkResult Device::queueSubmit(std::span<const VkSubmitInfo2> submits, VkFence fence) {
    std::lock_guard<std::mutex> lock(queue_mutex);
    const QueueHooks& hooks = queue_hooks;
    if (hooks.lock && !callHook(*this, "lock", hooks.lock)) return VK_ERROR_UNKNOWN;
    VkResult result = VK_ERROR_UNKNOWN;
    if (hooks.submit) {
        if (!callHook(*this, "submit", [&] { result = hooks.submit(queue, submits, fence); })) result = VK_ERROR_UNKNOWN;
    } else {
        result = fns.vkQueueSubmit2(queue, static_cast<std::uint32_t>(submits.size()), submits.data(), fence);
    }
    // An unlock that throws leaves the engine's lock in whatever state its code left it;
    // the submission itself happened, so its result stands.
    if (hooks.unlock) (void)callHook(*this, "unlock", hooks.unlock);
    return result;
}

VkResult Device::waitIdle() {
    std::lock_guard<std::mutex> lock(queue_mutex);
    return fns.vkDeviceWaitIdle(device);
}

}  // namespace vkcollide::vk
