#include "vk/event.hpp"

#include <utility>

#include "vk/debug_names.hpp"

namespace vkcollide::vk {

Result<Event> Event::create(Device& device, const std::string& name) {
    Event e;
    e.device_ = device.ref();
    VkEventCreateInfo ci{VK_STRUCTURE_TYPE_EVENT_CREATE_INFO};
    VkResult r = device.fns.vkCreateEvent(device.device, &ci, device.allocator(), &e.event_);
    if (r != VK_SUCCESS) {
        e.event_ = VK_NULL_HANDLE;
        return vulkanError(r, "vkCreateEvent for '" + name + "'");
    }
    nameObject(device, e.event_, name);
    return e;
}

Event& Event::operator=(Event&& o) noexcept {
    if (this != &o) {
        reset();
        device_ = std::move(o.device_);
        o.device_.reset();
        event_ = std::exchange(o.event_, VK_NULL_HANDLE);
    }
    return *this;
}

Result<void> Event::unset() const {
    if (!event_) return Error(ErrorCode::InvalidArgument, "Event::unset on an empty Event");
    VkResult r = device_->fns.vkResetEvent(device_->device, event_);
    if (r != VK_SUCCESS) return vulkanError(r, "vkResetEvent");
    return {};
}

Result<bool> Event::isSet() const {
    if (!event_) return Error(ErrorCode::InvalidArgument, "Event::isSet on an empty Event");
    VkResult r = device_->fns.vkGetEventStatus(device_->device, event_);
    if (r == VK_EVENT_SET) return true;
    if (r == VK_EVENT_RESET) return false;
    return vulkanError(r, "vkGetEventStatus");
}

void Event::reset() {
    if (device_ && event_) device_->fns.vkDestroyEvent(device_->device, event_, device_->allocator());
    event_ = VK_NULL_HANDLE;
}

}  // namespace vkcollide::vk
