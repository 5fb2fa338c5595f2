// What an engine lends besides its device, on the fake driver (no GPU): queue hooks around
// every submission, device memory from the engine's allocator, allocation callbacks on every
// object, the pipeline cache every pipeline goes through, and resources that outlive the
// Context.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "api/context_access.hpp"
#include "support/error_text.hpp"
#include "vk/fake_engine.hpp"
#include "vk/resources.hpp"
#include "vk/semaphore.hpp"

using namespace vkcollide;
using test::FakeVulkanScope;

namespace {

// Any words do for the fake: it never reads the SPIR-V.
constexpr std::uint32_t kFakeSpirv[] = {0x07230203u, 0x00010000u, 0u, 1u, 0u};

// Pipelines of one device made from the same program and state are one (Device::pipelines):
// `push_bytes` makes them differ where a test needs two.
vk::Pipeline makePipeline(vk::Device& device, const char* name, std::uint32_t push_bytes = 16) {
    auto p = vk::Pipeline::createCompute(device, kFakeSpirv, {}, push_bytes, name);
    REQUIRE(p);
    return std::move(*p);
}

using test::mentions;

// VkAllocationCallbacks that count what is outstanding (the fake never reallocates).
struct CountingCallbacks {
    int allocations = 0;
    int frees = 0;
    VkAllocationCallbacks callbacks{};

    CountingCallbacks() {
        callbacks.pUserData = this;
        callbacks.pfnAllocation = [](void* user, std::size_t size, std::size_t alignment, VkSystemAllocationScope) -> void* {
            ++static_cast<CountingCallbacks*>(user)->allocations;
            void* p = nullptr;
            return posix_memalign(&p, std::max(alignment, sizeof(void*)), size ? size : 1) == 0 ? p : nullptr;
        };
        callbacks.pfnReallocation = [](void*, void*, std::size_t, std::size_t, VkSystemAllocationScope) -> void* { return nullptr; };
        callbacks.pfnFree = [](void* user, void* memory) {
            if (!memory) return;
            ++static_cast<CountingCallbacks*>(user)->frees;
            std::free(memory);
        };
    }
    int outstanding() const { return allocations - frees; }
};

// The engine's allocator: ranges of one arena of host memory standing for its VkDeviceMemory
// (the fake binds any handle). Records every request and every free.
struct EngineAllocator {
    std::vector<std::byte> arena = std::vector<std::byte>(1 << 20);
    VkDeviceSize next = 8;  // starts off zero so an ignored offset would show
    std::map<std::uint64_t, DeviceMemoryRequest> live;
    std::vector<DeviceMemoryRequest> requests;
    std::vector<VkDeviceSize> offsets;
    int frees = 0;
    std::uint64_t next_user = 1;
    VkResult fail_with = VK_SUCCESS;
    VkDeviceSize misalign = 0;  // added to the offset (a broken allocator)
    bool forget_pointer = false;

    DeviceMemoryHooks hooks() {
        DeviceMemoryHooks h;
        h.allocate = [this](const DeviceMemoryRequest& r, DeviceMemoryBlock& out) {
            if (fail_with != VK_SUCCESS) return fail_with;
            const VkDeviceSize align = r.requirements.alignment;
            const VkDeviceSize offset = (next + align - 1) / align * align + misalign;
            next = offset + r.requirements.size;
            out.memory = reinterpret_cast<VkDeviceMemory>(std::uintptr_t{0xA7E4A});
            out.offset = offset;
            out.mapped = r.host_access && !forget_pointer ? arena.data() + offset : nullptr;
            out.user = next_user++;
            requests.push_back(r);
            requests.back().name = "";  // valid only during the call
            offsets.push_back(offset);
            live[out.user] = requests.back();
            return VK_SUCCESS;
        };
        h.free = [this](const DeviceMemoryBlock& block) {
            ++frees;
            live.erase(block.user);
        };
        return h;
    }
};

}  // namespace

