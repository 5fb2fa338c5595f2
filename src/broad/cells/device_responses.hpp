// Device responses (DetectSettings::reliable.device_responses, docs/api.md "Results on the
// GPU"): every colliding triangle's TriangleResponse computed on the GPU from the device
// pairs' sorted buckets, equal to the host result's responses to the bit
// (spirv/cells/device_responses.comp.glsl has the passes and why they match the CPU).
//
//   responses-clear   the lower partners' counts zeroed
//   responses-bucket  each triangle's lower partners counted, scanned and scattered
//   responses-list    each lower bucket sorted, the triangles in a pair marked, scanned and
//                     listed (spirv/cells/device_responses.comp.glsl: light, per triangle)
//   responses-sum     per listed triangle, dispatched indirectly: its unit normal, then its
//                     response summed in the CPU's order (device_responses_sum.comp.glsl:
//                     the double arithmetic, only where there is something to compute)
//   responses-to-host (for the host's result) the first responses copied to host memory by
//                     the transfer engine
//
// The header is the device pairs' (DevicePairsHeader::responses, ::response_capacity). The
// capacity is the run's triangles: it never overflows. The responses buffer is one the
// engine reads: a grown one is kept until the start of the second detection after.
//
// Not thread-safe; one per cell stage (ReliableMethod), recorded after DevicePairStage.
#pragma once

#include <cstdint>
#include <memory>
#include <span>

#include "broad/broad_phase_types.hpp"
#include "broad/cells/cell_stage.hpp"
#include "broad/cells/device_pairs.hpp"

namespace vkcollide::passes {

class DeviceResponseStage {
public:
    // Adds its rows to `io_table`.
    static Result<std::unique_ptr<DeviceResponseStage>> create(vk::Device& device, BufferTable& io_table);

    // After DevicePairStage::prepare() (with response_capacity = responseCapacity(cells)):
    // sizes the buffers for the run's triangles and survivors and uploads the parameters.
    // `host_capacity` > 0: the first that many responses are also copied to host memory
    // (for the host's result, hostResponses()); the header says whether they all fit.
    [[nodiscard]] Result<void> prepare(const CellStage& cells, const DevicePairStage& pairs, std::uint32_t host_capacity = 0);
    // The passes, after DevicePairStage::record() (its buckets and header) and before its
    // copies to the host; then the copy to the host, where prepared for one.
    void record(graph::Graph& g, const CellStage::Resources& cells, const DevicePairStage::Resources& sorted);
    // After the GPU work of a run prepared with a host capacity: the first `count`.
    std::span<const TriangleResponse> hostResponses(std::uint32_t count) const;
    std::uint32_t hostCapacity() const noexcept { return host_capacity_; }

    static std::uint32_t responseCapacity(const CellStage& cells) noexcept { return cells.triangleCount(); }
    VkBuffer buffer() const noexcept;
    VkDeviceAddress address() const noexcept;
    std::uint32_t capacity() const noexcept { return triangles_; }

private:
    DeviceResponseStage(vk::Device& device, BufferTable& table) : device_(&device), table_(&table) {}

    vk::Device* device_;
    BufferTable* table_;
    vk::Pipeline pipeline_, sum_pipeline_;
    struct Buffers {
        TableRow params, lower_counts, lower_offsets, lower, marks, positions, responders, args, normals, responses, host_responses;
    } buf_;
    std::uint32_t triangles_ = 0, max_groups_x_ = 0, host_capacity_ = 0;
};

}  // namespace vkcollide::passes
