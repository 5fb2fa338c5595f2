// The cell stage: every pair of triangles that may intersect, formed and filtered on
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
//             (download objects: survivors' triangles with their world vertices too)
// One submission, no host round trip inside a run. Every capacity is checked on the GPU:
// an overflow sets a flag with the size needed, and run() grows that buffer and runs
// again, so no pair is lost and nothing is accessed out of bounds. A budget
// (CellStageSettings::max_candidate_pairs) bounds what the scene may ask for: the setup
// sums the footprint boxes and the scan the pairs of footprints sharing a cell before
// anything grows or the sweep runs, the sweep counts candidates in 64 bits; past it the
// run fails with LimitExceeded, so pathological scenes (stacks of identical triangles)
// cost bounded time and memory.
//
// Two ways to use it: run() (prepare, record, run and finish on the caller's executor,
// pairs sorted and unique; tests and the stage benchmark), or as part of a larger graph
// (ReliableMethod): prepare(), record() after the passes that write the projection, and
// after that graph ran finish(stats), the survivors read in place (survivors(),
// gpuTriangles()); after an overflow record() and run the stage again (the broad phase's
// Again submission). It submits nothing itself.
//
// Not thread-safe; one instance per user. Its buffers are rows of a BufferTable (the
// broad phase's, or one of its own), sized by the stage for each run and after each
// overflow; they are kept between runs and only grow, so a steady scene allocates nothing
// per run.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "broad/buffer_table.hpp"
#include "broad/cell_stage_stats.hpp"
#include "cells/cells.h"
#include "graph/executor.hpp"
#include "vk/resources.hpp"
#include "vkcollide/narrow.hpp"
#include "vkcollide/types.hpp"

