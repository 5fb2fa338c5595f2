// Context::adopt on a fake driver (no GPU): one test per refusal, each naming what is
// missing, and the chain an engine builds from context.hpp's list being accepted.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "api/context_access.hpp"
#include "vk/device.hpp"
#include "vk/fake_vulkan.hpp"

using namespace vkcollide;
using test::FakeVulkanScope;

namespace {

// What an engine keeps from its vkCreateDevice call: the feature chain and extensions.
struct EngineDevice {
    VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    VkPhysicalDeviceVulkan12Features v12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
    VkPhysicalDeviceVulkan13Features v13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    std::vector<const char*> extensions;

    EngineDevice() {
        features.pNext = &v12;
        v12.pNext = &v13;
        enableRequiredFeatures(features, v12, v13);
    }
    EngineDevice(const EngineDevice&) = delete;

    AdoptedDevice lend(test::FakeVulkan& fake) const {
        AdoptedDevice lent;
        lent.get_instance_proc_addr = test::FakeVulkan::getInstanceProcAddr();
        lent.instance = fake.instanceHandle();
        lent.physical_device = fake.physicalHandle(0);
        lent.device = fake.deviceHandle();
        lent.queue_family = 0;
        lent.queue = fake.queueHandle();
        lent.enabled_features = &features;
        lent.enabled_extensions = extensions;
        return lent;
    }
};

// Turns one required feature off in the engine's chain.
void disable(EngineDevice& e, vk::Feature feature) {
    switch (feature) {
        case vk::Feature::ShaderInt64: e.features.features.shaderInt64 = VK_FALSE; break;
        case vk::Feature::FragmentStoresAndAtomics: e.features.features.fragmentStoresAndAtomics = VK_FALSE; break;
        case vk::Feature::BufferDeviceAddress: e.v12.bufferDeviceAddress = VK_FALSE; break;
        case vk::Feature::ScalarBlockLayout: e.v12.scalarBlockLayout = VK_FALSE; break;
        case vk::Feature::ShaderBufferInt64Atomics: e.v12.shaderBufferInt64Atomics = VK_FALSE; break;
        case vk::Feature::HostQueryReset: e.v12.hostQueryReset = VK_FALSE; break;
        case vk::Feature::DynamicRendering: e.v13.dynamicRendering = VK_FALSE; break;
        case vk::Feature::Synchronization2: e.v13.synchronization2 = VK_FALSE; break;
        case vk::Feature::Maintenance4: e.v13.maintenance4 = VK_FALSE; break;
        default: FAIL("not a required feature");
    }
}

}  // namespace

TEST_CASE("adopt accepts a device created with enableRequiredFeatures() and never destroys it", "[contract][adopt]") {
    FakeVulkanScope scope;
    EngineDevice engine;
    {
        auto ctx = Context::adopt(engine.lend(scope.fake()));
        REQUIRE(ctx);
        CHECK_FALSE((*ctx)->ownsDevice());
        CHECK((*ctx)->deviceInfo().name == "Fake GPU");
        // Nothing optional was listed: nothing optional is used.
        CHECK_FALSE(ContextAccess::device(**ctx).push_descriptor);
        CHECK_FALSE(ContextAccess::device(**ctx).conservative_rasterization);
        CHECK_FALSE(ContextAccess::device(**ctx).shader_float64);
        CHECK_FALSE(ContextAccess::device(**ctx).robust_buffer_access);
    }
    // The fake counts only what vkcollide itself created or destroyed: nothing.
    CHECK(scope.fake().instances_alive == 0);
    CHECK(scope.fake().devices_alive == 0);
}

TEST_CASE("adopt refuses each missing required feature by name", "[contract][adopt][error]") {
    for (std::size_t i = 0; i < vk::kFeatureCount; ++i) {
        const auto feature = static_cast<vk::Feature>(i);
        if (!vk::isRequired(feature)) continue;
        DYNAMIC_SECTION("without " << vk::featureName(feature)) {
            FakeVulkanScope scope;
            EngineDevice engine;
            disable(engine, feature);
            auto ctx = Context::adopt(engine.lend(scope.fake()));
            REQUIRE_FALSE(ctx);
            CHECK(ctx.error().code() == ErrorCode::UnsupportedFeature);
            const std::string& m = ctx.error().message();
            CHECK_THAT(m, Catch::Contains(std::string("features: ") + vk::featureName(feature) + " ("));
        }
    }
}

