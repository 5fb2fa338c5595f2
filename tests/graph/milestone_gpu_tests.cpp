// The executor's milestones on the device (validation with synchronization validation on:
// any message fails the test): a pass that calls PassContext::signalHost lets collect() call
// the milestone's callback with what the passes before it wrote already in host memory, and
// only what they wrote; once per submission, resubmitted or recorded; never where no such
// pass ran.
#include <catch2/catch.hpp>

#include "graph/executor.hpp"
#include "support/gpu_fixture.hpp"
#include "support/mapped_words.hpp"
#include "vk/event.hpp"

using namespace vkcollide;
using namespace vkcollide::graph;

using test::poison;
using test::wordAt;

namespace {

constexpr VkDeviceSize kLaterBytes = VkDeviceSize{16} << 20;  // enough work after the milestone to see it first

// early: filled with `value` on the GPU, copied to the host (`early_host`); then, with
// `milestone`, the pass that sets `event`; then a long fill of `later` and its first word
// copied to `late_host`.
void declare(Graph& g, std::uint32_t value, bool milestone, const vk::Event& event, vk::Buffer& early, vk::Buffer& early_host,
             vk::Buffer& later, vk::Buffer& late_host) {
    auto e = g.importBuffer("early", early, true);
    auto eh = g.importBuffer("early-host", early_host, true);
    auto l = g.importBuffer("later", later, true);
    auto lh = g.importBuffer("late-host", late_host, true);
    g.addPass("fill-early", PassKind::Transfer).use(e, Use::TransferDst).record([=](PassContext& pc) {
        pc.fillBuffer(pc.buffer(e).handle(), 0, 256, value);
    });
    g.addPass("copy-early", PassKind::Transfer).use(e, Use::TransferSrc).use(eh, Use::TransferDst).record([=](PassContext& pc) {
        pc.copyBuffer(pc.buffer(e).handle(), pc.buffer(eh).handle(), VkBufferCopy{0, 0, 256});
    });
    if (milestone)
        g.addPass("ready", PassKind::Transfer).use(eh, Use::TransferSrc).sideEffects().record([ev = event.handle()](PassContext& pc) {
            pc.signalHost(ev);
        });
    g.addPass("fill-later", PassKind::Transfer).use(l, Use::TransferDst).record([=](PassContext& pc) {
        pc.fillBuffer(pc.buffer(l).handle(), 0, kLaterBytes, value + 1);
    });
    g.addPass("copy-late", PassKind::Transfer).use(l, Use::TransferSrc).use(lh, Use::TransferDst).record([=](PassContext& pc) {
        pc.copyBuffer(pc.buffer(l).handle(), pc.buffer(lh).handle(), VkBufferCopy{0, 0, 256});
    });
}

}  // namespace

TEST_CASE("a milestone's callback runs mid-submission with the earlier passes' writes in host memory", "[gpu][graph][milestone]") {
    test::ValidatedContext ctx;
    vk::Device& dev = ctx.device();
    auto event = vk::Event::create(dev, "milestone-test");
    REQUIRE(event);
    auto early = vk::Buffer::create(dev, 256, 0, vk::MemoryKind::DeviceLocal, "early");
    auto early_host = vk::Buffer::create(dev, 256, 0, vk::MemoryKind::Readback, "early-host");
    auto later = vk::Buffer::create(dev, kLaterBytes, 0, vk::MemoryKind::DeviceLocal, "later");
    auto late_host = vk::Buffer::create(dev, 256, 0, vk::MemoryKind::Readback, "late-host");
    REQUIRE((early && early_host && later && late_host));

    graph::Executor exec(dev);
    int calls = 0;
    std::uint32_t seen = 0;
    // One run with `value`; the milestone armed, its pass in the graph or not.
    const auto run = [&](std::uint32_t value, bool pass) {
        poison(*early_host);
        poison(*late_host);
        Graph g;
        declare(g, value, pass, *event, *early, *early_host, *later, *late_host);
        exec.setMilestone({&*event, [&] {
                               ++calls;
                               seen = wordAt(*early_host, 63);
                           }});
        auto report = exec.run(g);
        INFO((report ? std::string() : report.error().message()));
        REQUIRE(report);
        CHECK(wordAt(*late_host, 0) == value + 1);
        return *report;
    };

    const ExecutionReport first = run(7, true);
    CHECK(calls == 1);
    CHECK(seen == 7u);
    CHECK(first.host.milestone_ms >= 0.0);
    CHECK(first.host.wait_ms >= 0.0);
    // The same commands: submitted again, the event unset first, the callback once more.
    const ExecutionReport second = run(7, true);
    CHECK(second.host.reused == 1u);
    CHECK(calls == 2);
    CHECK(seen == 7u);
    // Another value: recorded anew.
    run(9, true);
    CHECK(calls == 3);
    CHECK(seen == 9u);
    // Armed, but no pass sets the event: not called (the event was unset at the submission,
    // though the last one set it).
    seen = 0;
    run(11, false);
    CHECK(calls == 3);
    CHECK(seen == 0u);
    // Not armed: the next submission has no milestone.
    Graph g;
    declare(g, 13, true, *event, *early, *early_host, *later, *late_host);
    REQUIRE(exec.run(g));
    CHECK(calls == 3);
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}
