#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <new>
#include <optional>
#include <stdexcept>
#include <string>

#include "narrow/neighbours.hpp"
#include "narrow/radix_sort.hpp"
#include "narrow/sweep_and_prune.hpp"
#include "narrow/triangle_intersection.hpp"
#include "vkcollide/narrow.hpp"
#include "vkcollide/thread_pool.hpp"

// Stages (docs/narrow_phase.md has the measurements behind these choices):
//   1. validate and rank: every candidate checked, its (object, triangle) key radix sorted
//      once (unless already in order, as the GPU writes them); a key's rank orders pairs and responses canonically without comparing
//      candidates again, and equal neighbours in the sorted keys are the duplicates.
//   2. sweep and prune per grid cell (sweep_and_prune.hpp), in parallel; the same tasks apply
//      the self-collision switch and the neighbour rule.
//   3. the object-pair filter, called once per distinct object pair on this thread.
//   4. exact tests in parallel; each task keeps its hits as (rank, rank) keys.
//   5. the hit keys radix sorted: the canonical pair order.
//   6. responses, summed in that order.
// Every parallel stage writes per-task state that is combined in a fixed order or sorted,
// so the result does not depend on the thread count or on how tasks were scheduled.

#if defined(__GNUC__) || defined(__clang__)
#define VKCOLLIDE_ALWAYS_INLINE __attribute__((always_inline))
#else
#define VKCOLLIDE_ALWAYS_INLINE
#endif

namespace vkcollide {
namespace {

// Candidates per validation task.
constexpr std::size_t kValidateGrain = 8192;
// Sweep positions per task: about kTasksPerThread tasks per thread, within these bounds.
constexpr std::size_t kMinSweepGrain = 64;
constexpr std::size_t kMaxSweepGrain = 8192;
constexpr std::size_t kTasksPerThread = 8;
// Exact tests per task: large enough to amortise the hand-out, small enough to balance
// (a test costs 0.1 to 1 microseconds, more when the exact fallback runs).
constexpr std::size_t kTestGrain = 256;
// Box pairs a sweep task counts between looks at NarrowOptions::max_box_pairs (one atomic
// add per stride: nothing next to the sweep's nanoseconds per pair).
constexpr std::size_t kBoxBudgetStride = std::size_t{1} << 16;
// Thrown by a sweep visitor past the box-pair budget, caught by its task: unwinds the sweep.
struct BoxBudgetExceeded {};

using Clock = std::chrono::steady_clock;

double msBetween(Clock::time_point from, Clock::time_point to) {
    return std::chrono::duration<double, std::milli>(to - from).count();
}

std::string describe(const CandidateTriangle& c) {
    return "object " + std::to_string(c.object) + " triangle " + std::to_string(c.triangle);
}

bool isFinite(const Float3& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); }

bool isValid(const CandidateTriangle& c) {
    return isFinite(c.v[0]) && isFinite(c.v[1]) && isFinite(c.v[2]) && std::isfinite(c.box[0]) &&
           std::isfinite(c.box[1]) && std::isfinite(c.box[2]) && std::isfinite(c.box[3]) && std::isfinite(c.zmin) &&
           std::isfinite(c.zmax) && c.box[0] <= c.box[2] && c.box[1] <= c.box[3] && c.zmin <= c.zmax;
}

// The error for a candidate that failed isValid, naming the first broken rule.
Error invalidCandidate(const CandidateTriangle& c) {
    for (const Float3& p : c.v) {
        if (!isFinite(p)) return Error(ErrorCode::InvalidArgument, "runNarrowPhase: " + describe(c) + " has a non-finite vertex");
    }
    const bool finite_box = std::isfinite(c.box[0]) && std::isfinite(c.box[1]) && std::isfinite(c.box[2]) &&
                            std::isfinite(c.box[3]) && std::isfinite(c.zmin) && std::isfinite(c.zmax);
    if (!finite_box) return Error(ErrorCode::InvalidArgument, "runNarrowPhase: " + describe(c) + " has a non-finite box or depth");
    return Error(ErrorCode::InvalidArgument,
                 "runNarrowPhase: " + describe(c) + " has an empty box (needs x0 <= x1, y0 <= y1, zmin <= zmax)");
}

std::uint64_t keyOf(std::uint32_t high, std::uint32_t low) { return (std::uint64_t{high} << 32) | low; }

struct Vec3d {
    double x = 0, y = 0, z = 0;
};

Vec3d unitNormal(const CandidateTriangle& c) {
    const double ux = double(c.v[1].x) - c.v[0].x, uy = double(c.v[1].y) - c.v[0].y, uz = double(c.v[1].z) - c.v[0].z;
    const double vx = double(c.v[2].x) - c.v[0].x, vy = double(c.v[2].y) - c.v[0].y, vz = double(c.v[2].z) - c.v[0].z;
    const Vec3d n{uy * vz - uz * vy, uz * vx - ux * vz, ux * vy - uy * vx};
    const double length = std::sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
    if (!(length > 0) || !std::isfinite(length)) return {};  // zero-area (or overflowing) triangle: no normal
    return {n.x / length, n.y / length, n.z / length};
}

// What one sweep task found.
struct SweepTask {
    std::vector<narrow::IndexPair> tests;     // pairs to test (object filter still to apply)
    std::vector<std::uint64_t> object_pairs;  // distinct (object_a, object_b), a < b, when may_collide is set
    std::size_t sap_pairs = 0, filtered_pairs = 0, neighbour_pairs = 0;
};

}  // namespace