TEST_CASE("queue hooks: lock, the engine's submit and unlock around every submission", "[contract][hooks]") {
    FakeVulkanScope scope;
    test::FakeEngineDevice engine;
    std::vector<std::string> log;
    const auto real_submit = reinterpret_cast<PFN_vkQueueSubmit2>(
        test::FakeVulkan::getInstanceProcAddr()(scope.fake().instanceHandle(), "vkQueueSubmit2"));
    AdoptedDevice lent = engine.lend(scope.fake());
    lent.queue_hooks.lock = [&] { log.push_back("lock"); };
    lent.queue_hooks.unlock = [&] { log.push_back("unlock"); };
    lent.queue_hooks.submit = [&](VkQueue queue, std::span<const VkSubmitInfo2> submits, VkFence fence) {
        log.push_back("submit " + std::to_string(submits.size()));
        CHECK(queue == scope.fake().queueHandle());
        return real_submit(queue, static_cast<std::uint32_t>(submits.size()), submits.data(), fence);
    };
    auto ctx = Context::adopt(lent, [](MessageSeverity, std::string_view) {});
    REQUIRE(ctx);
    auto s = vk::Submission::create(ContextAccess::device(**ctx));
    REQUIRE(s);
    for (int i = 0; i < 2; ++i) {
        REQUIRE(s->begin());
        REQUIRE(s->submit());
        REQUIRE(s->wait());
    }
    CHECK(log == std::vector<std::string>{"lock", "submit 1", "unlock", "lock", "submit 1", "unlock"});
    CHECK(scope.fake().submits.size() == 2);  // each went through the engine's path to the driver
}

TEST_CASE("queue hooks come as a lock/unlock pair, and a hook that throws fails the submission, not the process",
          "[contract][hooks][error]") {
    FakeVulkanScope scope;
    test::FakeEngineDevice engine;
    AdoptedDevice half = engine.lend(scope.fake());
    half.queue_hooks.lock = [] {};
    auto refused = Context::adopt(half);
    REQUIRE_FALSE(refused);
    CHECK(refused.error().code() == ErrorCode::InvalidArgument);
    CHECK(mentions(refused.error(), "lock and unlock come as a pair"));

    AdoptedDevice throwing = engine.lend(scope.fake());
    int unlocks = 0;
    throwing.queue_hooks.lock = [] {};
    throwing.queue_hooks.unlock = [&] { ++unlocks; };
    throwing.queue_hooks.submit = [](VkQueue, std::span<const VkSubmitInfo2>, VkFence) -> VkResult {
        throw std::runtime_error("engine queue closed");
    };
    std::vector<std::string> messages;
    auto ctx = Context::adopt(throwing, [&](MessageSeverity, std::string_view m) { messages.emplace_back(m); });
    REQUIRE(ctx);
    auto s = vk::Submission::create(ContextAccess::device(**ctx));
    REQUIRE(s);
    REQUIRE(s->begin());
    auto r = s->submit();
    REQUIRE_FALSE(r);
    CHECK(r.error().vkResult() == VK_ERROR_UNKNOWN);
    CHECK(unlocks == 1);  // the lock is given back
    CHECK_FALSE(s->pending());
    REQUIRE(messages.size() == 1);
    CHECK(mentions(Error(ErrorCode::VulkanError, messages[0]), "engine queue closed"));
}

TEST_CASE("memory hooks: every buffer and image is bound in the engine's memory, every block is given back",
          "[contract][hooks][memory]") {
    FakeVulkanScope scope;
    EngineAllocator engine;
    ContextCreateInfo info;
    info.memory_hooks = engine.hooks();
    auto ctx = test::createFakeContext(info);
    vk::Device& dev = ContextAccess::device(*ctx);
    {
        auto upload = vk::Buffer::create(dev, 1000, 0, vk::MemoryKind::Upload, "upload");
        auto readback = vk::Buffer::create(dev, 300, 0, vk::MemoryKind::Readback, "readback");
        auto local = vk::Buffer::create(dev, 5000, 0, vk::MemoryKind::DeviceLocal, "local");
        auto image = vk::Image::create(dev, {VK_FORMAT_R32_UINT, 16, 16, 1, VK_IMAGE_USAGE_STORAGE_BIT}, "img");
        REQUIRE(upload);
        REQUIRE(readback);
        REQUIRE(local);
        REQUIRE(image);
        CHECK(scope.fake().allocations_alive == 0);  // no vkAllocateMemory of vkcollide's own
        REQUIRE(engine.requests.size() == 4);
        CHECK(engine.live.size() == 4);
        // Bound where the engine said, mapped through the engine's pointer.
        CHECK(scope.fake().bind_offsets == engine.offsets);
        CHECK(upload->memoryOffset() == engine.offsets[0]);
        CHECK(upload->mapped() == engine.arena.data() + engine.offsets[0]);
        CHECK(readback->mapped() == engine.arena.data() + engine.offsets[1]);
        std::memset(upload->mapped(), 0x5A, 1000);  // the range is really ours
        // Buffers need device addresses, images do not; the image says it is one.
        CHECK(engine.requests[0].device_address);
        CHECK(engine.requests[0].host_access);
        CHECK_FALSE(engine.requests[3].device_address);
        CHECK(engine.requests[3].image);
        std::uint64_t requested = 0;
        for (const auto& r : engine.requests) requested += r.requirements.size;
        CHECK(ctx->deviceMemoryInUse() == requested);
    }
    CHECK(engine.frees == 4);
    CHECK(engine.live.empty());
    CHECK(ctx->deviceMemoryInUse() == 0);
}

