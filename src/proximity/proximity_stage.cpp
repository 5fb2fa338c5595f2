#include "proximity/proximity_stage.hpp"

#include <algorithm>
#include <cstddef>
#include <cstring>
#include <iterator>
#include <span>
#include <string>

#include "broad/dispatch.hpp"
#include "broad/run_view.hpp"
#include "broad/stage.hpp"
#include "shaders/all.hpp"
#include "vkcollide/proximity.hpp"

namespace vkcollide::proximity {
namespace {

// The public record is the shader's (spirv/proximity.h).
static_assert(sizeof(gpu::ProximityRecord) == 64 && sizeof(ProximityPair) == 64);
static_assert(offsetof(gpu::ProximityRecord, object_a) == offsetof(ProximityPair, object_a) &&
              offsetof(gpu::ProximityRecord, a0) == offsetof(ProximityPair, a0) &&
              offsetof(gpu::ProximityRecord, b1) == offsetof(ProximityPair, b1) &&
              offsetof(gpu::ProximityRecord, distance) == offsetof(ProximityPair, distance) &&
              offsetof(gpu::ProximityRecord, weights_b) == offsetof(ProximityPair, weights_b) &&
              offsetof(gpu::ProximityRecord, normal) == offsetof(ProximityPair, normal));
static_assert(gpu::kProximityInBand == kProximityInBand && gpu::kProximityEdgeEdge == std::uint32_t(ProximityKind::EdgeEdge));
static_assert(sizeof(gpu::ProximityHeader) == 32 && sizeof(gpu::ProximityParams) == 128);
static_assert(sizeof(DeviceProximityHeader) == sizeof(gpu::ProximityHeader) && offsetof(gpu::ProximityHeader, in_band) == 28 &&
              offsetof(gpu::ProximityHeader, pairs_tested) == offsetof(DeviceProximityHeader, triangle_pairs));
static_assert(gpu::kProximityOverflow == kDeviceProximityOverflow && gpu::kProximityIncomplete == kDeviceProximityIncomplete);

}  // namespace

Result<std::unique_ptr<ProximityStage>> ProximityStage::create(vk::Device& device, passes::BufferTable& table) {
    if (!device.shader_float64)
        return Error(ErrorCode::UnsupportedFeature,
                     "proximity computes distances in double on the GPU and needs shaderFloat64, which " + device.info.name + " lacks");
    std::unique_ptr<ProximityStage> stage(new ProximityStage(device, table));
    using vk::MemoryKind;
    Buffers& b = stage->buf_;
    b.params = table.addOwned("proximity-params", MemoryKind::Upload);
    b.owned = table.addOwned("proximity-owned", MemoryKind::Upload);
    b.object_ids = table.addOwned("proximity-object-ids", MemoryKind::Upload);
    b.vertex_base = table.addOwned("proximity-vertex-base", MemoryKind::Upload);
    b.header = table.addOwned("proximity-header", MemoryKind::DeviceLocal);
    b.header_rb = table.addOwned("proximity-header-readback", MemoryKind::Readback);
    b.records = table.addOwned("proximity-records", MemoryKind::DeviceLocal);
    b.sorted = table.addOwned("proximity-sorted", MemoryKind::Readback);
    b.order = table.addOwned("proximity-order", MemoryKind::DeviceLocal);
    b.counts = table.addOwned("proximity-counts", MemoryKind::DeviceLocal);
    b.offsets = table.addOwned("proximity-offsets", MemoryKind::DeviceLocal);
    b.block_sums = table.addOwned("proximity-block-sums", MemoryKind::DeviceLocal);
    b.args = table.addOwned("proximity-args", MemoryKind::DeviceLocal, VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT);
    auto p = vk::Pipeline::createCompute(device, shaders::proximity_pairs_comp, {}, sizeof(gpu::Push), "proximity-pairs");
    if (!p) return p.error();
    stage->pipeline_ = std::move(*p);
    auto sort = vk::Pipeline::createCompute(device, shaders::proximity_sort_comp, {}, sizeof(gpu::Push), "proximity-sort");
    if (!sort) return sort.error();
    stage->sort_pipeline_ = std::move(*sort);
    return stage;
}

Result<void> ProximityStage::prepare(const passes::CellStage& cells, std::span<const passes::GpuMesh> meshes, double distance,
                                     std::uint32_t capacity) {
    distance_ = distance;
    triangles_ = cells.triangleCount();
    max_groups_x_ = cells.maxGroupsX();
    runs_ = count_ = 0;
    header_ = {};
    fixed_capacity_ = capacity != 0;
    const std::uint64_t automatic = std::min<std::uint64_t>(kMaxProximityCapacity, std::max<std::uint64_t>(8ull * triangles_, 4096));
    capacity_ = fixed_capacity_ ? capacity : std::max(capacity_, static_cast<std::uint32_t>(automatic));
    cells_args_ = cells.argsBuffer();
    std::uint64_t vertices = 0;
    for (const passes::GpuMesh& m : meshes) vertices += m.vertex_count;
    if (2 * vertices + 1 >= 0x7FFFFFFFull)
        return Error(ErrorCode::InvalidArgument, "proximity: " + std::to_string(vertices) + " vertices, more than 2^30 - 1");
    objects_ = static_cast<std::uint32_t>(meshes.size());
    buckets_ = static_cast<std::uint32_t>(2 * vertices);
    if (auto ok = reserveRows(false); !ok) return ok.error();
    auto* owned = static_cast<std::uint8_t*>(buf_.owned->mapped());
    auto* ids = static_cast<std::uint32_t*>(buf_.object_ids->mapped());
    auto* bases = static_cast<std::uint32_t*>(buf_.vertex_base->mapped());
    std::uint64_t at = 0, vertex_at = 0;
    for (std::size_t i = 0; i < meshes.size(); ++i) {
        const passes::GpuMesh& m = meshes[i];
        if (m.proximity_owned.size() != m.triangle_count)
            return Error(ErrorCode::InvalidArgument, "proximity: mesh " + std::to_string(i) + " has " +
                                                         std::to_string(m.proximity_owned.size()) + " owned-primitive entries for " +
                                                         std::to_string(m.triangle_count) + " triangles");
        if (!m.proximity_owned.empty()) std::memcpy(owned + at, m.proximity_owned.data(), m.proximity_owned.size());
        at += m.triangle_count;
        if (i > 0 && m.tag <= ids[i - 1])
            return Error(ErrorCode::InvalidArgument, "proximity: the meshes' ids (GpuMesh::tag) must ascend");
        ids[i] = m.tag;
        bases[i] = static_cast<std::uint32_t>(vertex_at);
        vertex_at += m.vertex_count;
    }
    buf_.vertex_base->flush();
    if (at != triangles_) return Error(ErrorCode::InvalidArgument, "proximity: the meshes' triangles are not the cell stage's");
    buf_.owned->flush();
    buf_.object_ids->flush();
    writeParams(cells);
    return {};
}

void ProximityStage::writeParams(const passes::CellStage& cells) {
    gpu::ProximityParams p{};
    p.cells = cells.paramsAddress();
    p.owned = buf_.owned->address();
    p.object_ids = buf_.object_ids->address();
    p.vertex_base = buf_.vertex_base->address();
    p.header = buf_.header->address();
    p.records = buf_.records->address();
    p.sorted = buf_.sorted->address();
    p.order = buf_.order->address();
    p.counts = buf_.counts->address();
    p.offsets = buf_.offsets->address();
    p.block_sums = buf_.block_sums->address();
    p.args = buf_.args->address();
    p.distance = distance_;
    p.capacity = capacity_;
    p.object_count = objects_;
    p.bucket_count = buckets_;
    p.block_count = static_cast<std::uint32_t>((std::uint64_t(buckets_) + gpu::kCellsScanBlock - 1) / gpu::kCellsScanBlock);
    p.max_groups_x = max_groups_x_;
    std::memcpy(buf_.params->mapped(), &p, sizeof p);
    buf_.params->flush();
}

void ProximityStage::record(graph::Graph& g, const passes::CellStage::Resources& cells) {
    const auto header = importRow(g, buf_.header);
    const auto header_rb = importRow(g, buf_.header_rb, true);
    const auto records = importRow(g, buf_.records);
    const auto sorted = importRow(g, buf_.sorted, true);
    const auto order = importRow(g, buf_.order);
    const auto counts = importRow(g, buf_.counts);
    const auto offsets = importRow(g, buf_.offsets);
    const auto sums = importRow(g, buf_.block_sums);
    const VkBuffer header_buffer = buf_.header->handle(), header_rb_buffer = buf_.header_rb->handle();
    const VkBuffer counts_buffer = buf_.counts->handle(), sort_args = buf_.args->handle();
    const auto args = importRow(g, buf_.args);
    const VkDeviceSize count_bytes = VkDeviceSize(std::max<std::uint32_t>(buckets_, 1)) * 4;
    const VkBuffer args_buffer = cells_args_;
    const VkDeviceAddress params = buf_.params->address();
    const vk::Pipeline* pipe = &pipeline_;
    passes::addPass(g, "proximity-clear", graph::PassKind::Transfer, passes::Stage::Proximity)
        .use(header, graph::Use::TransferDst)
        .use(counts, graph::Use::TransferDst)
        .record([header_buffer, counts_buffer, count_bytes](graph::PassContext& pc) {
            pc.fillBuffer(header_buffer, 0, sizeof(gpu::ProximityHeader), 0);
            pc.fillBuffer(counts_buffer, 0, count_bytes, 0);
        });
    passes::addPass(g, "proximity-pairs", graph::PassKind::Compute, passes::Stage::Proximity)
        .indirect(cells.args)
        .read(cells.header)
        .read(cells.candidates)
        .read(cells.triangles)
        .read(cells.geometry)
        .readWrite(header)
        .write(records)
        .write(args)
        .record([pipe, params, args_buffer](graph::PassContext& pc) {
            passes::bindAndPush(pc, *pipe, params);
            pc.dispatchIndirect(args_buffer, gpu::kCellsArgsPairs * 12);
            pc.shaderBarrier();
            passes::bindAndPush(pc, *pipe, params, 0, 1);
            pc.dispatch(1, 1, 1);
        });
    // The sort: per record (steps 0, 4, 6: indirect, from the count the pass found), the
    // scan over the buckets (1-3), per bucket (5).
    const vk::Pipeline* sort = &sort_pipeline_;
    const std::uint64_t bucket_groups = (std::uint64_t(buckets_) + gpu::kCellsGroupSize - 1) / gpu::kCellsGroupSize;
    const std::uint64_t blocks = (std::uint64_t(buckets_) + gpu::kCellsScanBlock - 1) / gpu::kCellsScanBlock;
    const std::uint32_t max_x = max_groups_x_;
    passes::addPass(g, "proximity-sort", graph::PassKind::Compute, passes::Stage::Proximity)
        .indirect(args)
        .read(header)
        .read(records)
        .readWrite(counts)
        .readWrite(offsets)
        .readWrite(sums)
        .readWrite(order)
        .write(sorted)
        .record([sort, params, sort_args, bucket_groups, blocks, max_x](graph::PassContext& pc) {
            auto step = [&](std::uint32_t s, std::uint64_t groups) {  // groups 0: one per record (indirect)
                passes::bindAndPush(pc, *sort, params, 0, s);
                if (groups) passes::dispatchGroups(pc, groups, max_x);
                else pc.dispatchIndirect(sort_args, 0);
                pc.shaderBarrier();
            };
            step(0, 0);
            step(1, blocks);
            step(2, 1);
            step(3, blocks);
            step(4, 0);
            step(5, bucket_groups);
            step(6, 0);
        });
    passes::addPass(g, "proximity-readback", graph::PassKind::Transfer, passes::Stage::Readback)
        .use(header, graph::Use::TransferSrc)
        .use(header_rb, graph::Use::TransferDst)
        .record([header_buffer, header_rb_buffer](graph::PassContext& pc) {
            VkBufferCopy copy{0, 0, sizeof(gpu::ProximityHeader)};
            pc.copyBuffer(header_buffer, header_rb_buffer, copy);
        });
}

Result<ProximityStage::Outcome> ProximityStage::finish() {
    ++runs_;
    count_ = 0;
    buf_.header_rb->invalidate();
    std::memcpy(&header_, buf_.header_rb->mapped(), sizeof header_);
    if (header_.flags & gpu::kProximityLoopLimit)
        return Error(ErrorCode::LimitExceeded, "proximity: a vertex or edge has more pairs within the distance than " +
                                                   vk::loopLimitPhrase(*device_, "sorts") + ": lower the distance, or detect on a GPU");
    if (header_.flags & gpu::kProximityIncomplete)
        return Error(ErrorCode::VulkanError, "proximity: the cell stage's run did not complete (internal error: it must run again first)");
    if (header_.flags & gpu::kProximityOverflow) {
        if (fixed_capacity_)
            return Error(ErrorCode::LimitExceeded, "proximity: found " + std::to_string(header_.needed) +
                                                       " pairs within the distance, more than ProximitySettings::capacity (" +
                                                       std::to_string(capacity_) + ")");
        if (header_.needed > kMaxProximityCapacity)
            return Error(ErrorCode::LimitExceeded, "proximity: found " + std::to_string(header_.needed) +
                                                       " pairs within the distance, more than kMaxProximityCapacity (" +
                                                       std::to_string(kMaxProximityCapacity) + "): lower the distance");
        const std::uint64_t grown = std::uint64_t(header_.needed) + header_.needed / 4 + 1024;
        capacity_ = static_cast<std::uint32_t>(std::min<std::uint64_t>(grown, kMaxProximityCapacity));
        if (auto ok = reserveRows(true); !ok) return ok.error();
        return Outcome::Rerun;
    }
    count_ = header_.count;
    if (count_) buf_.sorted->invalidate(0, VkDeviceSize(count_) * sizeof(gpu::ProximityRecord));
    return Outcome::Complete;
}

Result<void> ProximityStage::reserveRows(bool records_only) {
    using passes::rowSize;
    using vk::MemoryKind;
    const VkDeviceSize n = std::max<std::uint32_t>(capacity_, 1);
    const VkDeviceSize tris = std::max<std::uint32_t>(triangles_, 1);
    const VkDeviceSize blocks = (VkDeviceSize(buckets_) + gpu::kCellsScanBlock - 1) / gpu::kCellsScanBlock;
    const passes::RowSize rows[] = {
        rowSize(buf_.records, n * sizeof(gpu::ProximityRecord), MemoryKind::DeviceLocal),
        rowSize(buf_.sorted, n * sizeof(gpu::ProximityRecord), MemoryKind::Readback),
        rowSize(buf_.order, n * 16, MemoryKind::DeviceLocal),
        // The rest only with the run (records_only: left as they are).
        rowSize(buf_.params, sizeof(gpu::ProximityParams), MemoryKind::Upload),
        rowSize(buf_.owned, (tris + 3) / 4 * 4, MemoryKind::Upload),
        rowSize(buf_.object_ids, VkDeviceSize(objects_) * 4, MemoryKind::Upload),
        rowSize(buf_.vertex_base, VkDeviceSize(objects_) * 4, MemoryKind::Upload),
        rowSize(buf_.header, sizeof(gpu::ProximityHeader), MemoryKind::DeviceLocal),
        rowSize(buf_.header_rb, sizeof(gpu::ProximityHeader), MemoryKind::Readback),
        rowSize(buf_.counts, VkDeviceSize(buckets_) * 4, MemoryKind::DeviceLocal),
        rowSize(buf_.offsets, (VkDeviceSize(buckets_) + 1) * 4, MemoryKind::DeviceLocal),
        rowSize(buf_.block_sums, blocks * 4, MemoryKind::DeviceLocal),
        rowSize(buf_.args, 12, MemoryKind::DeviceLocal),
    };
    const std::string what = "proximity: " + std::to_string(capacity_) + " records for " + std::to_string(triangles_) + " triangles";
    if (auto ok = table_->reserve(*device_, std::span(rows, records_only ? 3 : std::size(rows)), what); !ok) return ok;
    // The sort loads and stores its keys as 16-byte vectors (proximity_sort.comp).
    if (buf_.order->address() % 16 != 0)
        return Error(ErrorCode::UnsupportedFeature, "proximity: the device placed 'proximity-order' at address " +
                                                        std::to_string(buf_.order->address()) + ", not a multiple of 16 bytes");
    return {};
}

void ProximityStage::refresh(const passes::CellStage& cells) {
    writeParams(cells);
    cells_args_ = cells.argsBuffer();
}

std::span<const gpu::ProximityRecord> ProximityStage::records() const noexcept {
    if (!count_) return {};
    return {static_cast<const gpu::ProximityRecord*>(buf_.sorted->mapped()), count_};
}

DeviceProximity ProximityStage::view() const noexcept {
    return {buf_.sorted->handle(), buf_.sorted->address(), buf_.header->handle(), buf_.header->address(), capacity_};
}

std::uint64_t ProximityStage::memoryBytes() const noexcept {
    std::uint64_t total = 0;
    for (const Row* r : {&buf_.params, &buf_.owned, &buf_.object_ids, &buf_.vertex_base, &buf_.header, &buf_.header_rb, &buf_.records,
                         &buf_.sorted, &buf_.order, &buf_.counts, &buf_.offsets, &buf_.block_sums, &buf_.args})
        total += (*r)->memoryBytes();
    return total;
}

}  // namespace vkcollide::proximity
