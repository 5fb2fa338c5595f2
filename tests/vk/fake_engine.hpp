// What the contract tests share when they play an engine on the fake driver: the feature
// chain an engine passes to vkCreateDevice, lent to Context::adopt, and a Context created
// on the fake with its messages kept.
#pragma once

#include <catch2/catch.hpp>

#include <memory>
#include <string>
#include <vector>

#include "vk/device.hpp"
#include "vk/fake_vulkan.hpp"

namespace vkcollide::test {

struct FakeEngineDevice {
    VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    VkPhysicalDeviceVulkan12Features v12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
    VkPhysicalDeviceVulkan13Features v13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};

    explicit FakeEngineDevice(bool timeline = true) {
        features.pNext = &v12;
        v12.pNext = &v13;
        enableRequiredFeatures(features, v12, v13);
        v12.timelineSemaphore = timeline ? VK_TRUE : VK_FALSE;
    }
    FakeEngineDevice(const FakeEngineDevice&) = delete;

    AdoptedDevice lend(FakeVulkan& fake) const {
        AdoptedDevice lent;
        lent.get_instance_proc_addr = FakeVulkan::getInstanceProcAddr();
        lent.instance = fake.instanceHandle();
        lent.physical_device = fake.physicalHandle(0);
        lent.device = fake.deviceHandle();
        lent.queue_family = 0;
        lent.queue = fake.queueHandle();
        lent.enabled_features = &features;
        return lent;
    }
};

// Context::create on the fake; messages go to `log` when given.
inline std::unique_ptr<Context> createFakeContext(ContextCreateInfo info = {}, std::vector<std::string>* log = nullptr) {
    info.get_instance_proc_addr = FakeVulkan::getInstanceProcAddr();
    info.on_message = [log](MessageSeverity, std::string_view text) {
        if (log) log->emplace_back(text);
    };
    auto ctx = Context::create(info);
    if (!ctx) FAIL("Context::create on the fake driver: " << ctx.error().message());
    return std::move(*ctx);
}

}  // namespace vkcollide::test