TEST_CASE("adopt refuses a chain from context.hpp's old list (no hostQueryReset, no maintenance4), naming both",
          "[contract][adopt][error]") {
    FakeVulkanScope scope;
    EngineDevice engine;
    engine.v12.hostQueryReset = VK_FALSE;
    engine.v13.maintenance4 = VK_FALSE;
    auto ctx = Context::adopt(engine.lend(scope.fake()));
    REQUIRE_FALSE(ctx);
    CHECK(ctx.error().code() == ErrorCode::UnsupportedFeature);
    CHECK_THAT(ctx.error().message(), Catch::Contains("hostQueryReset, maintenance4") &&
                                          Catch::Contains("enableRequiredFeatures"));
}

TEST_CASE("adopt reads the single-feature structs as well as the Vulkan 1.2/1.3 ones", "[contract][adopt]") {
    FakeVulkanScope scope;
    EngineDevice engine;
    engine.v12.hostQueryReset = VK_FALSE;
    engine.v13.maintenance4 = VK_FALSE;
    VkPhysicalDeviceMaintenance4Features maintenance4{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MAINTENANCE_4_FEATURES};
    maintenance4.maintenance4 = VK_TRUE;
    VkPhysicalDeviceHostQueryResetFeatures reset{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_HOST_QUERY_RESET_FEATURES};
    reset.hostQueryReset = VK_TRUE;
    reset.pNext = &maintenance4;
    engine.v13.pNext = &reset;
    CHECK(Context::adopt(engine.lend(scope.fake())));
}

TEST_CASE("adopt refuses null handles, naming each", "[contract][adopt][error]") {
    auto ctx = Context::adopt(AdoptedDevice{});
    REQUIRE_FALSE(ctx);
    CHECK(ctx.error().code() == ErrorCode::InvalidArgument);
    CHECK_THAT(ctx.error().message(), Catch::Contains("null: get_instance_proc_addr, instance, physical_device, device, queue"));

    FakeVulkanScope scope;
    EngineDevice engine;
    AdoptedDevice lent = engine.lend(scope.fake());
    lent.queue = VK_NULL_HANDLE;
    ctx = Context::adopt(lent);
    REQUIRE_FALSE(ctx);
    CHECK_THAT(ctx.error().message(), Catch::EndsWith("null: queue"));
}

TEST_CASE("adopt refuses a missing or malformed feature chain", "[contract][adopt][error]") {
    FakeVulkanScope scope;
    EngineDevice engine;
    AdoptedDevice lent = engine.lend(scope.fake());
    lent.enabled_features = nullptr;
    auto ctx = Context::adopt(lent);
    REQUIRE_FALSE(ctx);
    CHECK(ctx.error().code() == ErrorCode::InvalidArgument);
    CHECK_THAT(ctx.error().message(), Catch::Contains("enabled_features is null"));

    // The engine passed its VkPhysicalDeviceVulkan12Features instead of the chain's head.
    lent.enabled_features = reinterpret_cast<const VkPhysicalDeviceFeatures2*>(&engine.v12);
    ctx = Context::adopt(lent);
    REQUIRE_FALSE(ctx);
    CHECK(ctx.error().code() == ErrorCode::InvalidArgument);
    CHECK_THAT(ctx.error().message(), Catch::Contains("must point to a VkPhysicalDeviceFeatures2"));

    // A chain that loops back on itself is refused, not walked forever.
    lent = engine.lend(scope.fake());
    engine.v13.pNext = &engine.v12;
    ctx = Context::adopt(lent);
    engine.v13.pNext = nullptr;
    REQUIRE_FALSE(ctx);
    CHECK(ctx.error().code() == ErrorCode::InvalidArgument);
    CHECK_THAT(ctx.error().message(), Catch::Contains("loop"));
}

TEST_CASE("adopt refuses an instance created for Vulkan 1.2", "[contract][adopt][error]") {
    FakeVulkanScope scope;
    EngineDevice engine;
    AdoptedDevice lent = engine.lend(scope.fake());
    lent.api_version = VK_API_VERSION_1_2;
    auto ctx = Context::adopt(lent);
    REQUIRE_FALSE(ctx);
    CHECK(ctx.error().code() == ErrorCode::UnsupportedFeature);
    CHECK_THAT(ctx.error().message(), Catch::Contains("instance was created for Vulkan 1.2"));
}

