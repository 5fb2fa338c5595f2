// vk::Submission on the fake driver (no GPU): what reaches vkQueueSubmit2 (waits, signals,
// values, stages), the states a caller sees (poll, timeout, device loss, failed submits),
// and recording into an engine's command buffer. The fake's "GPU" finishes work at once or
// only when the test releases it (FakeVulkan::gpu_finishes_at_once, finishPending).
#include <catch2/catch.hpp>

#include "api/context_access.hpp"
#include "support/error_text.hpp"
#include "vk/fake_engine.hpp"
#include "vk/semaphore.hpp"
#include "vk/submission.hpp"

using namespace vkcollide;
using test::FakeVulkanScope;

namespace {

vk::Submission makeSubmission(Context& ctx) {
    auto s = vk::Submission::create(ContextAccess::device(ctx));
    REQUIRE(s);
    return std::move(*s);
}

vk::Semaphore timeline(Context& ctx, std::uint64_t initial = 0) {
    auto t = vk::Semaphore::createTimeline(ContextAccess::device(ctx), initial, "timeline");
    REQUIRE(t);
    return std::move(*t);
}

// Begins and submits an empty recording with `sync`.
Result<void> submitWith(vk::Submission& s, const SubmitSync& sync = {}) {
    auto cmd = s.begin();
    if (!cmd) return cmd.error();
    return s.submit(sync);
}

using test::mentions;

}  // namespace

