// A raster + compute graph end to end on the device, validation (with synchronization
// validation) on: any message fails the test.
#include <catch2/catch.hpp>

#include <cstring>

#include "graph/executor.hpp"
#include "test_shaders/all.hpp"
#include "support/gpu_fixture.hpp"
#include "support/graph_test_push.hpp"

using namespace vkcollide;
using namespace vkcollide::graph;
using test::DrawPush;
using test::SumPush;

TEST_CASE("raster then compute: watertight coverage counted twice, barriers derived", "[gpu][graph]") {
    test::ValidatedContext ctx;
    vk::Device& dev = ctx.device();
    // The sum pass reads a storage image through a pushed descriptor; VK_KHR_push_descriptor
    // is optional (context.hpp), and a device without it refuses the pipeline by name
    // (tests/vk/adopt_tests.cpp checks that refusal).
    if (!dev.push_descriptor) {
        WARN("skipped: " << ctx.context().deviceInfo().name << " has no VK_KHR_push_descriptor");
        return;
    }
    const vk::Pipeline::Binding no_bindings[1] = {};
    vk::Pipeline::RasterDesc rd;
    rd.vertex_spirv = shaders::graph_test_draw_vert;
    rd.fragment_spirv = shaders::graph_test_draw_frag;
    rd.color_formats = {VK_FORMAT_R32_UINT};
    auto draw = vk::Pipeline::createRaster(dev, rd, std::span(no_bindings, 0), sizeof(DrawPush), "graph-test-draw");
    REQUIRE(draw);
    const vk::Pipeline::Binding sum_bindings[] = {{0, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE}};
    auto sum = vk::Pipeline::createCompute(dev, shaders::graph_test_sum_comp, sum_bindings, sizeof(SumPush), "graph-test-sum");
    REQUIRE(sum);
    auto readback = vk::Buffer::create(dev, 8, 0, vk::MemoryKind::Readback, "counters");
    REQUIRE(readback);

    Graph g;
    auto color = g.createImage("coverage", {VK_FORMAT_R32_UINT, 64, 64, 1});
    auto counters = g.importBuffer("counters", *readback, true);
    g.addPass("clear-counters", PassKind::Transfer).use(counters, Use::TransferDst).record([&](PassContext& pc) {
        pc.fns().vkCmdFillBuffer(pc.cmd, pc.buffer(counters).handle(), 0, 8, 0);
    });
    g.addPass("draw", PassKind::Raster).colorAttachment(color).readWrite(counters).record([&](PassContext& pc) {
        // 32 x 16 pixels; the two triangles share the diagonal, which must not double-count.
        DrawPush push{{8, 8, 40, 24}, {64, 64}, pc.address(counters)};
        pc.fns().vkCmdBindPipeline(pc.cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, draw->handle());
        pc.fns().vkCmdPushConstants(pc.cmd, draw->layout(), VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                                    sizeof(push), &push);
        pc.fns().vkCmdDraw(pc.cmd, 6, 1, 0, 0);
    });
    g.addPass("sum", PassKind::Compute).use(color, Use::StorageRead).readWrite(counters).record([&](PassContext& pc) {
        VkDescriptorImageInfo ii{VK_NULL_HANDLE, pc.image(color).view(), VK_IMAGE_LAYOUT_GENERAL};
        VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
        w.dstBinding = 0;
        w.descriptorCount = 1;
        w.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
        w.pImageInfo = &ii;
        pc.fns().vkCmdBindPipeline(pc.cmd, VK_PIPELINE_BIND_POINT_COMPUTE, sum->handle());
        pc.fns().vkCmdPushDescriptorSetKHR(pc.cmd, VK_PIPELINE_BIND_POINT_COMPUTE, sum->layout(), 0, 1, &w);
        SumPush push{pc.address(counters) + 4};
        pc.fns().vkCmdPushConstants(pc.cmd, sum->layout(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
        pc.fns().vkCmdDispatch(pc.cmd, 8, 8, 1);
    });

    Executor exec(dev);
    for (int frame = 0; frame < 3; ++frame) {  // later runs reuse cached transients
        // Frame 0 sleeps in the driver's wait; later ones poll (frame 2 from the expected
        // end frame 1's GPU span gives).
        exec.setWaitPolling(frame == 0 ? 0 : 2'000'000);
        auto report = exec.run(g);
        INFO((report ? std::string() : report.error().message()));
        REQUIRE(report);
        REQUIRE(report->passes.size() == 3);
        CHECK(report->passes[1].name == "draw");
        for (const auto& p : report->passes) CHECK(p.gpu_ms >= 0.0);
        CHECK(report->total_gpu_ms > 0.0);
        // The host side of the one submission; the second run reuses the plan.
        CHECK(report->host.submissions == 1u);
        CHECK(report->host.gpu_span_ms == report->total_gpu_ms);
        CHECK(report->host.wait_ms >= 0.0);
        CHECK(report->host.launch_wake_ms >= 0.0);
        CHECK(exec.compilations() == 1u);
        readback->invalidate();
        std::uint32_t values[2];
        std::memcpy(values, readback->mapped(), sizeof(values));
        CHECK(values[0] == 32u * 16u);  // fragments
        CHECK(values[1] == 32u * 16u);  // covered pixels read back through the storage image
    }
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}
