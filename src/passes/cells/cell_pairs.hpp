// The cell pair stage: every pair of triangles that may intersect, formed and filtered on
// the GPU, compute only (docs/reliable.md has the method and the proof that it misses no
// intersecting pair, touching included, at any resolution).
//
//   setup     per triangle: input checks, world and sampling coordinates with error
//             bounds, the footprint box, and the count of footprints per cell
//   count-big big triangles' footprints, one workgroup per chunk of cells
//   scan      counts -> entry offsets; total checked against the entry capacity
//   fill      per footprint: (triangle, object, depth interval over the cell)
//   sweep     per cell: pairs whose depth intervals overlap and whose objects may collide
//   pairs     per candidate: neighbour rule, canonical cell, double-precision filter;
//             survivors appended as (a, b) global triangle ids, a < b
// One submission, no host round trip inside a run. Every capacity is checked on the GPU:
// an overflow sets a flag with the size needed, and run() grows that buffer and runs
// again, so no pair is lost and nothing is accessed out of bounds.
//
// Not thread-safe; one instance per user (it owns its buffers and executor). Buffers are
// kept between runs and only grow, so a steady scene allocates nothing per run.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "cells.h"
#include "graph/executor.hpp"
#include "vk/resources.hpp"

namespace vkcollide::passes {

// The scene of one run. Objects are gpu::ObjectGpu as the broad phase lays them out:
// vertex and index addresses (buffers with SHADER_DEVICE_ADDRESS usage, alive until the
// run is collected), triangle_base = the sum of the triangle counts before it, model rows
// of the 3x4 object-to-world transform. Positions and transform entries must be finite
// with magnitudes below 2^62, and so must world coordinates; a run that meets one that is
// not fails with InvalidMesh naming the object and triangle (docs/reliable.md).
struct CellPairsInput {
    std::span<const gpu::ObjectGpu> objects;
    // World -> sampling space: x, y in [0, 1] across the grid, z the depth (any affine map
    // with finite rows below 2^62; points outside [0, 1]^2 fall into the border cells).
    // Either given here, or written by an earlier pass of the same graph at
    // `projection_address` (then record() needs that buffer's ResourceId).
    std::optional<gpu::Projection> projection;
    VkDeviceAddress projection_address = 0;
    std::uint32_t resolution = 256;          // cells per side, 1 .. gpu::kCellsMaxResolution
    std::vector<std::uint8_t> self_collision;  // per object (non-zero: test its own pairs); empty: none
    // Whether two different objects a < b may collide; empty: every pair may.
    std::function<bool(std::uint32_t a, std::uint32_t b)> may_collide;
};

// Element counts of the buffers whose size is only known on the GPU. 0: estimate from
// the scene (or keep what an earlier run needed).
struct CellPairsCapacity {
    std::uint32_t entries = 0;     // footprints (16 + 4 bytes each)
    std::uint32_t items = 0;       // big-triangle work items (8 bytes)
    std::uint32_t candidates = 0;  // candidate pairs (12 bytes)
    std::uint32_t survivors = 0;   // surviving pairs (8 bytes, host-visible memory)
};

struct CellPairsSettings {
    // Run the double-precision filter where the device has shaderFloat64 enabled.
    bool filter = true;
    // Capacities of the first run; they grow (to 1.25x what was needed) on overflow.
    CellPairsCapacity initial;
    // Runs allowed per call (the first plus reruns after overflows).
    std::uint32_t max_runs = 8;
    // Dispatches are split into rows of at most this many workgroups (0: the device's
    // maxComputeWorkGroupCount[0]); tests set it small to exercise the split.
    std::uint32_t max_workgroups_x = 0;
};

struct CellPairsStats {
    std::uint64_t entries = 0;        // footprints: (triangle, cell) pairs
    std::uint64_t big_triangles = 0;  // triangles counted and filled in work items
    std::uint64_t items = 0;
    std::uint64_t deep_cells = 0;     // cells with more than kCellsSmallCell entries
    std::uint64_t max_cell = 0;       // most entries in one cell
    std::uint64_t candidates = 0;     // pairs the sweep found (with duplicates across cells)
    std::uint64_t neighbours = 0;     // left out by the sweep (not candidates): one object, shared vertex index
    std::uint64_t duplicates = 0;     // dropped: not the pair's canonical cell
    std::uint64_t filtered = 0;       // dropped: proved disjoint by the filter
    std::uint64_t survivors = 0;
    std::uint64_t host_duplicates = 0;  // survivors kept twice (canonical scan out of budget), removed
    std::uint32_t runs = 0;           // submissions this call took (1 without overflow)
    bool filter_ran = false;
};

struct CellPairsResult {
    // Global triangle ids (object's triangle_base + triangle), a < b, sorted, unique.
    std::vector<std::array<std::uint32_t, 2>> pairs;
    CellPairsStats stats;
    std::vector<graph::PassTiming> passes;  // the last run's passes, in order
    double gpu_ms = 0;                      // the last run, first pass start to last pass end
};

class CellPairs {
public:
    // Needs subgroup basic, ballot and arithmetic operations in compute shaders.
    static Result<std::unique_ptr<CellPairs>> create(vk::Device& device);

