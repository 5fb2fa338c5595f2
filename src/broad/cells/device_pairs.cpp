#include "broad/cells/device_pairs.hpp"

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstring>
#include <string>

#include "broad/dispatch.hpp"
#include "broad/run_view.hpp"
#include "broad/stage.hpp"
#include "shaders/all.hpp"
#include "vkcollide/world.hpp"

namespace vkcollide::passes {
namespace {

// The public layout is the shaders' (spirv/cells/cells.h).
static_assert(sizeof(gpu::DevicePair) == sizeof(TrianglePair) && offsetof(gpu::DevicePair, object_b) == offsetof(TrianglePair, object_b) &&
              offsetof(gpu::DevicePair, triangle_a) == offsetof(TrianglePair, triangle_a) &&
              offsetof(gpu::DevicePair, triangle_b) == offsetof(TrianglePair, triangle_b));
static_assert(sizeof(gpu::DevicePairsHeader) == sizeof(DevicePairsHeader) && offsetof(gpu::DevicePairsHeader, needed) == 4 &&
              offsetof(gpu::DevicePairsHeader, flags) == 8 && offsetof(gpu::DevicePairsHeader, capacity) == 12);
static_assert(gpu::kDevicePairsOverflow == kDevicePairsOverflow && gpu::kDevicePairsIncomplete == kDevicePairsIncomplete);
static_assert(sizeof(gpu::DevicePairsParams) == 11 * 8 + 6 * 4);

// A header the run copied to a readback row (`copied`), as the GPU left it; zeros otherwise.
template <typename Row>
gpu::DevicePairsHeader headerIn(const Row& row, bool copied) {
    gpu::DevicePairsHeader h{};
    if (!copied || !row->valid()) return h;
    row->invalidate();
    std::memcpy(static_cast<void*>(&h), row->mapped(), sizeof h);
    return h;
}

}  // namespace

Result<std::unique_ptr<DevicePairStage>> DevicePairStage::create(vk::Device& device, BufferTable& table) {
    std::unique_ptr<DevicePairStage> stage(new DevicePairStage(device, table));
    auto p = vk::Pipeline::createCompute(device, shaders::device_pairs_comp, {}, sizeof(gpu::Push), "device-pairs");
    if (!p) return p.error();
    stage->pipeline_ = std::move(*p);
    using vk::MemoryKind;
    Buffers& b = stage->buf_;
    b.params = table.addOwned("device-pairs-params", MemoryKind::Upload);
    b.object_ids = table.addOwned("device-pairs-object-ids", MemoryKind::Upload);
    b.counts = table.addOwned("device-pairs-counts", MemoryKind::DeviceLocal);
    b.offsets = table.addOwned("device-pairs-offsets", MemoryKind::DeviceLocal);
    b.out_offsets = table.addOwned("device-pairs-out-offsets", MemoryKind::DeviceLocal);
    b.block_sums = table.addOwned("device-pairs-block-sums", MemoryKind::DeviceLocal);
    b.partners = table.addOwned("device-pairs-partners", MemoryKind::DeviceLocal);
    b.args = table.addOwned("device-pairs-args", MemoryKind::DeviceLocal, VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT);
    // The two the engine reads: a grown one keeps the old buffer for two more starts.
    b.header = table.addOwned("device-pairs-header", MemoryKind::DeviceLocal, 0, true);
    b.pairs = table.addOwned("device-pairs", MemoryKind::DeviceLocal, 0, true);
    b.header_rb = table.addOwned("device-pairs-header-readback", MemoryKind::Readback);
    b.host_pairs = table.addOwned("device-pairs-host", MemoryKind::Readback);
    b.header_rb_early = table.addOwned("device-pairs-header-early", MemoryKind::Readback);
    for (std::uint32_t k = 0; k < kMaxEarlyChunks; ++k) {
        auto event = vk::Event::create(device, "device-pairs-ready-" + std::to_string(k));
        if (!event) return event.error();
        stage->events_.push_back(std::move(*event));
    }
    return stage;
}

void DevicePairStage::retire() { table_->retire(); }

Result<void> DevicePairStage::prepare(const CellStage& cells, std::span<const std::uint32_t> object_ids, std::uint32_t capacity,
                                      VkDeviceAddress fault_header, bool header_to_host, bool for_host, std::uint32_t response_capacity,
                                      std::uint32_t early_piece_pairs) {
    using vk::MemoryKind;
    triangles_ = cells.triangleCount();
    header_to_host_ = header_to_host;
    for_host_ = for_host;
    early_ = early_piece_pairs > 0 && for_host && header_to_host;
    max_groups_x_ = cells.maxGroupsX();
    const std::uint32_t survivors = cells.capacity().survivors;
    // Automatic: the survivor capacity, which holds every distinct pair of a complete run.
    capacity_ = capacity ? capacity : survivors;
    // Pieces of at least early_piece_pairs (kMinEarlyChunkPairs by default): a piece's naming
    // on the host wakes its threads and each event costs a barrier, worth it where the copy
    // is long.
    early_chunks_ = std::clamp<std::uint32_t>(early_piece_pairs ? capacity_ / early_piece_pairs : 1, 1, kMaxEarlyChunks);
    early_chunk_pairs_ = (capacity_ + early_chunks_ - 1) / early_chunks_;
    const VkDeviceSize tris = std::max<std::uint32_t>(triangles_, 1);
    const VkDeviceSize blocks = (tris + gpu::kCellsScanBlock - 1) / gpu::kCellsScanBlock;
    const RowSize plan[] = {
        rowSize(buf_.params, sizeof(gpu::DevicePairsParams), MemoryKind::Upload),
        rowSize(buf_.object_ids, object_ids.size_bytes(), MemoryKind::Upload),
        rowSize(buf_.counts, tris * 4, MemoryKind::DeviceLocal),
        rowSize(buf_.offsets, (tris + 1) * 4, MemoryKind::DeviceLocal),
        rowSize(buf_.out_offsets, (tris + 1) * 4, MemoryKind::DeviceLocal),
        rowSize(buf_.block_sums, blocks * 4, MemoryKind::DeviceLocal),
        rowSize(buf_.partners, VkDeviceSize(survivors) * 4, MemoryKind::DeviceLocal),
        rowSize(buf_.args, 12, MemoryKind::DeviceLocal),
        rowSize(buf_.header, sizeof(gpu::DevicePairsHeader), MemoryKind::DeviceLocal),
        rowSize(buf_.header_rb, header_to_host ? sizeof(gpu::DevicePairsHeader) : 0, MemoryKind::Readback),
        rowSize(buf_.pairs, VkDeviceSize(capacity_) * pairBytes(), MemoryKind::DeviceLocal),
        rowSize(buf_.host_pairs, for_host ? VkDeviceSize(capacity_) * pairBytes() : 0, MemoryKind::Readback),
        rowSize(buf_.header_rb_early, early_ ? sizeof(gpu::DevicePairsHeader) : 0, MemoryKind::Readback),
    };
    if (auto ok = table_->reserve(*device_, plan,
                                  "device pairs: capacity " + std::to_string(capacity_) + " with " + std::to_string(triangles_) + " triangles");
        !ok)
        return ok;
    if (!object_ids.empty()) {
        std::memcpy(buf_.object_ids->mapped(), object_ids.data(), object_ids.size_bytes());
        buf_.object_ids->flush();
    }
    gpu::DevicePairsParams p{};
    p.cells = cells.paramsAddress();
    p.fault_header = fault_header;
    p.object_ids = buf_.object_ids->address();
    p.counts = buf_.counts->address();
    p.offsets = buf_.offsets->address();
    p.out_offsets = buf_.out_offsets->address();
    p.block_sums = buf_.block_sums->address();
    p.partners = buf_.partners->address();
    p.args = buf_.args->address();
    p.header = buf_.header->address();
    p.pairs = buf_.pairs->address();
    p.triangle_count = triangles_;
    p.block_count = static_cast<std::uint32_t>((VkDeviceSize(triangles_) + gpu::kCellsScanBlock - 1) / gpu::kCellsScanBlock);
    p.capacity = capacity_;
    p.max_groups_x = max_groups_x_;
    p.response_capacity = response_capacity;
    p.packed = for_host ? 1u : 0u;
    std::memcpy(buf_.params->mapped(), &p, sizeof p);
    buf_.params->flush();
    return {};
}

DevicePairStage::Resources DevicePairStage::record(graph::Graph& g, const CellStage::Resources& cells, graph::ResourceId fault_header) {
    Buffers& b = buf_;
    const auto header = importRow(g, b.header);
    const auto pairs = importRow(g, b.pairs);
    const auto counts = importRow(g, b.counts);
    const auto offsets = importRow(g, b.offsets);
    const auto out_offsets = importRow(g, b.out_offsets);
    const auto sums = importRow(g, b.block_sums);
    const auto partners = importRow(g, b.partners);
    const auto args = importRow(g, b.args);
    const VkDeviceAddress params = buf_.params->address();
    const VkBuffer counts_buffer = buf_.counts->handle(), args_buffer = buf_.args->handle();
    const VkDeviceSize count_bytes = VkDeviceSize(std::max<std::uint32_t>(triangles_, 1)) * 4;
    // Per-triangle passes are sized by the run's triangles; per-survivor ones dispatch
    // indirectly from the count the pair pass left.
    const std::uint64_t tri_groups = (std::uint64_t(triangles_) + gpu::kCellsGroupSize - 1) / gpu::kCellsGroupSize;
    const std::uint64_t blocks = (std::uint64_t(triangles_) + gpu::kCellsScanBlock - 1) / gpu::kCellsScanBlock;
    const std::uint32_t max_x = max_groups_x_;
    const vk::Pipeline* pipe = &pipeline_;

    addPass(g, "pairs-clear", graph::PassKind::Transfer, Stage::Sorting)
        .use(counts, graph::Use::TransferDst)
        .record([counts_buffer, count_bytes](graph::PassContext& pc) { pc.fillBuffer(counts_buffer, 0, count_bytes, 0); });
    auto first = addPass(g, "pairs-args", graph::PassKind::Compute, Stage::Sorting);
    first.read(cells.header).write(header).write(args);
    if (fault_header.valid()) first.read(fault_header);
    first.record([pipe, params](graph::PassContext& pc) {
        bindAndPush(pc, *pipe, params, 0, 0);
        pc.dispatch(1, 1, 1);
    });
    auto scan = [pipe, params, blocks, max_x](graph::PassContext& pc, std::uint32_t level) {
        recordBlockScan(pc, *pipe, params, blocks, max_x, 2, level);  // steps 2-4
    };
    addPass(g, "pairs-bucket", graph::PassKind::Compute, Stage::Sorting)
        .indirect(args)
        .read(cells.survivors)
        .readWrite(header)
        .readWrite(counts)
        .write(offsets)
        .readWrite(sums)
        .write(partners)
        .record([pipe, params, args_buffer, scan](graph::PassContext& pc) {
            bindAndPush(pc, *pipe, params, 0, 1);
            pc.dispatchIndirect(args_buffer, 0);
            pc.shaderBarrier();
            scan(pc, 0);
            bindAndPush(pc, *pipe, params, 0, 5);
            pc.dispatchIndirect(args_buffer, 0);
        });
    addPass(g, "pairs-sort", graph::PassKind::Compute, Stage::Sorting)
        .read(cells.triangles)
        .read(offsets)
        .readWrite(header)
        .readWrite(counts)
        .readWrite(partners)
        .readWrite(sums)
        .write(out_offsets)
        .write(pairs)
        .record([pipe, params, tri_groups, max_x, scan](graph::PassContext& pc) {
            bindAndPush(pc, *pipe, params, 0, 6);
            dispatchGroups(pc, tri_groups, max_x);
            pc.shaderBarrier();
            scan(pc, 1);
            bindAndPush(pc, *pipe, params, 0, 7);
            dispatchGroups(pc, tri_groups, max_x);
        });
    return {header, pairs, counts, offsets, partners, sums};
}

// The pairs' copy to host memory, by the transfer engine: the shaders' stores to host memory
// cross the bus 15-20x slower on an H200 (1.7M pairs: 11.7 ms from a coalesced shader, 0.65 ms
// copied; about 52 GB/s). The whole capacity is copied, so the host's capacity follows the
// pairs found (ReliableMethod: 1.25x the last count; an overflow sorts once more), and each
// pair is its two global ids (DevicePairsParams.packed): 8 bytes, not 16. Early: the header
// first (the host reads the count with the first piece), then each piece and its event, so
// that the host sees event k set with the header and pieces 0..k in its memory; otherwise
// the capacity in one copy.
void DevicePairStage::recordPairsToHost(graph::Graph& g, const Resources& sorted, bool early) {
    Buffers& b = buf_;
    const auto host_pairs = importRow(g, b.host_pairs, true);
    std::array<VkEvent, kMaxEarlyChunks> events{};
    const std::uint32_t chunks = early ? early_chunks_ : 1;
    for (std::uint32_t k = 0; early && k < chunks; ++k) events[k] = events_[k].handle();
    const VkDeviceSize bytes = VkDeviceSize(capacity_) * pairBytes();
    auto pass = addPass(g, "pairs-to-host", graph::PassKind::Transfer, Stage::Readback);
    pass.use(sorted.pairs, graph::Use::TransferSrc).use(host_pairs, graph::Use::TransferDst);
    if (early) pass.use(sorted.header, graph::Use::TransferSrc).use(importRow(g, b.header_rb_early, true), graph::Use::TransferDst);
    pass.record([from = b.pairs->handle(), to = b.host_pairs->handle(), header = b.header->handle(), header_to = b.header_rb_early->handle(),
                 early, events, chunks, piece = early ? VkDeviceSize(early_chunk_pairs_) * pairBytes() : bytes,
                 bytes](graph::PassContext& pc) {
        if (early) pc.copyBuffer(header, header_to, VkBufferCopy{0, 0, sizeof(gpu::DevicePairsHeader)});
        for (std::uint32_t k = 0; k < chunks; ++k) {
            const VkDeviceSize at = k * piece;
            if (at < bytes) pc.copyBuffer(from, to, VkBufferCopy{at, at, std::min(piece, bytes - at)});
            if (early) pc.signalHost(events[k]);
        }
    });
}

void DevicePairStage::recordEarlyCopies(graph::Graph& g, const Resources& sorted) {
    if (early_) recordPairsToHost(g, sorted, true);
}

gpu::DevicePairsHeader DevicePairStage::earlyHeader() const { return headerIn(buf_.header_rb_early, early_); }

void DevicePairStage::recordCopies(graph::Graph& g, const Resources& sorted) {
    if (for_host_ && !early_) recordPairsToHost(g, sorted, false);
    if (!header_to_host_) return;
    Buffers& b = buf_;
    const auto header_rb = importRow(g, b.header_rb, true);
    addPass(g, "pairs-header-readback", graph::PassKind::Transfer, Stage::Readback)
        .use(sorted.header, graph::Use::TransferSrc)
        .use(header_rb, graph::Use::TransferDst)
        .record([from = b.header->handle(), to = b.header_rb->handle()](graph::PassContext& pc) {
            VkBufferCopy copy{0, 0, sizeof(gpu::DevicePairsHeader)};
            pc.copyBuffer(from, to, copy);
        });
}

std::span<const CandidatePair> DevicePairStage::hostPairs(std::uint32_t count) const {
    if (!for_host_ || count == 0) return {};
    count = std::min(count, capacity_);
    buf_.host_pairs->invalidate(0, VkDeviceSize(count) * sizeof(CandidatePair));
    return {static_cast<const CandidatePair*>(buf_.host_pairs->mapped()), count};
}

gpu::DevicePairsHeader DevicePairStage::header() const { return headerIn(buf_.header_rb, header_to_host_); }

DevicePairsView DevicePairStage::view() const noexcept {
    return {buf_.pairs->handle(), buf_.header->handle(), buf_.pairs->address(), buf_.header->address(), capacity_};
}

}  // namespace vkcollide::passes
