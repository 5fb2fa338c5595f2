// Sweep-and-prune over screen-space boxes (Cohen et al. 1995), as in section 7 of the
// paper: pairs of boxes that overlap in x, y and the depth extent z. Intervals are closed.
// The paper computes a box's depth extent only for pairs that overlap in x and y; here
// the extents arrive with the boxes, so the three tests are simply combined.
//
// One sweep along x over all boxes would visit, for every box, all boxes that overlap it
// in x alone: the GPU's candidates lie along intersection curves and in several depth
// layers, so that is a large multiple of the pairs that overlap in all three axes (45
// times for the demo scene, growing with the candidate count). So the boxes go into the
// cells of a grid over x, y and z, each box listed in every cell it touches, and a pair is
// looked at only in the cell of (max(x0a, x0b), max(y0a, y0b), max(z0a, z0b)), where both
// boxes are listed: exactly once. Cells are about three typical (median) boxes high and
// deep and eight wide; a cell is swept along x after sorting by x0, or, when it holds few
// boxes, checked pair by pair.
//
// Cells that hold boxes of a single object that does not self-collide cannot produce a
// pair and are skipped without sorting: objects do not self-collide by default, and then
// only the cells where objects meet cost anything.
//
// Parallel work: the cells are grouped into tiles (blocks of cells in x and y, all of z).
// Building lists each box in the tiles it touches (a counting sort, in parallel over the
// boxes); sweeping processes whole tiles, in parallel: a tile's boxes go into its cells
// (a counting sort in the task's own memory), then its active cells are swept.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <type_traits>
#include <vector>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "narrow/parallel.hpp"
#include "narrow/slots.hpp"
#include "vkcollide/narrow.hpp"

namespace vkcollide::narrow {

// Slots (i < j) of a pair.
struct IndexPair {
    std::uint32_t i = 0, j = 0;
    friend bool operator==(const IndexPair&, const IndexPair&) = default;
    friend auto operator<=>(const IndexPair&, const IndexPair&) = default;
};

// The boxes to sweep, one per slot (slots 0..count-1).
struct SweepInput {
    std::size_t count = 0;
    Strided<BoxZ> box;                          // by record
    const std::uint32_t* record_of = nullptr;   // slot -> record; null: slot == record
    Strided<std::uint32_t> object;              // by slot
    const NarrowOptions* options = nullptr;     // self-collision switch; null: every object on
    // The boxes' lowest low and highest high end per axis (x, y, z), when the caller has
    // them (the validation pass reads every box anyway); else the build computes them.
    bool has_range = false;
    float range_lo[3] = {0, 0, 0}, range_hi[3] = {0, 0, 0};
};

// At most this many slots (an entry keeps a slot in 28 bits).
inline constexpr std::size_t kMaxSweepSlots = (std::size_t{1} << 28) - 1;

class GridSweep {
public:
    // A box as listed in a tile or a cell (32 bytes).
    struct Entry {
        float x0, x1, y0, y1, z0, z1;
        // slot << 4 | self << 3 | starts: bits 0, 1, 2: x0, y0, z0 lie in this cell's slab
        // of x, y, z (cell entries only); bit 3: the object self-collides.
        std::uint32_t slot_flags;
        std::uint32_t object;
    };
    static_assert(sizeof(Entry) == 32);
    // Slabs of an entry on the three axes: lo[a] .. hi[a].
    struct CellRange {
        std::uint32_t lo[3], hi[3];
    };

    // A tile's active cells: entries cell after cell, cell k in [begin[k], begin[k + 1]).
    struct TileCells {
        std::vector<Entry> entries;
        std::vector<std::uint32_t> begin;
        // Scratch of fillTile and of the sweep.
        std::vector<std::uint32_t> count, first_object;
        std::vector<std::uint8_t> state;
        std::vector<CellRange> ranges;
        std::vector<std::uint64_t> keys;
        std::vector<Entry> sorted;
        std::vector<std::uint32_t> run;
    };

    // Preconditions: no NaN in the boxes; x0 <= x1, y0 <= y1, z0 <= z1; at most
    // kMaxSweepSlots slots. `executor` may be null (runs on the calling thread). The layout
    // depends only on the boxes, not on the thread count. Building again reuses the memory
    // of the previous build.
    void build(const SweepInput& in, Executor* executor);
    // All boxes of a candidate span, every object self-colliding (for tests).
    void build(std::span<const CandidateTriangle> in_candidates, Executor* executor);

    std::size_t tileCount() const noexcept { return tile_count_; }
    std::size_t cellCount() const noexcept;
    std::size_t entryCount() const noexcept { return entry_count_; }  // listings in tiles

