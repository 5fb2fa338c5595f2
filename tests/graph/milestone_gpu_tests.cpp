// The executor's milestones on the device (validation with synchronization validation on:
// any message fails the test): passes that call PassContext::signalHost let collect() call
// the milestone's callback, event by event in order, with what the commands before each
// event wrote already in host memory; once per event and submission, resubmitted or
// recorded; never for an event no pass set, nor for the ones after it.
#include <catch2/catch.hpp>

#include <array>
#include <vector>

#include "graph/executor.hpp"
#include "support/gpu_fixture.hpp"
#include "support/mapped_words.hpp"
#include "vk/event.hpp"

using namespace vkcollide;
using namespace vkcollide::graph;
using test::poison;
using test::wordAt;

namespace {

constexpr VkDeviceSize kLaterBytes = VkDeviceSize{16} << 20;  // work after the milestones

// Two pieces of `early` (256 bytes each) filled with `value` and `value + 1` on the GPU; one
// pass copies piece 0 to the host and sets events[0], then piece 1 and sets events[1]
// (`signals` of them: 0 sets none); then a long fill of `later` and its first word copied
// to `late_host` with `value + 2`.
void declare(Graph& g, std::uint32_t value, int signals, const std::vector<vk::Event>& events, vk::Buffer& early,
             vk::Buffer& early_host, vk::Buffer& later, vk::Buffer& late_host) {
    auto e = g.importBuffer("early", early, true);
    auto eh = g.importBuffer("early-host", early_host, true);
    auto l = g.importBuffer("later", later, true);
    auto lh = g.importBuffer("late-host", late_host, true);
    g.addPass("fill-early", PassKind::Transfer).use(e, Use::TransferDst).record([=](PassContext& pc) {
        pc.fillBuffer(pc.buffer(e).handle(), 0, 256, value);
        pc.fillBuffer(pc.buffer(e).handle(), 256, 256, value + 1);
    });
    const std::array<VkEvent, 2> handles{events[0].handle(), events[1].handle()};
    g.addPass("copy-early", PassKind::Transfer).use(e, Use::TransferSrc).use(eh, Use::TransferDst).record([=](PassContext& pc) {
        for (int k = 0; k < 2; ++k) {
            const VkDeviceSize at = VkDeviceSize(k) * 256;
            pc.copyBuffer(pc.buffer(e).handle(), pc.buffer(eh).handle(), VkBufferCopy{at, at, 256});
            if (k < signals) pc.signalHost(handles[static_cast<std::size_t>(k)]);
        }
    });
    g.addPass("fill-later", PassKind::Transfer).use(l, Use::TransferDst).record([=](PassContext& pc) {
        pc.fillBuffer(pc.buffer(l).handle(), 0, kLaterBytes, value + 2);
    });
    g.addPass("copy-late", PassKind::Transfer).use(l, Use::TransferSrc).use(lh, Use::TransferDst).record([=](PassContext& pc) {
        pc.copyBuffer(pc.buffer(l).handle(), pc.buffer(lh).handle(), VkBufferCopy{0, 0, 256});
    });
}

}  // namespace

TEST_CASE("a milestone's callback runs mid-submission, event by event, with the earlier commands' writes in host memory",
          "[gpu][graph][milestone]") {
    test::ValidatedContext ctx;
    vk::Device& dev = ctx.device();
    std::vector<vk::Event> events;
    for (int k = 0; k < 2; ++k) {
        auto event = vk::Event::create(dev, "milestone-test");
        REQUIRE(event);
        events.push_back(std::move(*event));
    }
    auto early = vk::Buffer::create(dev, 512, 0, vk::MemoryKind::DeviceLocal, "early");
    auto early_host = vk::Buffer::create(dev, 512, 0, vk::MemoryKind::Readback, "early-host");
    auto later = vk::Buffer::create(dev, kLaterBytes, 0, vk::MemoryKind::DeviceLocal, "later");
    auto late_host = vk::Buffer::create(dev, 256, 0, vk::MemoryKind::Readback, "late-host");
    REQUIRE((early && early_host && later && late_host));

    graph::Executor exec(dev);
    std::vector<std::size_t> reached;
    std::vector<std::uint32_t> seen;  // the piece's last word, as the callback saw it
    // One run with `value`, the milestone armed; `signals` of its events set by the graph.
    const auto run = [&](std::uint32_t value, int signals) {
        poison(*early_host);
        poison(*late_host);
        reached.clear();
        seen.clear();
        Graph g;
        declare(g, value, signals, events, *early, *early_host, *later, *late_host);
        exec.setMilestone({events, [&](std::size_t k) {
                               reached.push_back(k);
                               seen.push_back(wordAt(*early_host, 64 * k + 63));
                           }});
        auto report = exec.run(g);
        INFO((report ? std::string() : report.error().message()));
        REQUIRE(report);
        CHECK(wordAt(*late_host, 0) == value + 2);
        return *report;
    };
    using V = std::vector<std::size_t>;
    using W = std::vector<std::uint32_t>;

    const ExecutionReport first = run(7, 2);
    CHECK(reached == V{0, 1});
    CHECK(seen == W{7, 8});
    CHECK(first.host.milestone_ms >= 0.0);
    CHECK(first.host.wait_ms >= 0.0);
    // The same commands: submitted again, the events unset first, the callback once more each.
    const ExecutionReport second = run(7, 2);
    CHECK(second.host.reused == 1u);
    CHECK(reached == V{0, 1});
    CHECK(seen == W{7, 8});
    // Another value: recorded anew.
    run(9, 2);
    CHECK(seen == W{9, 10});
    // Only the first event set: the second is never reached (it was set last time, and
    // unset at this submission).
    run(11, 1);
    CHECK(reached == V{0});
    CHECK(seen == W{11});
    // None set: nothing reached.
    run(13, 0);
    CHECK(reached.empty());
    // Not armed: the next submission has no milestone, though its pass sets the events.
    reached.clear();
    Graph g;
    declare(g, 15, 2, events, *early, *early_host, *later, *late_host);
    REQUIRE(exec.run(g));
    CHECK(reached.empty());
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}
