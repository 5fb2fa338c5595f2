#include <algorithm>
#include <atomic>
#include <limits>
#include <optional>
#include <string>

#include "common/config.h"
#include "narrow/exact_stage.hpp"
#include "narrow/guarded_executor.hpp"
#include "narrow/workspace.hpp"
#include "narrow/neighbours.hpp"
#include "vkcollide/narrow.hpp"
#include "vkcollide/thread_pool.hpp"

// The record paths (docs/narrow_phase.md has the measurements behind these choices):
//   1. validate and rank: every record checked; its (object, triangle) key radix sorted
//      (unless already in order, as the GPU writes them); slot = rank, so slot order is
//      the canonical order, and equal neighbours in the sorted keys are the duplicates.
//   2. slots: the 80-byte records are read in place when in order; otherwise, and for
//      the 32-byte records, each slot's indices and world vertices are gathered.
//   3. sweep and prune per grid cell (sweep_and_prune.hpp), in parallel; the self-collision
//      switch is applied inside the sweep, the neighbour rule by the same tasks.
//   4. the back half (exact_stage.hpp): object-pair filter, exact tests, order, responses.
// Every parallel stage writes per-task state that is combined in a fixed order or sorted,
// so the result does not depend on the thread count or on how tasks were scheduled.

#if defined(__GNUC__) || defined(__clang__)
#define VKCOLLIDE_ALWAYS_INLINE __attribute__((always_inline))
#else
#define VKCOLLIDE_ALWAYS_INLINE
#endif

