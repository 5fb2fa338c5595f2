// Exact reference pairs of one scene frame, kept in a file so that repeated benchmark runs
// do not recompute them. The file is named by a 64-bit hash of everything the reference
// depends on (every position and index, transforms, self-collision flags, and
// kReferenceVersion for the reference's own rules), so a changed scene simply misses.
// Files are written to a temporary name and renamed: a killed run leaves no half file.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "bench_scenes.hpp"
#include "vkcollide/narrow.hpp"
#include "vkcollide/result.hpp"

namespace vkcollide::bench {

// Bump when tests/support/exact_reference changes what counts as a pair.
inline constexpr std::uint32_t kReferenceVersion = 1;

struct FrameReference {
    std::vector<TrianglePair> pairs;     // computeReferencePairs, sorted
    std::vector<std::uint8_t> crossing;  // per pair: 1 crossing, 0 touching (classifyContact)
    std::size_t crossingCount() const;
    std::uint64_t hash = 0;
    bool from_cache = false;
    double seconds = 0;  // to compute or to read
};

std::uint64_t hashObjects(const std::vector<BenchObject>& objects);

// The reference of `objects`, from `cache_dir` when it holds it (empty: no cache), else
// computed on `threads` threads (0: all) and stored there. A cache file that cannot be
// read or written is reported on stderr and ignored, never fatal.
Result<FrameReference> referenceFor(const std::vector<BenchObject>& objects, const std::string& cache_dir, unsigned threads);

}  // namespace vkcollide::bench
