// Context::create and listDevices on a fake driver (no GPU): every error path of the
// device layer, one test per ErrorCode it can return (vk-bootstrap's error_code_tests),
// each also checking that nothing created before the failure is left behind.
//
// The error codes the device layer does not produce are tested where they arise:
// InvalidMesh (tests/core/mesh_tests.cpp), ParseError and IoError (tests/io/),
// BufferTooSmall (tests/api/world_tests.cpp; checkEngineBuffer in engine_buffer_tests.cpp),
// GraphError (tests/graph/graph_plan_tests.cpp).
#include <catch2/catch.hpp>

#include <algorithm>
#include <string>

#include "api/context_access.hpp"
#include "vk/device.hpp"
#include "vk/fake_vulkan.hpp"
#include "vk/resources.hpp"

using namespace vkcollide;
using test::FakeVulkanScope;

namespace {

Result<std::unique_ptr<Context>> createOnFake(ContextCreateInfo info = {}) {
    info.get_instance_proc_addr = test::FakeVulkan::getInstanceProcAddr();
    info.on_message = [](MessageSeverity, std::string_view) {};
    return Context::create(info);
}

bool lists(const std::vector<std::string>& names, const char* name) {
    return std::find(names.begin(), names.end(), name) != names.end();
}

}  // namespace

TEST_CASE("fake driver: a complete device is created with every required feature and the optional ones it has",
          "[contract][context]") {
    FakeVulkanScope scope;
    auto& fake = scope.fake();
    fake.physical_devices[0].extensions = {VK_EXT_ROBUSTNESS_2_EXTENSION_NAME};
    {
        auto ctx = createOnFake();
        REQUIRE(ctx);
        CHECK((*ctx)->ownsDevice());
        CHECK((*ctx)->deviceInfo().missing.empty());
        CHECK(fake.device_features.missingRequired().empty());
        // Second line of defence and the double-precision filters, because the device has them.
        CHECK(fake.device_features.has(vk::Feature::RobustBufferAccess));
        CHECK(fake.device_features.has(vk::Feature::RobustBufferAccess2));
        CHECK(fake.device_features.has(vk::Feature::ShaderFloat64));
        CHECK(lists(fake.device_extensions, VK_EXT_ROBUSTNESS_2_EXTENSION_NAME));
        // Optional extensions the device lacks are not asked for.
        CHECK_FALSE(lists(fake.device_extensions, VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME));
        CHECK_FALSE(ContextAccess::device(**ctx).push_descriptor);
        CHECK(ContextAccess::device(**ctx).fns.vkCmdPushDescriptorSetKHR == nullptr);
        CHECK(ContextAccess::device(**ctx).shader_float64);
        CHECK(ContextAccess::device(**ctx).robust_buffer_access2);
        CHECK(fake.devices_alive == 1);
    }
    CHECK(fake.devices_alive == 0);
    CHECK(fake.instances_alive == 0);
}

TEST_CASE("fake driver: robust buffer access can be turned off (to measure its cost)", "[contract][context]") {
    FakeVulkanScope scope;
    scope.fake().physical_devices[0].extensions = {VK_EXT_ROBUSTNESS_2_EXTENSION_NAME};
    ContextCreateInfo info;
    info.robust_buffer_access = false;
    auto ctx = createOnFake(info);
    REQUIRE(ctx);
    CHECK_FALSE(scope.fake().device_features.has(vk::Feature::RobustBufferAccess));
    CHECK_FALSE(scope.fake().device_features.has(vk::Feature::RobustBufferAccess2));
    CHECK_FALSE(lists(scope.fake().device_extensions, VK_EXT_ROBUSTNESS_2_EXTENSION_NAME));
    CHECK_FALSE(ContextAccess::device(**ctx).robust_buffer_access);
}