TEST_CASE("memory hooks on non-coherent memory: whole atoms, flushes stay inside the engine's range", "[contract][hooks][memory]") {
    FakeVulkanScope scope;
    scope.fake().physical_devices[0].coherent_memory = false;
    scope.fake().physical_devices[0].non_coherent_atom_size = 64;
    EngineAllocator engine;
    ContextCreateInfo info;
    info.memory_hooks = engine.hooks();
    auto ctx = test::createFakeContext(info);
    auto buffer = vk::Buffer::create(ContextAccess::device(*ctx), 1000, 0, vk::MemoryKind::Readback, "readback");
    REQUIRE(buffer);
    REQUIRE(engine.requests.size() == 1);
    const DeviceMemoryRequest& r = engine.requests[0];
    CHECK(r.requirements.alignment % 64 == 0);
    CHECK(r.requirements.size % 64 == 0);
    const VkDeviceSize base = engine.offsets[0];
    buffer->flush();  // everything: the whole range, never VK_WHOLE_SIZE (the memory is not ours)
    REQUIRE(scope.fake().flushed.size() == 1);
    CHECK(scope.fake().flushed[0].offset == base);
    CHECK(scope.fake().flushed[0].size == r.requirements.size);
    buffer->invalidate(300, 100);  // [300, 400) -> [256, 448) of the range
    CHECK(scope.fake().invalidated.back().offset == base + 256);
    CHECK(scope.fake().invalidated.back().size == 192);
}

TEST_CASE("memory hooks: a failed or broken allocation is refused by name, and a broken block is given back",
          "[contract][hooks][memory][error]") {
    FakeVulkanScope scope;
    EngineAllocator engine;
    ContextCreateInfo info;
    info.memory_hooks = engine.hooks();
    auto ctx = test::createFakeContext(info);
    vk::Device& dev = ContextAccess::device(*ctx);

    engine.fail_with = VK_ERROR_OUT_OF_DEVICE_MEMORY;
    auto oom = vk::Buffer::create(dev, 256, 0, vk::MemoryKind::DeviceLocal, "big");
    REQUIRE_FALSE(oom);
    CHECK(oom.error().code() == ErrorCode::OutOfMemory);
    CHECK(mentions(oom.error(), "DeviceMemoryHooks::allocate of 256 bytes for 'big'"));
    engine.fail_with = VK_SUCCESS;

    engine.misalign = 4;
    auto misaligned = vk::Buffer::create(dev, 256, 0, vk::MemoryKind::DeviceLocal, "odd");
    REQUIRE_FALSE(misaligned);
    CHECK(misaligned.error().code() == ErrorCode::InvalidArgument);
    CHECK(mentions(misaligned.error(), "'odd' returned offset"));
    CHECK(mentions(misaligned.error(), "not a multiple of the requested alignment 256"));
    engine.misalign = 0;

    engine.forget_pointer = true;
    auto unmapped = vk::Buffer::create(dev, 256, 0, vk::MemoryKind::Upload, "up");
    REQUIRE_FALSE(unmapped);
    CHECK(mentions(unmapped.error(), "no host pointer"));

    CHECK(engine.frees == 2);  // both broken blocks went back to the engine
    CHECK(engine.live.empty());
    CHECK(ctx->deviceMemoryInUse() == 0);
    CHECK(scope.fake().buffers_alive == 0);

    ContextCreateInfo half;
    half.memory_hooks.allocate = [](const DeviceMemoryRequest&, DeviceMemoryBlock&) { return VK_SUCCESS; };
    half.get_instance_proc_addr = test::FakeVulkan::getInstanceProcAddr();
    auto refused = Context::create(half);
    REQUIRE_FALSE(refused);
    CHECK(refused.error().code() == ErrorCode::InvalidArgument);
    CHECK(mentions(refused.error(), "ContextCreateInfo::memory_hooks: allocate and free come as a pair"));
    CHECK(scope.fake().instances_alive == 1);  // only the first Context's
}