// Everything here is overwritten (or cleared) before it is read in a call; only the
// capacity carries over.
struct NarrowWorkspace::Impl {
    narrow::CellSweep sweep;
    std::vector<SweepTask> sweep_tasks;
    std::vector<std::uint8_t> in_pair;  // per candidate: in a pair whose boxes overlap (std::atomic_ref)
    std::vector<std::size_t> test_begin, object_filtered;
    std::vector<std::vector<std::uint64_t>> hits;
    std::vector<std::uint64_t> colliding, responders;
    std::vector<std::uint32_t> slot;
    std::vector<narrow::KeyIndex> keys;
    std::vector<std::uint32_t> rank_of;
    std::vector<std::size_t> found;  // per test task: hits found (max_pairs)
    std::vector<std::uint8_t> kept;  // per test task: its hits are stored
};

NarrowWorkspace::NarrowWorkspace() : impl_(std::make_unique<Impl>()) {}
NarrowWorkspace::~NarrowWorkspace() = default;
NarrowWorkspace::NarrowWorkspace(NarrowWorkspace&&) noexcept = default;
NarrowWorkspace& NarrowWorkspace::operator=(NarrowWorkspace&&) noexcept = default;

NarrowWorkspace::Impl& NarrowWorkspace::impl() {
    if (!impl_) impl_ = std::make_unique<Impl>();
    return *impl_;
}

Result<NarrowResult> runNarrowPhase(std::span<const CandidateTriangle> in_candidates, const NarrowOptions& options,
                                    ThreadPool& pool) {
    NarrowWorkspace workspace;
    return runNarrowPhase(in_candidates, options, pool, workspace);
}