TEST_CASE("fake driver: optional features the device lacks are left off, not required", "[contract][context]") {
    FakeVulkanScope scope;
    auto& fake = scope.fake();
    vk::FeatureSet& f = fake.physical_devices[0].features;
    f.set(vk::Feature::ShaderFloat64, false);
    f.set(vk::Feature::RobustBufferAccess, false);
    f.set(vk::Feature::RobustBufferAccess2, false);
    fake.physical_devices[0].extensions = {VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME};
    auto ctx = createOnFake();
    REQUIRE(ctx);
    CHECK_FALSE(fake.device_features.has(vk::Feature::ShaderFloat64));
    CHECK_FALSE(fake.device_features.has(vk::Feature::RobustBufferAccess));
    CHECK_FALSE(ContextAccess::device(**ctx).shader_float64);
    CHECK_FALSE(ContextAccess::device(**ctx).robust_buffer_access);
    CHECK(lists(fake.device_extensions, VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME));
    CHECK(ContextAccess::device(**ctx).push_descriptor);
    CHECK(ContextAccess::device(**ctx).fns.vkCmdPushDescriptorSetKHR != nullptr);
}

TEST_CASE("error LoaderUnavailable: the loader lacks vkCreateInstance", "[contract][context][error]") {
    FakeVulkanScope scope;
    scope.fake().missing_entry_points = {"vkCreateInstance"};
    auto ctx = createOnFake();
    REQUIRE_FALSE(ctx);
    CHECK(ctx.error().code() == ErrorCode::LoaderUnavailable);
    CHECK_THAT(ctx.error().message(), Catch::Contains("vkCreateInstance"));
    CHECK(scope.fake().instances_alive == 0);
}

TEST_CASE("error LoaderUnavailable: an instance entry point is missing (the instance is destroyed)", "[contract][context][error]") {
    FakeVulkanScope scope;
    scope.fake().missing_entry_points = {"vkGetPhysicalDeviceFeatures2"};
    auto ctx = createOnFake();
    REQUIRE_FALSE(ctx);
    CHECK(ctx.error().code() == ErrorCode::LoaderUnavailable);
    CHECK_THAT(ctx.error().message(), Catch::Contains("vkGetPhysicalDeviceFeatures2"));
    CHECK(scope.fake().instances_alive == 0);
}

TEST_CASE("error NoSuitableDevice: the loader is older than Vulkan 1.3", "[contract][context][error]") {
    FakeVulkanScope scope;
    scope.fake().loader_version = VK_API_VERSION_1_2;
    auto ctx = createOnFake();
    REQUIRE_FALSE(ctx);
    CHECK(ctx.error().code() == ErrorCode::NoSuitableDevice);
    CHECK_THAT(ctx.error().message(), Catch::Contains("1.2") && Catch::Contains("1.3"));
}

TEST_CASE("error NoSuitableDevice: no physical device", "[contract][context][error]") {
    FakeVulkanScope scope;
    scope.fake().physical_devices.clear();
    auto ctx = createOnFake();
    REQUIRE_FALSE(ctx);
    CHECK(ctx.error().code() == ErrorCode::NoSuitableDevice);
    CHECK_THAT(ctx.error().message(), Catch::Contains("no physical device"));
    CHECK(scope.fake().instances_alive == 0);
}

TEST_CASE("error NoSuitableDevice: the message names every device and each missing requirement", "[contract][context][error]") {
    FakeVulkanScope scope;
    auto& fake = scope.fake();
    fake.physical_devices.resize(3);
    fake.physical_devices[0].name = "Old GPU";
    fake.physical_devices[0].api_version = VK_API_VERSION_1_2;
    fake.physical_devices[1].name = "Half GPU";
    fake.physical_devices[1].features.set(vk::Feature::HostQueryReset, false);
    fake.physical_devices[1].features.set(vk::Feature::Maintenance4, false);
    fake.physical_devices[2].name = "Headless GPU";
    fake.physical_devices[2].queue_families = {{VK_QUEUE_COMPUTE_BIT, 1, 64, {1, 1, 1}}};
    auto ctx = createOnFake();
    REQUIRE_FALSE(ctx);
    CHECK(ctx.error().code() == ErrorCode::NoSuitableDevice);
    const std::string& m = ctx.error().message();
    CHECK_THAT(m, Catch::Contains("Old GPU") && Catch::Contains("Vulkan 1.3 (device reports 1.2)"));
    CHECK_THAT(m, Catch::Contains("Half GPU (discrete GPU): lacks hostQueryReset maintenance4"));
    CHECK_THAT(m, Catch::Contains("Headless GPU") && Catch::Contains("graphics+compute queue"));
    CHECK(fake.instances_alive == 0);
    CHECK(fake.devices_alive == 0);
}

