// The back half every entry shares: the object-pair filter, the exact tests, the pairs in
// canonical order and the responses.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "narrow/parallel.hpp"
#include "narrow/slots.hpp"
#include "narrow/sweep_and_prune.hpp"
#include "vkcollide/narrow.hpp"

namespace vkcollide::narrow {

// What one task of the pairing stage (the sweep, or the pair path's pairing up) found.
struct PairTask {
    std::vector<IndexPair> tests;             // slot pairs to test (object filter still to apply)
    std::vector<std::uint64_t> object_pairs;  // distinct (object_a, object_b), a < b, when may_collide is set
    std::size_t sap_pairs = 0, filtered_pairs = 0, neighbour_pairs = 0;
};

struct Vec3d {
    double x = 0, y = 0, z = 0;
};

inline std::uint64_t keyOf(std::uint32_t high, std::uint32_t low) { return (std::uint64_t{high} << 32) | low; }

// Times the stages of one call.
class StageClock {
public:
    using Clock = std::chrono::steady_clock;
    StageClock() : start_(Clock::now()), mark_(start_) {}
    // Stores the time since the last lap in out_ms.
    void lap(double& out_ms) {
        const Clock::time_point now = Clock::now();
        out_ms = std::chrono::duration<double, std::milli>(now - mark_).count();
        mark_ = now;
    }
    double totalMs() const { return std::chrono::duration<double, std::milli>(mark_ - start_).count(); }

private:
    Clock::time_point start_, mark_;
};

// Exact tests per parallel task for `tests` tests on `threads` threads.
std::size_t testGrain(std::size_t tests, unsigned threads);

// How many threads the pair path wants awake (Executor::prepare) for `input_pairs` pairs on
// `threads` threads: as many as its exact tests can use, none below kPrepareFrom pairs.
// From kPrepareFrom pairs on the pair path prepares on entry, so that workers asleep since
// the last call (the GPU's 0.3-2 ms) wake during its checks, slots and gather instead of
// when the tests need them; below, the tests take a few microseconds and waking costs more.
// The world also calls it with the last detection's count while it waits for the GPU.
inline constexpr std::size_t kPrepareFrom = 256;

// Pairs the GPU decided (NarrowOptions::pairs_decided) need no tests, and below this many
// the pair path runs on the calling thread and wakes nobody: what is left (checks, slots,
// gather, responses) costs about 50 ns a pair there, and waking workers and handing them
// chunks cost more. Measured with bench_narrow --decided (docs/narrow_phase.md).
inline constexpr std::size_t kSerialDecidedBelow = 2048;
bool runsOnCallingThread(std::size_t input_pairs, bool decided);

unsigned threadsToWake(std::size_t input_pairs, unsigned threads, bool decided);

// Stages 3 to 6 on the pairs that `tasks` found (their counters already in out.stats):
// may_collide once per distinct object pair (ascending, this thread), the exact tests in
// parallel, the colliding pairs in canonical order (sorted unless `tests_in_order`: the
// tests of all tasks, in task order, already ascend), out.pairs and out.responses.
// Slots must be in (object, triangle) order.
void testAndRespond(std::vector<PairTask>& tasks, const SlotData& slots, std::size_t slot_count, bool tests_in_order,
                    const NarrowOptions& options, Executor& executor, NarrowWorkspace::Impl& ws, NarrowResult& out,
                    StageClock& clock);

}  // namespace vkcollide::narrow
