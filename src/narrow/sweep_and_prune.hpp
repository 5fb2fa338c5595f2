// Sweep-and-prune over screen-space boxes (Cohen et al. 1995), as in section 7 of the
// paper: boxes are swept along x, and pairs that overlap in x are kept when they overlap
// in y and in the depth extent z too. Intervals are closed. The paper computes a box's
// depth extent only for pairs that overlap in x and y; here the extents arrive with the
// boxes, so the y and z tests are simply combined.
//
// One sweep along x over all boxes visits, for every box, all boxes that overlap it in x
// alone; the GPU's candidates lie along intersection curves and in several depth layers,
// so that is a large multiple of the pairs that overlap in all three axes (45 times for
// the demo scene, growing with the candidate count). The sweep therefore runs per cell
// of a grid over y and z: cells about twice as large as a typical box, each box listed in
// every cell it touches, each cell swept on its own. A pair is reported only in the cell
// of (max(y0a, y0b), max(z0a, z0b)), where both boxes are listed, so exactly once. Cells
// are built, sorted and swept in parallel.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <type_traits>
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

// What a visitor usually needs to judge a pair, carried in the sweep's own entries: most
// pairs are decided from these (neighbours through a shared vertex index, pairs of
// different objects) without reading the 80-byte candidates in random order.
struct CandidateTag {
    std::uint32_t object;
    std::uint32_t vertex_index[3];
};

// The boxes of a candidate span arranged in cells, ready to sweep. Entry positions
// [0, entryCount()) are the unit of parallel work: sweepRange(begin, end, visit) visits
// every overlapping pair whose first box (in sweep order) sits at a position in [begin,
// end), so ranges that tile [0, entryCount()) visit every pair exactly once.
class CellSweep {
public:
    // Preconditions: no NaN in box/zmin/zmax; box[0] <= box[2], box[1] <= box[3]; at most
    // 2^32 - 1 candidates. `pool` may be null (runs on the calling thread). The layout
    // (cell count, order of visits) may depend on the input order and thread count; the
    // set of pairs does not.
    void build(std::span<const CandidateTriangle> in_candidates, ThreadPool* pool);

    std::size_t entryCount() const noexcept { return entry_count_; }
    std::size_t cellCount() const noexcept { return cell_begin_.empty() ? 0 : cell_begin_.size() - 1; }

    // Calls visit(i, j), i < j, for every pair of candidates whose boxes overlap in x, y
    // and z and whose first box sits at a position in [begin, end); visit(i, j, tag_i,
    // tag_j) if it takes the candidates' tags too. Thread safe (const).
    template <typename Visit>
    void sweepRange(std::size_t begin, std::size_t end, Visit&& visit) const;

private:
    // A box as listed in one cell (48 bytes), so the sweep reads contiguous memory.
    struct Entry {
        float x0, x1, y0, y1, z0, z1;
        std::uint32_t id;      // candidate index
        std::uint32_t starts;  // bit 0: y0 is in this cell's strip; bit 1: z0 is in its slab
        CandidateTag tag;
    };
    // Whether boxes overlap box `a` in y and z: 1 or 0, without branches (compilers turn
    // even `&` of float comparisons into jumps, so on x86-64 this uses SSE2 masks).
    struct OverlapYZ {
        explicit OverlapYZ(const Entry& a) noexcept;
        std::uint32_t operator()(const Entry& b) const noexcept;
#if defined(__SSE2__)
        __m128 a_high, a_low;
#else
        float y0, y1, z0, z1;
#endif
    };

    std::unique_ptr<Entry[]> entries_;      // cell by cell, each sorted by (x0, id)
    std::size_t entry_count_ = 0, entry_capacity_ = 0;
    std::vector<std::size_t> cell_begin_;   // entries of cell c: [cell_begin_[c], cell_begin_[c + 1])
};