    // Calls visit(i, j), i < j, for every pair of slots whose boxes overlap in x, y and z,
    // that the self-collision switch allows and that belongs to a tile in [begin, end);
    // visit(i, j, object_i, object_j) if it takes the objects too. Tiles are disjoint in
    // pairs, so ranges that cover [0, tileCount()) visit every pair exactly once. Thread
    // safe (const); `scratch` is the caller's, one per thread.
    template <typename Visit>
    void sweepTiles(std::size_t begin, std::size_t end, TileCells& scratch, Visit&& visit) const;

    // The active cells of one tile (cells where a pair may be reported).
    void fillTile(std::size_t tile, TileCells& out) const;

private:
    // Cuts one axis into slabs of equal size. Monotone (a rounded subtraction, a
    // multiplication by a positive constant and a truncation are each monotone), so
    // [lo, hi] touches exactly the slabs slab(lo)..slab(hi), and slab(max(loa, lob)) =
    // max(slab(loa), slab(lob)). In float; cellsOf's SSE2 form computes the same values.
    struct Axis {
        float origin = 0, scale = 0, last_slab = 0;
        std::uint32_t last = 0;  // slab count - 1
        std::uint32_t count() const { return last + 1; }
        std::uint32_t operator()(float v) const {
            const float t = (v - origin) * scale;  // >= 0: origin is the lowest low end
            return static_cast<std::uint32_t>(std::min(t, last_slab));
        }
    };
    CellRange cellsOf(const Entry& e) const noexcept;
    CellRange cellsOf(const BoxZ& b) const noexcept;
    bool listInTiles(const SweepInput& in, Executor& executor, std::size_t max_cell_listings);

    Axis axis_[3];
    std::uint32_t tile_shift_[3] = {0, 0, 0};  // cells per tile along each axis: 1 << shift
    std::uint32_t tiles_[3] = {1, 1, 1};      // tiles along each axis
    std::size_t tile_count_ = 0, entry_count_ = 0;
    Buffer<Entry> entries_;              // tile by tile, slot order within a tile
    Buffer<std::uint32_t> tile_begin_;   // entries of tile t: [tile_begin_[t], tile_begin_[t + 1])
    Buffer<std::uint32_t> counts_;       // build scratch: per task and tile, then next position
};

namespace sweep_detail {

// Pairs of a cell checked one by one up to this many boxes; above, sorted by x0 and swept.
inline constexpr std::size_t kAllPairsMax = 16;

// Whether b overlaps a in x, y and z: 1 or 0, without branches (compilers turn even `&`
// of float comparisons into jumps, so on x86-64 this uses SSE2 masks).
struct Overlap {
    using Entry = GridSweep::Entry;
#if defined(__SSE2__)
    explicit Overlap(const Entry& a) noexcept
        : high_xy(_mm_setr_ps(a.x1, 0, a.y1, 0)), low_xy(_mm_setr_ps(0, a.x0, 0, a.y0)),
          high_z(_mm_setr_ps(a.z1, 0, 0, 0)), low_z(_mm_setr_ps(0, a.z0, 0, 0)) {}
    std::uint32_t operator()(const Entry& b) const noexcept {
        // Lanes (lo, hi, lo, hi): b's lows against a's highs, b's highs against a's lows.
        const __m128 b_xy = _mm_loadu_ps(&b.x0);
        const __m128 b_z = _mm_castsi128_ps(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(&b.z0)));
        const int xy = (_mm_movemask_ps(_mm_cmple_ps(b_xy, high_xy)) & 0x5) | (_mm_movemask_ps(_mm_cmpge_ps(b_xy, low_xy)) & 0xa);
        const int z = (_mm_movemask_ps(_mm_cmple_ps(b_z, high_z)) & 0x1) | (_mm_movemask_ps(_mm_cmpge_ps(b_z, low_z)) & 0x2);
        return static_cast<std::uint32_t>((xy | (z << 4)) + 1) >> 6;  // 1 exactly when all six bits are set
    }
    __m128 high_xy, low_xy, high_z, low_z;
#else
    explicit Overlap(const Entry& a) noexcept : a_(a) {}
    std::uint32_t operator()(const Entry& b) const noexcept {
        return static_cast<std::uint32_t>((b.x0 <= a_.x1) & (a_.x0 <= b.x1) & (b.y0 <= a_.y1) & (a_.y0 <= b.y1) &
                                          (b.z0 <= a_.z1) & (a_.z0 <= b.z1));
    }
    Entry a_;
#endif
};

// 1 when the pair may be reported here: this is the cell of the largest starts (on each
// axis one of the two starts here) and not two boxes of an object that does not
// self-collide.
inline std::uint32_t reportable(const GridSweep::Entry& a, const GridSweep::Entry& b) noexcept {
    const std::uint32_t starts = (((a.slot_flags | b.slot_flags) & 7) + 1) >> 3;
    const std::uint32_t other = static_cast<std::uint32_t>(a.object != b.object) | ((a.slot_flags >> 3) & 1);
    return starts & other;
}

std::uint32_t orderedBits(float x) noexcept;

}  // namespace sweep_detail

