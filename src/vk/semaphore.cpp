#include "vk/semaphore.hpp"

#include "vk/debug_names.hpp"

namespace vkcollide::vk {

Result<Semaphore> Semaphore::make(Device& device, bool timeline, std::uint64_t initial, const std::string& name) {
    if (timeline && !device.timeline_semaphore)
        return Error(ErrorCode::UnsupportedFeature, "timeline semaphore '" + name + "': the device has not enabled timelineSemaphore");
    Semaphore s;
    s.device_ = device.ref();
    s.timeline_ = timeline;
    VkSemaphoreTypeCreateInfo type{VK_STRUCTURE_TYPE_SEMAPHORE_TYPE_CREATE_INFO};
    type.semaphoreType = VK_SEMAPHORE_TYPE_TIMELINE;
    type.initialValue = initial;
    VkSemaphoreCreateInfo ci{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    ci.pNext = timeline ? &type : nullptr;
    VkResult r = device.fns.vkCreateSemaphore(device.device, &ci, device.allocator(), &s.semaphore_);
    if (r != VK_SUCCESS) {
        s.semaphore_ = VK_NULL_HANDLE;
        return vulkanError(r, "vkCreateSemaphore for '" + name + "'");
    }
    nameObject(device, s.semaphore_, name);
    return s;
}

Result<Semaphore> Semaphore::createBinary(Device& device, const std::string& name) { return make(device, false, 0, name); }

Result<Semaphore> Semaphore::createTimeline(Device& device, std::uint64_t initial, const std::string& name) {
    return make(device, true, initial, name);
}

Semaphore& Semaphore::operator=(Semaphore&& o) noexcept {
    if (this != &o) {
        reset();
        device_ = std::move(o.device_);
        o.device_.reset();
        semaphore_ = std::exchange(o.semaphore_, VK_NULL_HANDLE);
        timeline_ = o.timeline_;
    }
    return *this;
}

Result<void> Semaphore::needTimeline(const char* what) const {
    if (!semaphore_) return Error(ErrorCode::InvalidArgument, std::string(what) + " on an empty Semaphore");
    if (!timeline_) return Error(ErrorCode::InvalidArgument, std::string(what) + " on a binary semaphore (timeline only)");
    return {};
}

Result<std::uint64_t> Semaphore::value() const {
    if (auto ok = needTimeline("Semaphore::value"); !ok) return ok.error();
    std::uint64_t v = 0;
    VkResult r = device_->fns.vkGetSemaphoreCounterValue(device_->device, semaphore_, &v);
    if (r != VK_SUCCESS) return vulkanError(r, "vkGetSemaphoreCounterValue");
    return v;
}

Result<void> Semaphore::signal(std::uint64_t value) const {
    if (auto ok = needTimeline("Semaphore::signal"); !ok) return ok.error();
    VkSemaphoreSignalInfo si{VK_STRUCTURE_TYPE_SEMAPHORE_SIGNAL_INFO};
    si.semaphore = semaphore_;
    si.value = value;
    VkResult r = device_->fns.vkSignalSemaphore(device_->device, &si);
    if (r != VK_SUCCESS) return vulkanError(r, "vkSignalSemaphore");
    return {};
}

Result<bool> Semaphore::wait(std::uint64_t value, std::uint64_t timeout_ns) const {
    if (auto ok = needTimeline("Semaphore::wait"); !ok) return ok.error();
    VkSemaphoreWaitInfo wi{VK_STRUCTURE_TYPE_SEMAPHORE_WAIT_INFO};
    wi.semaphoreCount = 1;
    wi.pSemaphores = &semaphore_;
    wi.pValues = &value;
    VkResult r = device_->fns.vkWaitSemaphores(device_->device, &wi, timeout_ns);
    if (r == VK_TIMEOUT) return false;
    if (r != VK_SUCCESS) return vulkanError(r, "vkWaitSemaphores");
    return true;
}

void Semaphore::reset() {
    if (device_ && semaphore_) device_->fns.vkDestroySemaphore(device_->device, semaphore_, device_->allocator());
    semaphore_ = VK_NULL_HANDLE;
}

}  // namespace vkcollide::vk