#if defined(__SSE2__)
// Lanes (y0, y1, z0, z1): b's lows against a's highs, b's highs against a's lows.
inline CellSweep::OverlapYZ::OverlapYZ(const Entry& a) noexcept
    : a_high(_mm_setr_ps(a.y1, 0, a.z1, 0)), a_low(_mm_setr_ps(0, a.y0, 0, a.z0)) {}

inline std::uint32_t CellSweep::OverlapYZ::operator()(const Entry& b) const noexcept {
    const __m128 b_yz = _mm_loadu_ps(&b.y0);
    const int low_ok = _mm_movemask_ps(_mm_cmple_ps(b_yz, a_high));  // bits 0, 2: b.y0 <= a.y1, b.z0 <= a.z1
    const int high_ok = _mm_movemask_ps(_mm_cmpge_ps(b_yz, a_low));  // bits 1, 3: b.y1 >= a.y0, b.z1 >= a.z0
    const auto all = static_cast<std::uint32_t>((low_ok & 0x5) | (high_ok & 0xa));
    return (all + 1) >> 4;  // 1 exactly when all four bits are set
}
#else
inline CellSweep::OverlapYZ::OverlapYZ(const Entry& a) noexcept : y0(a.y0), y1(a.y1), z0(a.z0), z1(a.z1) {}

inline std::uint32_t CellSweep::OverlapYZ::operator()(const Entry& b) const noexcept {
    return static_cast<std::uint32_t>((b.y0 <= y1) & (y0 <= b.y1) & (b.z0 <= z1) & (z0 <= b.z1));
}
#endif

template <typename Visit>
void CellSweep::sweepRange(std::size_t begin, std::size_t end, Visit&& visit) const {
    if (begin >= end) return;
    // The cell holding `begin`: the last cell that starts at or before it.
    std::size_t cell = 0;
    {
        std::size_t lo = 0, hi = cellCount();
        while (hi - lo > 1) {
            const std::size_t mid = (lo + hi) / 2;
            if (cell_begin_[mid] <= begin) lo = mid; else hi = mid;
        }
        cell = lo;
    }
    const Entry* const entries = entries_.get();
    // Positions of reported partners of the current box, visited in batches: filling
    // the batch is branch-free, which matters because the tests below pass for a mixed,
    // unpredictable fraction of the pairs (about half in y, a quarter of those in z on
    // the demo's candidates).
    constexpr std::uint32_t kBatch = 64;
    std::uint32_t batch[kBatch];
    for (std::size_t s = begin; s < end; ++s) {
        while (cell_begin_[cell + 1] <= s) ++cell;
        const std::size_t cell_end = cell_begin_[cell + 1];
        const Entry a = entries[s];
        const auto flush = [&](std::uint32_t count) {
            for (std::uint32_t k = 0; k < count; ++k) {
                const Entry& b = entries[batch[k]];
                const bool a_first = a.id < b.id;
                const Entry& first = a_first ? a : b;
                const Entry& second = a_first ? b : a;
                if constexpr (std::is_invocable_v<Visit&, std::uint32_t, std::uint32_t, const CandidateTag&,
                                                  const CandidateTag&>) {
                    visit(first.id, second.id, first.tag, second.tag);
                } else {
                    visit(first.id, second.id);
                }
            }
        };
        const OverlapYZ overlaps(a);
        const float a_x1 = a.x1;
        const std::uint32_t a_starts = a.starts;
        std::uint32_t count = 0;
        // Sorted by x0: the boxes of this cell that overlap a in x are the ones up to the
        // first that starts after a ends.
        for (std::size_t t = s + 1; t < cell_end && entries[t].x0 <= a_x1; ++t) {
            const Entry& b = entries[t];
            // y and depth overlap, and this is the cell that reports the pair: the strip
            // of max(y0a, y0b), where one of the boxes starts in y, and the slab of
            // max(z0a, z0b), where one starts in z ((a | b) == 3 exactly when the sum
            // below is 4).
            batch[count] = static_cast<std::uint32_t>(t);  // kept only if count grows
            count += overlaps(b) & (((a_starts | b.starts) + 1) >> 2);
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
