// An event the device sets inside a submission and the host reads (vkGetEventStatus): how
// the host learns that part of a submission's work is done before all of it is (the
// graph's milestones, graph::Executor::setMilestone). Created without
// VK_EVENT_CREATE_DEVICE_ONLY_BIT, so that the host may read and reset it.
#pragma once

#include <string>

#include "vk/device.hpp"

namespace vkcollide::vk {

class Event {
public:
    Event() = default;
    static Result<Event> create(Device& device, const std::string& name);
    ~Event() { reset(); }
    Event(Event&& o) noexcept { *this = std::move(o); }
    Event& operator=(Event&& o) noexcept;

    VkEvent handle() const noexcept { return event_; }
    // Unsets it from the host. No command that sets it may be pending.
    Result<void> unset() const;
    // Whether the device has set it (VK_EVENT_SET). Errors: DeviceLost, or the query's.
    Result<bool> isSet() const;

    // Destroys the event (nothing pending may use it); keeps the DeviceRef until the
    // destructor (see resources.hpp).
    void reset();

private:
    DeviceRef device_;
    VkEvent event_ = VK_NULL_HANDLE;
};

}  // namespace vkcollide::vk