namespace {

Result<NarrowResult> narrowPhase(std::span<const CandidateTriangle> in_candidates, const NarrowOptions& options,
                                 ThreadPool& pool, NarrowWorkspace& io_workspace) {
    NarrowWorkspace::Impl& ws = io_workspace.impl();
    // Parallel bodies must not throw (ThreadPool): one that runs out of memory sets this
    // and stops; the call then returns OutOfMemory.
    std::atomic<bool> out_of_memory{false};
    const Error oom(ErrorCode::OutOfMemory, "runNarrowPhase: host memory ran out");
    std::atomic<bool> over_budget{false};
    std::atomic<std::size_t> box_pairs_seen{0};  // in whole strides, by the sweep tasks
    const Clock::time_point t_start = Clock::now();
    const std::size_t n = in_candidates.size();
    if (n > std::numeric_limits<std::uint32_t>::max()) {
        return Error(ErrorCode::InvalidArgument, "runNarrowPhase: more than 2^32-1 candidates");
    }

    // Stage 1: validate (in parallel; the error names the first bad candidate, as a serial
    // check would) and rank the keys.
    const auto keyAt = [&](std::size_t i) { return keyOf(in_candidates[i].object, in_candidates[i].triangle); };
    bool keys_ascending = true;
    {
        const std::size_t tasks = n == 0 ? 0 : (n - 1) / kValidateGrain + 1;
        std::vector<std::size_t> first_bad(tasks, n);
        std::vector<char> ascending(tasks, 1);
        pool.parallelFor(n, kValidateGrain, [&](std::size_t begin, std::size_t end) {
            std::size_t bad = n;
            bool task_ascending = true;
            std::uint64_t previous = keyAt(begin);
            for (std::size_t i = begin; i < end; ++i) {
                if (bad == n && !isValid(in_candidates[i])) bad = i;
                const std::uint64_t key = keyAt(i);
                task_ascending = task_ascending && (i == begin || previous < key);
                previous = key;
            }
            first_bad[begin / kValidateGrain] = bad;
            ascending[begin / kValidateGrain] = task_ascending ? 1 : 0;
        });
        const auto bad = std::min_element(first_bad.begin(), first_bad.end());
        if (bad != first_bad.end() && *bad < n) return invalidCandidate(in_candidates[*bad]);
        for (std::size_t t = 0; t < tasks; ++t) {
            keys_ascending = keys_ascending && ascending[t] &&
                             (t == 0 || keyAt(t * kValidateGrain - 1) < keyAt(t * kValidateGrain));
        }
    }
    // The GPU writes its records in (object, triangle) order: then the keys are already
    // sorted and unique, and a candidate's rank is its index. Otherwise sort, find
    // duplicates, rank.
    std::vector<narrow::KeyIndex>& keys = ws.keys;     // sorted; unused when the keys are ascending
    std::vector<std::uint32_t>& rank_of = ws.rank_of;  // candidate -> rank; unused when the keys are ascending
    if (!keys_ascending) {
        keys.resize(n);
        for (std::size_t i = 0; i < n; ++i) keys[i] = {keyAt(i), static_cast<std::uint32_t>(i)};
        narrow::radixSort(keys);
        for (std::size_t r = 1; r < n; ++r) {
            if (keys[r].key == keys[r - 1].key) {
                return Error(ErrorCode::InvalidArgument, "runNarrowPhase: object " + std::to_string(keys[r].key >> 32) +
                                                             " triangle " + std::to_string(keys[r].key & 0xffffffffu) +
                                                             " appears more than once");
            }
        }
        rank_of.resize(n);
        for (std::size_t r = 0; r < n; ++r) rank_of[keys[r].index] = static_cast<std::uint32_t>(r);
    }
    const auto rankOf = [&](std::uint32_t i) { return keys_ascending ? i : rank_of[i]; };
    const auto candidateOfRank = [&](std::uint64_t r) -> const CandidateTriangle& {
        const auto rank = static_cast<std::uint32_t>(r);
        return in_candidates[keys_ascending ? rank : keys[rank].index];
    };

    NarrowResult result;
    NarrowStats& stats = result.stats;
    NarrowTimings& timings = result.timings;
    stats.candidates = n;
    Clock::time_point t_mark = Clock::now();
    timings.validate_ms = msBetween(t_start, t_mark);
    const auto lap = [&](double& out_ms) {
        const Clock::time_point now = Clock::now();
        out_ms = msBetween(t_mark, now);
        t_mark = now;
    };

    // Stage 2: sweep and prune, self-collision switch, neighbour rule.
    narrow::CellSweep& sweep = ws.sweep;
    sweep.build(in_candidates, &pool);
    const std::size_t entries = sweep.entryCount();
    const std::size_t sweep_grain =
        std::clamp<std::size_t>(entries / (std::size_t{pool.threadCount()} * kTasksPerThread), kMinSweepGrain, kMaxSweepGrain);
    std::vector<SweepTask>& sweep_tasks = ws.sweep_tasks;
    sweep_tasks.resize(entries == 0 ? 0 : (entries - 1) / sweep_grain + 1);
    std::vector<std::uint8_t>& in_pair = ws.in_pair;
    in_pair.assign(n, 0);
    static_assert(std::atomic_ref<std::uint8_t>::required_alignment == 1);
    const bool filter_objects = static_cast<bool>(options.may_collide);
    // The self-collision switch, when it is the same for every object.
    const bool uniform_self = options.self_collision.empty();
    const bool self_default = options.default_self_collision;
    pool.parallelFor(entries, sweep_grain, [&](std::size_t begin, std::size_t end) {
      try {
        // Moved into a local (keeping the capacity of the last call) and back at the end:
        // tasks sit next to each other in memory, and growing vectors in place would share
        // cache lines between threads.
        SweepTask task = std::move(sweep_tasks[begin / sweep_grain]);
        task.tests.clear();
        task.object_pairs.clear();
        std::size_t sap_pairs = 0, filtered_pairs = 0, neighbour_pairs = 0;  // in registers, not in `task`
        std::size_t budget_mark = kBoxBudgetStride;  // sap_pairs at the next look at the budget
        std::uint64_t last_object_pair = std::numeric_limits<std::uint64_t>::max();
        // Runs for every reported pair, most of them neighbours: inlined into the sweep.
        sweep.sweepRange(begin, end, [&](std::uint32_t i, std::uint32_t j, const narrow::CandidateTag& a,
                                         const narrow::CandidateTag& b) VKCOLLIDE_ALWAYS_INLINE {
            ++sap_pairs;
            // The box-pair budget, every kBoxBudgetStride pairs: past it, stop this task
            // (BoxBudgetExceeded unwinds the sweep) and, at its next look, every other one.
            if (sap_pairs == budget_mark) {
                budget_mark += kBoxBudgetStride;
                if (box_pairs_seen.fetch_add(kBoxBudgetStride, std::memory_order_relaxed) + kBoxBudgetStride > options.max_box_pairs)
                    throw BoxBudgetExceeded{};
            }
            // Store only when not set yet: most pairs find both flags set, and reading keeps
            // the cache line shared instead of bouncing it between threads.
            for (const std::uint32_t k : {i, j}) {
                const std::atomic_ref<std::uint8_t> flag(in_pair[k]);
                if (!flag.load(std::memory_order_relaxed)) flag.store(1, std::memory_order_relaxed);
            }
            if (a.object == b.object) {
                if (!(uniform_self ? self_default : options.selfCollides(a.object))) {
                    ++filtered_pairs;
                    return;
                }
                // A shared index decides most neighbours; the positions only the rest.
                if (narrow::shareIndex(a.vertex_index, b.vertex_index) ||
                    narrow::areNeighbours(a.vertex_index, in_candidates[i].v, b.vertex_index, in_candidates[j].v)) {
                    ++neighbour_pairs;
                    return;
                }
            } else if (filter_objects) {
                const std::uint64_t object_pair = keyOf(std::min(a.object, b.object), std::max(a.object, b.object));
                if (object_pair != last_object_pair) task.object_pairs.push_back(object_pair);
                last_object_pair = object_pair;
            }
            task.tests.push_back({i, j});
        });
        task.sap_pairs = sap_pairs;
        task.filtered_pairs = filtered_pairs;
        task.neighbour_pairs = neighbour_pairs;
        std::sort(task.object_pairs.begin(), task.object_pairs.end());
        task.object_pairs.erase(std::unique(task.object_pairs.begin(), task.object_pairs.end()), task.object_pairs.end());
        sweep_tasks[begin / sweep_grain] = std::move(task);
      } catch (const std::bad_alloc&) {
        out_of_memory.store(true, std::memory_order_relaxed);
      } catch (const BoxBudgetExceeded&) {
        over_budget.store(true, std::memory_order_relaxed);
      }
    });
    if (out_of_memory.load()) return oom;
    std::vector<std::size_t>& test_begin = ws.test_begin;  // tests of task t: [test_begin[t], test_begin[t+1])
    test_begin.assign(sweep_tasks.size() + 1, 0);
    for (std::size_t t = 0; t < sweep_tasks.size(); ++t) {
        const SweepTask& task = sweep_tasks[t];
        stats.sap_pairs += task.sap_pairs;
        stats.filtered_pairs += task.filtered_pairs;
        stats.neighbour_pairs += task.neighbour_pairs;
        test_begin[t + 1] = test_begin[t] + task.tests.size();
    }
    // Exceeded exactly when the pairs all tasks counted are more than the budget (a task
    // stops early only once the strides counted so far are).
    if (over_budget.load() || stats.sap_pairs > options.max_box_pairs)
        return Error(ErrorCode::LimitExceeded, "runNarrowPhase: more than " + std::to_string(options.max_box_pairs) +
                                                   " pairs of candidates with overlapping boxes (NarrowOptions::max_box_pairs): "
                                                   "stacked or repeated triangles?");
    // The loop's end ordered every flag store before this (plain) read.
    for (std::size_t i = 0; i < n; ++i) stats.potentially_colliding_triangles += in_pair[i];
    lap(timings.sweep_ms);

    // Stage 3: the object-pair filter, once per distinct pair of objects with overlapping
    // boxes, in ascending order, on this thread.
    std::vector<std::uint64_t> object_pairs;
    std::vector<char> object_pair_allowed;
    if (filter_objects) {
        for (const SweepTask& task : sweep_tasks) object_pairs.insert(object_pairs.end(), task.object_pairs.begin(), task.object_pairs.end());
        std::sort(object_pairs.begin(), object_pairs.end());
        object_pairs.erase(std::unique(object_pairs.begin(), object_pairs.end()), object_pairs.end());
        object_pair_allowed.resize(object_pairs.size());
        for (std::size_t k = 0; k < object_pairs.size(); ++k) {
            const auto a = static_cast<std::uint32_t>(object_pairs[k] >> 32), b = static_cast<std::uint32_t>(object_pairs[k]);
            object_pair_allowed[k] = options.may_collide(a, b) ? 1 : 0;
        }
    }
    lap(timings.filter_ms);

    // Stage 4: exact tests over all tasks' pairs, as one index range. Hits are kept while
    // fewer than max_pairs are stored (each task decides when it starts, so at most a
    // task's tests more per thread) and always counted; past the budget the first
    // max_pairs hits in test order are kept (below), whatever the scheduling was.
    const std::size_t total_tests = test_begin.back();
    const std::size_t test_tasks = total_tests == 0 ? 0 : (total_tests - 1) / kTestGrain + 1;
    std::vector<std::vector<std::uint64_t>>& hits = ws.hits;  // (lower rank, higher rank) per hit
    hits.resize(test_tasks);
    std::vector<std::size_t>& object_filtered = ws.object_filtered;
    object_filtered.assign(test_tasks, 0);
    std::vector<std::size_t>& found = ws.found;  // hits per task, kept or not
    found.assign(test_tasks, 0);
    std::vector<std::uint8_t>& kept = ws.kept;  // 1: the task's hits are all in hits[task]
    kept.assign(test_tasks, 0);
    std::atomic<std::size_t> stored{0};
    const std::size_t budget = options.max_pairs;
    const auto testTask = [&](std::size_t begin, std::size_t end, bool keep) {
        const std::size_t task_index = begin / kTestGrain;
        std::vector<std::uint64_t> out = std::move(hits[task_index]);  // and back at the end (see the sweep)
        out.clear();
        std::size_t filtered = 0, hit_total = 0;
        std::size_t source = static_cast<std::size_t>(std::upper_bound(test_begin.begin(), test_begin.end(), begin) -
                                                      test_begin.begin()) - 1;
        std::uint64_t cached_pair = std::numeric_limits<std::uint64_t>::max();
        bool cached_allowed = true;
        for (std::size_t k = begin; k < end; ++k) {
            while (test_begin[source + 1] <= k) ++source;
            const narrow::IndexPair p = sweep_tasks[source].tests[k - test_begin[source]];
            const CandidateTriangle& a = in_candidates[p.i];
            const CandidateTriangle& b = in_candidates[p.j];
            if (filter_objects && a.object != b.object) {
                const std::uint64_t object_pair = keyOf(std::min(a.object, b.object), std::max(a.object, b.object));
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
            if (narrow::trianglesIntersect(a.v, b.v)) {
                ++hit_total;
                if (!keep) continue;
                const std::uint32_t ri = rankOf(p.i), rj = rankOf(p.j);
                out.push_back(ri < rj ? keyOf(ri, rj) : keyOf(rj, ri));
            }
        }
        hits[task_index] = std::move(out);
        object_filtered[task_index] = filtered;
        found[task_index] = hit_total;
        kept[task_index] = keep ? 1 : 0;
    };
    pool.parallelFor(total_tests, kTestGrain, [&](std::size_t begin, std::size_t end) {
        try {
            const bool keep = stored.load(std::memory_order_relaxed) < budget;
            testTask(begin, end, keep);
            if (keep) stored.fetch_add(hits[begin / kTestGrain].size(), std::memory_order_relaxed);
        } catch (const std::bad_alloc&) {
            out_of_memory.store(true, std::memory_order_relaxed);
        }
    });
    if (out_of_memory.load()) return oom;
    std::size_t filtered_late = 0, hit_count = 0, found_count = 0;
    for (std::size_t t = 0; t < test_tasks; ++t) {
        filtered_late += object_filtered[t];
        found_count += found[t];
    }
    if (found_count > budget) {
        // The first `budget` hits in test order: whole tasks, then part of the last one.
        // A task inside that prefix whose hits were not kept is tested again.
        std::size_t room = budget;
        for (std::size_t t = 0; t < test_tasks; ++t) {
            if (room == 0) {
                hits[t].clear();
                continue;
            }
            if (!kept[t] && found[t] > 0) testTask(t * kTestGrain, std::min(total_tests, (t + 1) * kTestGrain), true);
            if (hits[t].size() > room) hits[t].resize(room);
            room -= hits[t].size();
        }
        result.pairs_left_out = found_count - budget;
    }
    for (std::size_t t = 0; t < test_tasks; ++t) hit_count += hits[t].size();
    stats.filtered_pairs += filtered_late;
    stats.triangle_tests = total_tests - filtered_late;
    lap(timings.test_ms);

    // Stage 5: canonical order. Ranks follow (object, triangle), so sorting the
    // (lower rank, higher rank) keys sorts the pairs.
    std::vector<std::uint64_t>& colliding = ws.colliding;
    colliding.clear();
    colliding.reserve(hit_count);
    for (const auto& part : hits) colliding.insert(colliding.end(), part.begin(), part.end());
    narrow::radixSort(colliding);
    result.pairs.reserve(colliding.size());
    for (const std::uint64_t key : colliding) {
        const CandidateTriangle& a = candidateOfRank(key >> 32);
        const CandidateTriangle& b = candidateOfRank(key & 0xffffffffu);
        result.pairs.push_back({a.object, a.triangle, b.object, b.triangle});
    }
    stats.positive_tests = result.pairs.size() + result.pairs_left_out;
    lap(timings.sort_ms);

    // Stage 6: responses, summed in the order of the sorted pairs. Responders are the
    // ranks in pairs, in rank order, i.e. sorted by (object, triangle).
    std::vector<std::uint64_t>& responders = ws.responders;
    responders.clear();
    responders.reserve(2 * colliding.size());
    for (const std::uint64_t key : colliding) {
        responders.push_back(key >> 32);
        responders.push_back(key & 0xffffffffu);
    }
    narrow::radixSort(responders);
    responders.erase(std::unique(responders.begin(), responders.end()), responders.end());
    std::vector<std::uint32_t>& slot = ws.slot;  // rank -> responder; read only where written this call
    if (slot.size() < n) slot.resize(n);
    std::vector<Vec3d> normal(responders.size()), sum(responders.size());
    std::vector<std::uint32_t> partners(responders.size(), 0);
    for (std::size_t k = 0; k < responders.size(); ++k) {
        slot[responders[k]] = static_cast<std::uint32_t>(k);
        normal[k] = unitNormal(candidateOfRank(responders[k]));
    }
    for (const std::uint64_t key : colliding) {
        const std::uint32_t i = slot[key >> 32], j = slot[key & 0xffffffffu];
        const Vec3d &ni = normal[i], &nj = normal[j];
        sum[i].x += nj.x - ni.x; sum[i].y += nj.y - ni.y; sum[i].z += nj.z - ni.z;
        sum[j].x += ni.x - nj.x; sum[j].y += ni.y - nj.y; sum[j].z += ni.z - nj.z;
        ++partners[i];
        ++partners[j];
    }
    result.responses.reserve(responders.size());
    for (std::size_t k = 0; k < responders.size(); ++k) {
        const CandidateTriangle& c = candidateOfRank(responders[k]);
        const Vec3d& s = sum[k];
        const double length = std::sqrt(s.x * s.x + s.y * s.y + s.z * s.z);
        TriangleResponse r;
        r.object = c.object;
        r.triangle = c.triangle;
        r.partner_count = partners[k];
        if (length > 0) {
            r.direction = {static_cast<float>(s.x / length), static_cast<float>(s.y / length),
                           static_cast<float>(s.z / length)};
        }
        result.responses.push_back(r);
    }
    lap(timings.response_ms);
    timings.total_ms = msBetween(t_start, t_mark);
    return result;
}

}  // namespace

Result<NarrowResult> runNarrowPhase(std::span<const CandidateTriangle> in_candidates, const NarrowOptions& options,
                                    ThreadPool& pool, NarrowWorkspace& io_workspace) {
    // The API throws nothing: host memory running out on this thread (the parallel bodies
    // catch their own) becomes OutOfMemory.
    try {
        return narrowPhase(in_candidates, options, pool, io_workspace);
    } catch (const std::bad_alloc&) {
        return Error(ErrorCode::OutOfMemory, "runNarrowPhase: host memory ran out");
    } catch (const std::length_error&) {
        return Error(ErrorCode::OutOfMemory, "runNarrowPhase: an array would exceed its largest size");
    }
}

}  // namespace vkcollide
