#include <algorithm>
#include <atomic>
#include <bit>
#include <limits>
#include <optional>
#include <string>

#include "narrow/exact_stage.hpp"
#include "narrow/guarded_executor.hpp"
#include "narrow/workspace.hpp"
#include "narrow/neighbours.hpp"
#include "narrow/slots.hpp"
#include "vkcollide/narrow.hpp"
#include "vkcollide/thread_pool.hpp"

// The pair path (docs/narrow_phase.md):
//   1. every pair checked;
//   2. slots: the distinct triangles in id order, numbered through a marker per id (or,
//      when the ids span far more than the input, by sorting the pairs' ends);
//   3. each pair a key (lower slot, higher slot), the keys sorted and repeats dropped:
//      the distinct pairs in canonical order, since slots follow the global ids and
//      global ids follow (object, triangle);
//   4. each slot's indices and world vertices gathered from the TriangleSource;
//   5. pairing up, in parallel over the pairs: self-collision switch, neighbour rule;
//   6. the back half (exact_stage.hpp). Tests run in pair order, so the colliding pairs
//      come out sorted.
// Every step is a function of the set of distinct pairs, so the result does not depend on
// the input order, on repeats or on the thread count.

namespace vkcollide {
namespace {

using narrow::Buffer;
using narrow::keyOf;

constexpr std::size_t kPairGrain = 2048;
// Slots through one marker per id while ids span at most this many per input pair (plus
// a constant); beyond, through sorting the pairs' ends.
constexpr std::size_t kDenseIdsPerPair = 8;
constexpr std::size_t kDenseIdsFree = std::size_t{1} << 16;
constexpr std::size_t kPairUpGrain = 1024;
// Ends are numbered in 32 bits.
constexpr std::size_t kMaxPairs = (std::size_t{1} << 31) - 1;
// From this many input pairs on, the executor is told on entry that the tests will use
// several threads (Executor::prepare): a pool's workers, asleep since the last call (the
// GPU's 0.3-2 ms), wake during the checks, slots and gather instead of when the tests
// need them. Below, the tests take a few microseconds and waking costs more.
constexpr std::size_t kPrepareFrom = 256;

int bitsFor(std::uint64_t max_value) { return std::max(1, static_cast<int>(std::bit_width(max_value))); }

std::string pairName(std::size_t k, const CandidatePair& p) {
    return "runPairNarrowPhase: pair " + std::to_string(k) + " (" + std::to_string(p.a) + ", " + std::to_string(p.b) + ")";
}

}  // namespace

Result<NarrowResult> runPairNarrowPhase(std::span<const CandidatePair> in_pairs, const TriangleSource& source,
                                        const NarrowOptions& options, Executor& executor) {
    NarrowWorkspace workspace;
    return runPairNarrowPhase(in_pairs, source, options, executor, workspace);
}

namespace {

Result<NarrowResult> pairPhase(std::span<const CandidatePair> in_pairs, const TriangleSource& source, const NarrowOptions& options,
                               Executor& ex, NarrowWorkspace& io_workspace) {
    narrow::StageClock clock;
    NarrowWorkspace::Impl& ws = io_workspace.impl();
    const std::size_t input = in_pairs.size();
    if (input > kMaxPairs) {
        return Error(ErrorCode::InvalidArgument, "runPairNarrowPhase: " + std::to_string(input) + " pairs (at most " +
                                                     std::to_string(kMaxPairs) + ")");
    }
    if (input >= kPrepareFrom) {
        const unsigned threads = ex.threadCount();
        ex.prepare(static_cast<unsigned>(std::min<std::size_t>(threads, narrow::taskCount(input, narrow::testGrain(input, threads)))));
    }
    const std::uint32_t total = source.totalTriangles();
    const int id_bits = bitsFor(total == 0 ? 0 : total - 1);

    // Stage 1: check.
    Buffer<std::uint64_t>& keys = ws.pair_keys;
    keys.resize(input);
    std::vector<std::size_t> first_bad(narrow::taskCount(input, kPairGrain), input);
    ex.parallelFor(input, kPairGrain, [&](std::size_t begin, std::size_t end) {
        for (std::size_t k = begin; k < end; ++k) {
            const CandidatePair p = in_pairs[k];
            if (p.a >= total || p.b >= total || p.a == p.b) {
                first_bad[begin / kPairGrain] = k;
                return;
            }
        }
    });
    for (const std::size_t k : first_bad) {
        if (k == input) continue;
        const CandidatePair p = in_pairs[k];
        if (p.a < total && p.a == p.b) {
            const std::uint32_t object = narrow::objectOf(source, p.a);
            return Error(ErrorCode::InvalidArgument, pairName(k, p) + " pairs object " + std::to_string(object) +
                                                         " triangle " + std::to_string(p.a - source.triangleBase(object)) +
                                                         " with itself");
        }
        return Error(ErrorCode::InvalidArgument, pairName(k, p) + ": triangle id " + std::to_string(std::max(p.a, p.b)) +
                                                     " is not below the source's " + std::to_string(total) + " triangles");
    }
    // Stage 2: slots, the distinct triangles in id order. When ids span a range not much
    // larger than the input, a marker per id and a scan number them; otherwise sorting
    // the ends (id, 2 k + side) does.
    Buffer<std::uint32_t>& slot_of_end = ws.pair_slots;  // [2 k], [2 k + 1]: the slots of input pair k
    slot_of_end.resize(2 * input);
    std::size_t slot_count = 0;
    if (std::size_t{total} <= kDenseIdsPerPair * input + kDenseIdsFree) {
        Buffer<std::uint32_t>& slot_of = ws.responder_of;  // borrowed: free until the responses
        slot_of.resize(total);
        ex.parallelFor(total, kPairGrain, [&](std::size_t begin, std::size_t end) {
            std::fill(slot_of.begin() + begin, slot_of.begin() + end, 0u);
        });
        static_assert(std::atomic_ref<std::uint32_t>::required_alignment <= alignof(std::uint32_t));
        ex.parallelFor(input, kPairGrain, [&](std::size_t begin, std::size_t end) {
            for (std::size_t k = begin; k < end; ++k) {
                std::atomic_ref<std::uint32_t>(slot_of[in_pairs[k].a]).store(1, std::memory_order_relaxed);
                std::atomic_ref<std::uint32_t>(slot_of[in_pairs[k].b]).store(1, std::memory_order_relaxed);
            }
        });
        ws.slot_ids.resize(total);
        slot_count = narrow::compact(
            ex, total, [&](std::size_t g) { return slot_of[g] != 0; },
            [&](std::size_t out, std::size_t g) { ws.slot_ids[out] = static_cast<std::uint32_t>(g); });
        ws.slot_ids.resize(slot_count);
        narrow::exclusiveScan(ex, slot_of.data(), total);
        ex.parallelFor(input, kPairGrain, [&](std::size_t begin, std::size_t end) {
            for (std::size_t k = begin; k < end; ++k) {
                slot_of_end[2 * k] = slot_of[in_pairs[k].a];
                slot_of_end[2 * k + 1] = slot_of[in_pairs[k].b];
            }
        });
    } else {
        const int end_bits = bitsFor(2 * std::uint64_t{input});
        Buffer<std::uint64_t>& ends = ws.ends;
        ends.resize(2 * input);
        ex.parallelFor(input, kPairGrain, [&](std::size_t begin, std::size_t end) {
            for (std::size_t k = begin; k < end; ++k) {
                ends[2 * k] = (std::uint64_t{in_pairs[k].a} << end_bits) | (2 * k);
                ends[2 * k + 1] = (std::uint64_t{in_pairs[k].b} << end_bits) | (2 * k + 1);
            }
        });
        narrow::parallelSortKeys(ex, ends, ws.ends_scratch, id_bits + end_bits, end_bits);  // built in end order
        Buffer<std::uint32_t>& slot_begin = ws.responder_begin;  // borrowed: free until the responses
        slot_begin.resize(ends.size() + 1);
        slot_count = narrow::compact(
            ex, ends.size(), [&](std::size_t e) { return e == 0 || (ends[e] >> end_bits) != (ends[e - 1] >> end_bits); },
            [&](std::size_t out, std::size_t e) { slot_begin[out] = static_cast<std::uint32_t>(e); });
        slot_begin[slot_count] = static_cast<std::uint32_t>(ends.size());
        ws.slot_ids.resize(slot_count);
        const std::uint64_t end_mask = (std::uint64_t{1} << end_bits) - 1;
        ex.parallelFor(slot_count, kPairGrain, [&](std::size_t begin, std::size_t end) {
            for (std::size_t s = begin; s < end; ++s) {
                ws.slot_ids[s] = static_cast<std::uint32_t>(ends[slot_begin[s]] >> end_bits);
                for (std::size_t e = slot_begin[s]; e < slot_begin[s + 1]; ++e) {
                    slot_of_end[ends[e] & end_mask] = static_cast<std::uint32_t>(s);
                }
            }
        });
    }

    // Stage 3: the pairs as (lower slot, higher slot) keys, sorted, repeats dropped: the
    // distinct pairs in canonical order (slots follow the ids, ids follow (object, triangle)).
    const int slot_bits = bitsFor(slot_count == 0 ? 0 : slot_count - 1);
    ex.parallelFor(input, kPairGrain, [&](std::size_t begin, std::size_t end) {
        for (std::size_t k = begin; k < end; ++k) {
            const std::uint32_t sa = slot_of_end[2 * k], sb = slot_of_end[2 * k + 1];
            keys[k] = (std::uint64_t{std::min(sa, sb)} << slot_bits) | std::max(sa, sb);
        }
    });
    narrow::parallelSortKeys(ex, keys, ws.pair_scratch, 2 * slot_bits);
    Buffer<std::uint64_t>& distinct = ws.pair_scratch;
    distinct.resize(input);
    const std::size_t pairs = narrow::compact(
        ex, input, [&](std::size_t k) { return k == 0 || keys[k] != keys[k - 1]; },
        [&](std::size_t out, std::size_t k) { distinct[out] = keys[k]; });
    distinct.resize(pairs);
    keys.swap(distinct);  // keys: the distinct pairs, ascending
    const std::uint64_t slot_mask = (std::uint64_t{1} << slot_bits) - 1;

    NarrowResult result;
    result.stats.input_pairs = input;
    result.stats.candidates = slot_count;
    result.stats.potentially_colliding_triangles = slot_count;  // every one is in a pair
    result.stats.sap_pairs = pairs;
    if (pairs > options.max_box_pairs) throw narrow::BoxBudgetExceeded{};
    clock.lap(result.timings.validate_ms);

    // Stage 4: the slots' geometry.
    if (std::optional<Error> e =
            narrow::gatherSlots(source, ws.slot_ids, ex, ws.tags, ws.vertices, ws.table_keys, ws.table_scratch, ws.world)) {
        return Error(e->code(), "runPairNarrowPhase: " + e->message());
    }
    const narrow::SlotData slots = narrow::slotView(ws.tags, ws.vertices);
    clock.lap(result.timings.gather_ms);

    // Stage 5: pairing up.
    std::vector<narrow::PairTask>& tasks = ws.pair_tasks;
    tasks.resize(narrow::taskCount(pairs, kPairUpGrain));
    const bool filter_objects = static_cast<bool>(options.may_collide);
    ex.parallelFor(pairs, kPairUpGrain, [&](std::size_t begin, std::size_t end) {
        narrow::PairTask task = std::move(tasks[begin / kPairUpGrain]);  // see the sweep in narrow_phase.cpp
        task.tests.clear();
        task.object_pairs.clear();
        std::size_t filtered = 0, neighbours = 0;
        std::uint64_t last_object_pair = std::numeric_limits<std::uint64_t>::max();
        for (std::size_t q = begin; q < end; ++q) {
            const auto i = static_cast<std::uint32_t>(keys[q] >> slot_bits), j = static_cast<std::uint32_t>(keys[q] & slot_mask);
            const std::uint32_t object_i = slots.object[i], object_j = slots.object[j];
            if (object_i == object_j) {
                if (!options.selfCollides(object_i)) {
                    ++filtered;
                    continue;
                }
                const narrow::Index3& index_i = slots.vertex_index[i];
                const narrow::Index3& index_j = slots.vertex_index[j];
                if (narrow::shareIndex(index_i, index_j) || narrow::areNeighbours(index_i, slots.v[i], index_j, slots.v[j])) {
                    ++neighbours;
                    continue;
                }
            } else if (filter_objects) {
                const std::uint64_t object_pair = keyOf(object_i, object_j);  // i < j: object_i <= object_j
                if (object_pair != last_object_pair) task.object_pairs.push_back(object_pair);
                last_object_pair = object_pair;
            }
            task.tests.push_back({i, j});
        }
        task.sap_pairs = end - begin;
        task.filtered_pairs = filtered;
        task.neighbour_pairs = neighbours;
        std::sort(task.object_pairs.begin(), task.object_pairs.end());
        task.object_pairs.erase(std::unique(task.object_pairs.begin(), task.object_pairs.end()), task.object_pairs.end());
        tasks[begin / kPairUpGrain] = std::move(task);
    });
    for (const narrow::PairTask& task : tasks) {
        result.stats.filtered_pairs += task.filtered_pairs;
        result.stats.neighbour_pairs += task.neighbour_pairs;
    }
    clock.lap(result.timings.sweep_ms);

    narrow::testAndRespond(tasks, slots, slot_count, true, options, ex, ws, result, clock);
    return result;
}

}  // namespace

Result<NarrowResult> runPairNarrowPhase(std::span<const CandidatePair> in_pairs, const TriangleSource& source,
                                        const NarrowOptions& options, Executor& executor, NarrowWorkspace& io_workspace) {
    return narrow::guardedCall("runPairNarrowPhase", executor, options.max_box_pairs, [&](Executor& guarded) {
        return pairPhase(in_pairs, source, options, guarded, io_workspace);
    });
}

}  // namespace vkcollide
