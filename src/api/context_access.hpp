// The device behind a Context, for vkcollide's own subsystems (and its tests and stage
// benchmarks): not part of the public API, so engines never see vk::Device.
#pragma once

#include <memory>

#include "vk/device.hpp"
#include "vkcollide/context.hpp"

namespace vkcollide {

struct ContextAccess {
    static vk::Device& device(Context& context) noexcept { return *context.device_; }
    // What a world holds to keep the device alive after the Context is gone (Lifetime).
    static std::shared_ptr<vk::Device> deviceRef(const Context& context) noexcept { return context.device_; }
};

}  // namespace vkcollide
