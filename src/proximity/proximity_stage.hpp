// The proximity pass (DetectSettings::proximity, docs/proximity.md): after the cell stage
// ran with every triangle grown by half the distance (CellStageSettings::proximity_pad),
// one invocation per candidate triangle pair computes, in double on the CPU's world
// vertices, the distances of the vertices and edges the two triangles own
// (ownership.hpp) and writes every vertex-triangle and edge-edge pair within the distance
// (spirv/proximity_pairs.comp.glsl).
//
//   proximity-clear    the header and the sort's bucket counts
//   proximity-pairs    per candidate (the pair pass's indirect dispatch), then the header's
//                      count and flags
//   proximity-sort     the records into the result's order (spirv/proximity_sort.comp.glsl):
//                      bucketed by (kind, object_a, a0), each bucket sorted
//   proximity-readback the header for the host
//
// Capacity: the caller's (a detection that finds more fails with LimitExceeded naming the
// count), or automatic: first about 8 records per triangle, then what a run needed; an
// automatic capacity that overflows is grown and the pass alone run again (the candidates
// stay in the cell stage's buffers). The sorted records live in host-visible memory the GPU
// writes (the host reads them in place; a GPU reads them by address).
//
// Not thread-safe; one per cell stage (ReliableMethod).
#pragma once

#include <cstdint>
#include <memory>
#include <span>

#include "broad/broad_phase_types.hpp"
#include "broad/cells/cell_stage.hpp"
#include "proximity/proximity.h"

namespace vkcollide::proximity {

class ProximityStage {
public:
    // Needs shaderFloat64 (UnsupportedFeature otherwise, naming the device). Its buffers
    // are rows of `table` (the broad phase's, which must outlive the stage).
    static Result<std::unique_ptr<ProximityStage>> create(vk::Device& device, passes::BufferTable& table);

    // After CellStage::prepare(): the run's meshes (each with its owned primitives, one per
    // triangle: InvalidArgument naming the mesh otherwise), the distance (world units) and
    // the capacity (0: automatic).
    [[nodiscard]] Result<void> prepare(const passes::CellStage& cells, std::span<const passes::GpuMesh> meshes, double distance,
                                       std::uint32_t capacity);
    // The passes, after the cell stage's (`cells`: its resources in this graph).
    void record(graph::Graph& g, const passes::CellStage::Resources& cells);
    // After the graph ran (and the cell stage completed): Complete, or Rerun when an
    // automatic capacity overflowed (grown: refresh(), then record the pass again). Errors:
    // LimitExceeded past a fixed capacity; VulkanError when the cell stage's run failed
    // (the caller must rerun both).
    enum class Outcome { Complete, Rerun };
    [[nodiscard]] Result<Outcome> finish();
    // Before the pass is recorded alone (after the cell stage ran again, or after Rerun):
    // the parameters for the buffers as they are now (either may have grown).
    void refresh(const passes::CellStage& cells);

    // After a Complete finish(): the records in the result's order (a rare pair twice, side
    // by side), the header, and the passes run so far for this detection.
    std::span<const gpu::ProximityRecord> records() const noexcept;
    const gpu::ProximityHeader& header() const noexcept { return header_; }
    std::uint32_t runs() const noexcept { return runs_; }
    std::uint32_t capacity() const noexcept { return capacity_; }
    DeviceProximity view() const noexcept;
    std::uint64_t memoryBytes() const noexcept;

private:
    ProximityStage(vk::Device& device, passes::BufferTable& table) : device_(&device), table_(&table) {}
    using Row = passes::TableRow;
    // The rows for the prepared run through the table's one memory check; records_only:
    // the records, sorted and order for capacity_ (after an overflow).
    Result<void> reserveRows(bool records_only);
    void writeParams(const passes::CellStage& cells);

    vk::Device* device_;
    vk::Pipeline pipeline_, sort_pipeline_;
    passes::BufferTable* table_;
    struct Buffers {  // rows of table_
        Row params, owned, object_ids, vertex_base, header, header_rb, records, sorted, order, counts, offsets, block_sums, args;
    } buf_;
    std::uint32_t objects_ = 0, buckets_ = 0;
    double distance_ = 0;
    std::uint32_t capacity_ = 0, triangles_ = 0, max_groups_x_ = 0;
    bool fixed_capacity_ = false;
    std::uint32_t runs_ = 0, count_ = 0;
    VkBuffer cells_args_ = VK_NULL_HANDLE;  // the cell stage's indirect dispatches
    gpu::ProximityHeader header_{};
};

}  // namespace vkcollide::proximity
