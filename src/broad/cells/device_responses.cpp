#include "broad/cells/device_responses.hpp"

#include <algorithm>
#include <cstddef>
#include <cstring>
#include <string>

#include "broad/dispatch.hpp"
#include "broad/run_view.hpp"
#include "broad/stage.hpp"
#include "shaders/all.hpp"
#include "vkcollide/narrow.hpp"

namespace vkcollide::passes {
namespace {

// The public layout is the shader's (spirv/cells/cells.h): directions as float bits.
static_assert(sizeof(gpu::DeviceResponse) == sizeof(TriangleResponse) && offsetof(TriangleResponse, triangle) == 4 &&
              offsetof(TriangleResponse, direction) == offsetof(gpu::DeviceResponse, direction) &&
              offsetof(TriangleResponse, partner_count) == offsetof(gpu::DeviceResponse, partner_count));
static_assert(sizeof(gpu::DeviceResponsesParams) == 10 * 8 + 4 * 4);

}  // namespace

Result<std::unique_ptr<DeviceResponseStage>> DeviceResponseStage::create(vk::Device& device, BufferTable& table) {
    std::unique_ptr<DeviceResponseStage> stage(new DeviceResponseStage(device, table));
    auto p = vk::Pipeline::createCompute(device, shaders::device_responses_comp, {}, sizeof(gpu::Push), "device-responses");
    if (!p) return p.error();
    stage->pipeline_ = std::move(*p);
    auto sum = vk::Pipeline::createCompute(device, shaders::device_responses_sum_comp, {}, sizeof(gpu::Push), "device-responses-sum");
    if (!sum) return sum.error();
    stage->sum_pipeline_ = std::move(*sum);
    using vk::MemoryKind;
    Buffers& b = stage->buf_;
    b.params = table.addOwned("device-responses-params", MemoryKind::Upload);
    b.lower_counts = table.addOwned("device-responses-lower-counts", MemoryKind::DeviceLocal);
    b.lower_offsets = table.addOwned("device-responses-lower-offsets", MemoryKind::DeviceLocal);
    b.lower = table.addOwned("device-responses-lower", MemoryKind::DeviceLocal);
    b.marks = table.addOwned("device-responses-marks", MemoryKind::DeviceLocal);
    b.positions = table.addOwned("device-responses-positions", MemoryKind::DeviceLocal);
    b.responders = table.addOwned("device-responses-responders", MemoryKind::DeviceLocal);
    b.args = table.addOwned("device-responses-args", MemoryKind::DeviceLocal, VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT);
    b.normals = table.addOwned("device-responses-normals", MemoryKind::DeviceLocal);
    // The one the engine reads: a grown one keeps the old buffer for two more starts.
    b.responses = table.addOwned("device-responses", MemoryKind::DeviceLocal, 0, true);
    b.host_responses = table.addOwned("device-responses-host", MemoryKind::Readback);
    return stage;
}

Result<void> DeviceResponseStage::prepare(const CellStage& cells, const DevicePairStage& pairs, std::uint32_t host_capacity) {
    using vk::MemoryKind;
    triangles_ = cells.triangleCount();
    host_capacity_ = std::min(host_capacity, triangles_);
    max_groups_x_ = cells.maxGroupsX();
    const VkDeviceSize tris = std::max<std::uint32_t>(triangles_, 1);
    const VkDeviceSize survivors = std::max<std::uint32_t>(cells.capacity().survivors, 1);
    const RowSize plan[] = {
        rowSize(buf_.params, sizeof(gpu::DeviceResponsesParams), MemoryKind::Upload),
        rowSize(buf_.lower_counts, tris * 4, MemoryKind::DeviceLocal),
        rowSize(buf_.lower_offsets, (tris + 1) * 4, MemoryKind::DeviceLocal),
        rowSize(buf_.lower, survivors * 4, MemoryKind::DeviceLocal),
        rowSize(buf_.marks, tris * 4, MemoryKind::DeviceLocal),
        rowSize(buf_.positions, (tris + 1) * 4, MemoryKind::DeviceLocal),
        rowSize(buf_.responders, tris * 4, MemoryKind::DeviceLocal),
        rowSize(buf_.args, 12, MemoryKind::DeviceLocal),
        rowSize(buf_.normals, tris * 3 * sizeof(double), MemoryKind::DeviceLocal),
        rowSize(buf_.responses, tris * sizeof(gpu::DeviceResponse), MemoryKind::DeviceLocal),
        rowSize(buf_.host_responses, VkDeviceSize(host_capacity_) * sizeof(gpu::DeviceResponse), MemoryKind::Readback),
    };
    if (auto ok = table_->reserve(*device_, plan, "device responses: " + std::to_string(triangles_) + " triangles"); !ok) return ok;
    gpu::DeviceResponsesParams p{};
    p.pairs = pairs.paramsAddress();
    p.lower_counts = buf_.lower_counts->address();
    p.lower_offsets = buf_.lower_offsets->address();
    p.lower = buf_.lower->address();
    p.marks = buf_.marks->address();
    p.positions = buf_.positions->address();
    p.responders = buf_.responders->address();
    p.args = buf_.args->address();
    p.normals = buf_.normals->address();
    p.responses = buf_.responses->address();
    p.triangle_count = triangles_;
    p.block_count = static_cast<std::uint32_t>((VkDeviceSize(triangles_) + gpu::kCellsScanBlock - 1) / gpu::kCellsScanBlock);
    p.max_groups_x = max_groups_x_;
    std::memcpy(buf_.params->mapped(), &p, sizeof p);
    buf_.params->flush();
    return {};
}

void DeviceResponseStage::record(graph::Graph& g, const CellStage::Resources& cells, const DevicePairStage::Resources& sorted) {
    Buffers& b = buf_;
    const auto lower_counts = importRow(g, b.lower_counts);
    const auto lower_offsets = importRow(g, b.lower_offsets);
    const auto lower = importRow(g, b.lower);
    const auto marks = importRow(g, b.marks);
    const auto positions = importRow(g, b.positions);
    const auto responders = importRow(g, b.responders);
    const auto args = importRow(g, b.args);
    const auto normals = importRow(g, b.normals);
    const auto responses = importRow(g, b.responses);
    const VkDeviceAddress params = buf_.params->address();
    const VkBuffer counts_buffer = buf_.lower_counts->handle();
    const VkDeviceSize count_bytes = VkDeviceSize(std::max<std::uint32_t>(triangles_, 1)) * 4;
    const std::uint64_t tri_groups = (std::uint64_t(triangles_) + gpu::kCellsGroupSize - 1) / gpu::kCellsGroupSize;
    const std::uint64_t blocks = (std::uint64_t(triangles_) + gpu::kCellsScanBlock - 1) / gpu::kCellsScanBlock;
    const std::uint32_t max_x = max_groups_x_;
    const vk::Pipeline* pipe = &pipeline_;
    const vk::Pipeline* sum_pipe = &sum_pipeline_;
    const VkBuffer args_buffer = buf_.args->handle();
    // One step over every triangle, then a barrier.
    auto perTriangle = [pipe, params, tri_groups, max_x](graph::PassContext& pc, std::uint32_t step) {
        bindAndPush(pc, *pipe, params, 0, step);
        dispatchGroups(pc, tri_groups, max_x);
        pc.shaderBarrier();
    };
    // Both bookkeeping passes: a step over the triangles, a scan (steps 1-3), a last step.
    auto stepScanStep = [perTriangle, pipe, params, tri_groups, blocks, max_x](graph::PassContext& pc, std::uint32_t first,
                                                                               std::uint32_t level, std::uint32_t last) {
        perTriangle(pc, first);
        recordBlockScan(pc, *pipe, params, blocks, max_x, 1, level);
        bindAndPush(pc, *pipe, params, 0, last);
        dispatchGroups(pc, tri_groups, max_x);
    };

    addPass(g, "responses-clear", graph::PassKind::Transfer, Stage::Sorting)
        .use(lower_counts, graph::Use::TransferDst)
        .record([counts_buffer, count_bytes](graph::PassContext& pc) { pc.fillBuffer(counts_buffer, 0, count_bytes, 0); });
    addPass(g, "responses-bucket", graph::PassKind::Compute, Stage::Sorting)
        .write(args)
        .read(sorted.header)
        .read(sorted.counts)
        .read(sorted.offsets)
        .read(sorted.partners)
        .readWrite(sorted.block_sums)
        .readWrite(lower_counts)
        .write(lower_offsets)
        .write(lower)
        .record([stepScanStep](graph::PassContext& pc) { stepScanStep(pc, 0, 0, 4); });
    addPass(g, "responses-list", graph::PassKind::Compute, Stage::Sorting)
        .read(sorted.counts)
        .read(lower_offsets)
        .read(lower_counts)
        .readWrite(lower)
        .readWrite(sorted.header)
        .readWrite(sorted.block_sums)
        .readWrite(args)
        .write(marks)
        .write(positions)
        .write(responders)
        .record([stepScanStep](graph::PassContext& pc) { stepScanStep(pc, 5, 1, 6); });
    addPass(g, "responses-sum", graph::PassKind::Compute, Stage::Sorting)
        .indirect(args)
        .read(cells.triangles)
        .read(cells.geometry)
        .read(sorted.header)
        .read(sorted.counts)
        .read(sorted.offsets)
        .read(sorted.partners)
        .read(lower_offsets)
        .read(lower_counts)
        .read(lower)
        .read(responders)
        .write(normals)
        .write(responses)
        .record([sum_pipe, params, args_buffer](graph::PassContext& pc) {
            bindAndPush(pc, *sum_pipe, params, 0, 0);
            pc.dispatchIndirect(args_buffer, 0);
            pc.shaderBarrier();
            bindAndPush(pc, *sum_pipe, params, 0, 1);
            pc.dispatchIndirect(args_buffer, 0);
        });
    if (host_capacity_ == 0) return;
    // A copy by the transfer engine (as the device pairs' to the host): the host's capacity
    // follows the responses found (ReliableMethod), not the triangles.
    const auto host_responses = importRow(g, b.host_responses, true);
    addPass(g, "responses-to-host", graph::PassKind::Transfer, Stage::Readback)
        .use(responses, graph::Use::TransferSrc)
        .use(host_responses, graph::Use::TransferDst)
        .record([from = b.responses->handle(), to = b.host_responses->handle(),
                 bytes = VkDeviceSize(host_capacity_) * sizeof(gpu::DeviceResponse)](graph::PassContext& pc) {
            VkBufferCopy copy{0, 0, bytes};
            pc.copyBuffer(from, to, copy);
        });
}

std::span<const TriangleResponse> DeviceResponseStage::hostResponses(std::uint32_t count) const {
    if (host_capacity_ == 0 || count == 0) return {};
    count = std::min(count, host_capacity_);
    buf_.host_responses->invalidate(0, VkDeviceSize(count) * sizeof(TriangleResponse));
    return {static_cast<const TriangleResponse*>(buf_.host_responses->mapped()), count};
}

VkBuffer DeviceResponseStage::buffer() const noexcept { return buf_.responses->handle(); }
VkDeviceAddress DeviceResponseStage::address() const noexcept { return buf_.responses->address(); }

}  // namespace vkcollide::passes
