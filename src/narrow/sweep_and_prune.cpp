#include "narrow/sweep_and_prune.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <memory>

#include "vkcollide/thread_pool.hpp"

namespace vkcollide::narrow {
namespace {

// Cell size in typical (median) box extents, per axis. Smaller cells mean fewer boxes to
// sweep past but more boxes listed in several cells (docs/narrow_phase.md).
constexpr double kCellExtent = 2.0;
// At most this many cells (bounds the per-chunk histograms) and at most one per
// kCandidatesPerCell candidates.
constexpr std::size_t kMaxCells = 4096;
constexpr std::size_t kCandidatesPerCell = 4;
// Average cells per box allowed by the estimate (tall or deep boxes are listed often).
constexpr double kMaxListingsPerBox = 3.0;
// Boxes sampled to choose the grid: enough for a stable median, independent of n.
constexpr std::size_t kSampleSize = 1024;
// Candidates per task while building the cells: about kTasksPerThread tasks per thread,
// within these bounds (each task has a histogram of up to kMaxCells counters).
constexpr std::size_t kTasksPerThread = 4;
constexpr std::size_t kMinBuildGrain = 1024;
constexpr std::size_t kMaxBuildGrain = 16384;

void forChunks(ThreadPool* pool, std::size_t count, std::size_t grain,
               const std::function<void(std::size_t, std::size_t)>& body) {
    if (pool) {
        pool->parallelFor(count, grain, body);
    } else {
        for (std::size_t begin = 0; begin < count; begin += grain) body(begin, std::min(count, begin + grain));
    }
}

// Cuts one axis into `count` equal slabs. Monotone (a rounded subtraction, a
// multiplication by a positive constant and a truncation are each monotone), so an
// interval [lo, hi] touches exactly the slabs slab(lo)..slab(hi), and slab(max(loa, lob))
// = max(slab(loa), slab(lob)).
struct SlabMap {
    double origin = 0, scale = 0;
    std::uint32_t last = 0;  // slab count - 1