TEST_CASE("adopt refuses a physical device below Vulkan 1.3", "[contract][adopt][error]") {
    FakeVulkanScope scope;
    scope.fake().physical_devices[0].api_version = VK_API_VERSION_1_2;
    EngineDevice engine;
    auto ctx = Context::adopt(engine.lend(scope.fake()));
    REQUIRE_FALSE(ctx);
    CHECK(ctx.error().code() == ErrorCode::UnsupportedFeature);
    CHECK_THAT(ctx.error().message(), Catch::Contains("Fake GPU supports Vulkan 1.2"));
}

TEST_CASE("adopt refuses a queue family that does not exist", "[contract][adopt][error]") {
    FakeVulkanScope scope;
    EngineDevice engine;
    AdoptedDevice lent = engine.lend(scope.fake());
    lent.queue_family = 5;
    auto ctx = Context::adopt(lent);
    REQUIRE_FALSE(ctx);
    CHECK(ctx.error().code() == ErrorCode::InvalidArgument);
    CHECK_THAT(ctx.error().message(), Catch::Contains("queue family 5 does not exist"));
}

TEST_CASE("adopt refuses a queue family without graphics, compute or timestamps, naming each", "[contract][adopt][error]") {
    FakeVulkanScope scope;
    scope.fake().physical_devices[0].queue_families = {
        {VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT, 1, 64, {1, 1, 1}},
        {VK_QUEUE_TRANSFER_BIT, 1, 0, {1, 1, 1}},
        {VK_QUEUE_COMPUTE_BIT, 1, 64, {1, 1, 1}},
    };
    EngineDevice engine;
    AdoptedDevice lent = engine.lend(scope.fake());
    lent.queue_family = 1;
    auto ctx = Context::adopt(lent);
    REQUIRE_FALSE(ctx);
    CHECK(ctx.error().code() == ErrorCode::UnsupportedFeature);
    CHECK_THAT(ctx.error().message(), Catch::Contains("queue family 1 lacks: graphics, compute, timestamps"));
    lent.queue_family = 2;
    ctx = Context::adopt(lent);
    REQUIRE_FALSE(ctx);
    CHECK_THAT(ctx.error().message(), Catch::EndsWith("queue family 2 lacks: graphics"));
}

TEST_CASE("adopt refuses when the engine's loader lacks a device entry point", "[contract][adopt][error]") {
    FakeVulkanScope scope;
    scope.fake().missing_entry_points = {"vkCmdBeginRendering"};
    EngineDevice engine;
    auto ctx = Context::adopt(engine.lend(scope.fake()));
    REQUIRE_FALSE(ctx);
    CHECK(ctx.error().code() == ErrorCode::UnsupportedFeature);
    CHECK_THAT(ctx.error().message(), Catch::Contains("vkCmdBeginRendering"));
}

TEST_CASE("adopt uses the optional extensions and features the engine enabled, where the device has them",
          "[contract][adopt]") {
    FakeVulkanScope scope;
    scope.fake().physical_devices[0].extensions = {VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME, VK_EXT_ROBUSTNESS_2_EXTENSION_NAME};
    EngineDevice engine;
    engine.features.features.shaderFloat64 = VK_TRUE;
    engine.features.features.robustBufferAccess = VK_TRUE;
    VkPhysicalDeviceRobustness2FeaturesEXT robustness2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ROBUSTNESS_2_FEATURES_EXT};
    robustness2.robustBufferAccess2 = VK_TRUE;
    engine.v13.pNext = &robustness2;
    // Conservative rasterization is listed, but this device does not have it: not used.
    engine.extensions = {VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME, VK_EXT_ROBUSTNESS_2_EXTENSION_NAME,
                         VK_EXT_CONSERVATIVE_RASTERIZATION_EXTENSION_NAME};
    // vkCmdPushDescriptorSetKHR resolves on a device that enabled the extension.
    scope.fake().device_extensions = {VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME};
    auto ctx = Context::adopt(engine.lend(scope.fake()));
    REQUIRE(ctx);
    const vk::Device& d = ContextAccess::device(**ctx);
    CHECK(d.push_descriptor);
    CHECK(d.fns.vkCmdPushDescriptorSetKHR != nullptr);
    CHECK(d.shader_float64);
    CHECK(d.robust_buffer_access);
    CHECK(d.robust_buffer_access2);
    CHECK_FALSE(d.conservative_rasterization);
}
