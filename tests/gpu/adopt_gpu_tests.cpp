// An engine's own device, created from context.hpp's list and nothing more, adopted and
// used for a detection on the real driver with validation (and synchronization
// validation) on: the list is complete when this runs without a single message.
#include <catch2/catch.hpp>

#include <vector>

#include "api/context_access.hpp"
#include "test_shaders/all.hpp"
#include "support/gpu_fixture.hpp"
#include "vk/resources.hpp"
#include "vkcollide/scene.hpp"
#include "vkcollide/world.hpp"

using namespace vkcollide;

namespace {

// The engine: a VkDevice on the validated context's physical device and instance (so the
// validation layer watches it too), created with exactly the features context.hpp lists,
// written out here by hand as an engine developer would, and no extension at all.
class EngineDevice {
public:
    explicit EngineDevice(test::ValidatedContext& validated, bool host_query_reset = true) : host_(validated.device()) {
        features_.pNext = &v12_;
        v12_.pNext = &v13_;
        features_.features.shaderInt64 = VK_TRUE;
        features_.features.fragmentStoresAndAtomics = VK_TRUE;
        v12_.bufferDeviceAddress = VK_TRUE;
        v12_.scalarBlockLayout = VK_TRUE;
        v12_.shaderBufferInt64Atomics = VK_TRUE;
        v12_.hostQueryReset = host_query_reset ? VK_TRUE : VK_FALSE;
        v13_.dynamicRendering = VK_TRUE;
        v13_.synchronization2 = VK_TRUE;
        v13_.maintenance4 = VK_TRUE;
        const float priority = 1.0f;
        VkDeviceQueueCreateInfo queue{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
        queue.queueFamilyIndex = host_.queue_family;
        queue.queueCount = 1;
        queue.pQueuePriorities = &priority;
        VkDeviceCreateInfo ci{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
        ci.pNext = &features_;
        ci.queueCreateInfoCount = 1;
        ci.pQueueCreateInfos = &queue;
        REQUIRE(host_.instance_fns.vkCreateDevice(host_.physical, &ci, nullptr, &device_) == VK_SUCCESS);
        destroy_ = reinterpret_cast<PFN_vkDestroyDevice>(host_.instance_fns.vkGetDeviceProcAddr(device_, "vkDestroyDevice"));
        auto get_queue = reinterpret_cast<PFN_vkGetDeviceQueue>(host_.instance_fns.vkGetDeviceProcAddr(device_, "vkGetDeviceQueue"));
        get_queue(device_, host_.queue_family, 0, &queue_);
    }
    ~EngineDevice() { destroy_(device_, nullptr); }
    EngineDevice(const EngineDevice&) = delete;
    EngineDevice& operator=(const EngineDevice&) = delete;

    AdoptedDevice lend() const {
        AdoptedDevice lent;
        lent.get_instance_proc_addr = host_.global.vkGetInstanceProcAddr;
        lent.instance = host_.instance;
        lent.physical_device = host_.physical;
        lent.device = device_;
        lent.queue_family = host_.queue_family;
        lent.queue = queue_;
        lent.enabled_features = &features_;
        return lent;
    }

private:
    vk::Device& host_;
    VkPhysicalDeviceFeatures2 features_{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    VkPhysicalDeviceVulkan12Features v12_{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
    VkPhysicalDeviceVulkan13Features v13_{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    VkDevice device_ = VK_NULL_HANDLE;
    VkQueue queue_ = VK_NULL_HANDLE;
    PFN_vkDestroyDevice destroy_ = nullptr;
};

}  // namespace

TEST_CASE("a device with exactly context.hpp's features and no extension detects without a validation message",
          "[gpu][adopt]") {
    test::ValidatedContext validated;
    EngineDevice engine(validated);
    {
        auto ctx = Context::adopt(engine.lend());
        REQUIRE(ctx);
        CHECK_FALSE(ContextAccess::device(**ctx).push_descriptor);
        auto world = CollisionWorld::create(**ctx);
        REQUIRE(world);
        auto a = uvSphere(1.0f, 24, 12);
        auto b = uvSphere(1.0f, 24, 12);
        REQUIRE(a);
        REQUIRE(b);
        ObjectOptions moved;
        moved.transform[3] = 1.2f;
        REQUIRE((*world)->addMesh(*a));
        REQUIRE((*world)->addMesh(*b, moved));
        for (int frame = 0; frame < 2; ++frame) {
            auto hits = (*world)->detect();
            INFO((hits ? std::string() : hits.error().message()));
            REQUIRE(hits);
            CHECK_FALSE(hits->pairs.empty());
        }
        SECTION("the submit/collect path too") {
            REQUIRE((*world)->submit());
            auto hits = (*world)->collect();
            REQUIRE(hits);
            CHECK_FALSE(hits->pairs.empty());
        }
    }
    REQUIRE_NO_VALIDATION_MESSAGES(validated);
}

TEST_CASE("without VK_KHR_push_descriptor a pipeline with descriptor bindings is refused by name", "[gpu][adopt]") {
    test::ValidatedContext validated;
    EngineDevice engine(validated);
    auto ctx = Context::adopt(engine.lend());
    REQUIRE(ctx);
    const vk::Pipeline::Binding bindings[] = {{0, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE}};
    auto pipeline = vk::Pipeline::createCompute(ContextAccess::device(**ctx), shaders::graph_test_sum_comp, bindings, 8, "graph-test-sum");
    REQUIRE_FALSE(pipeline);
    CHECK(pipeline.error().code() == ErrorCode::UnsupportedFeature);
    CHECK_THAT(pipeline.error().message(), Catch::Contains("'graph-test-sum'") && Catch::Contains("VK_KHR_push_descriptor"));
    REQUIRE_NO_VALIDATION_MESSAGES(validated);
}

TEST_CASE("a real device created without hostQueryReset is refused by adopt, naming it", "[gpu][adopt]") {
    test::ValidatedContext validated;
    EngineDevice engine(validated, /*host_query_reset=*/false);
    auto ctx = Context::adopt(engine.lend());
    REQUIRE_FALSE(ctx);
    CHECK(ctx.error().code() == ErrorCode::UnsupportedFeature);
    CHECK_THAT(ctx.error().message(), Catch::Contains("features: hostQueryReset ("));
    REQUIRE_NO_VALIDATION_MESSAGES(validated);
}

TEST_CASE("vkcollide's own device turns on robust buffer access and shaderFloat64 where the device has them", "[gpu][context]") {
    test::ValidatedContext validated;
    const vk::Device& d = validated.device();
    const DeviceInfo& info = validated.context().deviceInfo();
    CHECK(d.shader_float64 == info.shader_float64);
    CHECK(d.robust_buffer_access2 == info.robustness2);
    CHECK(d.push_descriptor == info.push_descriptor);
    // Vulkan requires every implementation to support robustBufferAccess.
    CHECK(d.robust_buffer_access);
    REQUIRE_NO_VALIDATION_MESSAGES(validated);
}
