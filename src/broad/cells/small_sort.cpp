#include "broad/cells/small_sort.hpp"

#include <algorithm>
#include <cstring>
#include <string>

#include "broad/dispatch.hpp"
#include "broad/stage.hpp"
#include "shaders/all.hpp"
#include "vkcollide/narrow.hpp"

namespace vkcollide::passes {
namespace {

static_assert(sizeof(gpu::SmallSortParams) == 9 * 8 + 2 * 4);
static_assert(sizeof(gpu::SmallSortHeader) == 16);
static_assert(sizeof(CandidatePair) == 8 && sizeof(gpu::DeviceResponse) == sizeof(TriangleResponse));

constexpr std::uint32_t kMaxEnds = 2 * gpu::kSmallSortPairs;

// Twice the last count, at least kMinCopy, at most what the pass writes.
std::uint32_t copyCount(std::uint32_t last, std::uint32_t most) {
    return std::min(most, std::max(SmallSortStage::kMinCopy, 2 * last));
}

}  // namespace

Result<std::unique_ptr<SmallSortStage>> SmallSortStage::create(vk::Device& device, BufferTable& table) {
    std::unique_ptr<SmallSortStage> stage(new SmallSortStage(device, table));
    auto p = vk::Pipeline::createCompute(device, shaders::small_sort_comp, {}, sizeof(gpu::Push), "small-sort");
    if (!p) return p.error();
    stage->pipeline_ = std::move(*p);
    auto respond = vk::Pipeline::createCompute(device, shaders::small_sort_respond_comp, {}, sizeof(gpu::Push), "small-sort-respond");
    if (!respond) return respond.error();
    stage->respond_pipeline_ = std::move(*respond);
    using vk::MemoryKind;
    Buffers& b = stage->buf_;
    b.params = table.addOwned("small-sort-params", MemoryKind::Upload);
    b.header = table.addOwned("small-sort-header", MemoryKind::DeviceLocal);
    b.pairs = table.addOwned("small-sort-pairs", MemoryKind::DeviceLocal);
    b.ends = table.addOwned("small-sort-ends", MemoryKind::DeviceLocal);
    b.responders = table.addOwned("small-sort-responders", MemoryKind::DeviceLocal);
    b.run_begin = table.addOwned("small-sort-run-begin", MemoryKind::DeviceLocal);
    b.args = table.addOwned("small-sort-args", MemoryKind::DeviceLocal, VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT);
    b.normals = table.addOwned("small-sort-normals", MemoryKind::DeviceLocal);
    b.responses = table.addOwned("small-sort-responses", MemoryKind::DeviceLocal);
    b.host_header = table.addOwned("small-sort-header-host", MemoryKind::Readback);
    b.host_pairs = table.addOwned("small-sort-pairs-host", MemoryKind::Readback);
    b.host_responses = table.addOwned("small-sort-responses-host", MemoryKind::Readback);
    return stage;
}

Result<void> SmallSortStage::prepare(const CellStage& cells, std::uint32_t last_pairs, std::uint32_t last_responses) {
    using vk::MemoryKind;
    const std::uint32_t triangles = cells.triangleCount();
    copy_pairs_ = copyCount(last_pairs, gpu::kSmallSortPairs);
    copy_responses_ = copyCount(last_responses, std::min(kMaxEnds, std::max(triangles, 1u)));
    const RowSize plan[] = {
        rowSize(buf_.params, sizeof(gpu::SmallSortParams), MemoryKind::Upload),
        rowSize(buf_.header, sizeof(gpu::SmallSortHeader), MemoryKind::DeviceLocal),
        rowSize(buf_.pairs, VkDeviceSize(gpu::kSmallSortPairs) * 8, MemoryKind::DeviceLocal),
        rowSize(buf_.ends, VkDeviceSize(kMaxEnds) * 8, MemoryKind::DeviceLocal),
        rowSize(buf_.responders, VkDeviceSize(kMaxEnds) * 4, MemoryKind::DeviceLocal),
        rowSize(buf_.run_begin, VkDeviceSize(kMaxEnds + 1) * 4, MemoryKind::DeviceLocal),
        rowSize(buf_.args, 12, MemoryKind::DeviceLocal),
        rowSize(buf_.normals, VkDeviceSize(kMaxEnds) * 3 * sizeof(double), MemoryKind::DeviceLocal),
        rowSize(buf_.responses, VkDeviceSize(kMaxEnds) * sizeof(gpu::DeviceResponse), MemoryKind::DeviceLocal),
        rowSize(buf_.host_header, sizeof(gpu::SmallSortHeader), MemoryKind::Readback),
        rowSize(buf_.host_pairs, VkDeviceSize(copy_pairs_) * 8, MemoryKind::Readback),
        rowSize(buf_.host_responses, VkDeviceSize(copy_responses_) * sizeof(gpu::DeviceResponse), MemoryKind::Readback),
    };
    if (auto ok = table_->reserve(*device_, plan, "few pairs sorted in one pass"); !ok) return ok;
    gpu::SmallSortParams p{};
    p.cells = cells.paramsAddress();
    p.header = buf_.header->address();
    p.pairs = buf_.pairs->address();
    p.ends = buf_.ends->address();
    p.responders = buf_.responders->address();
    p.run_begin = buf_.run_begin->address();
    p.args = buf_.args->address();
    p.normals = buf_.normals->address();
    p.responses = buf_.responses->address();
    p.triangle_count = triangles;
    std::memcpy(buf_.params->mapped(), &p, sizeof p);
    buf_.params->flush();
    return {};
}

void SmallSortStage::record(graph::Graph& g, const CellStage::Resources& cells) {
    Buffers& b = buf_;
    const auto header = importRow(g, b.header), pairs = importRow(g, b.pairs), ends = importRow(g, b.ends);
    const auto responders = importRow(g, b.responders), run_begin = importRow(g, b.run_begin), args = importRow(g, b.args);
    const auto normals = importRow(g, b.normals), responses = importRow(g, b.responses);
    const VkDeviceAddress params = b.params->address();
    const vk::Pipeline* pipe = &pipeline_;
    const vk::Pipeline* respond = &respond_pipeline_;
    addPass(g, "pairs-small", graph::PassKind::Compute, Stage::Sorting)
        .read(cells.header)
        .read(cells.survivors)
        .write(header)
        .write(pairs)
        .write(ends)
        .write(responders)
        .write(run_begin)
        .write(args)
        .record([pipe, params](graph::PassContext& pc) {
            bindAndPush(pc, *pipe, params);
            pc.dispatch(1, 1, 1);
        });
    // Over the responders, as many workgroups as they need (none where the pass skipped).
    addPass(g, "pairs-small-responses", graph::PassKind::Compute, Stage::Sorting)
        .indirect(args)
        .read(cells.triangles)
        .read(cells.geometry)
        .read(header)
        .read(ends)
        .read(responders)
        .read(run_begin)
        .write(normals)
        .write(responses)
        .record([respond, params, args_buffer = b.args->handle()](graph::PassContext& pc) {
            bindAndPush(pc, *respond, params, 0, 0);
            pc.dispatchIndirect(args_buffer, 0);
            pc.shaderBarrier();
            bindAndPush(pc, *respond, params, 0, 1);
            pc.dispatchIndirect(args_buffer, 0);
        });
    const auto host_header = importRow(g, b.host_header, true), host_pairs = importRow(g, b.host_pairs, true);
    const auto host_responses = importRow(g, b.host_responses, true);
    addPass(g, "pairs-small-to-host", graph::PassKind::Transfer, Stage::Readback)
        .use(header, graph::Use::TransferSrc)
        .use(pairs, graph::Use::TransferSrc)
        .use(responses, graph::Use::TransferSrc)
        .use(host_header, graph::Use::TransferDst)
        .use(host_pairs, graph::Use::TransferDst)
        .use(host_responses, graph::Use::TransferDst)
        .record([header = b.header->handle(), pairs = b.pairs->handle(), responses = b.responses->handle(),
                 host_header = b.host_header->handle(), host_pairs = b.host_pairs->handle(), host_responses = b.host_responses->handle(),
                 pair_bytes = VkDeviceSize(copy_pairs_) * 8,
                 response_bytes = VkDeviceSize(copy_responses_) * sizeof(gpu::DeviceResponse)](graph::PassContext& pc) {
            pc.copyBuffer(header, host_header, VkBufferCopy{0, 0, sizeof(gpu::SmallSortHeader)});
            pc.copyBuffer(pairs, host_pairs, VkBufferCopy{0, 0, pair_bytes});
            pc.copyBuffer(responses, host_responses, VkBufferCopy{0, 0, response_bytes});
        });
}

SmallSortStage::Output SmallSortStage::result() const {
    Output out;
    gpu::SmallSortHeader h{};
    buf_.host_header->invalidate();
    std::memcpy(static_cast<void*>(&h), buf_.host_header->mapped(), sizeof h);
    if (h.status != gpu::kSmallSortDone) return out;
    out.pairs = h.pairs;
    out.responses = h.responses;
    // Counts past what the pass writes would be a broken header: never read past the copies.
    if (h.pairs > copy_pairs_ || h.responses > copy_responses_ || h.responses > 2 * h.pairs) return out;
    out.done = true;
    if (h.pairs > 0) {
        buf_.host_pairs->invalidate(0, VkDeviceSize(h.pairs) * sizeof(CandidatePair));
        out.sorted = {static_cast<const CandidatePair*>(buf_.host_pairs->mapped()), h.pairs};
    }
    if (h.responses > 0) {
        buf_.host_responses->invalidate(0, VkDeviceSize(h.responses) * sizeof(TriangleResponse));
        out.sorted_responses = {static_cast<const TriangleResponse*>(buf_.host_responses->mapped()), h.responses};
    }
    return out;
}

}  // namespace vkcollide::passes