namespace vkcollide::passes {

// The scene of one run. Objects are gpu::ObjectGpu as the broad phase lays them out:
// vertex and index addresses (buffers with SHADER_DEVICE_ADDRESS usage, alive until the
// run is collected), triangle_base = the sum of the triangle counts before it, model rows
// of the 3x4 object-to-world transform. Positions and transform entries must be finite
// with magnitudes below 2^62, and so must world coordinates; a run that meets one that is
// not fails with InvalidMesh naming the object and triangle (docs/reliable.md).
struct CellStageInput {
    std::span<const gpu::ObjectGpu> objects;
    // World -> sampling space: x, y in [0, 1] across the grid, z the depth (any affine map
    // with finite rows; points outside [0, 1]^2 fall into the border cells; rows of 2^62
    // or more are scaled by a power of two, and a written projection's non-finite rows
    // become 0, both on the GPU: slower, never a pair lost).
    // Either given here, or written by an earlier pass of the same graph at
    // `projection_address` (then record() needs that buffer's ResourceId).
    std::optional<gpu::Projection> projection;
    VkDeviceAddress projection_address = 0;
    std::uint32_t resolution = 256;          // cells per side, 1 .. gpu::kCellsMaxResolution
    std::vector<std::uint8_t> self_collision;  // per object (non-zero: test its own pairs); empty: none
    // Whether two different objects a < b may collide, as bits a * n + b over the n
    // objects ((n^2 + 31) / 32 words, uploaded as they are), or as a function called for
    // every a < b in prepare(); neither: every pair may.
    std::span<const std::uint32_t> pair_mask;
    std::function<bool(std::uint32_t a, std::uint32_t b)> may_collide;
    // Per object (non-zero: its geometry is only on the GPU): every survivor's triangle of
    // such an object is written, once, to gpuTriangles(). Empty: none.
    std::span<const std::uint8_t> download;
};

// Element counts of the buffers whose size is only known on the GPU. 0: estimate from
// the scene (or keep what an earlier run needed).
struct CellStageCapacity {
    std::uint32_t entries = 0;     // footprints (16 + 4 bytes each)
    std::uint32_t items = 0;       // big-triangle work items (8 bytes)
    std::uint32_t candidates = 0;  // candidate pairs (12 bytes)
    std::uint32_t survivors = 0;   // surviving pairs (8 bytes, host-visible memory)
    std::uint32_t gpu_triangles = 0;  // survivors' triangles of download objects (52 bytes, host-visible)
    std::uint32_t sorted = 0;  // footprints of huge cells (8 bytes each: their sort's runs and copies)
};

// ExactPass::Auto's thresholds (vkcollide/types.hpp), in the last run's canonical
// candidates (candidates less duplicates: what the filter examines, the same count either
// way): an exact pass of its own costs about 15 us (its arguments and a dispatch) and
// saves time in proportion to them (idle lanes, the lighter filter; docs/exact_gpu.md,
// "Two passes"): on an H100 it broke even at 30K (deform-pair-100K) and won 20 % at 430K
// (pile-shapes). The gap keeps a scene near the threshold from switching, and re-recording
// its commands, every frame.
inline constexpr std::uint64_t kExactInlineBelow = 32768;
inline constexpr std::uint64_t kExactQueuedFrom = 65536;

// With the exact pass to follow, the pair pass's filter (the plane sides) is skipped where
// it rejected under this share of the last filtered run's canonical candidates, for the
// next kFilterRecheckRuns runs, then run once to measure again: on an H100 it rejected 60-89 %
// of the piles', spheres' and CAD plates' candidates and paid for itself, 0-1.6 % of the
// touching and mating stacks' and walls' and cost 7-45 % of their pair + exact passes
// (docs/exact_gpu.md, "Two passes"). The exact pass decides every candidate either way.
inline constexpr double kFilterUsefulShare = 0.1;
inline constexpr std::uint32_t kFilterRecheckRuns = 15;

struct CellStageSettings {
    // Run the double-precision filter where the device has shaderFloat64 enabled.
    bool filter = true;
    // Decide every candidate the filter keeps exactly on the GPU (where the device has
    // shaderFloat64; docs/exact_gpu.md) and leave out neighbours (a bit-identical world
    // vertex): the survivors are then exactly the intersecting pairs.
    bool exact = false;
    // Where the exact decision runs; the survivors are the same either way.
    ExactPass exact_pass = ExactPass::Auto;
    // With the exact pass: skip the filter while it rejects under kFilterUsefulShare of the
    // candidates (false: always filter, as tests that count what it rejects need).
    bool skip_unhelpful_filter = true;
    // The budget of a run (DetectSettings::limits.max_candidate_pairs in a detection; the stage's
    // own limit is 2^31 - 1, its buffers' 32-bit indices): the cells of the triangles'
    // clamped footprint boxes (so the footprints, 20 bytes each, and the count pass's work)
    // and the candidate pairs (12 bytes each) at most this many each, and the sweep's
    // comparisons (CellStageStats::comparisons) at most gpu::kCellsComparisonsPerBudget
    // times it. Past one of them finish() fails with
    // LimitExceeded naming the count; no buffer ever grows beyond the budget's elements.
    std::uint64_t max_candidate_pairs = std::numeric_limits<std::uint64_t>::max();
    // Capacities of the first run (at most the budget); they grow (to 1.25x what was
    // needed, at most the budget) on overflow.
    CellStageCapacity initial;
    // Runs allowed per call (the first plus reruns after overflows).
    std::uint32_t max_runs = 8;
    // Proximity (src/proximity/): half the distance, in world units (0: off). Every triangle
    // is grown by it along each axis, so triangles closer than the distance become
    // candidates, and the sweep keeps one object's pairs that share a vertex index (the pair
    // pass leaves them out of the survivors instead).
    float proximity_pad = 0;
    // The survivors stay in device-local memory, for GPU stages only (device pairs with no
    // host result): survivors() is then empty, and the GPU's writes and the sort's reads
    // stay off the host bus.
    bool survivors_on_device = false;
    // Dispatches are split into rows of at most this many workgroups (0: the device's
    // maxComputeWorkGroupCount[0]); tests set it small to exercise the split.
    std::uint32_t max_workgroups_x = 0;
    // Candidates the pair pass decides per submission (0: automatic, what the device
    // decides in about kPairChunkTargetMs at the rate measured in earlier runs), so that a
    // submission left running after a timeout ends soon. More candidates than that:
    // finish() answers MorePairs until the chunks cover them all.
    std::uint32_t pair_chunk = 0;
    // Work of one chunk of the sweep, in comparisons at most (gpu::CellsParams::sweep_work;
    // 0: automatic, what the device sweeps in about kSweepChunkTargetMs at the rate its
    // last chunk measured, the whole sweep on a GPU until one takes longer), so that a
    // submission left running after a timeout ends soon. More left: finish() answers
    // MoreSweep until the chunks cover every entry and deep item.
    std::uint32_t sweep_work = 0;
    // Which cells drop a pair's repeats in the sweep (docs/reliable.md, "Piles"). Auto: on
    // a CPU implementation every cell of kCellsSweepDedupe entries or more (piles cost
    // seconds there); on a GPU only the deep cells swept in chunks (more than
    // kCellsDeepShared entries), with a shallow sweep compiled without the checks: their
    // state slowed every cell's sweep by up to a half on the H200, and its pair pass drops
    // repeats faster. The same pairs either way; tests pick each.
    enum class RepeatChecks { Auto, FromShallow, DeepChunksOnly };
    RepeatChecks repeat_checks = RepeatChecks::Auto;
    // How the fill takes its slots (docs/reliable.md, "Fill"). Auto: on a GPU a workgroup
    // whose footprints crowd into few cells takes each cell's slots at once through a table
    // in shared memory (PerCell); on a CPU implementation, where its barriers and shared
    // atomics cost more than the atomics they save (the bundled demo's fill about 3x slower
    // on lavapipe), every footprint takes its own (PerFootprint). The same pairs either
    // way; tests pick each.
    enum class FillSlots { Auto, PerCell, PerFootprint };
    FillSlots fill_slots = FillSlots::Auto;
    // Count the deep sweep's and the sorts' loops where the device ends long loops silently
    // (DeviceInfo::loop_iteration_limit; docs/reliable.md, "Huge cells"). false: never
    // (tests run a GPU's deep sweep on lavapipe with it, on scenes within that limit).
    bool loop_guard = true;
};

// The GPU time an automatic pair-pass chunk aims at (CellStageSettings::pair_chunk).
inline constexpr double kPairChunkTargetMs = 200.0;
// After a candidate overflow the survivors are sized for every candidate up to this many
// (32 MiB of host-visible memory), so that the rerun does not overflow them too.
inline constexpr std::uint32_t kSurvivorsForCandidates = 1u << 22;
// The GPU time an automatic sweep chunk aims at (CellStageSettings::sweep_work).
inline constexpr double kSweepChunkTargetMs = 200.0;
// The sweep's pass name in the graph (and in the passes' timings).
inline constexpr const char* kSweepPassName = "cells-sweep";
// The pair pass's name in the graph (and in the passes' timings).
inline constexpr const char* kPairPassName = "cells-pairs";
// The exact pass after each chunk of the pair pass (with CellStageSettings::exact).
inline constexpr const char* kExactPassName = "cells-exact";

struct CellStageResult {
    // Global triangle ids (object's triangle_base + triangle), a < b, sorted, unique.
    std::vector<std::array<std::uint32_t, 2>> pairs;
    CellStageStats stats;
    std::vector<graph::PassTiming> passes;  // the last run's passes, in order
    double gpu_ms = 0;                      // the last run, first pass start to last pass end
};

class CellStage {
public:
    // Needs subgroup basic, ballot and arithmetic operations in compute shaders. Its
    // buffers become rows of `table` (ReliableMethod: the broad phase's), which must
    // outlive the stage; without one, of a table the stage owns.
    static Result<std::unique_ptr<CellStage>> create(vk::Device& device, BufferTable* table = nullptr);

