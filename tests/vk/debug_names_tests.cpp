// Names for capture tools on the fake driver (no GPU): with VK_EXT_debug_utils on the
// instance every object the device layer creates is named "vkcollide: <what>"; without it
// (not offered, turned off, or not listed by an adopting engine) vkcollide makes no
// debug-utils call at all. Labels of recorded passes need a device that runs them:
// tests/gpu/debug_names_gpu_tests.cpp.
#include <catch2/catch.hpp>

#include <algorithm>
#include <string>
#include <vector>

#include "api/context_access.hpp"
#include "vk/fake_engine.hpp"
#include "vk/resources.hpp"
#include "vk/semaphore.hpp"

using namespace vkcollide;
using test::FakeVulkan;
using test::FakeVulkanScope;

namespace {

// Any words do for the fake: it never reads the SPIR-V.
constexpr std::uint32_t kFakeSpirv[] = {0x07230203u, 0x00010000u, 0u, 1u, 0u};

// One of each kind of object the device layer makes, as the library's own code makes them.
void makeOneOfEach(vk::Device& device) {
    auto buffer = vk::Buffer::create(device, 1024, 0, vk::MemoryKind::DeviceLocal, "ray-image");
    REQUIRE(buffer);
    auto image = vk::Image::create(device, {VK_FORMAT_R32_UINT, 8, 8, 2, VK_IMAGE_USAGE_STORAGE_BIT}, "depth-1");
    REQUIRE(image);
    auto pipeline = vk::Pipeline::createCompute(device, kFakeSpirv, {}, 16, "cells-sweep");
    REQUIRE(pipeline);
    auto submission = vk::Submission::create(device, "graph");
    REQUIRE(submission);
    auto semaphore = vk::Semaphore::createTimeline(device, 0, "timeline");
    REQUIRE(semaphore);
}

bool enabledDebugUtils(const FakeVulkan& fake) {
    const auto& e = fake.enabled_instance_extensions;
    return std::find(e.begin(), e.end(), VK_EXT_DEBUG_UTILS_EXTENSION_NAME) != e.end();
}

// Every object created since `from` has a name, and every name starts with "vkcollide: ".
void requireAllNamed(const FakeVulkan& fake, std::size_t from = 0) {
    REQUIRE(fake.created_objects.size() > from);
    for (std::size_t i = from; i < fake.created_objects.size(); ++i) {
        const auto& made = fake.created_objects[i];
        INFO("object type " << made.type << ", handle " << made.handle);
        auto it = fake.object_names.find(made.handle);
        REQUIRE(it != fake.object_names.end());
        CHECK(it->second.rfind("vkcollide: ", 0) == 0);
    }
}

std::string nameOf(const FakeVulkan& fake, VkObjectType type) {
    for (const auto& made : fake.created_objects)
        if (made.type == type) return fake.object_names.count(made.handle) ? fake.object_names.at(made.handle) : "";
    return "(none created)";
}

}  // namespace

