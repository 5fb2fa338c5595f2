#include "proximity/proximity_stage.hpp"

#include <algorithm>
#include <cstddef>
#include <cstring>
#include <string>

#include "passes/stage.hpp"
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
static_assert(sizeof(gpu::ProximityHeader) == 32 && sizeof(gpu::ProximityParams) == 56);

}  // namespace

Result<std::unique_ptr<ProximityStage>> ProximityStage::create(vk::Device& device) {
    if (!device.shader_float64)
        return Error(ErrorCode::UnsupportedFeature,
                     "proximity computes distances in double on the GPU and needs shaderFloat64, which " + device.info.name + " lacks");
    std::unique_ptr<ProximityStage> stage(new ProximityStage(device));
    auto p = vk::Pipeline::createCompute(device, shaders::proximity_pairs_comp, {}, sizeof(gpu::Push), "proximity-pairs");
    if (!p) return p.error();
    stage->pipeline_ = std::move(*p);
    return stage;
}

Result<void> ProximityStage::grow(vk::Buffer& buffer, VkDeviceSize size, vk::MemoryKind kind, const char* name) {
    size = std::max<VkDeviceSize>(size, 16);
    if (buffer.valid() && buffer.size() >= size) return {};
    buffer.reset();
    auto made = vk::Buffer::create(*device_, size, 0, kind, name);
    if (!made) return made.error();
    buffer = std::move(*made);
    return {};
}

Result<void> ProximityStage::prepare(const passes::CellPairs& cells, std::span<const passes::GpuMesh> meshes, double distance,
                                     std::uint32_t capacity) {
    using vk::MemoryKind;
    distance_ = distance;
    triangles_ = cells.triangleCount();
    max_groups_x_ = cells.maxGroupsX();
    runs_ = count_ = 0;
    header_ = {};
    fixed_capacity_ = capacity != 0;
    const std::uint64_t automatic = std::min<std::uint64_t>(kMaxProximityCapacity, std::max<std::uint64_t>(8ull * triangles_, 4096));
    capacity_ = fixed_capacity_ ? capacity : std::max(capacity_, static_cast<std::uint32_t>(automatic));
    cells_args_ = cells.argsBuffer();
    const VkDeviceSize tris = std::max<std::uint32_t>(triangles_, 1);
    for (auto ok : {grow(buf_.params, sizeof(gpu::ProximityParams), MemoryKind::Upload, "proximity-params"),
                    grow(buf_.owned, (tris + 3) / 4 * 4, MemoryKind::Upload, "proximity-owned"),
                    grow(buf_.object_ids, meshes.size() * 4, MemoryKind::Upload, "proximity-object-ids"),
                    grow(buf_.header, sizeof(gpu::ProximityHeader), MemoryKind::DeviceLocal, "proximity-header"),
                    grow(buf_.header_rb, sizeof(gpu::ProximityHeader), MemoryKind::Readback, "proximity-header-readback"),
                    grow(buf_.records, VkDeviceSize(capacity_) * sizeof(gpu::ProximityRecord), MemoryKind::Readback, "proximity-records")})
        if (!ok) return ok.error();
    auto* owned = static_cast<std::uint8_t*>(buf_.owned.mapped());
    auto* ids = static_cast<std::uint32_t*>(buf_.object_ids.mapped());
    std::uint64_t at = 0;
    for (std::size_t i = 0; i < meshes.size(); ++i) {
        const passes::GpuMesh& m = meshes[i];
        if (m.proximity_owned.size() != m.triangle_count)
            return Error(ErrorCode::InvalidArgument, "proximity: mesh " + std::to_string(i) + " has " +
                                                         std::to_string(m.proximity_owned.size()) + " owned-primitive entries for " +
                                                         std::to_string(m.triangle_count) + " triangles");
        if (!m.proximity_owned.empty()) std::memcpy(owned + at, m.proximity_owned.data(), m.proximity_owned.size());
        at += m.triangle_count;
        ids[i] = m.tag;
    }
    if (at != triangles_) return Error(ErrorCode::InvalidArgument, "proximity: the meshes' triangles are not the cell stage's");
    buf_.owned.flush();
    buf_.object_ids.flush();
    writeParams(cells);
    return {};
}

