// Sweep-and-prune over screen-space boxes (Cohen et al. 1995), as in section 7 of the
// paper: boxes are swept along x, pairs that overlap in x are tested in y, and only
// pairs that overlap in x and y are tested in the depth extent z. Intervals are closed.
//
// The paper computes a box's depth extent only for pairs that overlap in x and y; here
// the extents arrive with the boxes, so the three tests are simply combined.
//
// One sweep along x over all boxes visits, for every box, all boxes that overlap it in x
// alone; the GPU's candidates lie along intersection curves, so that is a large multiple
// of the pairs that also overlap in y (tens of times for the demo scene, growing with the
// candidate count). The sweep therefore runs per horizontal strip: the y range is cut
// into strips about as high as a typical box, each box is listed in every strip it
// touches, and each strip is swept on its own. A pair overlapping in y is reported only in
// the strip where the later of the two boxes starts (the strip of max(y0a, y0b)), so
// exactly once. Strips are built, sorted and swept in parallel.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "vkcollide/narrow.hpp"

namespace vkcollide::narrow {

// Indices (i < j) into the candidate span.
struct IndexPair {
    std::uint32_t i = 0, j = 0;
    friend bool operator==(const IndexPair&, const IndexPair&) = default;
    friend auto operator<=>(const IndexPair&, const IndexPair&) = default;
};

// The boxes of a candidate span arranged in strips, ready to sweep. Entry positions
// [0, entryCount()) are the unit of parallel work: sweepRange(begin, end, visit) visits
// every overlapping pair whose first box (in sweep order) sits at a position in [begin,
// end), so ranges that tile [0, entryCount()) visit every pair exactly once.
class StripSweep {
public:
    // Preconditions: no NaN in box/zmin/zmax; box[0] <= box[2], box[1] <= box[3]; at most
    // 2^32 - 1 candidates. `pool` may be null (runs on the calling thread). The layout
    // (strip count, order of visits) may depend on the input order and thread count; the
    // set of pairs does not.
    void build(std::span<const CandidateTriangle> in_candidates, ThreadPool* pool);

    std::size_t entryCount() const noexcept { return entries_.size(); }
    std::size_t stripCount() const noexcept { return strip_begin_.empty() ? 0 : strip_begin_.size() - 1; }

    // Calls visit(i, j), i < j, for every pair of candidates whose boxes overlap in x, y
    // and z and whose first box sits at a position in [begin, end). Thread safe (const).
    template <typename Visit>
    void sweepRange(std::size_t begin, std::size_t end, Visit&& visit) const;

private:
    // A box as listed in one strip: 32 bytes, so the sweep reads contiguous memory.
    struct Entry {
        float x0, x1, y0, y1, z0, z1;
        std::uint32_t id;      // candidate index
        std::uint32_t starts;  // 1 when the box starts (has its y0) in this strip
    };
    // 1 when a and b overlap in y and z, else 0, without branches: compilers turn even
    // `&` of float comparisons into jumps, so on x86-64 this uses SSE2 masks.
    static std::uint32_t overlapsInYZ(const Entry& a, const Entry& b) noexcept;

    std::vector<Entry> entries_;             // strip by strip, each sorted by (x0, id)
    std::vector<std::size_t> strip_begin_;   // entries of strip s: [strip_begin_[s], strip_begin_[s + 1])
};

inline std::uint32_t StripSweep::overlapsInYZ(const Entry& a, const Entry& b) noexcept {
#if defined(__SSE2__)
    // Lanes of (y0, y1, z0, z1): b's lows against a's highs, b's highs against a's lows.
    const __m128 b_yz = _mm_loadu_ps(&b.y0);
    const __m128 a_high = _mm_setr_ps(a.y1, 0, a.z1, 0), a_low = _mm_setr_ps(0, a.y0, 0, a.z0);
    const int low_ok = _mm_movemask_ps(_mm_cmple_ps(b_yz, a_high));   // bits 0, 2: b.y0 <= a.y1, b.z0 <= a.z1
    const int high_ok = _mm_movemask_ps(_mm_cmpge_ps(b_yz, a_low));   // bits 1, 3: b.y1 >= a.y0, b.z1 >= a.z0
    const auto all = static_cast<std::uint32_t>((low_ok & 0x5) | (high_ok & 0xa));
    return (all + 1) >> 4;  // 1 exactly when all four bits are set
#else
    return static_cast<std::uint32_t>((b.y0 <= a.y1) & (a.y0 <= b.y1) & (b.z0 <= a.z1) & (a.z0 <= b.z1));
#endif
}

template <typename Visit>
void StripSweep::sweepRange(std::size_t begin, std::size_t end, Visit&& visit) const {
    if (begin >= end) return;
    // The strip holding `begin`: the last strip that starts at or before it.
    std::size_t strip = 0;
    {
        std::size_t lo = 0, hi = stripCount();
        while (hi - lo > 1) {
            const std::size_t mid = (lo + hi) / 2;
            if (strip_begin_[mid] <= begin) lo = mid; else hi = mid;
        }
        strip = lo;
    }
    const Entry* const entries = entries_.data();
    // Positions of reported partners of the current box, visited in batches: filling
    // the batch is branch-free, which matters because the tests below pass for a mixed,
    // unpredictable fraction of the pairs (about half in y, a quarter of those in z on
    // the demo's candidates).
    constexpr std::uint32_t kBatch = 64;
    std::uint32_t batch[kBatch];
    for (std::size_t s = begin; s < end; ++s) {
        while (strip_begin_[strip + 1] <= s) ++strip;
        const std::size_t strip_end = strip_begin_[strip + 1];
        const Entry a = entries[s];
        const auto flush = [&](std::uint32_t count) {
            for (std::uint32_t k = 0; k < count; ++k) {
                const std::uint32_t other = entries[batch[k]].id;
                if (a.id < other) {
                    visit(a.id, other);
                } else {
                    visit(other, a.id);
                }
            }
        };
        std::uint32_t count = 0;
        // Sorted by x0: the boxes that overlap a in x are the ones up to the first that
        // starts after a ends.
        for (std::size_t t = s + 1; t < strip_end && entries[t].x0 <= a.x1; ++t) {
            const Entry& b = entries[t];
            // y overlap, the strip that reports the pair (the strip of max(y0a, y0b),
            // where one of the two boxes starts), depth overlap.
            batch[count] = static_cast<std::uint32_t>(t);
            count += overlapsInYZ(a, b) & (a.starts | b.starts);
            batch[count] = static_cast<std::uint32_t>(t);
            if (count == kBatch) {
                flush(count);
                count = 0;
            }
        }
        flush(count);
    }
}

// The pairs whose boxes overlap in x, y and z, sorted ascending (a convenience for tests).
std::vector<IndexPair> sweepAndPrunePairs(std::span<const CandidateTriangle> in_candidates, ThreadPool* pool = nullptr);

}  // namespace vkcollide::narrow
