#include <algorithm>
#include <bit>
#include <limits>
#include <optional>
#include <string>

#include "narrow/exact_stage.hpp"
#include "narrow/neighbours.hpp"
#include "narrow/slots.hpp"
#include "vkcollide/narrow.hpp"
#include "vkcollide/thread_pool.hpp"

// The pair path (docs/narrow_phase.md):
//   1. every pair checked and made a key (lower id, higher id), the keys radix sorted and
//      repeats dropped: the distinct pairs in canonical order, since global ids follow
//      (object, triangle);
//   2. slots: the distinct triangles, found by sorting the pairs' ends (id, end) and
//      numbering the ids; each pair's two slots come from the same sort;
//   3. each slot's indices and world vertices gathered from the TriangleSource;
//   4. pairing up, in parallel over the pairs: self-collision switch, neighbour rule;
//   5. the back half (exact_stage.hpp). Tests run in pair order, so the colliding pairs
//      come out sorted.
// Every step is a function of the set of distinct pairs, so the result does not depend on
// the input order, on repeats or on the thread count.

namespace vkcollide {
namespace {

using narrow::Buffer;
using narrow::keyOf;

constexpr std::size_t kPairGrain = 16384;
constexpr std::size_t kPairUpGrain = 4096;
// Ends are numbered in 32 bits.
constexpr std::size_t kMaxPairs = (std::size_t{1} << 31) - 1;

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

Result<NarrowResult> runPairNarrowPhase(std::span<const CandidatePair> in_pairs, const TriangleSource& source,
                                        const NarrowOptions& options, Executor& ex, NarrowWorkspace& io_workspace) {
    narrow::StageClock clock;
    NarrowWorkspace::Impl& ws = io_workspace.impl();
    const std::size_t input = in_pairs.size();
    if (input > kMaxPairs) {
        return Error(ErrorCode::InvalidArgument, "runPairNarrowPhase: " + std::to_string(input) + " pairs (at most " +
                                                     std::to_string(kMaxPairs) + ")");
    }
    const std::uint32_t total = source.totalTriangles();
    const int id_bits = bitsFor(total == 0 ? 0 : total - 1);

    // Stage 1: check, key, sort, drop repeats.
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
            keys[k] = (std::uint64_t{std::min(p.a, p.b)} << id_bits) | std::max(p.a, p.b);
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
    narrow::parallelRadixSort(ex, keys, ws.pair_scratch, 2 * id_bits);
    Buffer<std::uint64_t>& distinct = ws.pair_scratch;
    distinct.resize(input);
    const std::size_t pairs = narrow::compact(
        ex, input, [&](std::size_t k) { return k == 0 || keys[k] != keys[k - 1]; },
        [&](std::size_t out, std::size_t k) { distinct[out] = keys[k]; });
    distinct.resize(pairs);
    keys.swap(distinct);  // keys: the distinct pairs, ascending

    // Stage 2: slots. Sort the ends (id, 2 q + side) and number the distinct ids.
    const int end_bits = bitsFor(2 * std::uint64_t{pairs});
    const std::uint64_t low_mask = (std::uint64_t{1} << id_bits) - 1;
    Buffer<std::uint64_t>& ends = ws.ends;
    ends.resize(2 * pairs);
    ex.parallelFor(pairs, kPairGrain, [&](std::size_t begin, std::size_t end) {
        for (std::size_t q = begin; q < end; ++q) {
            ends[2 * q] = ((keys[q] >> id_bits) << end_bits) | (2 * q);
            ends[2 * q + 1] = ((keys[q] & low_mask) << end_bits) | (2 * q + 1);
        }
    });
    narrow::parallelRadixSort(ex, ends, ws.ends_scratch, id_bits + end_bits);
    Buffer<std::uint32_t>& slot_begin = ws.responder_begin;  // borrowed: free until the responses
    slot_begin.resize(ends.size() + 1);
    const std::size_t slot_count = narrow::compact(
        ex, ends.size(), [&](std::size_t e) { return e == 0 || (ends[e] >> end_bits) != (ends[e - 1] >> end_bits); },
        [&](std::size_t out, std::size_t e) { slot_begin[out] = static_cast<std::uint32_t>(e); });
    slot_begin[slot_count] = static_cast<std::uint32_t>(ends.size());
    ws.slot_ids.resize(slot_count);
    Buffer<std::uint32_t>& pair_slots = ws.pair_slots;  // [2 q], [2 q + 1]: the slots of distinct pair q
    pair_slots.resize(2 * pairs);
    const std::uint64_t end_mask = (std::uint64_t{1} << end_bits) - 1;
    ex.parallelFor(slot_count, kPairGrain, [&](std::size_t begin, std::size_t end) {
        for (std::size_t s = begin; s < end; ++s) {
            ws.slot_ids[s] = static_cast<std::uint32_t>(ends[slot_begin[s]] >> end_bits);
            for (std::size_t e = slot_begin[s]; e < slot_begin[s + 1]; ++e) {
                pair_slots[ends[e] & end_mask] = static_cast<std::uint32_t>(s);
            }
        }
    });
    NarrowResult result;
    result.stats.input_pairs = input;
    result.stats.candidates = slot_count;
    result.stats.potentially_colliding_triangles = slot_count;  // every one is in a pair
    result.stats.sap_pairs = pairs;
    clock.lap(result.timings.validate_ms);

    // Stage 3: the slots' geometry.
    if (std::optional<Error> e =
            narrow::gatherSlots(source, ws.slot_ids, ex, ws.tags, ws.vertices, ws.table_keys, ws.table_scratch)) {
        return Error(e->code(), "runPairNarrowPhase: " + e->message());
    }
    const narrow::SlotData slots = narrow::slotView(ws.tags, ws.vertices);
    clock.lap(result.timings.gather_ms);

    // Stage 4: pairing up.
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
            const std::uint32_t i = pair_slots[2 * q], j = pair_slots[2 * q + 1];
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

}  // namespace vkcollide
