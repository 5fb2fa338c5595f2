// Failed detections leave a working world: a detection that runs out of
// time, meets a lost device or runs out of device memory fails with its own ErrorCode, the
// world reports a state the engine can act on (CollisionWorld::state()), can be destroyed
// at once, and detects again when the cause is gone. Faults are forced by a tiny timeout
// setting and by Vulkan entry points replaced in the device's dispatch table (the tables
// are per device, so only this test's Context sees them). A pair filter that throws fails
// its detection by name.
#include <catch2/catch.hpp>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>

#include "stability_support.hpp"
#include "support/gpu_fixture.hpp"
#include "support/pathological_scenes.hpp"
#include "vk/device.hpp"

using namespace vkcollide;
using namespace vkcollide::test;

namespace {


std::unique_ptr<CollisionWorld> worldOf(Context& context, const TestScene& scene, unsigned threads = 2) {
    auto w = CollisionWorld::create(context, {.threads = threads});
    REQUIRE(w);
    for (const SceneObject& o : scene.objects) REQUIRE((*w)->addMesh(o.mesh, o.options));
    return std::move(*w);
}

// Polls until the world is no longer Busy (bounded: the work is finite).
WorldState settled(CollisionWorld& w) {
    const auto until = std::chrono::steady_clock::now() + std::chrono::minutes(5);
    while (w.state() == WorldState::Busy && std::chrono::steady_clock::now() < until)
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    return w.state();
}

// Replaces device entry points for one scope; the replacements read these (a test runs
// one at a time).
struct Injected {
    static inline PFN_vkWaitForFences wait = nullptr;
    static inline PFN_vkGetFenceStatus status = nullptr;  // polled waits (DetectSettings::limits.wait_poll_us)
    static inline PFN_vkQueueSubmit2 submit = nullptr;
    static inline PFN_vkAllocateMemory allocate = nullptr;
    static inline std::atomic<bool> lose_device{false};
    static inline std::atomic<VkDeviceSize> fail_above{~VkDeviceSize(0)};
    static inline std::atomic<int> calls{0};

    // Waits for real, then reports a lost device (the work is done: nothing runs after it).
    static VKAPI_ATTR VkResult VKAPI_CALL waitLost(VkDevice d, uint32_t n, const VkFence* f, VkBool32 all, uint64_t t) {
        ++calls;
        const VkResult r = wait(d, n, f, all, t);
        return lose_device ? VK_ERROR_DEVICE_LOST : r;
    }
    static VKAPI_ATTR VkResult VKAPI_CALL statusLost(VkDevice d, VkFence f) {
        ++calls;
        const VkResult r = status(d, f);
        return lose_device && r != VK_NOT_READY ? VK_ERROR_DEVICE_LOST : r;
    }
    static VKAPI_ATTR VkResult VKAPI_CALL submitLost(VkQueue q, uint32_t n, const VkSubmitInfo2* s, VkFence f) {
        ++calls;
        return lose_device ? VK_ERROR_DEVICE_LOST : submit(q, n, s, f);
    }
    static VKAPI_ATTR VkResult VKAPI_CALL allocateSome(VkDevice d, const VkMemoryAllocateInfo* i, const VkAllocationCallbacks* a,
                                                       VkDeviceMemory* m) {
        if (i->allocationSize > fail_above) return VK_ERROR_OUT_OF_DEVICE_MEMORY;
        return allocate(d, i, a, m);
    }

    explicit Injected(vk::Device& device) : device_(&device) {
        wait = device.fns.vkWaitForFences;
        status = device.fns.vkGetFenceStatus;
        submit = device.fns.vkQueueSubmit2;
        allocate = device.fns.vkAllocateMemory;
        device.fns.vkWaitForFences = waitLost;
        device.fns.vkGetFenceStatus = statusLost;
        device.fns.vkQueueSubmit2 = submitLost;
        device.fns.vkAllocateMemory = allocateSome;
        lose_device = false;
        fail_above = ~VkDeviceSize(0);
        calls = 0;
    }
    ~Injected() {
        device_->fns.vkWaitForFences = wait;
        device_->fns.vkGetFenceStatus = status;
        device_->fns.vkQueueSubmit2 = submit;
        device_->fns.vkAllocateMemory = allocate;
    }
    Injected(const Injected&) = delete;
    Injected& operator=(const Injected&) = delete;

private:
    vk::Device* device_;
};

}  // namespace

