// CellStage::record: the stage's passes on the render graph. Every shader reaches its
// buffers through device addresses, so each pass declares the buffers it touches and the
// graph derives the barriers between passes; inside a pass, dependent dispatches are
// separated by shader barriers. Indirect arguments are always written one pass before
// the pass that dispatches from them (indirect reads need the graph's barrier).
#include <algorithm>

#include "broad/cells/cell_stage.hpp"
#include "broad/dispatch.hpp"
#include "broad/run_view.hpp"
#include "broad/stage.hpp"

namespace vkcollide::passes {
namespace {

using graph::PassContext;
using graph::PassKind;
using graph::Use;

std::uint64_t groupsFor(std::uint64_t items) { return (items + gpu::kCellsGroupSize - 1) / gpu::kCellsGroupSize; }

// Each pass declares its stage, so a broad phase sums its GPU time (stage.hpp).
graph::PassBuilder pass(graph::Graph& g, const char* name, PassKind kind, Stage stage) { return addPass(g, name, kind, stage); }

}  // namespace

CellStage::Resources CellStage::record(graph::Graph& g, graph::ResourceId projection) {
    survivor_count_ = gpu_triangle_count_ = 0;  // until this recording's finish()
    const VkDeviceAddress params = buf_.params->address();
    const std::uint64_t cells = recordedCells();  // the buffers hold as many
    const std::uint64_t blocks = (cells + gpu::kCellsScanBlock - 1) / gpu::kCellsScanBlock;
    const std::uint64_t tri_groups = groupsFor(triangles_);
    const auto header = importRow(g, buf_.header);
    const auto header_rb = importRow(g, buf_.header_rb, true);
    const auto tris = importRow(g, buf_.triangles);
    const auto geometry = importRow(g, buf_.geometry);
    const auto counts = importRow(g, buf_.counts);
    const auto offsets = importRow(g, buf_.offsets);
    const auto sums = importRow(g, buf_.block_sums);
    const auto entries = importRow(g, buf_.entries);
    const auto chunk_cells = importRow(g, buf_.chunk_cells);
    const auto big = importRow(g, buf_.big_items);
    const auto deep = importRow(g, buf_.deep_items);
    const auto candidates = importRow(g, buf_.candidates);
    const auto survivors = importRow(g, buf_.survivors, !survivors_on_device_);
    const auto args = importRow(g, buf_.args);
    const auto gpu_triangles = importRow(g, buf_.gpu_triangles, true);
    const auto marks = importRow(g, buf_.marks);
    const VkBuffer marks_buffer = has_download_ ? buf_.marks->handle() : VK_NULL_HANDLE;
    const VkDeviceSize marks_bytes = (VkDeviceSize(std::max(triangles_, 1u)) + 31) / 32 * 4;
    const VkBuffer args_buffer = buf_.args->handle();
    const VkBuffer header_buffer = buf_.header->handle();
    const VkBuffer counts_buffer = buf_.counts->handle();
    const auto& P = pipes_;
    const std::uint32_t max_x = max_groups_x_;

    pass(g, "cells-clear", PassKind::Transfer, Stage::Footprints).use(header, Use::TransferDst).use(counts, Use::TransferDst)
        .use(marks, Use::TransferDst).record(
        [header_buffer, counts_buffer, cells, marks_buffer, marks_bytes](PassContext& pc) {
            makeEngineWritesVisible(pc);
            // Header: flags 0, bad_triangle ~0, counters 0.
            pc.fillBuffer(header_buffer, 0, 4, 0);
            pc.fillBuffer(header_buffer, 4, 4, 0xFFFFFFFFu);
            pc.fillBuffer(header_buffer, 8, sizeof(gpu::CellsHeader) - 8, 0);
            pc.fillBuffer(counts_buffer, 0, cells * 4, 0);
            if (marks_buffer != VK_NULL_HANDLE) pc.fillBuffer(marks_buffer, 0, marks_bytes, 0);
        });

    auto setup = pass(g, "cells-setup", PassKind::Compute, Stage::Footprints);
    setup.readWrite(header).write(tris).write(geometry).readWrite(counts).write(big).write(args);
    if (projection.valid()) setup.read(projection);
    setup.record([&P, params, tri_groups, max_x](PassContext& pc) {
        bindAndPush(pc, P.setup, params);
        dispatchGroups(pc, tri_groups, max_x);
        pc.shaderBarrier();
        bindAndPush(pc, P.args, params, 0, 0);
        pc.dispatch(1, 1, 1);
    });

    pass(g, "cells-count-big", PassKind::Compute, Stage::Footprints)
        .indirect(args)
        .read(tris)
        .read(big)
        .read(header)
        .readWrite(counts)
        .record([&P, params, args_buffer](PassContext& pc) {
            bindAndPush(pc, P.big, params, 0, 0);
            pc.dispatchIndirect(args_buffer, gpu::kCellsArgsBig * 12);
        });

    pass(g, "cells-scan", PassKind::Compute, Stage::Footprints)
        .readWrite(counts)
        .readWrite(offsets)
        .readWrite(sums)
        .readWrite(header)
        .write(deep)
        .write(args)
        .write(chunk_cells)
        .record([&P, params, blocks, max_x](PassContext& pc) {
            bindAndPush(pc, P.scan, params, 0, 0);
            dispatchGroups(pc, blocks, max_x);
            pc.shaderBarrier();
            bindAndPush(pc, P.scan, params, 0, 1);
            pc.dispatch(1, 1, 1);
            pc.shaderBarrier();
            bindAndPush(pc, P.scan, params, 0, 2);
            dispatchGroups(pc, blocks, max_x);
            pc.shaderBarrier();
            bindAndPush(pc, P.args, params, 0, 1);
            pc.dispatch(1, 1, 1);
        });

    pass(g, "cells-fill", PassKind::Compute, Stage::Footprints)
        .indirect(args)
        .read(tris)
        .read(big)
        .read(offsets)
        .read(header)
        .readWrite(counts)
        .write(entries)
        .record([&P, fill = fillSlot().pipeline, params, tri_groups, args_buffer, max_x](PassContext& pc) {
            bindAndPush(pc, *fill, params);
            dispatchGroups(pc, tri_groups, max_x);
            bindAndPush(pc, P.big, params, 0, 1);  // other cells than the small triangles': no barrier needed
            pc.dispatchIndirect(args_buffer, gpu::kCellsArgsBig * 12);
        });

    recordSweep(g, {header, entries, chunk_cells, offsets, counts, deep, importRow(g, buf_.sorted), candidates, args});
    sweep_chunks_ = 1;  // a run starts its sweep over
    return recordPairPass(g, {header, header_rb, tris, geometry, candidates, survivors, args, gpu_triangles, marks, importRow(g, buf_.exact_queue)},
                          0);
}

// The sweep over the chunk of entries and deep items the arguments hold (the scan's last
// step, or recordSweepChunk's arguments pass, sized it).
void CellStage::recordSweep(graph::Graph& g, const SweepIds& id) {
    const VkDeviceAddress params = buf_.params->address();
    const VkBuffer args_buffer = buf_.args->handle();
    const vk::Pipeline* shallow = shallowSweepSlot().pipeline;
    // The loop counters only where the device ends long loops (llvmpipe).
    const vk::Pipeline* deep = deepSweepSlot().pipeline;
    const vk::Pipeline* sort = &pipes_.deep_sort;
    pass(g, kSweepPassName, PassKind::Compute, Stage::Pairing)
        .indirect(id.args)
        .readWrite(id.entries)  // huge cells are sorted in place
        .read(id.chunk_cells)
        .read(id.offsets)
        .readWrite(id.counts)  // kCellsCandidateBit: cells with a candidate
        .read(id.deep)
        .readWrite(id.sorted)
        .readWrite(id.header)
        .write(id.candidates)
        .record([shallow, deep, sort, params, args_buffer](PassContext& pc) {
            // The huge cells' sort first, over the deep items where there are huge cells
            // (every workgroup but a huge cell's first returns at once; none elsewhere).
            bindAndPush(pc, *sort, params);
            pc.dispatchIndirect(args_buffer, gpu::kCellsArgsSort * 12);
            pc.shaderBarrier();
            // The deep cells first: their few workgroups run longest (a sort of up to
            // kCellsDeepShared entries, then walks across the cell). Dispatched after the
            // tiles, they started in the tiles' last wave and ran past it (run 43, H100:
            // deform-pair-1M's sweep 0.87 -> 0.54 ms, pile-cgal 0.75 -> 0.59).
            bindAndPush(pc, *deep, params);
            pc.dispatchIndirect(args_buffer, gpu::kCellsArgsDeep * 12);
            bindAndPush(pc, *shallow, params);
            pc.dispatchIndirect(args_buffer, gpu::kCellsArgsSweep * 12);
        });
}

CellStage::Resources CellStage::recordSweepChunk(graph::Graph& g) {
    survivor_count_ = gpu_triangle_count_ = 0;
    const VkDeviceAddress params = buf_.params->address();
    const auto& P = pipes_;
    const auto header = importRow(g, buf_.header), args = importRow(g, buf_.args), candidates = importRow(g, buf_.candidates);
    pass(g, "cells-sweep-args", PassKind::Compute, Stage::Pairing)
        .readWrite(header)  // where the last chunk ended
        .write(args)
        .record([&P, params](PassContext& pc) {
            bindAndPush(pc, P.args, params, 0, 1);
            pc.dispatch(1, 1, 1);
        });
    recordSweep(g, {header, importRow(g, buf_.entries), importRow(g, buf_.chunk_cells), importRow(g, buf_.offsets),
                    importRow(g, buf_.counts), importRow(g, buf_.deep_items), importRow(g, buf_.sorted), candidates, args});
    ++sweep_chunks_;
    return recordPairPass(g,
                          {header, importRow(g, buf_.header_rb, true), importRow(g, buf_.triangles), importRow(g, buf_.geometry), candidates,
                           importRow(g, buf_.survivors, !survivors_on_device_), args, importRow(g, buf_.gpu_triangles, true),
                           importRow(g, buf_.marks), importRow(g, buf_.exact_queue)},
                          0);
}

// The pair pass over chunk `chunk` of the candidates (its arguments first), with the exact
// decision the exact pass over what it queued (its arguments first), then the header to
// the host: the last passes of a run, and all of a later chunk's submission.
CellStage::Resources CellStage::recordPairPass(graph::Graph& g, const PairPassIds& id, std::uint32_t chunk) {
    const VkDeviceAddress params = buf_.params->address();
    const VkBuffer args_buffer = buf_.args->handle();
    const VkBuffer header_buffer = buf_.header->handle(), header_rb_buffer = buf_.header_rb->handle();
    const auto& P = pipes_;
    // The run's form of the pair pass (pairSlot(); P.use_filter switches the filter).
    const bool queued = exactQueued();
    const vk::Pipeline* pairs = pairSlot().pipeline;
    pass(g, "cells-pair-args", PassKind::Compute, Stage::Pairing)
        .readWrite(id.header)  // the chunks done so far
        .write(id.args)
        .record([&P, params, chunk](PassContext& pc) {
            bindAndPush(pc, P.args, params, 0, 2 + chunk);
            pc.dispatch(1, 1, 1);
        });
    pass(g, kPairPassName, PassKind::Compute, Stage::Filtering)
        .indirect(id.args)
        .readWrite(id.candidates)  // proximity: marks the candidates outside their canonical cell
        .read(id.tris)
        .read(id.geometry)
        .readWrite(id.header)
        .readWrite(id.marks)
        .write(id.gpu_triangles)
        .write(id.survivors)
        .write(id.exact_queue)
        .record([pairs, params, args_buffer, chunk](PassContext& pc) {
            bindAndPush(pc, *pairs, params, 0, chunk);
            pc.dispatchIndirect(args_buffer, gpu::kCellsArgsPairChunk * 12);
        });
    if (queued) {
        pass(g, "cells-exact-args", PassKind::Compute, Stage::Filtering)
            .readWrite(id.header)  // the queue's length
            .write(id.args)
            .record([&P, params](PassContext& pc) {
                bindAndPush(pc, P.args, params, 0, gpu::kCellsArgsStepExact);
                pc.dispatch(1, 1, 1);
            });
        pass(g, kExactPassName, PassKind::Compute, Stage::Filtering)
            .indirect(id.args)
            .read(id.exact_queue)
            .read(id.tris)
            .read(id.geometry)
            .readWrite(id.header)
            .readWrite(id.marks)
            .write(id.gpu_triangles)
            .write(id.survivors)
            .record([&P, params, args_buffer](PassContext& pc) {
                bindAndPush(pc, P.exact, params);
                pc.dispatchIndirect(args_buffer, gpu::kCellsArgsExact * 12);
            });
    }
    pass(g, "cells-readback", PassKind::Transfer, Stage::Readback)
        .use(id.header, Use::TransferSrc)
        .use(id.header_rb, Use::TransferDst)
        .record([header_buffer, header_rb_buffer](PassContext& pc) {
            VkBufferCopy copy{0, 0, sizeof(gpu::CellsHeader)};
            pc.copyBuffer(header_buffer, header_rb_buffer, copy);
        });
    next_chunk_ = chunk + 1;
    return {id.header, id.survivors, id.tris, id.candidates, id.geometry, id.args};
}

CellStage::Resources CellStage::recordPairChunk(graph::Graph& g) {
    survivor_count_ = gpu_triangle_count_ = 0;
    return recordPairPass(g,
                          {importRow(g, buf_.header), importRow(g, buf_.header_rb, true),
                           importRow(g, buf_.triangles), importRow(g, buf_.geometry),
                           importRow(g, buf_.candidates),
                           importRow(g, buf_.survivors, !survivors_on_device_), importRow(g, buf_.args),
                           importRow(g, buf_.gpu_triangles, true), importRow(g, buf_.marks), importRow(g, buf_.exact_queue)},
                          next_chunk_);
}

}  // namespace vkcollide::passes