namespace vkcollide {
namespace {

using narrow::BoxZ;
using narrow::Buffer;
using narrow::keyOf;
using narrow::Strided;


// Either kind of record, seen through strided views.
struct RecordView {
    std::size_t n = 0;
    Strided<std::uint32_t> object, triangle;
    Strided<BoxZ> box;
};

template <typename Record>
RecordView viewOf(std::span<const Record> records) {
    RecordView v;
    v.n = records.size();
    if (!records.empty()) {
        v.object = {&records[0].object, sizeof(Record)};
        v.triangle = {&records[0].triangle, sizeof(Record)};
        v.box = {reinterpret_cast<const BoxZ*>(&records[0].box[0]), sizeof(Record)};
    }
    return v;
}

bool validBox(const BoxZ& b) {
    return std::isfinite(b.x0) && std::isfinite(b.y0) && std::isfinite(b.x1) && std::isfinite(b.y1) && std::isfinite(b.z0) &&
           std::isfinite(b.z1) && b.x0 <= b.x1 && b.y0 <= b.y1 && b.z0 <= b.z1;
}

std::string describe(std::uint32_t object, std::uint32_t triangle) {
    return "object " + std::to_string(object) + " triangle " + std::to_string(triangle);
}

std::string boxProblem(const BoxZ& b) {
    const bool finite = std::isfinite(b.x0) && std::isfinite(b.y0) && std::isfinite(b.x1) && std::isfinite(b.y1) &&
                        std::isfinite(b.z0) && std::isfinite(b.z1);
    return finite ? " has an empty box (needs x0 <= x1, y0 <= y1, zmin <= zmax)" : " has a non-finite box or depth";
}

// The boxes' extent per axis, found while validating (the sweep needs it).
struct BoxRange {
    float lo[3], hi[3];
};

// Stage 1. check(i) returns an error message for a bad record i (its first broken rule)
// or nothing. Fills ws.record_of when the keys are not ascending; returns whether they are.
template <typename Check>
Result<bool> validateAndRank(const RecordView& rv, Check&& check, Executor& ex, NarrowWorkspace::Impl& ws,
                             BoxRange& out_range) {
    const std::size_t n = rv.n;
    const auto keyAt = [&](std::size_t i) { return keyOf(rv.object[i], rv.triangle[i]); };
    const std::size_t tasks = narrow::taskCount(n, narrow::kValidateGrain);
    std::vector<std::size_t> first_bad(tasks, n);
    std::vector<char> ascending(tasks, 1);
    std::vector<BoxRange> task_range(tasks);
    ex.parallelFor(n, narrow::kValidateGrain, [&](std::size_t begin, std::size_t end) {
        std::size_t bad = n;
        bool task_ascending = true;
        std::uint64_t previous = keyAt(begin);
        const BoxZ first = rv.box[begin];
        BoxRange r{{first.x0, first.y0, first.z0}, {first.x1, first.y1, first.z1}};
        for (std::size_t i = begin; i < end; ++i) {
            const BoxZ b = rv.box[i];
            if (bad == n && (!validBox(b) || check(i))) bad = i;
            // Comparisons with NaN are false: a bad box does not spoil the range (and fails anyway).
            r.lo[0] = b.x0 < r.lo[0] ? b.x0 : r.lo[0], r.hi[0] = b.x1 > r.hi[0] ? b.x1 : r.hi[0];
            r.lo[1] = b.y0 < r.lo[1] ? b.y0 : r.lo[1], r.hi[1] = b.y1 > r.hi[1] ? b.y1 : r.hi[1];
            r.lo[2] = b.z0 < r.lo[2] ? b.z0 : r.lo[2], r.hi[2] = b.z1 > r.hi[2] ? b.z1 : r.hi[2];
            const std::uint64_t key = keyAt(i);
            task_ascending = task_ascending && (i == begin || previous < key);
            previous = key;
        }
        first_bad[begin / narrow::kValidateGrain] = bad;
        ascending[begin / narrow::kValidateGrain] = task_ascending ? 1 : 0;
        task_range[begin / narrow::kValidateGrain] = r;
    });
    if (tasks > 0) {
        out_range = task_range[0];
        for (const BoxRange& r : task_range) {
            for (int a = 0; a < 3; ++a) out_range.lo[a] = std::min(out_range.lo[a], r.lo[a]), out_range.hi[a] = std::max(out_range.hi[a], r.hi[a]);
        }
    }
    const auto bad = std::min_element(first_bad.begin(), first_bad.end());
    if (bad != first_bad.end() && *bad < n) {
        const std::size_t i = *bad;
        std::optional<std::string> problem = check(i);
        if (!problem) problem = boxProblem(rv.box[i]);
        return Error(ErrorCode::InvalidArgument, "runNarrowPhase: " + describe(rv.object[i], rv.triangle[i]) + *problem);
    }
    bool keys_ascending = true;
    for (std::size_t t = 0; t < tasks; ++t) {
        keys_ascending = keys_ascending && ascending[t] && (t == 0 || keyAt(t * narrow::kValidateGrain - 1) < keyAt(t * narrow::kValidateGrain));
    }
    if (keys_ascending) return true;
    // Sort the keys, find duplicates (neighbours once sorted), rank.
    Buffer<narrow::KeyIndex>& keys = ws.keys;
    keys.resize(n);
    ex.parallelFor(n, narrow::kValidateGrain, [&](std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) keys[i] = {keyAt(i), static_cast<std::uint32_t>(i)};
    });
    narrow::parallelRadixSort(ex, keys, ws.key_scratch, 64);
    std::vector<std::size_t> first_repeat(tasks, n);
    ex.parallelFor(n, narrow::kValidateGrain, [&](std::size_t begin, std::size_t end) {
        for (std::size_t r = std::max<std::size_t>(begin, 1); r < end; ++r) {
            if (keys[r].key == keys[r - 1].key) {
                first_repeat[begin / narrow::kValidateGrain] = r;
                break;
            }
        }
    });
    for (const std::size_t r : first_repeat) {
        if (r < n) {
            return Error(ErrorCode::InvalidArgument,
                         "runNarrowPhase: " + describe(static_cast<std::uint32_t>(keys[r].key >> 32),
                                                       static_cast<std::uint32_t>(keys[r].key)) +
                             " appears more than once");
        }
    }
    ws.record_of.resize(n);
    ex.parallelFor(n, narrow::kValidateGrain, [&](std::size_t begin, std::size_t end) {
        for (std::size_t r = begin; r < end; ++r) ws.record_of[r] = keys[r].index;
    });
    return false;
}

// Stages 3 and on, once the slots are known.
Result<NarrowResult> sweepAndTest(const RecordView& rv, const BoxRange& range, const std::uint32_t* record_of,
                                  const narrow::SlotData& slots, const NarrowOptions& options, Executor& ex,
                                  NarrowWorkspace::Impl& ws, NarrowResult&& result, narrow::StageClock& clock) {
    const std::size_t n = rv.n;
    NarrowStats& stats = result.stats;
    narrow::SweepInput input;
    input.count = n;
    input.box = rv.box;
    input.record_of = record_of;
    input.object = slots.object;
    input.options = &options;
    input.has_range = true;
    std::copy(std::begin(range.lo), std::end(range.lo), input.range_lo);
    std::copy(std::begin(range.hi), std::end(range.hi), input.range_hi);
    narrow::GridSweep& sweep = ws.sweep;
    sweep.build(input, &ex);
    const std::size_t tiles = sweep.tileCount();
    const std::size_t sweep_grain = narrow::grainFor(tiles, ex.threadCount(), narrow::kTasksPerThread, 1, narrow::kMaxSweepGrain);
    std::vector<narrow::PairTask>& tasks = ws.pair_tasks;
    tasks.resize(narrow::taskCount(tiles, sweep_grain));
    Buffer<std::uint8_t>& in_pair = ws.in_pair;
    in_pair.resize(n);
    ex.parallelFor(n, 1u << 18, [&](std::size_t begin, std::size_t end) {
        std::fill(in_pair.begin() + begin, in_pair.begin() + end, std::uint8_t{0});
    });
    static_assert(std::atomic_ref<std::uint8_t>::required_alignment == 1);
    const bool filter_objects = static_cast<bool>(options.may_collide);
    std::atomic<std::size_t> box_pairs_seen{0};  // in whole strides, by the sweep tasks
    ex.parallelFor(tiles, sweep_grain, [&](std::size_t begin, std::size_t end) {
        // Moved into a local (keeping the capacity of the last call) and back at the end:
        // tasks sit next to each other in memory, and growing vectors in place would share
        // cache lines between threads.
        narrow::PairTask task = std::move(tasks[begin / sweep_grain]);
        task.tests.clear();
        task.object_pairs.clear();
        std::size_t sap_pairs = 0, neighbour_pairs = 0;  // in registers, not in `task`
        std::size_t budget_mark = narrow::kBoxBudgetStride;      // sap_pairs at the next look at the budget
        std::uint64_t last_object_pair = std::numeric_limits<std::uint64_t>::max();
        // Runs for every reported pair: inlined into the sweep.
        narrow::GridSweep::TileCells cells;
        sweep.sweepTiles(begin, end, cells, [&](std::uint32_t i, std::uint32_t j, std::uint32_t object_i,
                                                std::uint32_t object_j) VKCOLLIDE_ALWAYS_INLINE {
            ++sap_pairs;
            // The box-pair budget, every narrow::kBoxBudgetStride pairs: past it, this task throws
            // (GuardedExecutor ends the loop) and the call returns LimitExceeded.
            if (sap_pairs == budget_mark) {
                budget_mark += narrow::kBoxBudgetStride;
                if (box_pairs_seen.fetch_add(narrow::kBoxBudgetStride, std::memory_order_relaxed) + narrow::kBoxBudgetStride > options.max_box_pairs)
                    throw narrow::BoxBudgetExceeded{};
            }
            // Store only when not set yet: most pairs find both flags set, and reading keeps
            // the cache line shared instead of bouncing it between threads.
            for (const std::uint32_t k : {i, j}) {
                const std::atomic_ref<std::uint8_t> flag(in_pair[k]);
                if (!flag.load(std::memory_order_relaxed)) flag.store(1, std::memory_order_relaxed);
            }
            if (object_i == object_j) {
                // A shared index decides most neighbours; the positions only the rest.
                const narrow::Index3& index_i = slots.vertex_index[i];
                const narrow::Index3& index_j = slots.vertex_index[j];
                if (narrow::shareIndex(index_i, index_j) || narrow::areNeighbours(index_i, slots.v[i], index_j, slots.v[j])) {
                    ++neighbour_pairs;
                    return;
                }
            } else if (filter_objects) {
                const std::uint64_t object_pair = keyOf(std::min(object_i, object_j), std::max(object_i, object_j));
                if (object_pair != last_object_pair) task.object_pairs.push_back(object_pair);
                last_object_pair = object_pair;
            }
            task.tests.push_back({i, j});
        });
        task.sap_pairs = sap_pairs;
        task.filtered_pairs = 0;
        task.neighbour_pairs = neighbour_pairs;
        std::sort(task.object_pairs.begin(), task.object_pairs.end());
        task.object_pairs.erase(std::unique(task.object_pairs.begin(), task.object_pairs.end()), task.object_pairs.end());
        tasks[begin / sweep_grain] = std::move(task);
    });
    for (const narrow::PairTask& task : tasks) {
        stats.sap_pairs += task.sap_pairs;
        stats.neighbour_pairs += task.neighbour_pairs;
    }
    // Exceeded exactly when all tasks' pairs are more than the budget (a task throws only
    // once the strides counted so far are).
    if (stats.sap_pairs > options.max_box_pairs) throw narrow::BoxBudgetExceeded{};
    // The loop's end ordered every flag store before these (plain) reads.
    std::vector<std::size_t> flagged(narrow::taskCount(n, narrow::kValidateGrain), 0);
    ex.parallelFor(n, narrow::kValidateGrain, [&](std::size_t begin, std::size_t end) {
        std::size_t c = 0;
        for (std::size_t i = begin; i < end; ++i) c += in_pair[i];
        flagged[begin / narrow::kValidateGrain] = c;
    });
    for (const std::size_t c : flagged) stats.potentially_colliding_triangles += c;
    clock.lap(result.timings.sweep_ms);

    narrow::testAndRespond(tasks, slots, n, false, options, ex, ws, result, clock);
    return std::move(result);
}

Result<NarrowResult> tooMany(std::size_t n) {
    return Error(ErrorCode::InvalidArgument, "runNarrowPhase: " + std::to_string(n) + " candidates (at most " +
                                                 std::to_string(narrow::kMaxSweepSlots) + ")");
}

}  // namespace

