#include "broad/peeling/packing.hpp"

#include <algorithm>

#include "shaders/all.hpp"

namespace vkcollide::passes {

using graph::PassContext;
using graph::PassKind;

static_assert(gpu::kPackRowWidth == gpu::kGroupSize, "pack_rowcount reduces a row with the workgroup helpers");

Result<std::unique_ptr<Packing>> Packing::create(vk::Device& device) {
    std::unique_ptr<Packing> p(new Packing());
    for (auto r : {makeCompute(device, p->pack_rowcount_, shaders::pack_rowcount_comp, "pack-rowcount"),
                   makeCompute(device, p->scan_counts_, shaders::scan_counts_comp, "scan-counts"),
                   makeCompute(device, p->pack_shift_, shaders::pack_shift_comp, "pack-shift"),
                   makeCompute(device, p->pack_move_, shaders::pack_move_comp, "pack-move"),
                   makeCompute(device, p->scan_blocksum_, shaders::scan_blocksum_comp, "scan-blocksum"),
                   makeCompute(device, p->scan_scatter_, shaders::scan_scatter_comp, "scan-scatter")})
        if (!r) return r.error();
    return p;
}

VkDeviceSize Packing::scratchBytes(std::uint32_t triangles) {
    const VkDeviceSize tris = std::max<std::uint32_t>(triangles, 1);
    const VkDeviceSize rows = (tris + gpu::kPackRowWidth - 1) / gpu::kPackRowWidth;
    const VkDeviceSize blocks = (tris + gpu::kGroupSize - 1) / gpu::kGroupSize;
    // Paper: row counts, row offsets, per-row pointers and shifted columns; scan: block sums and offsets.
    return std::max(2 * rows + 2 * rows * gpu::kPackRowWidth, 2 * blocks) * 4;
}

void Packing::record(graph::Graph& g, const RunView& run, const Buffers& b) const {
    const VkDeviceAddress frame = run.frame_address;
    const std::uint32_t rows = run.frame.pack_rows, blocks = run.frame.pack_blocks;
    if (run.settings.packing == PackingMethod::Paper) {
        addPass(g, "pack-count", PassKind::Compute, Stage::Packing)
            .read(b.sparse)
            .write(b.scratch)
            .record([this, frame, rows](PassContext& pc) {
                bindAndPush(pc, pack_rowcount_, frame);
                dispatchGroups(pc, rows);
                pc.shaderBarrier();
                bindAndPush(pc, scan_counts_, frame, 0, rows);
                pc.dispatch(1, 1, 1);
            });
        addPass(g, "pack-shift", PassKind::Compute, Stage::Packing)
            .read(b.sparse)
            .readWrite(b.scratch)
            .readWrite(b.header)
            .record([this, frame, rows](PassContext& pc) {
                bindAndPush(pc, pack_shift_, frame);
                dispatchItems(pc, rows, 64);
            });
        auto move = addPass(g, "pack-move", PassKind::Compute, Stage::Packing);
        move.read(b.sparse).read(b.scratch).read(b.projection).write(b.records);
        if (b.sparse_depth.valid()) move.read(b.sparse_depth);
        move.record([this, frame, rows](PassContext& pc) {
            bindAndPush(pc, pack_move_, frame);
            dispatchGroups(pc, rows);
        });
        return;
    }
    addPass(g, "pack-scan", PassKind::Compute, Stage::Packing)
        .read(b.sparse)
        .write(b.scratch)
        .readWrite(b.header)
        .record([this, frame, blocks](PassContext& pc) {
            bindAndPush(pc, scan_blocksum_, frame);
            dispatchGroups(pc, blocks);
            pc.shaderBarrier();
            bindAndPush(pc, scan_counts_, frame, 0, blocks);
            pc.dispatch(1, 1, 1);
        });
    auto scatter = addPass(g, "pack-scatter", PassKind::Compute, Stage::Packing);
    scatter.read(b.sparse).read(b.scratch).read(b.projection).write(b.records);
    if (b.sparse_depth.valid()) scatter.read(b.sparse_depth);
    scatter.record([this, frame, blocks](PassContext& pc) {
        bindAndPush(pc, scan_scatter_, frame);
        dispatchGroups(pc, blocks);
    });
}

}  // namespace vkcollide::passes