    // One of the stage's compute programs (SPIR-V and the name its pipeline carries).
    struct Program {
        std::span<const std::uint32_t> code;
        const char* name;
    };

    // Whether the double-precision filter can run (shaderFloat64 enabled on the device).
    bool filterSupported() const noexcept { return device_->shader_float64; }

    // Checks the input, sizes the buffers and uploads the run's parameters. Errors:
    // InvalidArgument (resolution, projection, object layout), OutOfMemory (a buffer
    // larger than the device allows).
    [[nodiscard]] Result<void> prepare(const CellStageInput& input, const CellStageSettings& settings = {});
    // Makes now every pipeline a run with `settings` may record on this device, whichever
    // form the scene or the last run picks (the pair pass with the exact decision inside and
    // the filter with the exact pass), instead of at the run that first needs it
    // (CollisionWorld::preparePipelines). Errors: the driver's, by the program's name.
    [[nodiscard]] Result<void> makeEveryPipeline(const CellStageSettings& settings);
    // Adds the stage's passes (names start with "cells-") to `graph`, after prepare().
    // `projection` is the buffer an earlier pass wrote the projection into, when the
    // input gave projection_address. The header readback is the last pass. Returns the
    // buffers later GPU stages of the same graph read (device_pairs.hpp).
    struct Resources {
        graph::ResourceId header, survivors, triangles, candidates, geometry, args;
    };
    Resources record(graph::Graph& graph, graph::ResourceId projection = {});
    // Those buffers imported into a graph of their own (a later stage run alone).
    Resources importOutputs(graph::Graph& g) {
        return {importRow(g, buf_.header),         importRow(g, buf_.survivors, !survivors_on_device_),
                importRow(g, buf_.triangles),   importRow(g, buf_.candidates),
                importRow(g, buf_.geometry),     importRow(g, buf_.args)};
    }
    // The indirect dispatches the stage writes (kCellsArgs* slots of 12 bytes): the pair
    // pass's serves any later pass over the candidates.
    VkBuffer argsBuffer() const noexcept { return buf_.args->handle(); }
    // The setup's records, one per triangle (gpu::CellsTriangle, gpu::CellsGeometry): what
    // the pair pass and later stages read; the tests check their layout word by word.
    VkBuffer trianglesBuffer() const noexcept { return buf_.triangles->handle(); }
    VkBuffer geometryBuffer() const noexcept { return buf_.geometry->handle(); }
    // The prepared run as later GPU stages see it: the parameters' address (CellsParams),
    // its triangles and the dispatch row limit.
    VkDeviceAddress paramsAddress() const noexcept { return buf_.params->address(); }
    std::uint32_t triangleCount() const noexcept { return triangles_; }
    std::uint32_t maxGroupsX() const noexcept { return max_groups_x_; }
    // After the recorded graph ran: reads the header. Complete: `out` holds the pairs
    // and statistics. Rerun: a buffer overflowed; it has been grown (and the parameters
    // re-uploaded), so record and run the stage again. MoreSweep: the sweep has chunks to go
    // (CellStageSettings::sweep_work): recordSweepChunk() and run that. MorePairs: the pair
    // pass has chunks to go (CellStageSettings::pair_chunk): recordPairChunk() and run that. Errors: InvalidMesh or
    // InvalidArgument for bad input found on the GPU (naming object and triangle);
    // LimitExceeded past the budget (CellStageSettings::max_candidate_pairs), naming the
    // count the run needed. After any error the stage is ready for the next prepare().
    enum class Outcome { Complete, Rerun, MoreSweep, MorePairs };
    // After MoreSweep: the sweep's next chunk, then the pair pass's first chunk (it does
    // nothing unless the sweep is complete) and the header readback. Returns what later
    // passes of the same graph read, as record() does.
    Resources recordSweepChunk(graph::Graph& g);
    // After MorePairs: the pair pass over the next chunk and the header readback; the same.
    Resources recordPairChunk(graph::Graph& g);
    // After the submission that swept the chunk finish() last read: its sweep pass's GPU
    // time, from which the automatic sweep chunk (CellStageSettings::sweep_work) is sized.
    void noteSweepTime(std::span<const graph::PassTiming> passes);
    // After a complete run that decided `candidates`: its passes (one pair-pass chunk or
    // several, among others), whose pair-pass time gives the rate the automatic chunk of
    // later runs is sized from.
    void notePairPassTime(std::span<const graph::PassTiming> passes, std::uint64_t candidates);
    std::uint32_t pairChunk() const noexcept { return pair_chunk_; }
    [[nodiscard]] Result<Outcome> finish(CellStageResult& out);
    // The same without host work beyond the header: Complete fills `out_stats` (not
    // host_duplicates) and makes survivors() and gpuTriangles() valid.
    [[nodiscard]] Result<Outcome> finish(CellStageStats& out_stats);
    // After a Complete finish, until the next prepare() or record(): the
    // survivors as the GPU wrote them (global ids, a < b, unsorted, a rare pair twice)
    // and the download objects' triangles, read in place from host-visible (cached where
    // the device has it) memory.
    std::span<const CandidatePair> survivors() const noexcept;
    std::span<const GpuTriangle> gpuTriangles() const noexcept;
    // After finish() failed on bad input found on the GPU: the flags (gpu::kCellsBad*),
    // the object (index in the input) and its triangle.
    struct BadInput {
        std::uint32_t flags = 0, object = 0, triangle = 0;
    };
    const std::optional<BadInput>& badInput() const noexcept { return bad_input_; }