Result<NarrowResult> runNarrowPhase(std::span<const CandidateTriangle> in_candidates, const NarrowOptions& options,
                                    Executor& executor) {
    NarrowWorkspace workspace;
    return runNarrowPhase(in_candidates, options, executor, workspace);
}

namespace {

Result<NarrowResult> triangleRecordPhase(std::span<const CandidateTriangle> in_candidates, const NarrowOptions& options,
                                         Executor& executor, NarrowWorkspace& io_workspace) {
    narrow::StageClock clock;
    NarrowWorkspace::Impl& ws = io_workspace.impl();
    const std::size_t n = in_candidates.size();
    if (n > narrow::kMaxSweepSlots) return tooMany(n);
    const RecordView rv = viewOf(in_candidates);
    const auto check = [&](std::size_t i) -> std::optional<std::string> {
        const CandidateTriangle& c = in_candidates[i];
        if (!narrow::isFinite(c.v[0]) || !narrow::isFinite(c.v[1]) || !narrow::isFinite(c.v[2])) return " has a non-finite vertex";
        return std::nullopt;
    };
    BoxRange range{};
    Result<bool> ascending = validateAndRank(rv, check, executor, ws, range);
    if (!ascending) return ascending.error();
    NarrowResult result;
    result.stats.candidates = n;
    clock.lap(result.timings.validate_ms);

    // In order: the records are the slots. Otherwise copy them into slot order.
    narrow::SlotData slots;
    if (*ascending) {
        if (n > 0) {
            const CandidateTriangle& first = in_candidates[0];
            slots.object = {&first.object, sizeof(CandidateTriangle)};
            slots.triangle = {&first.triangle, sizeof(CandidateTriangle)};
            slots.vertex_index = {&first.vertex_index, sizeof(CandidateTriangle)};
            slots.v = {&first.v, sizeof(CandidateTriangle)};
        }
    } else {
        ws.tags.resize(n);
        ws.vertices.resize(n);
        executor.parallelFor(n, narrow::kValidateGrain, [&](std::size_t begin, std::size_t end) {
            for (std::size_t s = begin; s < end; ++s) {
                const CandidateTriangle& c = in_candidates[ws.record_of[s]];
                ws.tags[s] = {c.object, c.triangle, {c.vertex_index[0], c.vertex_index[1], c.vertex_index[2]}};
                ws.vertices[s] = {{c.v[0], c.v[1], c.v[2]}};
            }
        });
        slots = narrow::slotView(ws.tags, ws.vertices);
    }
    clock.lap(result.timings.gather_ms);
    return sweepAndTest(rv, range, *ascending ? nullptr : ws.record_of.data(), slots, options, executor, ws, std::move(result),
                        clock);
}

Result<NarrowResult> leanRecordPhase(std::span<const CandidateRecord> in_records, const TriangleSource& source,
                                     const NarrowOptions& options, Executor& executor, NarrowWorkspace& io_workspace) {
    narrow::StageClock clock;
    NarrowWorkspace::Impl& ws = io_workspace.impl();
    const std::size_t n = in_records.size();
    if (n > narrow::kMaxSweepSlots) return tooMany(n);
    const RecordView rv = viewOf(in_records);
    const auto check = [&](std::size_t i) -> std::optional<std::string> {
        const CandidateRecord& r = in_records[i];
        if (r.object >= source.objectCount()) {
            return " names an object the source does not have (" + std::to_string(source.objectCount()) + " objects)";
        }
        if (r.triangle >= source.triangleCount(r.object)) {
            return " is past the object's last triangle (" + std::to_string(source.triangleCount(r.object)) + " triangles)";
        }
        return std::nullopt;
    };
    BoxRange range{};
    Result<bool> ascending = validateAndRank(rv, check, executor, ws, range);
    if (!ascending) return ascending.error();
    NarrowResult result;
    result.stats.candidates = n;
    clock.lap(result.timings.validate_ms);

    // Global ids in slot order (ascending), then the gather.
    const std::uint32_t* record_of = *ascending ? nullptr : ws.record_of.data();
    ws.slot_ids.resize(n);
    executor.parallelFor(n, narrow::kValidateGrain, [&](std::size_t begin, std::size_t end) {
        for (std::size_t s = begin; s < end; ++s) {
            const CandidateRecord& r = in_records[record_of ? record_of[s] : s];
            ws.slot_ids[s] = source.triangleBase(r.object) + r.triangle;
        }
    });
    if (std::optional<Error> e = narrow::gatherSlots(source, ws.slot_ids, executor, ws.tags, ws.vertices, ws.table_keys,
                                                     ws.table_scratch, ws.world)) {
        return Error(e->code(), "runNarrowPhase: " + e->message());
    }
    clock.lap(result.timings.gather_ms);
    return sweepAndTest(rv, range, record_of, narrow::slotView(ws.tags, ws.vertices), options, executor, ws, std::move(result),
                        clock);
}

}  // namespace