TEST_CASE("with VK_EXT_debug_utils offered, Context::create enables it and names every object it creates", "[vk][debug-names]") {
    FakeVulkanScope scope;
    FakeVulkan& fake = scope.fake();
    fake.instance_extensions = {VK_EXT_DEBUG_UTILS_EXTENSION_NAME};
    auto ctx = test::createFakeContext();
    CHECK(enabledDebugUtils(fake));
    REQUIRE(ContextAccess::device(*ctx).debug_utils);
    makeOneOfEach(ContextAccess::device(*ctx));
    requireAllNamed(fake);
    // Each by what it is to vkcollide: the buffer-table row, the program, the submission.
    CHECK(nameOf(fake, VK_OBJECT_TYPE_BUFFER) == "vkcollide: ray-image");
    CHECK(nameOf(fake, VK_OBJECT_TYPE_DEVICE_MEMORY) == "vkcollide: ray-image memory");
    CHECK(nameOf(fake, VK_OBJECT_TYPE_IMAGE) == "vkcollide: depth-1");
    CHECK(nameOf(fake, VK_OBJECT_TYPE_PIPELINE) == "vkcollide: cells-sweep");
    CHECK(nameOf(fake, VK_OBJECT_TYPE_PIPELINE_LAYOUT) == "vkcollide: cells-sweep layout");
    CHECK(nameOf(fake, VK_OBJECT_TYPE_SHADER_MODULE) == "vkcollide: cells-sweep shader");
    CHECK(nameOf(fake, VK_OBJECT_TYPE_PIPELINE_CACHE) == "vkcollide: pipeline cache");
    CHECK(nameOf(fake, VK_OBJECT_TYPE_COMMAND_POOL) == "vkcollide: graph pool");
    CHECK(nameOf(fake, VK_OBJECT_TYPE_COMMAND_BUFFER) == "vkcollide: graph");
    CHECK(nameOf(fake, VK_OBJECT_TYPE_FENCE) == "vkcollide: graph fence");
    CHECK(nameOf(fake, VK_OBJECT_TYPE_SEMAPHORE) == "vkcollide: timeline");
    CHECK(fake.labels.empty());  // nothing was recorded
}

TEST_CASE("without VK_EXT_debug_utils, or with names turned off, vkcollide makes no debug-utils call", "[vk][debug-names]") {
    FakeVulkanScope scope;
    FakeVulkan& fake = scope.fake();
    ContextCreateInfo info;
    SECTION("the loader does not offer it") {}
    SECTION("offered, but ContextCreateInfo::debug_names is false") {
        fake.instance_extensions = {VK_EXT_DEBUG_UTILS_EXTENSION_NAME};
        info.debug_names = false;
    }
    auto ctx = test::createFakeContext(info);
    CHECK_FALSE(enabledDebugUtils(fake));
    CHECK_FALSE(ContextAccess::device(*ctx).debug_utils);
    makeOneOfEach(ContextAccess::device(*ctx));
    CHECK(fake.debug_utils_calls == 0);
    CHECK(ContextAccess::device(*ctx).fns.vkCmdBeginDebugUtilsLabelEXT == nullptr);
}

TEST_CASE("validation turns debug utils on, and names still follow ContextCreateInfo::debug_names", "[vk][debug-names]") {
    FakeVulkanScope scope;
    FakeVulkan& fake = scope.fake();
    fake.validation_layer_installed = true;
    ContextCreateInfo info;
    info.validation = true;
    info.debug_names = GENERATE(true, false);
    auto ctx = test::createFakeContext(info);
    CHECK(enabledDebugUtils(fake));  // the messages need it either way
    CHECK(ContextAccess::device(*ctx).debug_utils == info.debug_names);
    makeOneOfEach(ContextAccess::device(*ctx));
    if (info.debug_names) requireAllNamed(fake);
    else CHECK(fake.debug_utils_calls == 0);
}

TEST_CASE("an adopted device gets names only where the engine lists VK_EXT_debug_utils among its instance extensions", "[vk][debug-names]") {
    FakeVulkanScope scope;
    FakeVulkan& fake = scope.fake();
    test::FakeEngineDevice engine;
    AdoptedDevice lent = engine.lend(fake);
    const char* const listed[] = {VK_KHR_SURFACE_EXTENSION_NAME, VK_EXT_DEBUG_UTILS_EXTENSION_NAME};
    const bool lists = GENERATE(true, false);
    if (lists) lent.enabled_instance_extensions = listed;
    auto ctx = Context::adopt(lent);
    REQUIRE(ctx);
    CHECK(ContextAccess::device(**ctx).debug_utils == lists);
    const std::size_t before = fake.created_objects.size();  // the engine's own objects are not vkcollide's
    makeOneOfEach(ContextAccess::device(**ctx));
    if (lists) requireAllNamed(fake, before);
    else CHECK(fake.debug_utils_calls == 0);
}