    // prepare(), then record, run (on `executor`, default waits) and finish until complete
    // (at most settings.max_runs runs; then OutOfMemory).
    [[nodiscard]] Result<CellStageResult> run(graph::Executor& executor, const CellStageInput& input, const CellStageSettings& settings = {});
    // The runs finish() has read since prepare() (the first plus one per overflow).
    std::uint32_t runs() const noexcept { return runs_; }

    // The capacities the next run uses.
    const CellStageCapacity& capacity() const noexcept { return capacity_; }
    // Bytes of device and host-visible memory the stage holds.
    std::uint64_t memoryBytes() const noexcept;

private:
    explicit CellStage(vk::Device& device) : device_(&device) {}
    Result<void> ensureBuffers();
    // The cells the per-cell buffers are sized for: `exact` rounded up to a sixteenth of its
    // power of two. A resolution that moves by a cell or so a frame (a deforming scene's
    // follows its extent) then seldom re-creates those buffers.
    static std::uint64_t roundedCells(std::uint64_t exact);
    // The cells the count buffer's clear and the scan's dispatches cover (the shaders stop
    // at the params' cell and block counts): every cell the per-cell buffers hold, while
    // that is at most kRecordedCellsSlack times this run's rounded count, else the rounded
    // count. The recorded commands then stay the same while a deforming scene's cell count
    // swings within that band, and the executor submits its command buffer again instead of
    // recording it (0.03 ms a frame on the H200's host; a sixteenth's rounding alone left
    // deform-tori, deform-blobs and deform-armadillo-bunny recording on 73-100 % of their
    // frames: results/h200_2026-12-07/README.md, run 31). The band costs a clear of 4 bytes
    // and an idle scan workgroup per 1,024 cells beyond the run's. Where the buffers hold
    // more than that (they keep the most cells a run ever needed: the grid tuner's trials
    // at finer grids, a scene that spread out), the most cells one of the last kRecentRuns
    // runs needed within the same band: otherwise a scene swinging below a
    // quarter of the buffers recorded anew every frame (deform-blobs and
    // deform-armadillo-bunny on the H100: tuned to 0.35x, 104-227 cells a side after trials
    // at up to 1.41x; results/h200_2026-12-07/README.md, session 59).
    static constexpr std::uint64_t kRecordedCellsSlack = 4;
    static constexpr std::size_t kRecentRuns = 32;
    std::uint64_t recordedCells() const;
    std::array<std::uint64_t, kRecentRuns> recent_cells_{};  // rounded counts, a ring (0: none)
    std::size_t recent_next_ = 0;
    std::uint32_t automaticPairChunk() const;
    struct PairPassIds {
        graph::ResourceId header, header_rb, tris, geometry, candidates, survivors, args, gpu_triangles, marks, exact_queue;
    };
    // The pair pass, the last passes of every submission of the stage: returns what later
    // passes of the same graph read (record(), the chunks').
    Resources recordPairPass(graph::Graph& g, const PairPassIds& ids, std::uint32_t chunk);
    struct SweepIds {
        graph::ResourceId header, entries, chunk_cells, offsets, counts, deep, sorted, candidates, args;
    };
    void recordSweep(graph::Graph& g, const SweepIds& ids);
    std::uint32_t automaticSweepWork() const;
    // CellsParams::loop_guard: ~0u, or below the device's loop iteration limit with room for
    // the loops the count leaves out (a few hundred).
    std::uint32_t loopGuard() const;
    static constexpr std::uint32_t kLoopGuardMargin = 5535;
    void writeParams();
    Result<void> checkFailure(const gpu::CellsHeader& header);
    Result<void> checkBudget(const gpu::CellsHeader& header) const;