Result<NarrowResult> runNarrowPhase(std::span<const CandidateRecord> in_records, const TriangleSource& source,
                                    const NarrowOptions& options, Executor& executor) {
    NarrowWorkspace workspace;
    return runNarrowPhase(in_records, source, options, executor, workspace);
}

namespace {

// The sweeps form their own pairs: none of them was decided before.
Result<NarrowResult> notDecided() {
    return Error(ErrorCode::InvalidArgument, "runNarrowPhase: NarrowOptions::pairs_decided applies to runPairNarrowPhase only");
}

}  // namespace

Result<NarrowResult> runNarrowPhase(std::span<const CandidateTriangle> in_candidates, const NarrowOptions& options,
                                    Executor& executor, NarrowWorkspace& io_workspace) {
    if (options.pairs_decided) return notDecided();
    return narrow::guardedCall("runNarrowPhase", executor, options.max_box_pairs, [&](Executor& guarded) {
        return triangleRecordPhase(in_candidates, options, guarded, io_workspace);
    });
}

Result<NarrowResult> runNarrowPhase(std::span<const CandidateRecord> in_records, const TriangleSource& source,
                                    const NarrowOptions& options, Executor& executor, NarrowWorkspace& io_workspace) {
    if (options.pairs_decided) return notDecided();
    return narrow::guardedCall("runNarrowPhase", executor, options.max_box_pairs, [&](Executor& guarded) {
        return leanRecordPhase(in_records, source, options, guarded, io_workspace);
    });
}

}  // namespace vkcollide