TEST_CASE("allocation callbacks without all three functions are refused by name", "[contract][hooks][error]") {
    FakeVulkanScope scope;
    CountingCallbacks counting;
    VkAllocationCallbacks broken = counting.callbacks;
    broken.pfnReallocation = nullptr;
    ContextCreateInfo info;
    info.get_instance_proc_addr = test::FakeVulkan::getInstanceProcAddr();
    info.allocation_callbacks = &broken;
    auto created = Context::create(info);
    REQUIRE_FALSE(created);
    CHECK(created.error().code() == ErrorCode::InvalidArgument);
    CHECK(mentions(created.error(), "ContextCreateInfo::allocation_callbacks"));
    test::FakeEngineDevice engine;
    AdoptedDevice lent = engine.lend(scope.fake());
    lent.allocation_callbacks = &broken;
    auto adopted = Context::adopt(lent);
    REQUIRE_FALSE(adopted);
    CHECK(mentions(adopted.error(), "AdoptedDevice::allocation_callbacks"));
    CHECK(counting.allocations == 0);
    CHECK(scope.fake().instances_alive == 0);
}

TEST_CASE("allocation callbacks reach every object vkcollide creates, and every destruction", "[contract][hooks]") {
    FakeVulkanScope scope;
    CountingCallbacks counting;
    {
        ContextCreateInfo info;
        info.allocation_callbacks = &counting.callbacks;
        auto ctx = test::createFakeContext(info);
        vk::Device& dev = ContextAccess::device(*ctx);
        auto buffer = vk::Buffer::create(dev, 1024, 0, vk::MemoryKind::Upload, "b");
        auto image = vk::Image::create(dev, {VK_FORMAT_R32_UINT, 8, 8, 2, VK_IMAGE_USAGE_STORAGE_BIT}, "i");
        auto semaphore = vk::Semaphore::createTimeline(dev, 0, "t");
        REQUIRE(buffer);
        REQUIRE(image);
        REQUIRE(semaphore);
        vk::Pipeline pipeline = makePipeline(dev, "p");
        auto s = vk::Submission::create(dev);
        REQUIRE(s);
        REQUIRE(s->begin());
        REQUIRE(s->submit());
        REQUIRE(s->wait());
        // instance, device, pipeline cache, buffer + memory, image + memory + 3 views,
        // semaphore, pipeline + layout (the module is gone already), pool + fence
        CHECK(counting.outstanding() >= 15);
    }
    CHECK(counting.allocations > 15);
    CHECK(counting.outstanding() == 0);
    CHECK(scope.fake().allocator_mismatches.empty());
    CHECK(scope.fake().devices_alive == 0);
}

TEST_CASE("every pipeline goes through the engine's pipeline cache, and the Context creates none then", "[contract][hooks][cache]") {
    FakeVulkanScope scope;
    test::FakeEngineDevice engine;
    AdoptedDevice lent = engine.lend(scope.fake());
    lent.pipeline_cache = reinterpret_cast<VkPipelineCache>(std::uintptr_t{0xCAC4E});
    auto ctx = Context::adopt(lent, [](MessageSeverity, std::string_view) {});
    REQUIRE(ctx);
    CHECK(scope.fake().pipeline_caches_alive == 0);
    {
        vk::Pipeline a = makePipeline(ContextAccess::device(**ctx), "a");
        vk::Pipeline b = makePipeline(ContextAccess::device(**ctx), "b", 32);
    }
    REQUIRE(scope.fake().pipelines_cache_used.size() == 2);
    for (VkPipelineCache used : scope.fake().pipelines_cache_used) CHECK(used == lent.pipeline_cache);
    ctx->reset();
    CHECK(scope.fake().pipeline_caches_alive == 0);  // borrowed, never destroyed
}