void ProximityStage::writeParams(const passes::CellPairs& cells) {
    gpu::ProximityParams p{};
    p.cells = cells.paramsAddress();
    p.owned = buf_.owned.address();
    p.object_ids = buf_.object_ids.address();
    p.header = buf_.header.address();
    p.records = buf_.records.address();
    p.distance = distance_;
    p.capacity = capacity_;
    std::memcpy(buf_.params.mapped(), &p, sizeof p);
    buf_.params.flush();
}

void ProximityStage::record(graph::Graph& g, const passes::CellPairs::Resources& cells) {
    const auto header = g.importBuffer("proximity-header", buf_.header);
    const auto header_rb = g.importBuffer("proximity-header-readback", buf_.header_rb, true);
    const auto records = g.importBuffer("proximity-records", buf_.records, true);
    const VkBuffer header_buffer = buf_.header.handle(), header_rb_buffer = buf_.header_rb.handle();
    const VkBuffer args_buffer = cells_args_;
    const VkDeviceAddress params = buf_.params.address();
    const vk::Pipeline* pipe = &pipeline_;
    passes::addPass(g, "proximity-clear", graph::PassKind::Transfer, passes::Stage::Proximity)
        .use(header, graph::Use::TransferDst)
        .record([header_buffer](graph::PassContext& pc) { pc.fillBuffer(header_buffer, 0, sizeof(gpu::ProximityHeader), 0); });
    passes::addPass(g, "proximity-pairs", graph::PassKind::Compute, passes::Stage::Proximity)
        .indirect(cells.args)
        .read(cells.header)
        .read(cells.candidates)
        .read(cells.triangles)
        .read(cells.geometry)
        .readWrite(header)
        .write(records)
        .record([pipe, params, args_buffer](graph::PassContext& pc) {
            gpu::Push push{params, 0, 0, 0, 0};
            pc.bindPipeline(VK_PIPELINE_BIND_POINT_COMPUTE, pipe->handle());
            pc.pushConstants(pipe->layout(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
            pc.dispatchIndirect(args_buffer, gpu::kCellsArgsPairs * 12);
            pc.shaderBarrier();
            push.step = 1;
            pc.pushConstants(pipe->layout(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
            pc.dispatch(1, 1, 1);
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
    buf_.header_rb.invalidate();
    std::memcpy(&header_, buf_.header_rb.mapped(), sizeof header_);
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
        if (auto ok = grow(buf_.records, VkDeviceSize(capacity_) * sizeof(gpu::ProximityRecord), vk::MemoryKind::Readback,
                           "proximity-records");
            !ok)
            return ok.error();
        return Outcome::Rerun;
    }
    count_ = header_.count;
    if (count_) buf_.records.invalidate(0, VkDeviceSize(count_) * sizeof(gpu::ProximityRecord));
    return Outcome::Complete;
}

Result<graph::ExecutionReport> ProximityStage::runAlone(passes::CellPairs& cells, std::uint64_t timeout_ns) {
    writeParams(cells);  // the records buffer may have grown
    cells_args_ = cells.argsBuffer();
    graph::Graph g;
    record(g, cells.importOutputs(g));
    return executor_.run(g, timeout_ns);
}

std::span<const gpu::ProximityRecord> ProximityStage::records() const noexcept {
    if (!count_) return {};
    return {static_cast<const gpu::ProximityRecord*>(buf_.records.mapped()), count_};
}

std::uint64_t ProximityStage::memoryBytes() const noexcept {
    std::uint64_t total = executor_.memoryBytes();
    for (const vk::Buffer* b : {&buf_.params, &buf_.owned, &buf_.object_ids, &buf_.header, &buf_.header_rb, &buf_.records})
        total += b->memoryBytes();
    return total;
}

}  // namespace vkcollide::proximity