    // Whether the double-precision filter can run (shaderFloat64 enabled on the device).
    bool filterSupported() const noexcept { return filter_pipeline_.handle() != VK_NULL_HANDLE; }

    // Checks the input, sizes the buffers and uploads the run's parameters. Errors:
    // InvalidArgument (resolution, projection, object layout), OutOfMemory (a buffer
    // larger than the device allows).
    [[nodiscard]] Result<void> prepare(const CellPairsInput& input, const CellPairsSettings& settings = {});
    // Adds the stage's passes (names start with "cells-") to `graph`, after prepare().
    // `projection` is the buffer an earlier pass wrote the projection into, when the
    // input gave projection_address. The header readback is the last pass.
    void record(graph::Graph& graph, graph::ResourceId projection = {});
    // After the recorded graph ran: reads the header. Complete: `out` holds the pairs
    // and statistics. Rerun: a buffer overflowed; it has been grown (and the parameters
    // re-uploaded), so record and run the stage again. Errors: InvalidMesh or
    // InvalidArgument for bad input found on the GPU (naming object and triangle).
    enum class Outcome { Complete, Rerun };
    [[nodiscard]] Result<Outcome> finish(CellPairsResult& out);

    // prepare(), then record, run and finish with its own executor until complete (at
    // most settings.max_runs runs; then OutOfMemory).
    [[nodiscard]] Result<CellPairsResult> run(const CellPairsInput& input, const CellPairsSettings& settings = {});

    // The capacities the next run uses.
    const CellPairsCapacity& capacity() const noexcept { return capacity_; }
    // Bytes of device and host-visible memory the stage holds.
    std::uint64_t memoryBytes() const noexcept;

private:
    explicit CellPairs(vk::Device& device) : device_(&device), executor_(device) {}
    Result<void> ensureBuffers();
    void writeParams();
    Result<void> checkFailure(const gpu::CellsHeader& header) const;

    vk::Device* device_;
    graph::Executor executor_;
    struct Pipelines {
        vk::Pipeline setup, big, scan, fill, sweep, deep, args, pairs;
    } pipes_;
    vk::Pipeline filter_pipeline_;  // the pair pass with the filter (needs shaderFloat64)
    struct Buffers {
        vk::Buffer params, objects, object_flags, pair_mask, projection, header, header_rb;
        vk::Buffer triangles, geometry, counts, offsets, block_sums, entries, entry_cells;
        vk::Buffer big_items, deep_items, candidates, survivors, args;
    } buf_;
    // The prepared run.
    std::vector<gpu::ObjectGpu> objects_;
    std::uint32_t triangles_ = 0, resolution_ = 0;
    VkDeviceAddress projection_address_ = 0;
    bool use_filter_ = false, has_pair_mask_ = false, has_self_ = false;
    std::uint32_t max_groups_x_ = 0;
    CellPairsCapacity capacity_;
    std::uint32_t runs_ = 0;
};

}  // namespace vkcollide::passes
