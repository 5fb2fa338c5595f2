// The device layer on lavapipe (or whatever device the machine has), validation on.
#include <catch2/catch.hpp>

#include <cstdlib>

#include "api/context_access.hpp"
#include "support/gpu_fixture.hpp"
#include "vk/resources.hpp"

using namespace vkcollide;

TEST_CASE("a validated context finds a device that meets every requirement", "[gpu][context]") {
    test::ValidatedContext ctx;
    const DeviceInfo& info = ctx.context().deviceInfo();
    CHECK_FALSE(info.name.empty());
    CHECK(info.missing.empty());
    CHECK(VK_API_VERSION_MINOR(info.api_version) >= 3);
    CHECK(ctx.context().ownsDevice());
    CHECK(ctx.device().timestamp_valid_bits > 0);
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("listDevices reports every device with what it lacks", "[gpu][context]") {
    auto devices = Context::listDevices();
    REQUIRE(devices);
    REQUIRE_FALSE(devices->empty());
    bool any_suitable = false;
    for (const auto& d : *devices) any_suitable |= d.missing.empty();
    CHECK(any_suitable);
}

TEST_CASE("asking for a device name that does not exist names the devices there are", "[gpu][context]") {
    ContextCreateInfo info;
    info.device_name = "no-such-gpu-xyz";
    auto ctx = Context::create(info);
    REQUIRE_FALSE(ctx);
    CHECK(ctx.error().code() == ErrorCode::NoSuitableDevice);
    CHECK_THAT(ctx.error().message(), Catch::Contains("no-such-gpu-xyz") && Catch::Contains("devices:"));
}

TEST_CASE("VKCOLLIDE_DEVICE picks a device by name", "[gpu][context]") {
    auto devices = Context::listDevices();
    REQUIRE(devices);
    std::string name;
    for (const auto& d : *devices)
        if (d.missing.empty()) name = d.name;
    REQUIRE_FALSE(name.empty());
    ::setenv("VKCOLLIDE_DEVICE", name.c_str(), 1);
    auto ctx = Context::create();
    ::unsetenv("VKCOLLIDE_DEVICE");
    REQUIRE(ctx);
    CHECK((*ctx)->deviceInfo().name == name);
}

TEST_CASE("adopting an engine's device borrows it without owning it", "[gpu][context]") {
    // Play the engine: make a device through vkcollide's own context, then lend its handles.
    test::ValidatedContext engine;
    vk::Device& d = engine.device();
    // vkcollide's own device has at least the required features on.
    VkPhysicalDeviceVulkan13Features v13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    VkPhysicalDeviceVulkan12Features v12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
    VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    features.pNext = &v12;
    v12.pNext = &v13;
    enableRequiredFeatures(features, v12, v13);
    AdoptedDevice lent;
    lent.enabled_features = &features;
    lent.get_instance_proc_addr = d.global.vkGetInstanceProcAddr;
    lent.instance = d.instance;
    lent.physical_device = d.physical;
    lent.device = d.device;
    lent.queue_family = d.queue_family;
    lent.queue = d.queue;
    {
        auto adopted = Context::adopt(lent);
        REQUIRE(adopted);
        CHECK_FALSE((*adopted)->ownsDevice());
        CHECK((*adopted)->deviceInfo().name == engine.context().deviceInfo().name);
        auto buf = vk::Buffer::create(ContextAccess::device(**adopted), 1024, 0, vk::MemoryKind::Readback, "probe");
        REQUIRE(buf);
        CHECK(buf->mapped() != nullptr);
    }
    // The adopted context is gone; the engine's device must still work.
    CHECK(d.fns.vkDeviceWaitIdle(d.device) == VK_SUCCESS);
    REQUIRE_NO_VALIDATION_MESSAGES(engine);
}

TEST_CASE("adopt rejects missing handles with a message naming them", "[gpu][context]") {
    AdoptedDevice lent;
    auto ctx = Context::adopt(lent);
    REQUIRE_FALSE(ctx);
    CHECK(ctx.error().code() == ErrorCode::InvalidArgument);
    CHECK_THAT(ctx.error().message(), Catch::Contains("get_instance_proc_addr"));
}

TEST_CASE("buffers are mapped where host-visible and have device addresses", "[gpu][context]") {
    test::ValidatedContext ctx;
    auto up = vk::Buffer::create(ctx.device(), 4096, 0, vk::MemoryKind::Upload, "up");
    auto dev = vk::Buffer::create(ctx.device(), 4096, 0, vk::MemoryKind::DeviceLocal, "dev");
    REQUIRE(up);
    REQUIRE(dev);
    CHECK(up->mapped() != nullptr);
    CHECK(up->address() != 0);
    CHECK(dev->address() != 0);
    auto zero = vk::Buffer::create(ctx.device(), 0, 0, vk::MemoryKind::DeviceLocal, "zero");
    REQUIRE_FALSE(zero);
    CHECK_THAT(zero.error().message(), Catch::Contains("'zero'"));
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("validation messages reach the test log (the check that fails tests works)", "[gpu][context]") {
    test::ValidatedContext ctx;
    vk::Device& d = ctx.device();
    // Deliberately invalid: a zero-sized buffer breaks VUID-VkBufferCreateInfo-size-00912.
    VkBufferCreateInfo ci{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    ci.size = 0;
    ci.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    VkBuffer buffer = VK_NULL_HANDLE;
    VkResult r = d.fns.vkCreateBuffer(d.device, &ci, nullptr, &buffer);
    if (r == VK_SUCCESS && buffer) d.fns.vkDestroyBuffer(d.device, buffer, nullptr);
    CHECK_FALSE(ctx.messages().empty());
    CHECK(ctx.context().validationMessageCount() >= 1);
}
