// What an engine lends besides its device, with a whole detection on the device and
// validation (with synchronization validation) on: every submission through the engine's
// queue hooks, all device memory from the engine's allocator, host allocations through its
// callbacks, pipelines through its pipeline cache; a Context destroyed while a detection is
// in flight; two worlds on one Context on two threads.
#include <catch2/catch.hpp>

#include <atomic>
#include <cstdlib>
#include <cstring>
#include <map>
#include <mutex>
#include <set>
#include <thread>

#include "api/context_access.hpp"
#include "support/gpu_fixture.hpp"
#include "support/test_scenes.hpp"
#include "vk/resources.hpp"
#include "vkcollide/world.hpp"

using namespace vkcollide;
using namespace vkcollide::test;

namespace {

// Validation on for a Context of the test's own, its warnings and errors kept: check() at
// the end reports them and fails on any.
struct MessageLog {
    std::mutex mutex;
    std::vector<std::string> lines;
    ContextCreateInfo validated() {
        ContextCreateInfo info;
        info.validation = true;
        info.on_message = [this](MessageSeverity severity, std::string_view text) {
            std::lock_guard<std::mutex> lock(mutex);
            if (severity != MessageSeverity::Info) lines.emplace_back(text);
        };
        return info;
    }
    void check() {
        std::lock_guard<std::mutex> lock(mutex);
        for (const auto& m : lines) UNSCOPED_INFO(m);
        CHECK(lines.empty());
    }
};

DetectSettings fixedSettings() {
    DetectSettings s;
    s.resolution = 128;
    s.direction = std::array<float, 3>{0.15f, -0.2f, 1.0f};
    return s;
}

std::vector<TrianglePair> detectSpheres(Context& context, int frames = 1) {
    auto world = CollisionWorld::create(context, {.threads = 2});
    REQUIRE(world);
    auto scene = overlappingSpheres(0.5f);
    REQUIRE(scene);
    for (const SceneObject& o : scene->objects) REQUIRE((*world)->addMesh(o.mesh, o.options));
    std::vector<TrianglePair> pairs;
    for (int i = 0; i < frames; ++i) {
        auto r = (*world)->detect(fixedSettings());
        INFO((r ? std::string() : r.error().message()));
        REQUIRE(r);
        if (i > 0) CHECK(r->pairs == pairs);
        pairs = r->pairs;
    }
    return pairs;
}

// Host allocation callbacks with a header, so reallocation and any alignment work; counts
// what is outstanding. Drivers may call them from their own threads.
struct HostCallbacks {
    std::atomic<long> live{0}, total{0};
    VkAllocationCallbacks callbacks{};

    struct Header {
        void* raw;
        std::size_t size;
    };
    static void* allocate(HostCallbacks& self, std::size_t size, std::size_t alignment) {
        alignment = std::max<std::size_t>(alignment, alignof(std::max_align_t));
        auto* raw = static_cast<std::byte*>(std::malloc(size + alignment + sizeof(Header)));
        if (!raw) return nullptr;
        auto start = reinterpret_cast<std::uintptr_t>(raw + sizeof(Header));
        auto* p = reinterpret_cast<std::byte*>((start + alignment - 1) / alignment * alignment);
        const Header h{raw, size};
        std::memcpy(p - sizeof(Header), &h, sizeof(Header));
        ++self.live;
        ++self.total;
        return p;
    }
    static Header header(void* p) {
        Header h;
        std::memcpy(&h, static_cast<std::byte*>(p) - sizeof(Header), sizeof(Header));
        return h;
    }
    static void release(HostCallbacks& self, void* p) {
        if (!p) return;
        --self.live;
        std::free(header(p).raw);
    }

