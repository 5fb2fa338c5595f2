// Device pairs (DetectSettings::reliable.device_pairs, docs/api.md "Results on the GPU"): the cell
// stage's exact survivors sorted on the GPU into the host result's order and written as
// TrianglePair records (spirv/cells/device_pairs.comp.glsl has the passes), in rows of the
// broad phase's table, so that an engine's next command buffer can read them after the
// world's signal.
//
//   pairs-args     the header (capacity; Incomplete when the run failed or a mesh failed
//                  the GPU input check) and the dispatch over the survivors
//   pairs-bucket   survivors counted per lower triangle id, scanned, scattered
//   pairs-sort     each bucket sorted by the higher id, repeats dropped, scanned, written
//   pairs-to-host  (for the host's result) the pairs copied to host memory by the transfer engine
//   pairs-header-readback  (with a host copy of the header) the header copied to host memory
//
// With device responses (DeviceResponseStage, device_responses.hpp) their passes run between
// pairs-sort and the copies to the host, over this stage's buckets; the header is shared.
// Early copies (prepare's `early`, for the host's result with its responses on the GPU):
// pairs-to-host runs right after pairs-sort, before the responses' passes, and copies the
// header, then the pairs in up to kMaxEarlyChunks pieces, each followed by the setting of its event
// (events()), so that the host names each piece while the GPU copies the next and then
// computes the responses.
//
// Capacity: the caller's, or (0) the cell stage's survivor capacity, which bounds the
// distinct pairs of a complete run, so an automatic capacity never overflows. A caller's
// smaller capacity overflows with kDevicePairsOverflow and the needed count (the first
// `capacity` pairs in order are written), never silently.
//
// The output buffers are re-created when they grow; the old ones are kept until the start
// of the second detection after (rows the engine reads, BufferTable::retire()), so reads the
// engine ordered before the next detection of this stage never meet a freed buffer.
//
// Not thread-safe; one per cell stage (ReliableMethod).
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "broad/broad_phase_types.hpp"
#include "broad/cells/cell_stage.hpp"
#include "vk/event.hpp"

namespace vkcollide::passes {

class DevicePairStage {
public:
    // Adds its rows to `io_table`.
    static Result<std::unique_ptr<DevicePairStage>> create(vk::Device& device, BufferTable& io_table);

    // After CellStage::prepare() (and again after it grew its buffers): sizes the buffers for
    // its survivors and triangles and uploads the parameters. `object_ids`: per object of the
    // run, the id its pairs carry. `fault_header`: the broad phase's header whose GPU input
    // check counts mark the run incomplete (0: none). `capacity`: pairs, 0: automatic.
    // `header_to_host`: the passes end by copying the header to host memory (header()).
    // `for_host`: the sorted pairs are also copied to host-visible memory for the host's
    // result (hostPairs()); the engine's device-local buffer is then only the copy's source.
    // `response_capacity`: the responses the device responses' buffer holds (the header
    // says it; DeviceResponseStage), 0 without them. `early_piece_pairs` (with for_host and
    // header_to_host): the early copies in pieces of at least that many pairs (at most
    // kMaxEarlyChunks of them); 0: none.
    [[nodiscard]] Result<void> prepare(const CellStage& cells, std::span<const std::uint32_t> object_ids, std::uint32_t capacity,
                                       VkDeviceAddress fault_header, bool header_to_host = false, bool for_host = false,
                                       std::uint32_t response_capacity = 0, std::uint32_t early_piece_pairs = 0);
    // The passes, after the cell stage's (`cells`: its resources in this graph, or its
    // outputs imported alone after it ran again on an overflow, so that the buffers hold
    // the final run's pairs); `fault_header` the broad phase header's resource (invalid:
    // not in this graph).
    // Returns what later passes read: the copies below, DeviceResponseStage (the buckets).
    struct Resources {
        graph::ResourceId header, pairs, counts, offsets, partners, block_sums;
    };
    Resources record(graph::Graph& g, const CellStage::Resources& cells, graph::ResourceId fault_header = {});
    // Prepared `early`: the pass that copies the header, then each piece of the pairs to host
    // memory and sets its event, right after record(); otherwise nothing.
    void recordEarlyCopies(graph::Graph& g, const Resources& sorted);
    // The copies to host memory the run was prepared for (header_to_host, for_host; the
    // pairs' only when not early), after record() and any passes over its buckets.
    void recordCopies(graph::Graph& g, const Resources& sorted);
    // Prepared early: the events the early copy sets, one per piece of the pairs, in order;
    // else none. Piece k holds the pairs [k, k + 1) * earlyChunkPairs() (of the capacity).
    std::span<const vk::Event> events() const noexcept { return {events_.data(), early_ ? early_chunks_ : 0u}; }
    std::uint32_t earlyChunkPairs() const noexcept { return early_chunk_pairs_; }
    // After the first event was seen set: the header as it was when the pairs were copied.
    gpu::DevicePairsHeader earlyHeader() const;
    // The most pieces, and the fewest pairs a piece of more than one holds by default
    // (prepare's early_piece_pairs: 0 copies nothing early).
    static constexpr std::uint32_t kMaxEarlyChunks = 4;
    static constexpr std::uint32_t kMinEarlyChunkPairs = 1u << 17;
    // Called at each detection's start: frees what was retired two starts ago.
    void retire();

    DevicePairsView view() const noexcept;
    // The prepared run's parameters (DevicePairsParams) and triangles, for DeviceResponseStage.
    VkDeviceAddress paramsAddress() const noexcept { return buf_.params->address(); }
    std::uint32_t triangleCount() const noexcept { return triangles_; }
    // After the GPU work of a run prepared with header_to_host: its header.
    gpu::DevicePairsHeader header() const;
    // After the GPU work of a run prepared for_host: the first `count` pairs, as their global
    // triangle ids (a < b, ascending; the host names the objects: narrow::runSortedPairs).
    std::span<const CandidatePair> hostPairs(std::uint32_t count) const;

private:
    DevicePairStage(vk::Device& device, BufferTable& table) : device_(&device), table_(&table) {}

    vk::Device* device_;
    BufferTable* table_;
    vk::Pipeline pipeline_;
    struct Buffers {
        TableRow params, object_ids, counts, offsets, out_offsets, block_sums, partners, args, header, pairs, header_rb, host_pairs,
            header_rb_early;
    } buf_;
    std::vector<vk::Event> events_;  // kMaxEarlyChunks
    std::uint32_t early_chunks_ = 1, early_chunk_pairs_ = 0;
    std::uint32_t triangles_ = 0, capacity_ = 0, max_groups_x_ = 0;
    bool header_to_host_ = false, for_host_ = false, early_ = false;
    // A pair's bytes in `pairs` and its host copy: for the host alone, its two global ids.
    VkDeviceSize pairBytes() const noexcept { return for_host_ ? sizeof(CandidatePair) : sizeof(gpu::DevicePair); }
    // pairs-to-host: early (recordEarlyCopies) or after the responses' passes (recordCopies).
    void recordPairsToHost(graph::Graph& g, const Resources& sorted, bool early);
};

}  // namespace vkcollide::passes