TEST_CASE("error NoSuitableDevice: no device matches the requested name", "[contract][context][error]") {
    FakeVulkanScope scope;
    ContextCreateInfo info;
    info.device_name = "no-such-gpu";
    auto ctx = createOnFake(info);
    REQUIRE_FALSE(ctx);
    CHECK(ctx.error().code() == ErrorCode::NoSuitableDevice);
    CHECK_THAT(ctx.error().message(), Catch::Contains("'no-such-gpu'") && Catch::Contains("Fake GPU"));
}

TEST_CASE("error UnsupportedFeature: validation requested but the layer is not installed", "[contract][context][error]") {
    FakeVulkanScope scope;
    ContextCreateInfo info;
    info.validation = true;
    auto ctx = createOnFake(info);
    REQUIRE_FALSE(ctx);
    CHECK(ctx.error().code() == ErrorCode::UnsupportedFeature);
    CHECK_THAT(ctx.error().message(), Catch::Contains("VK_LAYER_KHRONOS_validation"));
    // With the layer present, the same request succeeds.
    scope.fake().validation_layer_installed = true;
    CHECK(createOnFake(info));
}

TEST_CASE("error VulkanError: vkCreateInstance fails, the VkResult is kept", "[contract][context][error]") {
    FakeVulkanScope scope;
    scope.fake().create_instance_result = VK_ERROR_INCOMPATIBLE_DRIVER;
    auto ctx = createOnFake();
    REQUIRE_FALSE(ctx);
    CHECK(ctx.error().code() == ErrorCode::VulkanError);
    CHECK(ctx.error().vkResult() == VK_ERROR_INCOMPATIBLE_DRIVER);
    CHECK_THAT(ctx.error().message(), Catch::Contains("vkCreateInstance") && Catch::Contains("VK_ERROR_INCOMPATIBLE_DRIVER"));
}

TEST_CASE("error OutOfMemory: host memory at instance creation, device memory at device creation", "[contract][context][error]") {
    FakeVulkanScope scope;
    scope.fake().create_instance_result = VK_ERROR_OUT_OF_HOST_MEMORY;
    auto ctx = createOnFake();
    REQUIRE_FALSE(ctx);
    CHECK(ctx.error().code() == ErrorCode::OutOfMemory);
    CHECK(ctx.error().vkResult() == VK_ERROR_OUT_OF_HOST_MEMORY);

    scope.fake().create_instance_result = VK_SUCCESS;
    scope.fake().create_device_result = VK_ERROR_OUT_OF_DEVICE_MEMORY;
    ctx = createOnFake();
    REQUIRE_FALSE(ctx);
    CHECK(ctx.error().code() == ErrorCode::OutOfMemory);
    CHECK_THAT(ctx.error().message(), Catch::Contains("vkCreateDevice on Fake GPU"));
    CHECK(scope.fake().instances_alive == 0);
}

TEST_CASE("error DeviceLost: vkCreateDevice reports a lost device, the instance is destroyed", "[contract][context][error]") {
    FakeVulkanScope scope;
    scope.fake().create_device_result = VK_ERROR_DEVICE_LOST;
    auto ctx = createOnFake();
    REQUIRE_FALSE(ctx);
    CHECK(ctx.error().code() == ErrorCode::DeviceLost);
    CHECK(ctx.error().vkResult() == VK_ERROR_DEVICE_LOST);
    CHECK(scope.fake().instances_alive == 0);
    CHECK(scope.fake().devices_alive == 0);
}

TEST_CASE("error UnsupportedFeature: a device entry point is missing, the device is destroyed", "[contract][context][error]") {
    FakeVulkanScope scope;
    scope.fake().missing_entry_points = {"vkCmdWriteTimestamp2"};
    auto ctx = createOnFake();
    REQUIRE_FALSE(ctx);
    CHECK(ctx.error().code() == ErrorCode::UnsupportedFeature);
    CHECK_THAT(ctx.error().message(), Catch::Contains("vkCmdWriteTimestamp2"));
    CHECK(scope.fake().devices_alive == 0);
    CHECK(scope.fake().instances_alive == 0);
}