    HostCallbacks() {
        callbacks.pUserData = this;
        callbacks.pfnAllocation = [](void* user, std::size_t size, std::size_t alignment, VkSystemAllocationScope) -> void* {
            return allocate(*static_cast<HostCallbacks*>(user), size, alignment);
        };
        callbacks.pfnReallocation = [](void* user, void* old, std::size_t size, std::size_t alignment,
                                       VkSystemAllocationScope) -> void* {
            auto& self = *static_cast<HostCallbacks*>(user);
            if (!old) return allocate(self, size, alignment);
            if (size == 0) {
                release(self, old);
                return nullptr;
            }
            void* p = allocate(self, size, alignment);
            if (p) std::memcpy(p, old, std::min(size, header(old).size));
            release(self, old);
            return p;
        };
        callbacks.pfnFree = [](void* user, void* p) { release(*static_cast<HostCallbacks*>(user), p); };
    }
};

// The engine's device-memory allocator: one VkDeviceMemory per request, the resource placed
// at a non-zero offset (as a sub-allocating allocator would), persistently mapped when
// vkcollide needs host access.
struct EngineAllocator {
    vk::Device* engine = nullptr;
    std::mutex mutex;
    std::map<std::uint64_t, VkDeviceSize> live;  // user -> bytes requested
    std::uint64_t next_user = 1;
    int allocations = 0, frees = 0;

    DeviceMemoryHooks hooks() {
        DeviceMemoryHooks h;
        h.allocate = [this](const DeviceMemoryRequest& r, DeviceMemoryBlock& out) {
            std::lock_guard<std::mutex> lock(mutex);
            const VkDeviceSize offset = r.requirements.alignment;
            VkMemoryAllocateFlagsInfo flags{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_FLAGS_INFO};
            flags.flags = VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT;
            VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
            ai.pNext = r.device_address ? &flags : nullptr;
            ai.allocationSize = offset + r.requirements.size;
            ai.memoryTypeIndex = r.memory_type;
            VkResult res = engine->fns.vkAllocateMemory(engine->device, &ai, nullptr, &out.memory);
            if (res != VK_SUCCESS) return res;
            if (r.host_access) {
                void* base = nullptr;
                res = engine->fns.vkMapMemory(engine->device, out.memory, 0, VK_WHOLE_SIZE, 0, &base);
                if (res != VK_SUCCESS) return res;
                out.mapped = static_cast<std::byte*>(base) + offset;
            }
            out.offset = offset;
            out.user = next_user++;
            live[out.user] = r.requirements.size;
            ++allocations;
            return VK_SUCCESS;
        };
        h.free = [this](const DeviceMemoryBlock& block) {
            std::lock_guard<std::mutex> lock(mutex);
            engine->fns.vkFreeMemory(engine->device, block.memory, nullptr);
            live.erase(block.user);
            ++frees;
        };
        return h;
    }
    VkDeviceSize liveBytes() {
        std::lock_guard<std::mutex> lock(mutex);
        VkDeviceSize sum = 0;
        for (const auto& [user, bytes] : live) sum += bytes;
        return sum;
    }
};

// Counts vkQueueSubmit2 calls that bypass the engine's hook (the adopted Context's table
// points here in the test below); there must be none.
std::atomic<int> g_bypassed_submits{0};
VKAPI_ATTR VkResult VKAPI_CALL bypassedSubmit(VkQueue, std::uint32_t, const VkSubmitInfo2*, VkFence) {
    ++g_bypassed_submits;
    return VK_ERROR_UNKNOWN;
}

// Records the pipeline cache every pipeline creation passes, then creates the pipeline.
// (lavapipe keeps no pipelines in a cache, so its data cannot show that the cache was used.)
struct CacheSpy {
    static inline PFN_vkCreateComputePipelines compute = nullptr;
    static inline PFN_vkCreateGraphicsPipelines graphics = nullptr;
    static inline std::mutex mutex;
    static inline std::vector<VkPipelineCache> used;