TEST_CASE("a detection that runs out of time fails with Timeout, the world is Busy, then works again", "[stability][gpu][failures]") {
    ValidatedContext ctx;
    // 150 slabs: 304 layers peeled, long enough on any device that a 0 ms wait runs out.
    auto c = slabsOverContact(150);
    REQUIRE(c);
    auto world = worldOf(ctx.context(), c->scene);
    DetectSettings impatient = c->settings;
    impatient.limits.timeout_ms = 0;

    SECTION("the measuring submission runs out: Timeout, and the world settles") {
        auto r = world->detect(impatient);
        REQUIRE_FALSE(r);
        CHECK(r.error().code() == ErrorCode::Timeout);
        CHECK(settled(*world) == WorldState::Ready);
        auto again = world->detect(c->settings);
        REQUIRE(again);
        CHECK((again->pairs == *c->reference));
    }
    // Once the depth is known a detection is one submission of all 304 peeling steps
    // (about a second on lavapipe), so the world is still Busy when the wait gives up.
    REQUIRE(world->detect(c->settings));
    impatient.peeling.measure_layers = false;
    SECTION("detect(): Busy refuses what the running work reads, settled the pairs are right") {
        auto r = world->detect(impatient);
        REQUIRE_FALSE(r);
        CHECK(r.error().code() == ErrorCode::Timeout);
        CHECK(mentions(r.error(), "did not finish within 0 ms"));
        CHECK_FALSE(world->pending());
        if (world->state() == WorldState::Busy) {
            // The slabs' buffers are read by the running work: not to be changed or freed.
            auto update = world->updateVertices(2, c->scene.objects[2].mesh.positions);
            REQUIRE_FALSE(update);
            CHECK(update.error().code() == ErrorCode::Timeout);
            auto remove = world->removeObject(2);
            REQUIRE_FALSE(remove);
            CHECK(remove.error().code() == ErrorCode::Timeout);
            // A new detection with as little patience names the old work.
            auto still = world->detect(impatient);
            REQUIRE_FALSE(still);
            CHECK(still.error().code() == ErrorCode::Timeout);
            CHECK(mentions(still.error(), "earlier detection"));
        } else {
            WARN("the GPU finished 304 peeling steps before the world looked: Busy not seen");
        }
        CHECK(settled(*world) == WorldState::Ready);
        REQUIRE(world->updateVertices(2, c->scene.objects[2].mesh.positions));
        auto again = world->detect(c->settings);
        REQUIRE(again);
        CHECK((again->pairs == *c->reference));
    }
    SECTION("submit()/collect(): collect times out, the next detection waits for the old work") {
        REQUIRE(world->submit(impatient));
        auto r = world->collect();
        REQUIRE_FALSE(r);
        CHECK(r.error().code() == ErrorCode::Timeout);
        CHECK_FALSE(world->pending());
        // No settling by hand: detect() waits (within its own timeout) for the old work.
        auto again = world->detect(c->settings);
        REQUIRE(again);
        CHECK((again->pairs == *c->reference));
        CHECK(world->state() == WorldState::Ready);
    }
    SECTION("a Busy world can be destroyed at once") {
        auto r = world->detect(impatient);
        REQUIRE_FALSE(r);
        world.reset();  // waits for the work before freeing what it reads
    }
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("a polling wait finds the same pairs and still honours the timeout", "[stability][gpu][failures]") {
    ValidatedContext ctx;
    auto c = slabsOverContact(150);  // about a second of GPU work on lavapipe
    REQUIRE(c);
    auto world = worldOf(ctx.context(), c->scene);
    for (std::uint32_t poll : {0u, 500u, 2'000'000u}) {
        INFO("wait_poll_us " << poll);
        DetectSettings s = c->settings;
        s.limits.wait_poll_us = poll;
        auto r = world->detect(s);
        REQUIRE(r);
        CHECK((r->pairs == *c->reference));
    }
    // Polling for up to two seconds does not outlast a 1 ms timeout.
    DetectSettings impatient = c->settings;
    impatient.peeling.measure_layers = false;
    impatient.limits.timeout_ms = 1;
    impatient.limits.wait_poll_us = 2'000'000;
    const auto t0 = std::chrono::steady_clock::now();
    auto r = world->detect(impatient);
    const double waited_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (r) {
        WARN("the GPU finished 304 peeling steps within 1 ms: the timeout was not reached");
    } else {
        CHECK(r.error().code() == ErrorCode::Timeout);
        CHECK(mentions(r.error(), "did not finish within 1 ms"));
        CHECK(waited_s < 1.9);  // not the whole polling budget (the recording takes a few ms)
    }
    CHECK(settled(*world) == WorldState::Ready);
    auto again = world->detect(c->settings);
    REQUIRE(again);
    CHECK((again->pairs == *c->reference));
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("a lost device fails the detection with DeviceLost and every later one at once", "[stability][gpu][failures]") {
    ValidatedContext ctx;
    auto c = slabsOverContact(2);
    REQUIRE(c);
    for (bool at_submit : {false, true}) {
        INFO((at_submit ? "vkQueueSubmit2" : "vkWaitForFences or vkGetFenceStatus") << " reports the loss");
        Injected faults(ctx.device());
        auto world = worldOf(ctx.context(), c->scene);
        REQUIRE(world->detect(c->settings));
        Injected::lose_device = true;
        if (at_submit) {  // only the submission fails
            ctx.device().fns.vkWaitForFences = Injected::wait;
            ctx.device().fns.vkGetFenceStatus = Injected::status;
        }
        auto r = world->detect(c->settings);
        REQUIRE_FALSE(r);
        CHECK(r.error().code() == ErrorCode::DeviceLost);
        CHECK(world->state() == WorldState::DeviceLost);
        // Later detections fail at once, without touching the device.
        const int calls = Injected::calls;
        auto again = world->detect(c->settings);
        REQUIRE_FALSE(again);
        CHECK(again.error().code() == ErrorCode::DeviceLost);
        CHECK(mentions(again.error(), "create a new Context"));
        CHECK_FALSE(world->submit(c->settings));
        CHECK(Injected::calls == calls);
        Injected::lose_device = false;
        world.reset();  // destructible
    }
    // The device was not really lost: a new world on it works.
    auto fresh = worldOf(ctx.context(), c->scene);
    auto r = fresh->detect(c->settings);
    REQUIRE(r);
    CHECK((r->pairs == *c->reference));
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("device memory running out mid-detection is OutOfMemory, and the world detects again", "[stability][gpu][failures]") {
    ValidatedContext ctx;
    auto c = slabsOverContact(2);
    REQUIRE(c);
    Injected faults(ctx.device());
    auto world = worldOf(ctx.context(), c->scene);
    DetectSettings small = c->settings, large = c->settings;
    small.resolution = 64;
    large.resolution = 512;
    auto before = world->detect(small);
    REQUIRE(before);
    // Every buffer the larger run needs beyond what the first made fails to allocate.
    Injected::fail_above = 64 * 64 * 64;
    for (SamplingBackend backend : {SamplingBackend::Raster, SamplingBackend::Compute}) {
        large.peeling.backend = backend;
        INFO(toString(backend));
        auto r = world->detect(large);
        REQUIRE_FALSE(r);
        CHECK(r.error().code() == ErrorCode::OutOfMemory);
        CHECK(world->state() == WorldState::Ready);
        auto same = world->detect(small);  // buffers it needs may have been freed: made again
        REQUIRE(same);
        CHECK((same->pairs == before->pairs));
    }
    Injected::fail_above = ~VkDeviceSize(0);
    auto r = world->detect(large);
    REQUIRE(r);
    auto fresh = worldOf(ctx.context(), c->scene);
    auto expected = fresh->detect(large);
    REQUIRE(expected);
    CHECK((r->pairs == expected->pairs));
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("a pair filter that throws fails its detection by name, and the world stays Ready", "[stability][gpu][failures]") {
    ValidatedContext ctx;
    auto c = repeatedTriangle(3);  // objects 0 (three copies) and 1 (crossing them)
    REQUIRE(c);
    auto world = worldOf(ctx.context(), c->scene);
    REQUIRE(world->setPairFilter([](ObjectId a, ObjectId b) -> bool {
        if (a == 0 && b == 1) throw std::runtime_error("no rule for 0 and 1");
        return true;
    }));
    auto r = world->detect(c->settings);
    REQUIRE_FALSE(r);
    CHECK(r.error().code() == ErrorCode::InvalidArgument);
    CHECK(mentions(r.error(), "pair filter threw for objects 0 and 1: no rule for 0 and 1"));
    CHECK(world->state() == WorldState::Ready);
    REQUIRE(world->setPairFilter([](ObjectId, ObjectId) -> bool { throw 7; }));
    auto odd = world->detect(c->settings);
    REQUIRE_FALSE(odd);
    CHECK(mentions(odd.error(), "pair filter threw"));
    REQUIRE(world->setPairFilter([](ObjectId, ObjectId) { return true; }));
    auto ok = world->detect(c->settings);
    REQUIRE(ok);
    CHECK((ok->pairs == *c->reference));
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}