template <typename Visit>
void GridSweep::sweepTiles(std::size_t begin, std::size_t end, TileCells& cells, Visit&& visit) const {
    using namespace sweep_detail;
    // Reported partners of the current box, visited in batches: filling the batch is
    // branch-free, which matters because the tests pass for an unpredictable fraction.
    constexpr std::uint32_t kBatch = 32;
    std::uint32_t batch[kBatch];
    const auto flush = [&](const Entry* list, const Entry& a, std::uint32_t count) {
        const std::uint32_t a_slot = a.slot_flags >> 4;
        for (std::uint32_t k = 0; k < count; ++k) {
            const Entry& b = list[batch[k]];
            const std::uint32_t b_slot = b.slot_flags >> 4;
            const bool a_first = a_slot < b_slot;
            const std::uint32_t first = a_first ? a_slot : b_slot, second = a_first ? b_slot : a_slot;
            if constexpr (std::is_invocable_v<Visit&, std::uint32_t, std::uint32_t, std::uint32_t, std::uint32_t>) {
                visit(first, second, a_first ? a.object : b.object, a_first ? b.object : a.object);
            } else {
                visit(first, second);
            }
        }
    };
    std::vector<Entry>& sorted = cells.sorted;
    for (std::size_t tile = begin; tile < end; ++tile) {
        fillTile(tile, cells);
        for (std::size_t c = 0; c + 1 < cells.begin.size(); ++c) {
            const Entry* list = cells.entries.data() + cells.begin[c];
            const std::size_t k = cells.begin[c + 1] - cells.begin[c];
            if (k <= kAllPairsMax) {
                for (std::size_t i = 0; i + 1 < k; ++i) {
                    const Entry& a = list[i];
                    const Overlap overlaps(a);
                    std::uint32_t count = 0;
                    for (std::size_t j = i + 1; j < k; ++j) {
                        batch[count] = static_cast<std::uint32_t>(j);  // kept only if count grows
                        count += overlaps(list[j]) & reportable(a, list[j]);
                    }
                    flush(list, a, count);  // count <= 15 < kBatch
                }
                continue;
            }
            // Sort by (x0, slot): the boxes that overlap a in x are then the ones after it
            // up to the first that starts after a ends.
            std::vector<std::uint64_t>& keys = cells.keys;
            keys.resize(k);
            for (std::size_t i = 0; i < k; ++i) keys[i] = (std::uint64_t{orderedBits(list[i].x0)} << 32) | i;
            std::sort(keys.begin(), keys.end());  // ties: position, which follows the slot
            sorted.resize(k);
            for (std::size_t i = 0; i < k; ++i) sorted[i] = list[keys[i] & 0xffffffffu];
            // Runs of one object in x order: an object that does not self-collide skips
            // the rest of its run in one step (boxes of one object lie side by side).
            std::vector<std::uint32_t>& run = cells.run;
            run.resize(k);
            run[k - 1] = 1;
            for (std::size_t i = k - 1; i-- > 0;) run[i] = sorted[i + 1].object == sorted[i].object ? run[i + 1] + 1 : 1;
            for (std::size_t i = 0; i + 1 < k; ++i) {
                const Entry& a = sorted[i];
                const Overlap overlaps(a);
                const bool a_other_only = (a.slot_flags & 8) == 0;
                std::uint32_t count = 0;
                for (std::size_t j = i + 1; j < k && sorted[j].x0 <= a.x1;) {
                    const Entry& b = sorted[j];
                    if (a_other_only && b.object == a.object) {
                        j += run[j];
                        continue;
                    }
                    batch[count] = static_cast<std::uint32_t>(j);
                    count += overlaps(b) & ((((a.slot_flags | b.slot_flags) & 7) + 1) >> 3);
                    ++j;
                    if (count == kBatch) {
                        flush(sorted.data(), a, count);
                        count = 0;
                    }
                }
                flush(sorted.data(), a, count);
            }
        }
    }
}

// The pairs whose boxes overlap in x, y and z, sorted ascending (a convenience for tests;
// every object self-colliding).
std::vector<IndexPair> sweepAndPrunePairs(std::span<const CandidateTriangle> in_candidates, Executor* executor = nullptr);

}  // namespace vkcollide::narrow