    static VKAPI_ATTR VkResult VKAPI_CALL createCompute(VkDevice d, VkPipelineCache c, std::uint32_t n,
                                                        const VkComputePipelineCreateInfo* ci, const VkAllocationCallbacks* a,
                                                        VkPipeline* out) {
        record(c, n);
        return compute(d, c, n, ci, a, out);
    }
    static VKAPI_ATTR VkResult VKAPI_CALL createGraphics(VkDevice d, VkPipelineCache c, std::uint32_t n,
                                                         const VkGraphicsPipelineCreateInfo* ci, const VkAllocationCallbacks* a,
                                                         VkPipeline* out) {
        record(c, n);
        return graphics(d, c, n, ci, a, out);
    }
    static void record(VkPipelineCache c, std::uint32_t n) {
        std::lock_guard<std::mutex> lock(mutex);
        used.insert(used.end(), n, c);
    }
    static void install(vk::Device& d) {
        compute = d.fns.vkCreateComputePipelines;
        graphics = d.fns.vkCreateGraphicsPipelines;
        used.clear();
        d.fns.vkCreateComputePipelines = createCompute;
        d.fns.vkCreateGraphicsPipelines = createGraphics;
    }
};

// Records the allocation callbacks the render graph's timestamp query pools are created
// with (the one object created outside src/vk).
struct QueryPoolSpy {
    static inline PFN_vkCreateQueryPool create = nullptr;
    static inline std::vector<const VkAllocationCallbacks*> callbacks;
    static VKAPI_ATTR VkResult VKAPI_CALL spy(VkDevice d, const VkQueryPoolCreateInfo* ci, const VkAllocationCallbacks* a,
                                              VkQueryPool* out) {
        callbacks.push_back(a);
        return create(d, ci, a, out);
    }
    static void install(vk::Device& d) {
        create = d.fns.vkCreateQueryPool;
        callbacks.clear();
        d.fns.vkCreateQueryPool = spy;
    }
};

std::size_t cacheBytes(const vk::Device& dev, VkPipelineCache cache) {
    std::size_t size = 0;
    REQUIRE(dev.fns.vkGetPipelineCacheData(dev.device, cache, &size, nullptr) == VK_SUCCESS);
    return size;
}

}  // namespace

