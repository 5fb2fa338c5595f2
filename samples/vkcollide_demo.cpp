// The main job: runs a raster + compute render graph on the device vkcollide finds and
// prints the device and each pass's GPU time.
#include <cstdio>
#include <cstring>

#include "graph/executor.hpp"
#include "shaders/all.hpp"
#include "vkcollide/context.hpp"

using namespace vkcollide;
using namespace vkcollide::graph;

int main() {
    auto ctx = Context::create();
    if (!ctx) {
        std::fprintf(stderr, "vkcollide_demo: %s\n", ctx.error().message().c_str());
        return 1;
    }
    vk::Device& dev = (*ctx)->device();
    std::printf("device: %s (%s), %s\n", dev.info.name.c_str(), toString(dev.info.type), dev.info.driver.c_str());

    struct DrawPush {
        float rect[4];
        float extent[2];
        VkDeviceAddress counter;
    };
    vk::Pipeline::RasterDesc rd;
    rd.vertex_spirv = shaders::graph_test_draw_vert;
    rd.fragment_spirv = shaders::graph_test_draw_frag;
    rd.color_formats = {VK_FORMAT_R32_UINT};
    auto draw = vk::Pipeline::createRaster(dev, rd, {}, sizeof(DrawPush), "demo-draw");
    const vk::Pipeline::Binding bindings[] = {{0, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE}};
    auto sum = vk::Pipeline::createCompute(dev, shaders::graph_test_sum_comp, bindings, sizeof(VkDeviceAddress), "demo-sum");
    auto readback = vk::Buffer::create(dev, 8, 0, vk::MemoryKind::Readback, "counters");
    if (!draw || !sum || !readback) {
        std::fprintf(stderr, "vkcollide_demo: setup failed\n");
        return 1;
    }
    const std::uint32_t size = 1024;
    Graph g;
    auto color = g.createImage("coverage", {VK_FORMAT_R32_UINT, size, size, 1});
    auto counters = g.importBuffer("counters", *readback, true);
    g.addPass("clear", PassKind::Transfer).use(counters, Use::TransferDst).record([&](PassContext& pc) {
        pc.fns().vkCmdFillBuffer(pc.cmd, pc.buffer(counters).handle(), 0, 8, 0);
    });
    g.addPass("raster", PassKind::Raster).colorAttachment(color).readWrite(counters).record([&](PassContext& pc) {
        DrawPush push{{100, 100, 900, 700}, {float(size), float(size)}, pc.address(counters)};
        pc.fns().vkCmdBindPipeline(pc.cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, draw->handle());
        pc.fns().vkCmdPushConstants(pc.cmd, draw->layout(), VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                                    sizeof(push), &push);
        pc.fns().vkCmdDraw(pc.cmd, 6, 1, 0, 0);
    });
    g.addPass("compute", PassKind::Compute).use(color, Use::StorageRead).readWrite(counters).record([&](PassContext& pc) {
        VkDescriptorImageInfo ii{VK_NULL_HANDLE, pc.image(color).view(), VK_IMAGE_LAYOUT_GENERAL};
        VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
        w.descriptorCount = 1;
        w.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
        w.pImageInfo = &ii;
        pc.fns().vkCmdBindPipeline(pc.cmd, VK_PIPELINE_BIND_POINT_COMPUTE, sum->handle());
        pc.fns().vkCmdPushDescriptorSetKHR(pc.cmd, VK_PIPELINE_BIND_POINT_COMPUTE, sum->layout(), 0, 1, &w);
        VkDeviceAddress target = pc.address(counters) + 4;
        pc.fns().vkCmdPushConstants(pc.cmd, sum->layout(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(target), &target);
        pc.fns().vkCmdDispatch(pc.cmd, size / 8, size / 8, 1);
    });
    graph::Executor exec(dev);
    auto report = exec.run(g);
    if (!report) {
        std::fprintf(stderr, "vkcollide_demo: %s\n", report.error().message().c_str());
        return 1;
    }
    readback->invalidate();
    std::uint32_t counts[2];
    std::memcpy(counts, readback->mapped(), sizeof(counts));
    for (const auto& p : report->passes) std::printf("  %-10s %8.3f ms\n", p.name.c_str(), p.gpu_ms);
    std::printf("  total      %8.3f ms; fragments %u, covered pixels %u (expected %u)\n", report->total_gpu_ms, counts[0],
                counts[1], 800u * 600u);
    return counts[0] == 800u * 600u && counts[1] == 800u * 600u ? 0 : 1;
}
