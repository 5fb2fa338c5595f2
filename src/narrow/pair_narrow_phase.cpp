#include <algorithm>
#include <limits>
#include <optional>
#include <string>

#include "common/config.h"
#include "narrow/calling_thread_executor.hpp"
#include "narrow/exact_stage.hpp"
#include "narrow/guarded_executor.hpp"
#include "narrow/workspace.hpp"
#include "narrow/neighbours.hpp"
#include "narrow/pair_keys.hpp"
#include "narrow/pair_narrow_phase.hpp"
#include "narrow/slots.hpp"
#include "vkcollide/narrow.hpp"
#include "vkcollide/thread_pool.hpp"

// The pair path (docs/narrow_phase.md):
//   1-3. (pair_keys.hpp) every pair checked; slots: the distinct triangles in id order;
//      each pair a key (lower slot, higher slot), the keys sorted and repeats dropped:
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

// Ends are numbered in 32 bits.
constexpr std::size_t kMaxPairs = (std::size_t{1} << 31) - 1;

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
                               Executor& ex, NarrowWorkspace& io_workspace, std::vector<TrianglePair>& pair_memory,
                               std::vector<TriangleResponse>& response_memory) {
    narrow::StageClock clock;
    NarrowWorkspace::Impl& ws = io_workspace.impl();
    const std::size_t input = in_pairs.size();
    if (input > kMaxPairs) {
        return Error(ErrorCode::InvalidArgument, "runPairNarrowPhase: " + std::to_string(input) + " pairs (at most " +
                                                     std::to_string(kMaxPairs) + ")");
    }
    if (const unsigned wake = narrow::threadsToWake(input, ex.threadCount(), options.pairs_decided)) ex.prepare(wake);
    const std::uint32_t total = source.totalTriangles();

    // Stages 1 to 3 (pair_keys.hpp): checks, slots, the distinct pairs as sorted keys.
    narrow::PairKeys front;
    if (const std::optional<std::size_t> bad = narrow::buildPairKeys(ex, in_pairs, total, narrow::PairKeysForm::Automatic, ws, front)) {
        const std::size_t k = *bad;
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
    const std::size_t slot_count = front.slot_count, pairs = front.pairs;
    const int slot_bits = front.slot_bits;
    const Buffer<std::uint64_t>& keys = ws.pair_keys;  // the distinct pairs, ascending
    const std::uint64_t slot_mask = (std::uint64_t{1} << slot_bits) - 1;

    NarrowResult result;
    result.pairs = std::move(pair_memory);  // their memory only: sized where they are written
    result.pairs.clear();
    result.responses = std::move(response_memory);
    result.responses.clear();
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
    tasks.resize(narrow::taskCount(pairs, narrow::kPairUpGrain));
    const bool filter_objects = static_cast<bool>(options.may_collide);
    ex.parallelFor(pairs, narrow::kPairUpGrain, [&](std::size_t begin, std::size_t end) {
        narrow::PairTask task = std::move(tasks[begin / narrow::kPairUpGrain]);  // see the sweep in narrow_phase.cpp
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
        tasks[begin / narrow::kPairUpGrain] = std::move(task);
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
    return narrow::runPairNarrowPhaseInto(in_pairs, source, options, executor, io_workspace, {}, {});
}

Result<NarrowResult> narrow::runPairNarrowPhaseInto(std::span<const CandidatePair> in_pairs, const TriangleSource& source,
                                                    const NarrowOptions& options, Executor& executor, NarrowWorkspace& io_workspace,
                                                    std::vector<TrianglePair> pair_memory,
                                                    std::vector<TriangleResponse> response_memory) {
    // Few decided pairs: every loop on this thread (results never depend on the executor).
    narrow::CallingThreadExecutor calling_thread;
    Executor& chosen = narrow::runsOnCallingThread(in_pairs.size(), options.pairs_decided) ? calling_thread : executor;
    return narrow::guardedCall("runPairNarrowPhase", chosen, options.max_box_pairs, [&](Executor& guarded) {
        return pairPhase(in_pairs, source, options, guarded, io_workspace, pair_memory, response_memory);
    });
}

}  // namespace vkcollide