TEST_CASE("an engine's queue hooks, memory allocator, allocation callbacks and pipeline cache see all of a detection",
          "[gpu][hooks]") {
    ValidatedContext engine_ctx;
    vk::Device& engine = engine_ctx.device();
    const std::vector<TrianglePair> expected = detectSpheres(engine_ctx.context());
    REQUIRE_FALSE(expected.empty());

    VkPipelineCacheCreateInfo ci{VK_STRUCTURE_TYPE_PIPELINE_CACHE_CREATE_INFO};
    VkPipelineCache engine_cache = VK_NULL_HANDLE;
    REQUIRE(engine.fns.vkCreatePipelineCache(engine.device, &ci, nullptr, &engine_cache) == VK_SUCCESS);

    VkPhysicalDeviceVulkan13Features v13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    VkPhysicalDeviceVulkan12Features v12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
    VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    features.pNext = &v12;
    v12.pNext = &v13;
    enableRequiredFeatures(features, v12, v13);

    HostCallbacks host;
    EngineAllocator allocator{&engine};
    std::atomic<int> locks{0}, unlocks{0}, hooked_submits{0}, inside{0};
    {
        AdoptedDevice lent;
        lent.enabled_features = &features;
        lent.get_instance_proc_addr = engine.global.vkGetInstanceProcAddr;
        lent.instance = engine.instance;
        lent.physical_device = engine.physical;
        lent.device = engine.device;
        lent.queue_family = engine.queue_family;
        lent.queue = engine.queue;
        lent.pipeline_cache = engine_cache;
        lent.allocation_callbacks = &host.callbacks;
        lent.memory_hooks = allocator.hooks();
        // The engine's lock is its own queue mutex; its submit path is its own pointer.
        lent.queue_hooks.lock = [&] {
            engine.queue_mutex.lock();
            ++locks;
        };
        lent.queue_hooks.unlock = [&] {
            ++unlocks;
            engine.queue_mutex.unlock();
        };
        lent.queue_hooks.submit = [&](VkQueue queue, std::span<const VkSubmitInfo2> submits, VkFence fence) {
            CHECK(locks.load() == unlocks.load() + 1);  // called inside the lock
            ++hooked_submits;
            return engine.fns.vkQueueSubmit2(queue, static_cast<std::uint32_t>(submits.size()), submits.data(), fence);
        };
        auto adopted = Context::adopt(lent);
        REQUIRE(adopted);
        Context& ctx = **adopted;
        ContextAccess::device(ctx).fns.vkQueueSubmit2 = bypassedSubmit;  // anything not through the hook fails
        g_bypassed_submits = 0;
        CacheSpy::install(ContextAccess::device(ctx));
        QueryPoolSpy::install(ContextAccess::device(ctx));
        {
            auto world = CollisionWorld::create(ctx, {.threads = 2});
            REQUIRE(world);
            auto scene = overlappingSpheres(0.5f);
            REQUIRE(scene);
            for (const SceneObject& o : scene->objects) REQUIRE((*world)->addMesh(o.mesh, o.options));
            auto r = (*world)->detect(fixedSettings());
            INFO((r ? std::string() : r.error().message()));
            REQUIRE(r);
            CHECK(r->pairs == expected);
            REQUIRE((*world)->submit(fixedSettings()));
            auto c = (*world)->collect();
            REQUIRE(c);
            CHECK(c->pairs == expected);

            CHECK(allocator.allocations > 0);
            CHECK(ctx.deviceMemoryInUse() == allocator.liveBytes());  // one counter, everything
            CHECK(ctx.deviceMemoryInUse() >= r->stats.gpu_memory_bytes);
            auto saved = ctx.pipelineCacheData();
            REQUIRE(saved);
            CHECK(saved->size() == cacheBytes(engine, engine_cache));
        }
        CHECK(g_bypassed_submits.load() == 0);
        REQUIRE(CacheSpy::used.size() >= 10);  // the world's pipelines (24 at the time of writing)
        for (VkPipelineCache used : CacheSpy::used) CHECK(used == engine_cache);
        REQUIRE_FALSE(QueryPoolSpy::callbacks.empty());
        for (const VkAllocationCallbacks* a : QueryPoolSpy::callbacks) CHECK(a == ContextAccess::device(ctx).allocator());
        CHECK(hooked_submits.load() >= 2);
        CHECK(locks.load() == hooked_submits.load());
        CHECK(unlocks.load() == locks.load());
        CHECK(ctx.deviceMemoryInUse() == 0);
    }
    CHECK(allocator.frees == allocator.allocations);
    CHECK(host.total.load() > 0);
    CHECK(host.live.load() == 0);
    engine.fns.vkDestroyPipelineCache(engine.device, engine_cache, nullptr);
    REQUIRE_NO_VALIDATION_MESSAGES(engine_ctx);
}

TEST_CASE("vkcollide's own device with the engine's allocation callbacks and a saved pipeline cache leaks nothing",
          "[gpu][hooks]") {
    HostCallbacks host;
    std::vector<std::byte> saved;
    MessageLog log;
    ContextCreateInfo info = log.validated();
    info.allocation_callbacks = &host.callbacks;
    std::vector<TrianglePair> first;
    {
        auto ctx = Context::create(info);
        REQUIRE(ctx);
        first = detectSpheres(**ctx);
        auto data = (*ctx)->pipelineCacheData();
        REQUIRE(data);
        saved = *data;
        CHECK(saved.size() >= sizeof(VkPipelineCacheHeaderVersionOne));
        CHECK(vk::pipelineCacheDataMatches(ContextAccess::device(**ctx), saved));
    }
    CHECK(host.total.load() > 0);
    CHECK(host.live.load() == 0);  // instance, device and every object gone
    info.pipeline_cache_data = saved;
    {
        auto ctx = Context::create(info);
        REQUIRE(ctx);
        CHECK(detectSpheres(**ctx) == first);
    }
    CHECK(host.live.load() == 0);
    log.check();
}

