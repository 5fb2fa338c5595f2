// checkEngineBuffer on a fake driver (no GPU): each rule an engine buffer must meet is
// refused by name, in the documented order, before its device address is asked for.
#include <catch2/catch.hpp>

#include "api/context_access.hpp"
#include "vk/engine_buffer.hpp"
#include "vk/fake_vulkan.hpp"
#include "vk/resources.hpp"

using namespace vkcollide;

namespace {

struct FakeEngine {
    test::FakeVulkanScope scope;
    std::unique_ptr<Context> context;
    vk::Buffer buffer;  // plays the engine's buffer: 1000 bytes (the fake's requirement: 1024)

    FakeEngine() {
        ContextCreateInfo info;
        info.get_instance_proc_addr = test::FakeVulkan::getInstanceProcAddr();
        auto ctx = Context::create(info);
        REQUIRE(ctx);
        context = std::move(*ctx);
        auto b = vk::Buffer::create(ContextAccess::device(*context), 1000, 0, vk::MemoryKind::DeviceLocal, "engine vertices");
        REQUIRE(b);
        buffer = std::move(*b);
    }

    vk::EngineBufferUse use() const {
        vk::EngineBufferUse u;
        u.buffer = buffer.handle();
        u.declared_usage = VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT | VK_BUFFER_USAGE_VERTEX_BUFFER_BIT;
        u.declared_size = 1000;
        u.offset = 16;
        u.bytes = 12 * 80;
        return u;
    }
};

}  // namespace

TEST_CASE("checkEngineBuffer returns the address of the first byte read", "[contract][engine-buffer]") {
    FakeEngine e;
    auto address = vk::checkEngineBuffer(ContextAccess::device(*e.context), e.use(), "object 0 ('ball'): vertex buffer");
    REQUIRE(address);
    CHECK(*address == e.buffer.address() + 16);
}

TEST_CASE("checkEngineBuffer refuses a buffer declared without SHADER_DEVICE_ADDRESS usage", "[contract][engine-buffer][error]") {
    FakeEngine e;
    vk::EngineBufferUse u = e.use();
    u.declared_usage = VK_BUFFER_USAGE_VERTEX_BUFFER_BIT | VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    auto address = vk::checkEngineBuffer(ContextAccess::device(*e.context), u, "object 0 ('ball'): vertex buffer");
    REQUIRE_FALSE(address);
    CHECK(address.error().code() == ErrorCode::InvalidArgument);
    CHECK_THAT(address.error().message(), Catch::StartsWith("object 0 ('ball'): vertex buffer was not declared with "
                                                            "VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT"));
    u.declared_usage = 0;  // nothing declared at all
    CHECK_FALSE(vk::checkEngineBuffer(ContextAccess::device(*e.context), u, "vertex buffer"));
}

TEST_CASE("checkEngineBuffer refuses a null buffer, a misaligned offset and an empty range", "[contract][engine-buffer][error]") {
    FakeEngine e;
    vk::EngineBufferUse u = e.use();
    u.buffer = VK_NULL_HANDLE;
    auto r = vk::checkEngineBuffer(ContextAccess::device(*e.context), u, "index buffer");
    REQUIRE_FALSE(r);
    CHECK(r.error().message() == "index buffer is VK_NULL_HANDLE");

    u = e.use();
    u.offset = 6;
    r = vk::checkEngineBuffer(ContextAccess::device(*e.context), u, "index buffer");
    REQUIRE_FALSE(r);
    CHECK(r.error().code() == ErrorCode::InvalidArgument);
    CHECK_THAT(r.error().message(), Catch::Contains("offset 6 is not a multiple of 4"));

    u = e.use();
    u.bytes = 0;
    r = vk::checkEngineBuffer(ContextAccess::device(*e.context), u, "index buffer");
    REQUIRE_FALSE(r);
    CHECK_THAT(r.error().message(), Catch::Contains("0 bytes"));
}

TEST_CASE("checkEngineBuffer refuses reads past the declared size, and a size the buffer cannot have",
          "[contract][engine-buffer][error]") {
    FakeEngine e;
    vk::EngineBufferUse u = e.use();
    u.bytes = 1000 - 16 + 4;
    auto r = vk::checkEngineBuffer(ContextAccess::device(*e.context), u, "vertex buffer");
    REQUIRE_FALSE(r);
    CHECK(r.error().code() == ErrorCode::BufferTooSmall);
    CHECK_THAT(r.error().message(), Catch::Contains("of 1000 bytes is smaller than the 16 + 988 bytes"));

    // An offset beyond the declared size must not wrap around in the check.
    u = e.use();
    u.offset = 2000;
    r = vk::checkEngineBuffer(ContextAccess::device(*e.context), u, "vertex buffer");
    REQUIRE_FALSE(r);
    CHECK(r.error().code() == ErrorCode::BufferTooSmall);

    // Declared larger than vkGetBufferMemoryRequirements allows (1024 for this buffer).
    u = e.use();
    u.declared_size = 4096;
    r = vk::checkEngineBuffer(ContextAccess::device(*e.context), u, "vertex buffer");
    REQUIRE_FALSE(r);
    CHECK(r.error().code() == ErrorCode::BufferTooSmall);
    CHECK_THAT(r.error().message(), Catch::Contains("declared as 4096 bytes but holds at most 1024"));
}
