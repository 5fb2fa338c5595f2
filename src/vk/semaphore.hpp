// A semaphore vkcollide creates on its own device: for tests that play the engine, and for
// code that needs a timeline of its own. Engines pass their own semaphores (SubmitSync);
// this class is not how they reach vkcollide.
#pragma once

#include <cstdint>
#include <string>

#include "vk/device.hpp"

namespace vkcollide::vk {

class Semaphore {
public:
    Semaphore() = default;
    // A binary semaphore.
    static Result<Semaphore> createBinary(Device& device, const std::string& name);
    // A timeline semaphore starting at `initial`. Errors: UnsupportedFeature when the
    // device has not enabled timelineSemaphore; VulkanError / OutOfMemory.
    static Result<Semaphore> createTimeline(Device& device, std::uint64_t initial, const std::string& name);
    ~Semaphore() { reset(); }
    Semaphore(Semaphore&& o) noexcept { *this = std::move(o); }
    Semaphore& operator=(Semaphore&& o) noexcept;

    VkSemaphore handle() const noexcept { return semaphore_; }
    bool timeline() const noexcept { return timeline_; }

    // Timeline only: the counter now; signal from the host; wait up to timeout_ns for
    // the counter to reach `value` (false after the timeout).
    Result<std::uint64_t> value() const;
    Result<void> signal(std::uint64_t value) const;
    Result<bool> wait(std::uint64_t value, std::uint64_t timeout_ns) const;

    // Destroys the semaphore (nothing pending may use it); keeps the DeviceRef until the
    // destructor (see resources.hpp).
    void reset();

private:
    static Result<Semaphore> make(Device& device, bool timeline, std::uint64_t initial, const std::string& name);
    Result<void> needTimeline(const char* what) const;

    DeviceRef device_;
    VkSemaphore semaphore_ = VK_NULL_HANDLE;
    bool timeline_ = false;
};

}  // namespace vkcollide::vk