TEST_CASE("pipeline statistics: every pipeline's where the driver offers them, an error naming why where not", "[gpu][hooks]") {
    MessageLog log;
    ContextCreateInfo info = log.validated();
    auto off = Context::create(info);
    REQUIRE(off);
    auto none = (*off)->pipelineStatistics();
    REQUIRE_FALSE(none);
    CHECK(none.error().code() == ErrorCode::UnsupportedFeature);
    CHECK_THAT(none.error().message(), Catch::Contains("pipeline_statistics was off"));

    info.pipeline_statistics = true;
    auto ctx = Context::create(info);
    REQUIRE(ctx);
    const std::vector<TrianglePair> pairs = detectSpheres(**ctx);
    auto stats = (*ctx)->pipelineStatistics();
    const vk::Device& d = ContextAccess::device(**ctx);
    if (d.capture_statistics) CHECK(pairs == detectSpheres(**off));  // capturing changes no result
    if (!d.capture_statistics) {  // lavapipe (Mesa 22.3) does not offer the extension
        REQUIRE_FALSE(stats);
        CHECK(stats.error().code() == ErrorCode::UnsupportedFeature);
        CHECK_THAT(stats.error().message(), Catch::Contains(d.info.name) && Catch::Contains("VK_KHR_pipeline_executable_properties"));
    } else {
        REQUIRE(stats);
        std::set<std::string> names;
        for (const PipelineStatistics& p : *stats) {
            INFO(p.pipeline << " / " << p.executable);
            names.insert(p.pipeline);
            CHECK_FALSE(p.pipeline.empty());
            CHECK_FALSE(p.statistics.empty());
            for (const PipelineStatistic& s : p.statistics) CHECK_FALSE(s.name.empty());
        }
        // Every pipeline the detection made has at least one executable (pipelines may share
        // a name: the same program for two bindings).
        CHECK(stats->size() >= d.pipelines_created);
        CHECK(names.size() >= 10);
    }
    log.check();
}

TEST_CASE("a Context destroyed while a detection is in flight: collect() and the world's destruction still work",
          "[gpu][lifetime]") {
    ValidatedContext reference_ctx;
    const std::vector<TrianglePair> expected = detectSpheres(reference_ctx.context());
    MessageLog log;
    auto ctx = Context::create(log.validated());
    REQUIRE(ctx);
    auto world = CollisionWorld::create(**ctx, {.threads = 2});
    REQUIRE(world);
    auto scene = overlappingSpheres(0.5f);
    REQUIRE(scene);
    for (const SceneObject& o : scene->objects) REQUIRE((*world)->addMesh(o.mesh, o.options));
    // The first detection measures the depth complexity; the second is one submission in flight.
    REQUIRE((*world)->detect(fixedSettings()));
    REQUIRE((*world)->submit(fixedSettings()));
    ctx->reset();  // the Context goes first: the world's Buffer::reset must not reach into it later
    auto r = (*world)->collect();
    REQUIRE(r);
    CHECK(r->pairs == expected);
    world->reset();  // the last owner of the device: vkDestroyDevice and vkDestroyInstance here
    log.check();  // the layer reports objects left at vkDestroyDevice: none
    REQUIRE_NO_VALIDATION_MESSAGES(reference_ctx);
}

TEST_CASE("two worlds on one Context on two threads: the queue is shared safely", "[gpu][threads]") {
    ValidatedContext ctx;
    const std::vector<TrianglePair> expected = detectSpheres(ctx.context());
    std::vector<TrianglePair> results[2];
    std::thread threads[2];
    for (int t = 0; t < 2; ++t)
        threads[t] = std::thread([&, t] {
            auto world = CollisionWorld::create(ctx.context(), {.threads = 1});
            if (!world) return;
            auto scene = overlappingSpheres(0.5f);
            if (!scene) return;
            for (const SceneObject& o : scene->objects)
                if (!(*world)->addMesh(o.mesh, o.options)) return;
            for (int frame = 0; frame < 12; ++frame) {
                auto r = (*world)->detect(fixedSettings());
                if (!r) return;
                if (frame > 0 && r->pairs != results[t]) return;
                results[t] = r->pairs;
            }
        });
    for (auto& t : threads) t.join();
    CHECK(results[0] == expected);
    CHECK(results[1] == expected);
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);  // no THREADING error on the queue
}
