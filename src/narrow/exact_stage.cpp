#include "narrow/exact_stage.hpp"

#include <algorithm>
#include <atomic>
#include <limits>

#include "common/config.h"
#include "narrow/radix_sort.hpp"
#include "narrow/responses.hpp"
#include "narrow/triangle_intersection.hpp"
#include "narrow/workspace.hpp"

namespace vkcollide {

NarrowWorkspace::NarrowWorkspace() : impl_(std::make_unique<Impl>()) {}
NarrowWorkspace::~NarrowWorkspace() = default;
NarrowWorkspace::NarrowWorkspace(NarrowWorkspace&&) noexcept = default;
NarrowWorkspace& NarrowWorkspace::operator=(NarrowWorkspace&&) noexcept = default;

NarrowWorkspace::Impl& NarrowWorkspace::impl() {
    if (!impl_) impl_ = std::make_unique<Impl>();
    return *impl_;
}

namespace narrow {

std::size_t testGrain(std::size_t tests, unsigned threads) { return grainFor(tests, threads, 4, kMinTestGrain, kMaxTestGrain); }

bool runsOnCallingThread(std::size_t input_pairs, bool decided) { return decided && input_pairs < kSerialDecidedBelow; }

unsigned threadsToWake(std::size_t input_pairs, unsigned threads, bool decided) {
    if (input_pairs < kPrepareFrom || runsOnCallingThread(input_pairs, decided)) return 0;
    return static_cast<unsigned>(std::min<std::size_t>(threads, taskCount(input_pairs, testGrain(input_pairs, threads))));
}

void testAndRespond(std::vector<PairTask>& tasks, const SlotData& slots, std::size_t slot_count, bool tests_in_order,
                    const NarrowOptions& options, Executor& ex, NarrowWorkspace::Impl& ws, NarrowResult& out,
                    StageClock& clock) {
    NarrowStats& stats = out.stats;
    NarrowTimings& timings = out.timings;
    std::vector<std::size_t>& test_begin = ws.test_begin;  // tests of task t: [test_begin[t], test_begin[t+1])
    test_begin.assign(tasks.size() + 1, 0);
    for (std::size_t t = 0; t < tasks.size(); ++t) test_begin[t + 1] = test_begin[t] + tasks[t].tests.size();

    // Stage 3: the object-pair filter, once per distinct pair of objects with candidate
    // pairs, in ascending order, on this thread.
    const bool filter_objects = static_cast<bool>(options.may_collide);
    std::vector<std::uint64_t> object_pairs;
    std::vector<char> object_pair_allowed;
    if (filter_objects) {
        for (const PairTask& task : tasks) object_pairs.insert(object_pairs.end(), task.object_pairs.begin(), task.object_pairs.end());
        std::sort(object_pairs.begin(), object_pairs.end());
        object_pairs.erase(std::unique(object_pairs.begin(), object_pairs.end()), object_pairs.end());
        object_pair_allowed.resize(object_pairs.size());
        for (std::size_t k = 0; k < object_pairs.size(); ++k) {
            const auto a = static_cast<std::uint32_t>(object_pairs[k] >> 32), b = static_cast<std::uint32_t>(object_pairs[k]);
            object_pair_allowed[k] = options.may_collide(a, b) ? 1 : 0;
        }
    }
    clock.lap(timings.filter_ms);

    // Stage 4: exact tests over all tasks' pairs, as one index range. Hits are stored while
    // fewer than max_pairs are (each task decides when it starts, so at most a task's
    // tests more per thread) and always counted; past the budget the first max_pairs hits
    // in test order are kept (below), whatever the scheduling was.
    const std::size_t total_tests = test_begin.back();
    const std::size_t test_grain = testGrain(total_tests, ex.threadCount());
    const std::size_t test_tasks = taskCount(total_tests, test_grain);
    std::vector<std::vector<std::uint64_t>>& hits = ws.hits;  // (lower slot, higher slot) per hit
    hits.resize(test_tasks);
    std::vector<std::size_t>& object_filtered = ws.object_filtered;
    object_filtered.assign(test_tasks, 0);
    std::vector<std::size_t>& found_per_task = ws.found;  // hits per task, stored or not
    found_per_task.assign(test_tasks, 0);
    std::vector<std::uint8_t>& kept = ws.kept;  // 1: the task's hits are all in hits[task]
    kept.assign(test_tasks, 0);
    std::atomic<std::size_t> stored{0};
    const std::size_t budget = options.max_pairs;
    const bool decided = options.pairs_decided;
    const auto testTask = [&](std::size_t begin, std::size_t end, bool keep) {
        const std::size_t task_index = begin / test_grain;
        // Built in a local (keeping the capacity of the last call) and moved back at the
        // end: tasks sit next to each other in memory, and growing vectors in place would
        // share cache lines between threads.
        std::vector<std::uint64_t> found = std::move(hits[task_index]);
        found.clear();
        std::size_t filtered = 0, hit_total = 0;
        std::size_t source = static_cast<std::size_t>(std::upper_bound(test_begin.begin(), test_begin.end(), begin) -
                                                      test_begin.begin()) - 1;
        std::uint64_t cached_pair = std::numeric_limits<std::uint64_t>::max();
        bool cached_allowed = true;
        for (std::size_t k = begin; k < end; ++k) {
            while (test_begin[source + 1] <= k) ++source;
            const IndexPair p = tasks[source].tests[k - test_begin[source]];
            if (filter_objects) {
                const std::uint32_t a = slots.object[p.i], b = slots.object[p.j];
                if (a != b) {
                    const std::uint64_t object_pair = keyOf(std::min(a, b), std::max(a, b));
                    if (object_pair != cached_pair) {
                        cached_pair = object_pair;
                        const auto it = std::lower_bound(object_pairs.begin(), object_pairs.end(), object_pair);
                        cached_allowed = object_pair_allowed[static_cast<std::size_t>(it - object_pairs.begin())] != 0;
                    }
                    if (!cached_allowed) {
                        ++filtered;
                        continue;
                    }
                }
            }
            if (decided || trianglesIntersect(slots.v[p.i], slots.v[p.j])) {
                ++hit_total;
                if (keep) found.push_back(keyOf(p.i, p.j));
            }
        }
        hits[task_index] = std::move(found);
        object_filtered[task_index] = filtered;
        found_per_task[task_index] = hit_total;
        kept[task_index] = keep ? 1 : 0;
    };
    ex.parallelFor(total_tests, test_grain, [&](std::size_t begin, std::size_t end) {
        const bool keep = stored.load(std::memory_order_relaxed) < budget;
        testTask(begin, end, keep);
        if (keep) stored.fetch_add(hits[begin / test_grain].size(), std::memory_order_relaxed);
    });
    std::size_t filtered_late = 0, hit_count = 0, found_count = 0;
    for (std::size_t t = 0; t < test_tasks; ++t) {
        filtered_late += object_filtered[t];
        found_count += found_per_task[t];
    }
    if (found_count > budget) {
        // The first `budget` hits in test order: whole tasks, then part of the last one. A
        // task inside that prefix whose hits were not stored is tested again.
        std::size_t room = budget;
        for (std::size_t t = 0; t < test_tasks; ++t) {
            if (room == 0) {
                hits[t].clear();
                continue;
            }
            if (!kept[t] && found_per_task[t] > 0) testTask(t * test_grain, std::min(total_tests, (t + 1) * test_grain), true);
            if (hits[t].size() > room) hits[t].resize(room);
            room -= hits[t].size();
        }
        out.pairs_left_out = found_count - budget;
    }
    for (std::size_t t = 0; t < test_tasks; ++t) hit_count += hits[t].size();
    stats.filtered_pairs += filtered_late;
    stats.triangle_tests = decided ? 0 : total_tests - filtered_late;
    clock.lap(timings.test_ms);

    // Stage 5: canonical order. Slots follow (object, triangle), so sorting the
    // (lower slot, higher slot) keys sorts the pairs.
    Buffer<std::uint64_t>& colliding = ws.colliding;
    colliding.resize(hit_count);
    resizeFresh(out.pairs, hit_count, ex);  // fresh pages touched in parallel
    // Plain pointers and copies: the strided slot views read through std::byte, which may
    // alias anything, so members reached through references would be reloaded per pair.
    // The keys' address is passed in, not captured: the radix sort swaps `colliding` with
    // its scratch buffer once per pass, so after an odd number of passes the sorted keys
    // live in what was the scratch.
    const auto fill_from = [pairs_out = out.pairs.data(), object = slots.object, triangle = slots.triangle](const std::uint64_t* hit_keys,
                                                                                                            std::size_t k) {
        const auto i = static_cast<std::uint32_t>(hit_keys[k] >> 32), j = static_cast<std::uint32_t>(hit_keys[k]);
        pairs_out[k] = {object[i], triangle[i], object[j], triangle[j]};
    };
    {
        // Each task's hits copied to their place (and, already in order, turned into pairs
        // on the way): in parallel only when the copy outweighs a fork-join.
        std::vector<std::size_t>& at = ws.hit_begin;
        at.assign(hits.size() + 1, 0);
        for (std::size_t t = 0; t < hits.size(); ++t) at[t + 1] = at[t] + hits[t].size();
        const auto place = [&, in_order = tests_in_order, keys = colliding.data()](std::size_t first, std::size_t last) {
            for (std::size_t t = first; t < last; ++t) {
                std::copy(hits[t].begin(), hits[t].end(), colliding.begin() + at[t]);
                if (!in_order) continue;
                const std::size_t end = at[t + 1];
                for (std::size_t k = at[t]; k < end; ++k) fill_from(keys, k);
            }
        };
        if (hit_count < kSerialBelow) {
            place(0, hits.size());
        } else {
            ex.parallelFor(hits.size(), 16, place);
        }
    }
    if (!tests_in_order) {
        parallelRadixSort(ex, colliding, ws.colliding_scratch, 32 + keyBits(slot_count));
        ex.parallelFor(hit_count, kResultGrain, [&, keys = colliding.data()](std::size_t begin, std::size_t end) {
            for (std::size_t k = begin; k < end; ++k) fill_from(keys, k);
        });
    }
    stats.positive_tests = hit_count + out.pairs_left_out;
    clock.lap(timings.sort_ms);

    // Stage 6: responses.
    respond(colliding, slots, slot_count, ResponseForm::Automatic, ex, ws, out);
    clock.lap(timings.response_ms);
    timings.total_ms = clock.totalMs();
}

}  // namespace narrow
}  // namespace vkcollide