TEST_CASE("the Context's own pipeline cache: used by every pipeline, saved and loaded again, stale data ignored",
          "[contract][hooks][cache]") {
    FakeVulkanScope scope;
    std::vector<std::byte> saved;
    {
        auto ctx = test::createFakeContext();
        CHECK(scope.fake().pipeline_caches_alive == 1);
        CHECK(scope.fake().last_pipeline_cache_initial_size == 0);
        const VkPipelineCache own = ContextAccess::device(*ctx).pipeline_cache;
        REQUIRE(own != VK_NULL_HANDLE);
        vk::Pipeline a = makePipeline(ContextAccess::device(*ctx), "a");
        vk::Pipeline b = makePipeline(ContextAccess::device(*ctx), "b", 32);
        CHECK(scope.fake().pipelines_cache_used == std::vector<VkPipelineCache>{own, own});
        auto data = ctx->pipelineCacheData();
        REQUIRE(data);
        saved = *data;
        CHECK(saved.size() == sizeof(VkPipelineCacheHeaderVersionOne) + 2);
    }
    CHECK(scope.fake().pipeline_caches_alive == 0);

    ContextCreateInfo info;
    info.pipeline_cache_data = saved;
    std::vector<std::string> log;
    {
        auto ctx = test::createFakeContext(info, &log);
        CHECK(scope.fake().last_pipeline_cache_initial_size == saved.size());
        CHECK(log.empty());
    }
    // Data from another device (the header's deviceID differs): ignored, said so.
    std::vector<std::byte> other = saved;
    other[12] = std::byte{99};
    info.pipeline_cache_data = other;
    auto ctx = test::createFakeContext(info, &log);
    CHECK(scope.fake().last_pipeline_cache_initial_size == 0);
    REQUIRE(log.size() == 1);
    CHECK(log[0].find("another device or driver") != std::string::npos);
    std::vector<std::byte> truncated(saved.begin(), saved.begin() + 10);
    CHECK_FALSE(vk::pipelineCacheDataMatches(ContextAccess::device(*ctx), truncated));
    CHECK(vk::pipelineCacheDataMatches(ContextAccess::device(*ctx), saved));
}

TEST_CASE("a Context destroyed before its resources: they keep the device alive, the last one destroys it",
          "[contract][lifetime]") {
    FakeVulkanScope scope;
    scope.fake().gpu_finishes_at_once = false;
    CountingCallbacks counting;
    ContextCreateInfo info;
    info.allocation_callbacks = &counting.callbacks;
    auto ctx = test::createFakeContext(info);
    vk::Device& dev = ContextAccess::device(*ctx);
    auto buffer = vk::Buffer::create(dev, 1024, 0, vk::MemoryKind::Upload, "b");
    auto image = vk::Image::create(dev, {VK_FORMAT_R32_UINT, 8, 8, 1, VK_IMAGE_USAGE_STORAGE_BIT}, "i");
    auto semaphore = vk::Semaphore::createTimeline(dev, 0, "t");
    auto s = vk::Submission::create(dev);
    REQUIRE(buffer);
    REQUIRE(image);
    REQUIRE(semaphore);
    REQUIRE(s);
    vk::Pipeline pipeline = makePipeline(dev, "p");
    REQUIRE(s->begin());
    REQUIRE(s->submit());  // still running when the Context goes

    ctx.reset();
    CHECK(scope.fake().devices_alive == 1);
    std::memset(buffer->mapped(), 1, 1024);  // still valid memory
    auto p = s->poll();
    REQUIRE(p);
    CHECK(*p == vk::Completion::NotYet);

    buffer->reset();  // reset keeps the device: a raw Device* next to it stays valid
    image = vk::Image{};
    pipeline = vk::Pipeline{};
    semaphore = vk::Semaphore{};
    CHECK(scope.fake().devices_alive == 1);
    *buffer = vk::Buffer{};
    CHECK(scope.fake().devices_alive == 1);
    *s = vk::Submission{};  // the last one: waits for its work, then the device goes
    CHECK(scope.fake().unbounded_waits == 1);
    CHECK(scope.fake().devices_alive == 0);
    CHECK(scope.fake().instances_alive == 0);
    CHECK(scope.fake().allocator_mismatches.empty());
    CHECK(counting.outstanding() == 0);
}
