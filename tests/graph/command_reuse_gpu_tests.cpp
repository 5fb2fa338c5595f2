// The executor's command buffer reuse on the device (validation with synchronization
// validation on: any message fails the test). A graph declared anew for every run, as a
// detection does, records its command buffer once and submits it again while nothing
// changes; a changed parameter, a destroyed object, a direct recording or the engine's
// command buffer records anew. Before every run the host overwrites the results, so a
// resubmitted command buffer that did not run would show.
#include <catch2/catch.hpp>

#include <cstring>
#include <optional>

#include "graph/executor.hpp"
#include "support/engine_commands.hpp"
#include "support/gpu_fixture.hpp"
#include "support/mapped_words.hpp"
#include "support/graph_test_push.hpp"
#include "test_shaders/all.hpp"
#include "vk/semaphore.hpp"

using namespace vkcollide;
using namespace vkcollide::graph;
using test::DrawPush;
using test::SumPush;
using test::poison;
using test::wordAt;

namespace {

// Transfer writes before later transfer writes (the fills below overlap on purpose).
void transferBarrier(const PassContext& pc) {
    VkMemoryBarrier2 mb{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
    mb.srcStageMask = mb.dstStageMask = VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT;  // the layer files fills under copies
    mb.srcAccessMask = mb.dstAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT;
    VkDependencyInfo d{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    d.memoryBarrierCount = 1;
    d.pMemoryBarriers = &mb;
    pc.pipelineBarrier(d);
}

// What a run may change: the draw's push constants, the sum's dispatch, a transient's size.
struct Params {
    float rect[4] = {8, 8, 40, 24};
    std::uint32_t sum_groups_x = 8;
    VkDeviceSize scratch_bytes = 256;
};

// The raster + compute graph of graph_gpu_tests.cpp through the tape, plus a cleared
// transient: fragments counted into word 0, covered pixels summed into word 1.
void declare(Graph& g, const Params& p, vk::Buffer& counters_buffer, const vk::Pipeline& draw, const vk::Pipeline& sum) {
    auto color = g.createImage("coverage", {VK_FORMAT_R32_UINT, 64, 64, 1});
    auto scratch = g.createBuffer("scratch", p.scratch_bytes);
    auto counters = g.importBuffer("counters", counters_buffer, true);
    g.addPass("clear", PassKind::Transfer).use(counters, Use::TransferDst).use(scratch, Use::TransferDst).record([=](PassContext& pc) {
            pc.fillBuffer(pc.buffer(counters).handle(), 0, 8, 0);
            pc.fillBuffer(pc.buffer(scratch).handle(), 0, 64, 0);
        });
    g.addPass("draw", PassKind::Raster).colorAttachment(color).readWrite(counters).record([=, &draw](PassContext& pc) {
        DrawPush push{{p.rect[0], p.rect[1], p.rect[2], p.rect[3]}, {64, 64}, pc.address(counters)};
        pc.bindPipeline(VK_PIPELINE_BIND_POINT_GRAPHICS, draw.handle());
        pc.pushConstants(draw.layout(), VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(push), &push);
        pc.draw(6);
    });
    g.addPass("sum", PassKind::Compute).use(color, Use::StorageRead).readWrite(counters).record([=, &sum](PassContext& pc) {
        VkDescriptorImageInfo ii{VK_NULL_HANDLE, pc.image(color).view(), VK_IMAGE_LAYOUT_GENERAL};
        VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
        w.dstBinding = 0;
        w.descriptorCount = 1;
        w.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
        w.pImageInfo = &ii;
        pc.bindPipeline(VK_PIPELINE_BIND_POINT_COMPUTE, sum.handle());
        pc.pushDescriptorSet(VK_PIPELINE_BIND_POINT_COMPUTE, sum.layout(), 0, {&w, 1});
        SumPush push{pc.address(counters) + 4};
        pc.pushConstants(sum.layout(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
        pc.dispatch(p.sum_groups_x, 8, 1);
    });
}

}  // namespace

TEST_CASE("a steady graph is recorded once and submitted again, and a changed push constant, dispatch size or object records anew",
          "[gpu][graph][reuse]") {
    test::ValidatedContext ctx;
    vk::Device& dev = ctx.device();
    if (!dev.push_descriptor) {  // the sum pass pushes its descriptor (as graph_gpu_tests.cpp)
        WARN("skipped: " << ctx.context().deviceInfo().name << " has no VK_KHR_push_descriptor");
        return;
    }
    vk::Pipeline::RasterDesc rd;
    rd.vertex_spirv = shaders::graph_test_draw_vert;
    rd.fragment_spirv = shaders::graph_test_draw_frag;
    rd.color_formats = {VK_FORMAT_R32_UINT};
    auto draw = vk::Pipeline::createRaster(dev, rd, {}, sizeof(DrawPush), "reuse-test-draw");
    REQUIRE(draw);
    const vk::Pipeline::Binding sum_bindings[] = {{0, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE}};
    auto sum = vk::Pipeline::createCompute(dev, shaders::graph_test_sum_comp, sum_bindings, sizeof(SumPush), "reuse-test-sum");
    REQUIRE(sum);
    auto counters = vk::Buffer::create(dev, 8, 0, vk::MemoryKind::Readback, "counters");
    REQUIRE(counters);

    graph::Executor exec(dev);
    Params params;
    // One run of a freshly declared graph; whether it was a resubmission; the two counters.
    struct Outcome {
        bool reused = false;
        std::uint32_t fragments = 0, pixels = 0;
    };
    const auto run = [&]() -> Outcome {
        poison(*counters);
        Graph g;
        declare(g, params, *counters, *draw, *sum);
        const std::uint64_t before = exec.reuses();
        auto report = exec.run(g);
        INFO((report ? std::string() : report.error().message()));
        REQUIRE(report);
        CHECK(report->host.submissions == 1u);
        CHECK(report->host.reused == exec.reuses() - before);
        REQUIRE(report->passes.size() == 3);
        for (const auto& pass : report->passes) CHECK(pass.gpu_ms >= 0.0);  // fresh timestamps, reused or not
        CHECK(report->total_gpu_ms > 0.0);
        return {report->host.reused == 1, wordAt(*counters, 0), wordAt(*counters, 1)};
    };

    Outcome o = run();
    CHECK_FALSE(o.reused);
    CHECK(o.fragments == 32u * 16u);
    CHECK(o.pixels == 32u * 16u);
    for (int i = 0; i < 2; ++i) {
        o = run();
        CHECK(o.reused);
        CHECK(o.fragments == 32u * 16u);
        CHECK(o.pixels == 32u * 16u);
    }
    CHECK(exec.reuses() == 2u);

    SECTION("a changed push constant records anew, then is reused") {
        params.rect[2] = 24;  // 16 x 16 pixels
        o = run();
        CHECK_FALSE(o.reused);
        CHECK(o.fragments == 16u * 16u);
        CHECK(o.pixels == 16u * 16u);
        o = run();
        CHECK(o.reused);
        CHECK(o.pixels == 16u * 16u);
    }
    SECTION("a changed dispatch size records anew") {
        params.sum_groups_x = 2;  // columns 0..15: 8 of the rectangle's 32
        o = run();
        CHECK_FALSE(o.reused);
        CHECK(o.fragments == 32u * 16u);
        CHECK(o.pixels == 8u * 16u);
        o = run();
        CHECK(o.reused);
        CHECK(o.pixels == 8u * 16u);
    }
    SECTION("an imported buffer destroyed and created again (same size) records anew") {
        *counters = vk::Buffer{};  // the handle value may come back for the new one
        auto again = vk::Buffer::create(dev, 8, 0, vk::MemoryKind::Readback, "counters");
        REQUIRE(again);
        *counters = std::move(*again);
        o = run();
        CHECK_FALSE(o.reused);
        CHECK(o.pixels == 32u * 16u);
        CHECK(run().reused);
    }
    SECTION("a transient created again (grown) records anew") {
        params.scratch_bytes = 4096;  // same commands: only the buffer behind them changes
        o = run();
        CHECK_FALSE(o.reused);
        CHECK(o.pixels == 32u * 16u);
        CHECK(run().reused);
    }
    SECTION("any buffer of the device destroyed records anew, even with equal commands") {
        {
            auto unrelated = vk::Buffer::create(dev, 64, 0, vk::MemoryKind::DeviceLocal, "unrelated");
            REQUIRE(unrelated);
        }
        o = run();
        CHECK_FALSE(o.reused);
        CHECK(o.pixels == 32u * 16u);
        CHECK(run().reused);
    }
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("a callback that records through PassContext::cmd keeps its order and is never submitted again",
          "[gpu][graph][reuse]") {
    test::ValidatedContext ctx;
    vk::Device& dev = ctx.device();
    auto out = vk::Buffer::create(dev, 16, 0, vk::MemoryKind::Readback, "out");
    REQUIRE(out);
    graph::Executor exec(dev);
    // Words 0..2 written by tape, direct, tape calls in that order (the same word twice,
    // so the order shows); word 3 by the tape only.
    const auto run = [&](bool direct) {
        poison(*out);
        Graph g;
        auto id = g.importBuffer("out", *out, true);
        g.addPass("fill", PassKind::Transfer).use(id, Use::TransferDst).record([=](PassContext& pc) {
            const VkBuffer b = pc.buffer(id).handle();
            pc.fillBuffer(b, 0, 8, 1);
            transferBarrier(pc);
            if (direct) pc.fns().vkCmdFillBuffer(pc.cmd, b, 4, 8, 2);
            transferBarrier(pc);
            pc.fillBuffer(b, 8, 8, 3);
        });
        auto report = exec.run(g);
        REQUIRE(report);
        CHECK(wordAt(*out, 0) == 1u);
        CHECK(wordAt(*out, 1) == (direct ? 2u : 1u));
        CHECK(wordAt(*out, 2) == 3u);
        CHECK(wordAt(*out, 3) == 3u);
        return report->host.reused == 1;
    };
    CHECK_FALSE(run(true));
    CHECK_FALSE(run(true));
    CHECK_FALSE(run(true));
    CHECK(exec.reuses() == 0u);
    // The tape alone afterwards: recorded (the direct runs reset the pool), then reused.
    CHECK_FALSE(run(false));
    CHECK(run(false));
    CHECK_FALSE(run(true));
    CHECK_FALSE(run(false));
    CHECK(run(false));
    CHECK(exec.reuses() == 2u);
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("work recorded into the engine's command buffer is never a resubmission, and keeps the executor's own",
          "[gpu][graph][reuse]") {
    test::ValidatedContext ctx;
    vk::Device& dev = ctx.device();
    REQUIRE(dev.timeline_semaphore);
    auto out = vk::Buffer::create(dev, 8, 0, vk::MemoryKind::Readback, "out");
    auto timeline = vk::Semaphore::createTimeline(dev, 0, "engine-timeline");
    REQUIRE(out);
    REQUIRE(timeline);
    {
        graph::Executor exec(dev);
        std::uint64_t value = 0;
        // engine: the engine's command buffer takes the work and the engine submits it.
        const auto run = [&](bool engine) {
            poison(*out);
            Graph g;
            auto id = g.importBuffer("out", *out, true);
            g.addPass("fill", PassKind::Transfer).use(id, Use::TransferDst).record([=](PassContext& pc) {
                pc.fillBuffer(pc.buffer(id).handle(), 0, 8, 5);
            });
            if (!engine) {
                auto report = exec.run(g);
                REQUIRE(report);
                CHECK(wordAt(*out, 1) == 5u);
                return report->host.reused == 1;
            }
            test::EngineCommands engine_commands(dev);
            const EngineCommandBuffer target{engine_commands.cmd, timeline->handle(), ++value};
            SubmitTarget into{{}, &target};
            REQUIRE(exec.submit(g, kDefaultTimeoutNs, &into));
            engine_commands.submit(timeline->handle(), value);
            auto report = exec.collect();
            REQUIRE(report);
            CHECK(wordAt(*out, 1) == 5u);
            return report->host.reused == 1;
        };
        CHECK_FALSE(run(false));
        CHECK(run(false));
        CHECK_FALSE(run(true));
        CHECK_FALSE(run(true));
        CHECK(exec.reuses() == 1u);
        CHECK(run(false));  // the executor's own command buffer outlived the engine's runs
        CHECK(exec.reuses() == 2u);
    }
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}