    vk::Device* device_;
    // Made when a run first needs them (ensurePipelines()). `pairs`: without float64;
    // `pairs_inline` (the exact decision inside), `pairs_filter` (the filter, queueing for
    // the exact pass) and `exact`: with it.
    struct Pipelines {
        vk::Pipeline setup, big, scan, fill, fill_per_footprint, sweep, sweep_plain, deep_sort, deep, deep_guarded, args, pairs;
        vk::Pipeline pairs_inline, pairs_filter, exact;
    } pipes_;
    static std::vector<Program> programs(bool float64);
    // A form of a pass: where its pipeline is kept and the program it is made from.
    struct Slot {
        vk::Pipeline* pipeline;
        const Program* program;
    };
    Slot fillSlot();
    Slot shallowSweepSlot();
    Slot deepSweepSlot();
    Slot pairSlot();
    Result<void> ensurePipelines();
    // The forms a run with `settings` takes on this device whatever its scene (the sweep's
    // repeat checks, the fill's slots, the loop guard), and whether it decides exactly.
    void chooseForms(const CellStageSettings& settings);
    using Row = TableRow;  // rows of table_
    void addRows();
    std::unique_ptr<BufferTable> own_table_;  // without a caller's table
    BufferTable* table_ = nullptr;
    struct Buffers {
        Row params, objects, object_flags, pair_mask, projection, header, header_rb;
        Row triangles, geometry, counts, offsets, block_sums, entries, chunk_cells;
        Row big_items, deep_items, sorted, candidates, survivors, args, gpu_triangles, marks, exact_queue;
    } buf_;
    // The prepared run.
    std::vector<gpu::ObjectGpu> objects_;
    std::uint32_t triangles_ = 0, resolution_ = 0;
    VkDeviceAddress projection_address_ = 0;
    float proximity_pad_ = 0;
    bool survivors_on_device_ = false;
    // The exact decision in a pass of its own this run (ExactPass), and the last run's
    // canonical candidates (~0: none yet).
    bool exact_queued_ = false;
    bool exactQueued() const noexcept { return use_exact_ && exact_queued_; }  // this run has the exact pass
    // This run filters before the exact pass, where a filter that rejects little may be skipped.
    bool filterSkippable() const noexcept { return use_filter_ && exactQueued() && skip_unhelpful_filter_; }
    std::uint64_t last_canonical_ = ~std::uint64_t{0};
    bool skip_unhelpful_filter_ = true;    // CellStageSettings::skip_unhelpful_filter
    std::uint32_t filter_skips_left_ = 0;  // runs that skip the filter before it is measured again
    bool use_filter_ = false, use_exact_ = false, has_pair_mask_ = false, has_self_ = false, has_download_ = false;
    std::uint32_t download_triangles_ = 0;
    std::uint32_t survivor_count_ = 0, gpu_triangle_count_ = 0;  // of the last Complete finish
    std::optional<BadInput> bad_input_;
    std::uint32_t max_groups_x_ = 0;
    std::uint32_t budget_ = 0;             // the run's budget, at most kMaxElements
    std::uint64_t asked_budget_ = 0;       // as the settings gave it (for the messages)
    CellStageCapacity capacity_;
    std::uint32_t runs_ = 0;
    std::uint32_t pair_chunk_ = 0, next_chunk_ = 0;  // the run's chunk size; the chunk recorded next
    std::uint32_t sweep_dedupe_ = gpu::kCellsSweepDedupe;  // CellsParams::sweep_dedupe
    bool plain_sweep_ = false;                              // the shallow sweep without repeat checks
    bool fill_per_cell_ = true;  // the fill takes a crowded workgroup's slots per cell
    bool loop_guard_ = true;                                // CellStageSettings::loop_guard
    double pair_rate_ = 0;  // candidates per GPU ms of the pair pass, measured (0: not yet)
    // The sweep's chunks: their work (CellsParams::sweep_work), whether it is automatic,
    // the work of the chunk finish() last read, the chunks recorded for this run so far,
    // and the work per GPU ms measured (0: not yet).
    std::uint32_t sweep_work_ = ~0u;
    bool auto_sweep_work_ = true;
    double last_sweep_chunk_work_ = 0;
    std::uint32_t sweep_chunks_ = 0;
    double sweep_rate_ = 0;
};

}  // namespace vkcollide::passes