TEST_CASE("submit passes its waits and signals to vkQueueSubmit2 with their values and stages", "[contract][submission]") {
    FakeVulkanScope scope;
    auto ctx = test::createFakeContext();
    auto binary = vk::Semaphore::createBinary(ContextAccess::device(*ctx), "binary");
    REQUIRE(binary);
    vk::Semaphore t = timeline(*ctx, 5);
    vk::Submission s = makeSubmission(*ctx);
    const SemaphoreSubmit waits[] = {{binary->handle(), 0, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT},
                                     {t.handle(), 5, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT}};
    const SemaphoreSubmit signals[] = {{t.handle(), 9, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT}};
    // The binary wait needs a signal first, as on a driver: an earlier submission makes it.
    const SemaphoreSubmit signal_binary[] = {{binary->handle()}};
    REQUIRE(submitWith(s, {.signal = signal_binary}));
    REQUIRE(s.wait());
    REQUIRE(submitWith(s, {.wait = waits, .signal = signals}));
    REQUIRE(s.wait());

    const auto& submits = scope.fake().submits;
    REQUIRE(submits.size() == 2);
    const auto& last = submits[1];
    REQUIRE(last.waits.size() == 2);
    CHECK(last.waits[0].semaphore == binary->handle());
    CHECK(last.waits[0].stageMask == VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
    CHECK(last.waits[1].semaphore == t.handle());
    CHECK(last.waits[1].value == 5);
    CHECK(last.waits[1].stageMask == VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT);
    REQUIRE(last.signals.size() == 1);
    CHECK(last.signals[0].value == 9);
    CHECK(last.signals[0].stageMask == VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT);
    CHECK(last.fence != VK_NULL_HANDLE);
    CHECK(scope.fake().timelineValue(t.handle()) == 9);
}

TEST_CASE("timeline: the second submission waits for the first one's signal, both wait for the host's",
          "[contract][submission]") {
    FakeVulkanScope scope;
    auto ctx = test::createFakeContext();
    vk::Semaphore t = timeline(*ctx);
    vk::Submission first = makeSubmission(*ctx), second = makeSubmission(*ctx);
    const SemaphoreSubmit wait1[] = {{t.handle(), 1}}, signal2[] = {{t.handle(), 2}};
    const SemaphoreSubmit wait2[] = {{t.handle(), 2}}, signal3[] = {{t.handle(), 3}};
    REQUIRE(submitWith(first, {.wait = wait1, .signal = signal2}));
    REQUIRE(submitWith(second, {.wait = wait2, .signal = signal3}));

    // Nothing can run before the host signals 1: both stay pending, polls do not block.
    for (auto* s : {&first, &second}) {
        auto p = s->poll();
        REQUIRE(p);
        CHECK(*p == vk::Completion::NotYet);
        CHECK(s->pending());
    }
    REQUIRE(t.signal(1));
    auto p2 = second.poll();
    REQUIRE(p2);
    CHECK(*p2 == vk::Completion::Done);
    CHECK(second.state() == vk::Submission::State::Idle);
    auto p1 = first.poll();
    REQUIRE(p1);
    CHECK(*p1 == vk::Completion::Done);
    CHECK(scope.fake().timelineValue(t.handle()) == 3);
}

TEST_CASE("poll: not ready while the work runs, done after, Idle and Recording are done", "[contract][submission]") {
    FakeVulkanScope scope;
    scope.fake().gpu_finishes_at_once = false;
    auto ctx = test::createFakeContext();
    vk::Submission s = makeSubmission(*ctx);
    auto idle = s.poll();
    REQUIRE(idle);
    CHECK(*idle == vk::Completion::Done);  // nothing submitted yet
    REQUIRE(s.begin());
    CHECK(s.state() == vk::Submission::State::Recording);
    REQUIRE(s.submit());
    for (int i = 0; i < 3; ++i) {
        auto p = s.poll();
        REQUIRE(p);
        CHECK(*p == vk::Completion::NotYet);
    }
    scope.fake().finishPending();
    auto p = s.poll();
    REQUIRE(p);
    CHECK(*p == vk::Completion::Done);
    CHECK_FALSE(s.pending());
    CHECK(scope.fake().unbounded_waits == 0);  // polls never block
}

TEST_CASE("a timeout leaves the work pending: wait again, begin refuses, nothing is freed", "[contract][submission][error]") {
    FakeVulkanScope scope;
    scope.fake().gpu_finishes_at_once = false;
    auto ctx = test::createFakeContext();
    vk::Submission s = makeSubmission(*ctx);
    REQUIRE(submitWith(s));

    auto late = s.wait(1'000'000);
    REQUIRE_FALSE(late);
    CHECK(late.error().code() == ErrorCode::VulkanError);
    CHECK(late.error().vkResult() == VK_TIMEOUT);
    CHECK(mentions(late.error(), "still pending"));
    CHECK(s.pending());
    auto again = s.waitFor(1'000'000);
    REQUIRE(again);
    CHECK(*again == vk::Completion::NotYet);
    // begin() must not reset a command buffer the GPU may still run.
    auto cmd = s.begin();
    REQUIRE_FALSE(cmd);
    CHECK(cmd.error().vkResult() == VK_TIMEOUT);
    CHECK(s.pending());

    scope.fake().finishPending();
    REQUIRE(s.wait());
    CHECK(s.begin());
}

TEST_CASE("reset waits without a limit for pending work before destroying anything", "[contract][submission]") {
    FakeVulkanScope scope;
    scope.fake().gpu_finishes_at_once = false;
    auto ctx = test::createFakeContext();
    {
        vk::Submission s = makeSubmission(*ctx);
        REQUIRE(submitWith(s));
        CHECK(scope.fake().fences_alive == 1);
    }
    CHECK(scope.fake().unbounded_waits == 1);
    CHECK(scope.fake().fences_alive == 0);
    CHECK(scope.fake().command_pools_alive == 0);
}

TEST_CASE("device loss while pending: DeviceLost, the submission stays Lost and is still destructible",
          "[contract][submission][error]") {
    FakeVulkanScope scope;
    scope.fake().gpu_finishes_at_once = false;
    auto ctx = test::createFakeContext();
    vk::Submission s = makeSubmission(*ctx);
    REQUIRE(submitWith(s));
    scope.fake().device_status = VK_ERROR_DEVICE_LOST;
    auto p = s.poll();
    REQUIRE_FALSE(p);
    CHECK(p.error().code() == ErrorCode::DeviceLost);
    CHECK(s.lost());
    auto w = s.wait();
    REQUIRE_FALSE(w);
    CHECK(w.error().code() == ErrorCode::DeviceLost);
    auto b = s.begin();
    REQUIRE_FALSE(b);
    CHECK(b.error().code() == ErrorCode::DeviceLost);
    s.reset();
    CHECK(scope.fake().fences_alive == 0);
}

TEST_CASE("a failed vkQueueSubmit2 leaves nothing pending, and device loss there leaves it Lost", "[contract][submission][error]") {
    FakeVulkanScope scope;
    auto ctx = test::createFakeContext();
    vk::Submission s = makeSubmission(*ctx);
    scope.fake().submit_result = VK_ERROR_OUT_OF_DEVICE_MEMORY;
    auto oom = submitWith(s);
    REQUIRE_FALSE(oom);
    CHECK(oom.error().code() == ErrorCode::OutOfMemory);
    CHECK(s.state() == vk::Submission::State::Idle);
    auto p = s.poll();
    REQUIRE(p);
    CHECK(*p == vk::Completion::Done);

    scope.fake().submit_result = VK_SUCCESS;
    REQUIRE(submitWith(s));  // usable again
    REQUIRE(s.wait());

    scope.fake().submit_result = VK_ERROR_DEVICE_LOST;
    auto lost = submitWith(s);
    REQUIRE_FALSE(lost);
    CHECK(lost.error().code() == ErrorCode::DeviceLost);
    CHECK(s.lost());
}

TEST_CASE("a bad SubmitSync is refused by name and the recording stays open to submit again", "[contract][submission][error]") {
    FakeVulkanScope scope;
    auto ctx = test::createFakeContext();
    vk::Semaphore t = timeline(*ctx);
    vk::Submission s = makeSubmission(*ctx);
    REQUIRE(s.begin());
    const SemaphoreSubmit null_wait[] = {{t.handle(), 1}, {VK_NULL_HANDLE, 1}};
    auto r1 = s.submit({.wait = null_wait});
    REQUIRE_FALSE(r1);
    CHECK(r1.error().code() == ErrorCode::InvalidArgument);
    CHECK(mentions(r1.error(), "SubmitSync::wait[1]: semaphore is VK_NULL_HANDLE"));
    const SemaphoreSubmit no_stages[] = {{t.handle(), 1, 0}};
    auto r2 = s.submit({.signal = no_stages});
    REQUIRE_FALSE(r2);
    CHECK(mentions(r2.error(), "SubmitSync::signal[0]: stages is 0"));
    CHECK(s.state() == vk::Submission::State::Recording);
    CHECK(scope.fake().submits.empty());

    const SemaphoreSubmit good[] = {{t.handle(), 1}};
    REQUIRE(s.submit({.signal = good}));
    REQUIRE(s.wait());
    CHECK(scope.fake().submits.size() == 1);
    auto twice = s.submit();
    REQUIRE_FALSE(twice);
    CHECK(mentions(twice.error(), "begin() first"));
}

TEST_CASE("recording into the engine's command buffer: nothing is submitted, the engine's timeline says when it is done",
          "[contract][submission]") {
    FakeVulkanScope scope;
    auto ctx = test::createFakeContext();
    vk::Semaphore t = timeline(*ctx, 3);
    vk::Submission s = makeSubmission(*ctx);
    const auto engine_cmd = reinterpret_cast<VkCommandBuffer>(std::uintptr_t{0xE0E0});
    auto cmd = s.beginIn({engine_cmd, t.handle(), 4});
    REQUIRE(cmd);
    CHECK(*cmd == engine_cmd);
    // SubmitSync makes no sense here: the engine orders its own command buffer.
    const SemaphoreSubmit sig[] = {{t.handle(), 5}};
    auto refused = s.submit({.signal = sig});
    REQUIRE_FALSE(refused);
    CHECK(mentions(refused.error(), "engine orders its own submission"));
    REQUIRE(s.submit());
    CHECK(scope.fake().submits.empty());
    auto p = s.poll();
    REQUIRE(p);
    CHECK(*p == vk::Completion::NotYet);
    auto w = s.waitFor(1000);
    REQUIRE(w);
    CHECK(*w == vk::Completion::NotYet);

    REQUIRE(t.signal(4));  // the engine's submission finished
    REQUIRE(s.wait());
    CHECK_FALSE(s.pending());
    // The next recording may go to vkcollide's own command buffer again.
    REQUIRE(submitWith(s));
    REQUIRE(s.wait());
    CHECK(scope.fake().submits.size() == 1);
}

TEST_CASE("recording into the engine's command buffer refuses what would look finished before it ran",
          "[contract][submission][error]") {
    FakeVulkanScope scope;
    auto ctx = test::createFakeContext();
    vk::Semaphore t = timeline(*ctx, 7);
    vk::Submission s = makeSubmission(*ctx);
    const auto engine_cmd = reinterpret_cast<VkCommandBuffer>(std::uintptr_t{0xE0E0});
    auto reached = s.beginIn({engine_cmd, t.handle(), 7});
    REQUIRE_FALSE(reached);
    CHECK(mentions(reached.error(), "already reached (the timeline is at 7)"));
    auto zero = s.beginIn({engine_cmd, t.handle(), 0});
    REQUIRE_FALSE(zero);
    CHECK(mentions(zero.error(), "value is 0"));
    auto no_cmd = s.beginIn({VK_NULL_HANDLE, t.handle(), 8});
    REQUIRE_FALSE(no_cmd);
    CHECK(mentions(no_cmd.error(), "command_buffer is VK_NULL_HANDLE"));
    auto no_timeline = s.beginIn({engine_cmd, VK_NULL_HANDLE, 8});
    REQUIRE_FALSE(no_timeline);
    CHECK(mentions(no_timeline.error(), "timeline is VK_NULL_HANDLE"));
    CHECK(s.state() == vk::Submission::State::Idle);
}

TEST_CASE("recording into an engine command buffer needs timelineSemaphore on an adopted device", "[contract][submission][error]") {
    FakeVulkanScope scope;
    test::FakeEngineDevice engine(/*timeline=*/false);
    auto ctx = Context::adopt(engine.lend(scope.fake()), [](MessageSeverity, std::string_view) {});
    REQUIRE(ctx);  // optional: adopt accepts the device
    CHECK_FALSE(ContextAccess::device(**ctx).timeline_semaphore);
    auto s = vk::Submission::create(ContextAccess::device(**ctx));
    REQUIRE(s);
    const auto engine_cmd = reinterpret_cast<VkCommandBuffer>(std::uintptr_t{0xE0E0});
    const auto fake_timeline = reinterpret_cast<VkSemaphore>(std::uintptr_t{0x5E5E});
    auto r = s->beginIn({engine_cmd, fake_timeline, 1});
    REQUIRE_FALSE(r);
    CHECK(r.error().code() == ErrorCode::UnsupportedFeature);
    CHECK(mentions(r.error(), "timelineSemaphore"));
    auto t = vk::Semaphore::createTimeline(ContextAccess::device(**ctx), 0, "t");
    REQUIRE_FALSE(t);
    CHECK(t.error().code() == ErrorCode::UnsupportedFeature);
}

TEST_CASE("timelineSemaphore is optional: enabled on vkcollide's own device where supported, read from an engine's chain",
          "[contract][context]") {
    FakeVulkanScope scope;
    {
        auto ctx = test::createFakeContext();
        CHECK(scope.fake().device_features.has(vk::Feature::TimelineSemaphore));
        CHECK(ContextAccess::device(*ctx).timeline_semaphore);
        CHECK(ctx->deviceInfo().timeline_semaphore);
    }
    scope.fake().physical_devices[0].features.set(vk::Feature::TimelineSemaphore, false);
    {
        auto ctx = test::createFakeContext();  // not required
        CHECK_FALSE(scope.fake().device_features.has(vk::Feature::TimelineSemaphore));
        CHECK_FALSE(ContextAccess::device(*ctx).timeline_semaphore);
    }
    // The single-feature struct counts as well as VkPhysicalDeviceVulkan12Features.
    test::FakeEngineDevice engine(/*timeline=*/false);
    VkPhysicalDeviceTimelineSemaphoreFeatures single{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_TIMELINE_SEMAPHORE_FEATURES};
    single.timelineSemaphore = VK_TRUE;
    engine.v13.pNext = &single;
    auto adopted = Context::adopt(engine.lend(scope.fake()), [](MessageSeverity, std::string_view) {});
    REQUIRE(adopted);
    CHECK(ContextAccess::device(**adopted).timeline_semaphore);
}

TEST_CASE("submitSyncOnly: a batch of only waits and signals, so a failed detection never leaves the engine waiting",
          "[contract][submission]") {
    FakeVulkanScope scope;
    scope.fake().gpu_finishes_at_once = false;
    auto ctx = test::createFakeContext();
    vk::Semaphore t = timeline(*ctx);
    vk::Submission s = makeSubmission(*ctx);
    REQUIRE(s.begin());
    const SemaphoreSubmit signal[] = {{t.handle(), 6}};
    auto recording = s.submitSyncOnly({.signal = signal});
    REQUIRE_FALSE(recording);  // a recording in progress must be submitted or abandoned first
    CHECK(mentions(recording.error(), "while recording"));
    REQUIRE(s.submit());
    // The earlier work finishes; submitSyncOnly then starts from Idle.
    scope.fake().finishPending();
    const SemaphoreSubmit wait[] = {{t.handle(), 0}};
    REQUIRE(s.submitSyncOnly({.wait = wait, .signal = signal}));
    CHECK(s.pending());
    REQUIRE(scope.fake().submits.size() == 2);
    CHECK(scope.fake().submits[1].waits.size() == 1);
    CHECK(scope.fake().submits[1].signals.size() == 1);
    CHECK(scope.fake().submits[1].fence != VK_NULL_HANDLE);
    scope.fake().finishPending();
    REQUIRE(s.wait());
    CHECK(scope.fake().timelineValue(t.handle()) == 6);
    const SemaphoreSubmit bad[] = {{VK_NULL_HANDLE}};
    auto refused = s.submitSyncOnly({.signal = bad});
    REQUIRE_FALSE(refused);
    CHECK(mentions(refused.error(), "SubmitSync::signal[0]"));
}