TEST_CASE("listDevices on the fake driver reports what each device lacks and destroys its instance", "[contract][context]") {
    FakeVulkanScope scope;
    auto& fake = scope.fake();
    fake.physical_devices.resize(2);
    fake.physical_devices[1].name = "Lean GPU";
    fake.physical_devices[1].features.set(vk::Feature::ShaderBufferInt64Atomics, false);
    fake.physical_devices[1].extensions = {VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME};
    auto devices = Context::listDevices(test::FakeVulkan::getInstanceProcAddr());
    REQUIRE(devices);
    REQUIRE(devices->size() == 2);
    CHECK((*devices)[0].missing.empty());
    CHECK_FALSE((*devices)[0].push_descriptor);
    CHECK((*devices)[0].shader_float64);
    CHECK((*devices)[1].missing == std::vector<std::string>{"shaderBufferInt64Atomics"});
    CHECK((*devices)[1].push_descriptor);
    CHECK(fake.instances_alive == 0);
}

TEST_CASE("Buffer::flush and invalidate pass their own range, widened to whole atoms", "[contract][resources]") {
    FakeVulkanScope scope;
    auto& fake = scope.fake();
    fake.physical_devices[0].coherent_memory = false;
    fake.physical_devices[0].non_coherent_atom_size = 64;
    auto ctx = createOnFake();
    REQUIRE(ctx);
    auto buffer = vk::Buffer::create(ContextAccess::device(**ctx), 1000, 0, vk::MemoryKind::Readback, "readback");
    REQUIRE(buffer);  // the fake allocates 1024 bytes for it
    REQUIRE(buffer->mapped() != nullptr);

    buffer->flush(300, 100);  // bytes [300, 400) -> atoms [256, 448)
    REQUIRE(fake.flushed.size() == 1);
    CHECK(fake.flushed[0].offset == 256);
    CHECK(fake.flushed[0].size == 192);

    buffer->flush(0, 64);  // exactly one atom
    CHECK(fake.flushed.back().offset == 0);
    CHECK(fake.flushed.back().size == 64);

    buffer->flush(900, 100);  // reaches the end of the buffer: to the end of the allocation
    CHECK(fake.flushed.back().offset == 896);
    CHECK(fake.flushed.back().size == VK_WHOLE_SIZE);

    buffer->flush();  // everything
    CHECK(fake.flushed.back().offset == 0);
    CHECK(fake.flushed.back().size == VK_WHOLE_SIZE);

    buffer->invalidate(130, 10);  // [130, 140) -> [128, 192)
    REQUIRE(fake.invalidated.size() == 1);
    CHECK(fake.invalidated[0].offset == 128);
    CHECK(fake.invalidated[0].size == 64);

    buffer->reset();
    CHECK(fake.buffers_alive == 0);
    CHECK(fake.allocations_alive == 0);
}

TEST_CASE("Buffer::flush is a no-op on coherent memory", "[contract][resources]") {
    FakeVulkanScope scope;
    auto ctx = createOnFake();
    REQUIRE(ctx);
    auto buffer = vk::Buffer::create(ContextAccess::device(**ctx), 256, 0, vk::MemoryKind::Upload, "upload");
    REQUIRE(buffer);
    buffer->flush(0, 16);
    buffer->invalidate(0, 16);
    CHECK(scope.fake().flushed.empty());
    CHECK(scope.fake().invalidated.empty());
}

TEST_CASE("Context::deviceMemoryInUse counts every allocation vkcollide holds, until it is freed", "[contract][resources]") {
    FakeVulkanScope scope;
    auto ctx = createOnFake();
    REQUIRE(ctx);
    CHECK((*ctx)->deviceMemoryInUse() == 0);
    auto a = vk::Buffer::create(ContextAccess::device(**ctx), 1000, 0, vk::MemoryKind::DeviceLocal, "a");  // 1024 allocated
    auto b = vk::Buffer::create(ContextAccess::device(**ctx), 100, 0, vk::MemoryKind::Upload, "b");        // 256 allocated
    REQUIRE(a);
    REQUIRE(b);
    CHECK((*ctx)->deviceMemoryInUse() == 1024 + 256);
    vk::Buffer moved = std::move(*a);  // a move hands the allocation over, it is counted once
    CHECK((*ctx)->deviceMemoryInUse() == 1024 + 256);
    moved.reset();
    CHECK((*ctx)->deviceMemoryInUse() == 256);
    b->reset();
    CHECK((*ctx)->deviceMemoryInUse() == 0);
}