    std::uint32_t count() const { return last + 1; }
    std::uint32_t operator()(float v) const {
        const double t = (double(v) - origin) * scale;  // >= 0: origin is the lowest low end
        return t >= double(last) ? last : static_cast<std::uint32_t>(t);
    }
    void setCount(double slabs, double range) {
        last = static_cast<std::uint32_t>(slabs) - 1;
        scale = range > 0 ? slabs / range : 0;
    }
};

struct Grid {
    SlabMap y, z;  // cell of (y, z) = slab_y * z.count() + slab_z
    std::size_t cells() const { return std::size_t{y.count()} * z.count(); }
};

struct Range {
    float y_min, y_max, z_min, z_max;
};

double medianOf(std::vector<float>& v) {
    const auto middle = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
    std::nth_element(v.begin(), middle, v.end());
    return double(*middle);
}

Grid chooseGrid(std::span<const CandidateTriangle> in_candidates, const Range& range) {
    const std::size_t n = in_candidates.size();
    Grid grid;
    grid.y.origin = range.y_min;
    grid.z.origin = range.z_min;
    const double range_y = double(range.y_max) - double(range.y_min);
    const double range_z = double(range.z_max) - double(range.z_min);
    const double max_cells = double(std::clamp<std::size_t>(n / kCandidatesPerCell, 1, kMaxCells));
    if (max_cells == 1) return grid;

    // Median extents of an evenly spaced sample.
    const std::size_t step = std::max<std::size_t>(1, n / kSampleSize);
    std::vector<float> heights, depths;
    for (std::size_t i = 0; i < n; i += step) {
        heights.push_back(in_candidates[i].box[3] - in_candidates[i].box[1]);
        depths.push_back(in_candidates[i].zmax - in_candidates[i].zmin);
    }
    const double cell_y = kCellExtent * medianOf(heights), cell_z = kCellExtent * medianOf(depths);
    const auto slabsFor = [&](double extent, double cell) {
        if (!(extent > 0)) return 1.0;
        return std::clamp(cell > 0 ? std::ceil(extent / cell) : max_cells, 1.0, max_cells);
    };
    double slabs_y = slabsFor(range_y, cell_y), slabs_z = slabsFor(range_z, cell_z);
    if (slabs_y * slabs_z > max_cells) {  // too many: shrink both by the same factor
        const double f = std::sqrt(max_cells / (slabs_y * slabs_z));
        slabs_y = std::max(1.0, std::floor(slabs_y * f));
        slabs_z = std::max(1.0, std::floor(slabs_z * f));
    }
    // Coarser while the sample says boxes would be listed too often, on the axis whose
    // boxes span more slabs.
    for (;;) {
        grid.y.setCount(slabs_y, range_y);
        grid.z.setCount(slabs_z, range_z);
        double listings = 0, span_y = 0, span_z = 0;
        std::size_t sampled = 0;
        for (std::size_t i = 0; i < n; i += step, ++sampled) {
            const CandidateTriangle& c = in_candidates[i];
            const double sy = grid.y(c.box[3]) - grid.y(c.box[1]) + 1, sz = grid.z(c.zmax) - grid.z(c.zmin) + 1;
            listings += sy * sz;
            span_y += sy;
            span_z += sz;
        }
        if (listings <= kMaxListingsPerBox * double(sampled) || (slabs_y == 1 && slabs_z == 1)) break;
        if ((span_y >= span_z && slabs_y > 1) || slabs_z == 1) {
            slabs_y = std::ceil(slabs_y / 2);
        } else {
            slabs_z = std::ceil(slabs_z / 2);
        }
    }
    return grid;
}

// Sorts one cell's keys. Cells are small and their keys arrive in candidate order, which
// follows the meshes and so is partly sorted already: insertion sort (adaptive, no
// recursion) up to a few dozen keys, std::sort above.
void sortKeys(std::uint64_t* first, std::uint64_t* last) {
    if (last - first > 48) {
        std::sort(first, last);
        return;
    }
    for (std::uint64_t* i = first + (first != last); i < last; ++i) {
        const std::uint64_t key = *i;
        std::uint64_t* j = i;
        for (; j > first && *(j - 1) > key; --j) *j = *(j - 1);
        *j = key;
    }
}

// A float's bits as an unsigned integer with the same order (-0 and +0 both map to +0's).
std::uint32_t orderedBits(float x) {
    x += 0.0f;  // -0 -> +0
    std::uint32_t bits;
    std::memcpy(&bits, &x, sizeof bits);
    return (bits & 0x80000000u) ? ~bits : (bits | 0x80000000u);
}

}  // namespace

void CellSweep::build(std::span<const CandidateTriangle> in_candidates, ThreadPool* pool) {
    const std::size_t n = in_candidates.size();
    entry_count_ = 0;
    cell_begin_.assign(2, 0);
    if (n == 0) return;
    // Tasks of candidates: a few per thread, not too small to be worth handing out.
    const std::size_t threads = pool ? pool->threadCount() : 1;
    const std::size_t grain = std::clamp<std::size_t>(n / (threads * kTasksPerThread), kMinBuildGrain, kMaxBuildGrain);
    const std::size_t chunks = (n - 1) / grain + 1;

    // The y and z ranges (per chunk, then combined), then the grid.
    std::vector<Range> chunk_range(chunks);
    forChunks(pool, n, grain, [&](std::size_t begin, std::size_t end) {
        const CandidateTriangle& first = in_candidates[begin];
        Range r{first.box[1], first.box[3], first.zmin, first.zmax};
        for (std::size_t i = begin; i < end; ++i) {
            const CandidateTriangle& c = in_candidates[i];
            r = {std::min(r.y_min, c.box[1]), std::max(r.y_max, c.box[3]), std::min(r.z_min, c.zmin),
                 std::max(r.z_max, c.zmax)};
        }
        chunk_range[begin / grain] = r;
    });
    Range range = chunk_range[0];
    for (const Range& r : chunk_range) {
        range = {std::min(range.y_min, r.y_min), std::max(range.y_max, r.y_max), std::min(range.z_min, r.z_min),
                 std::max(range.z_max, r.z_max)};
    }
    const Grid grid = chooseGrid(in_candidates, range);
    const std::size_t cells = grid.cells();
    const std::uint32_t slabs_z = grid.z.count();
    const auto forEachCell = [&](const CandidateTriangle& c, auto&& f) {
        const std::uint32_t y0 = grid.y(c.box[1]), y1 = grid.y(c.box[3]);
        const std::uint32_t z0 = grid.z(c.zmin), z1 = grid.z(c.zmax);
        for (std::uint32_t y = y0; y <= y1; ++y) {
            for (std::uint32_t z = z0; z <= z1; ++z) f(std::size_t{y} * slabs_z + z, (y == y0 ? 1u : 0u) | (z == z0 ? 2u : 0u));
        }
    };

    // Counting sort into cells, stable and parallel: each chunk counts its listings per
    // cell, a prefix sum (cell-major, chunk-minor) gives each chunk its slots.
    std::vector<std::size_t> slots(chunks * cells, 0);
    forChunks(pool, n, grain, [&](std::size_t begin, std::size_t end) {
        std::size_t* count = &slots[(begin / grain) * cells];
        for (std::size_t i = begin; i < end; ++i) forEachCell(in_candidates[i], [&](std::size_t cell, std::uint32_t) { ++count[cell]; });
    });
    cell_begin_.assign(cells + 1, 0);
    std::size_t total = 0;
    for (std::size_t cell = 0; cell < cells; ++cell) {
        cell_begin_[cell] = total;
        for (std::size_t c = 0; c < chunks; ++c) {
            const std::size_t count = slots[c * cells + cell];
            slots[c * cells + cell] = total;
            total += count;
        }
    }
    cell_begin_[cells] = total;

    // Scatter the entries (candidates read in order) with their sort keys: x0's bits made
    // orderable as an unsigned integer, then the position in the cell, which follows the
    // candidate index, so equal x0 keep index order and the sort needs no tie-break.
    // Plain arrays: every element is written before it is read, nothing to zero first.
    if (total > entry_capacity_) {
        entries_.reset(new Entry[total]);
        entry_capacity_ = total;
    }
    entry_count_ = total;
    const std::unique_ptr<Entry[]> unsorted(new Entry[total]);
    const std::unique_ptr<std::uint64_t[]> sort_keys(new std::uint64_t[total]);
    forChunks(pool, n, grain, [&](std::size_t begin, std::size_t end) {
        std::size_t* next = &slots[(begin / grain) * cells];
        for (std::size_t i = begin; i < end; ++i) {
            const CandidateTriangle& c = in_candidates[i];
            const std::uint64_t x_key = std::uint64_t{orderedBits(c.box[0])} << 32;
            Entry entry{c.box[0], c.box[2], c.box[1], c.box[3], c.zmin, c.zmax, static_cast<std::uint32_t>(i), 0,
                        {c.object, {c.vertex_index[0], c.vertex_index[1], c.vertex_index[2]}}};
            forEachCell(c, [&](std::size_t cell, std::uint32_t starts) {
                const std::size_t slot = next[cell]++;
                entry.starts = starts;
                unsorted[slot] = entry;
                sort_keys[slot] = x_key | (slot - cell_begin_[cell]);
            });
        }
    });

    // Sort each cell by (x0, index): small arrays of integer keys, then a gather within
    // the cell. Cells are independent, so this is parallel too.
    const std::size_t cell_grain = std::max<std::size_t>(1, cells / (threads * kTasksPerThread));
    forChunks(pool, cells, cell_grain, [&](std::size_t begin, std::size_t end) {
        for (std::size_t cell = begin; cell < end; ++cell) {
            const std::size_t first = cell_begin_[cell], last = cell_begin_[cell + 1];
            sortKeys(sort_keys.get() + first, sort_keys.get() + last);
            for (std::size_t k = first; k < last; ++k) entries_[k] = unsorted[first + (sort_keys[k] & 0xffffffffu)];
        }
    });
}

std::vector<IndexPair> sweepAndPrunePairs(std::span<const CandidateTriangle> in_candidates, ThreadPool* pool) {
    CellSweep sweep;
    sweep.build(in_candidates, pool);
    std::vector<IndexPair> pairs;
    sweep.sweepRange(0, sweep.entryCount(), [&](std::uint32_t i, std::uint32_t j) { pairs.push_back({i, j}); });
    std::sort(pairs.begin(), pairs.end());
    return pairs;
}

}  // namespace vkcollide::narrow
