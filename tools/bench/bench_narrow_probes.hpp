// Two probes of bench_narrow that time one piece of the narrow phase instead of whole calls.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "vkcollide/narrow.hpp"

namespace vkcollide::bench {

// --wake-probe: how long after a call starts a pool's sleeping workers take part. Per
// thread count: `repeat` rounds of a sleep (gap_us, at least 2 ms: the workers sleep),
// then a loop of 64 chunks per thread of 2 us each, without and with prepare() just before
// it; prints the median time from the call until the first, the middle and the last worker
// took its first chunk (a worker that took none counts as the loop's end), and the loop's.
void wakeProbe(const std::vector<unsigned>& threads, unsigned repeat, unsigned gap_us);

// --front-probe: the pair path's front (src/narrow/pair_keys.hpp) on `pairs`, its serial
// and its parallel form, per thread count: median ms of `repeat` calls, each after a
// sleep of gap_us and a prepare() as runPairNarrowPhase does (so the parallel form finds
// the workers as the real call would). Prints one line per thread count; the serial form
// should win below narrow::kSerialPairsBelow and lose above.
void frontProbe(const std::string& label, std::span<const CandidatePair> pairs, std::uint32_t total,
                const std::vector<unsigned>& threads, unsigned repeat, unsigned gap_us);

// The header of frontProbe's lines.
void frontProbeHeader();

}  // namespace vkcollide::bench
