#include "broad/common_stages.hpp"

#include <algorithm>
#include <cstddef>

#include "shaders/all.hpp"

namespace vkcollide::passes {

using graph::PassContext;
using graph::PassKind;
using graph::Use;

Result<std::unique_ptr<CommonStages>> CommonStages::create(vk::Device& device) {
    std::unique_ptr<CommonStages> c(new CommonStages());
    for (auto r : {makeCompute(device, c->validate_, shaders::validate_comp, "validate"),
                   makeCompute(device, c->bounds_, shaders::bounds_comp, "bounds"),
                   makeCompute(device, c->fit_, shaders::fit_comp, "fit")})
        if (!r) return r.error();
    return c;
}

void CommonStages::recordFront(graph::Graph& g, const RunView& run, const GraphBuffers& buffers, const CoreBuffers& core,
                               const std::vector<std::pair<BufferId, VkDeviceSize>>& cleared) const {
    const VkDeviceAddress frame = run.frame_address;
    const graph::ResourceId header = buffers[core.header];
    std::vector<std::pair<graph::ResourceId, VkDeviceSize>> zeroed;
    auto clear = addPass(g, "clear", PassKind::Transfer, Stage::Prepare);
    clear.use(header, Use::TransferDst);
    for (const auto& [row, size] : cleared) {
        clear.use(buffers[row], Use::TransferDst);
        zeroed.push_back({buffers[row], size});
    }
    clear.record([header, zeroed](PassContext& pc) {
        makeEngineWritesVisible(pc);
        // Disjoint ranges: counters 0, bound minima +inf (ordered), maxima and checks 0.
        constexpr VkDeviceSize mins = offsetof(gpu::Header, bounds), maxs = mins + 12;
        const VkBuffer h = pc.buffer(header).handle();
        pc.fillBuffer(h, 0, mins, 0);
        pc.fillBuffer(h, mins, 12, 0xFFFFFFFFu);
        pc.fillBuffer(h, maxs, sizeof(gpu::Header) - maxs, 0);
        for (const auto& [id, size] : zeroed) pc.fillBuffer(pc.buffer(id).handle(), 0, size, 0);
    });
    if (run.any_gpu_check) {
        addPass(g, "validate", PassKind::Compute, Stage::Prepare).readWrite(header).record([this, run](PassContext& pc) {
            for (std::uint32_t i = 0; i < run.meshes.size(); ++i) {
                if (!run.meshes[i].check_on_gpu) continue;
                bindAndPush(pc, validate_, run.frame_address, i);
                dispatchItems(pc, run.meshes[i].triangle_count);
            }
        });
    }
    if (!run.settings.region) {
        addPass(g, "bounds", PassKind::Compute, Stage::Prepare).readWrite(header).record([this, run](PassContext& pc) {
            // One dispatch per batch of objects (vertex_base restarts at each; one batch
            // unless the scene has more than kBoundsBatchVertices vertices).
            const std::span<const gpu::ObjectGpu> objects = run.objects;
            for (std::uint32_t first = 0; first < objects.size();) {
                std::uint32_t end = first + 1;
                while (end < objects.size() &&
                       objects[end].vertex_base == std::uint64_t{objects[end - 1].vertex_base} + objects[end - 1].vertex_count)
                    ++end;
                bindAndPush(pc, bounds_, run.frame_address, first, end - first);
                dispatchItems(pc, std::uint64_t{objects[end - 1].vertex_base} + objects[end - 1].vertex_count);
                first = end;
            }
        });
        addPass(g, "fit", PassKind::Compute, Stage::Prepare)
            .read(header)
            .write(buffers[core.projection])
            .record([this, frame](PassContext& pc) {
                bindAndPush(pc, fit_, frame);
                pc.dispatch(1, 1, 1);
            });
    }
}

void CommonStages::recordReadback(graph::Graph& g, const GraphBuffers& buffers, const CoreBuffers& core) const {
    const graph::ResourceId header = buffers[core.header], header_rb = buffers[core.header_readback];
    addPass(g, "readback-header", PassKind::Transfer, Stage::Readback)
        .use(header, Use::TransferSrc)
        .use(header_rb, Use::TransferDst)
        .record([header, header_rb](PassContext& pc) {
            VkBufferCopy copy{0, 0, sizeof(gpu::Header)};
            pc.copyBuffer(pc.buffer(header).handle(), pc.buffer(header_rb).handle(), copy);
        });
}

}  // namespace vkcollide::passes
