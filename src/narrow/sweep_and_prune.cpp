#include "narrow/sweep_and_prune.hpp"

#include "common/config.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>

namespace vkcollide::narrow {
namespace {


struct Range {
    float lo[3], hi[3];
};

double medianOf(std::vector<float>& v) {
    const auto middle = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
    std::nth_element(v.begin(), middle, v.end());
    return double(*middle);
}

BoxZ boxOf(const SweepInput& in, std::size_t slot) { return in.box[in.record_of ? in.record_of[slot] : slot]; }

// Cell states while filling a tile.
constexpr std::uint8_t kEmpty = 0, kMixed = 2, kSelf = 4;

}  // namespace

namespace sweep_detail {

std::uint32_t orderedBits(float x) noexcept {
    x += 0.0f;  // -0 -> +0
    std::uint32_t bits;
    std::memcpy(&bits, &x, sizeof bits);
    return (bits & 0x80000000u) ? ~bits : (bits | 0x80000000u);
}

}  // namespace sweep_detail

std::size_t GridSweep::cellCount() const noexcept {
    return std::size_t{axis_[0].count()} * axis_[1].count() * axis_[2].count();
}

GridSweep::CellRange GridSweep::cellsOf(const Entry& e) const noexcept {
    CellRange r;
#if defined(__SSE2__)
    // (x0, x1, y0, y1) at once, then (z0, z1): the same float operations as Axis.
    const __m128 xy = _mm_loadu_ps(&e.x0);
    const __m128 origin = _mm_setr_ps(axis_[0].origin, axis_[0].origin, axis_[1].origin, axis_[1].origin);
    const __m128 scale = _mm_setr_ps(axis_[0].scale, axis_[0].scale, axis_[1].scale, axis_[1].scale);
    const __m128 last = _mm_setr_ps(axis_[0].last_slab, axis_[0].last_slab, axis_[1].last_slab, axis_[1].last_slab);
    alignas(16) std::int32_t c[4];
    _mm_store_si128(reinterpret_cast<__m128i*>(c), _mm_cvttps_epi32(_mm_min_ps(_mm_mul_ps(_mm_sub_ps(xy, origin), scale), last)));
    r.lo[0] = static_cast<std::uint32_t>(c[0]), r.hi[0] = static_cast<std::uint32_t>(c[1]);
    r.lo[1] = static_cast<std::uint32_t>(c[2]), r.hi[1] = static_cast<std::uint32_t>(c[3]);
#else
    r.lo[0] = axis_[0](e.x0), r.hi[0] = axis_[0](e.x1), r.lo[1] = axis_[1](e.y0), r.hi[1] = axis_[1](e.y1);
#endif
    r.lo[2] = axis_[2](e.z0), r.hi[2] = axis_[2](e.z1);
    return r;
}

GridSweep::CellRange GridSweep::cellsOf(const BoxZ& b) const noexcept {
    CellRange r;
#if defined(__SSE2__)
    // (x0, y0, x1, y1) at once: the same float operations as Axis.
    const __m128 lanes = _mm_loadu_ps(&b.x0);
    const __m128 origin = _mm_setr_ps(axis_[0].origin, axis_[1].origin, axis_[0].origin, axis_[1].origin);
    const __m128 scale = _mm_setr_ps(axis_[0].scale, axis_[1].scale, axis_[0].scale, axis_[1].scale);
    const __m128 last = _mm_setr_ps(axis_[0].last_slab, axis_[1].last_slab, axis_[0].last_slab, axis_[1].last_slab);
    alignas(16) std::int32_t c[4];
    _mm_store_si128(reinterpret_cast<__m128i*>(c), _mm_cvttps_epi32(_mm_min_ps(_mm_mul_ps(_mm_sub_ps(lanes, origin), scale), last)));
    r.lo[0] = static_cast<std::uint32_t>(c[0]), r.lo[1] = static_cast<std::uint32_t>(c[1]);
    r.hi[0] = static_cast<std::uint32_t>(c[2]), r.hi[1] = static_cast<std::uint32_t>(c[3]);
#else
    r.lo[0] = axis_[0](b.x0), r.hi[0] = axis_[0](b.x1), r.lo[1] = axis_[1](b.y0), r.hi[1] = axis_[1](b.y1);
#endif
    r.lo[2] = axis_[2](b.z0), r.hi[2] = axis_[2](b.z1);
    return r;
}

void GridSweep::build(const SweepInput& in, Executor* executor) {
    const std::size_t n = in.count;
    entry_count_ = 0;
    tile_count_ = 0;
    for (Axis& a : axis_) a = Axis{};
    tile_begin_.resize(1);
    tile_begin_[0] = 0;
    if (n == 0) return;
    CallbackExecutor serial(1, {});
    Executor& ex = executor ? *executor : serial;

    // The ranges (per task, then combined), unless the caller has them.
    Range range{{in.range_lo[0], in.range_lo[1], in.range_lo[2]}, {in.range_hi[0], in.range_hi[1], in.range_hi[2]}};
    if (!in.has_range) {
        const std::size_t grain = grainFor(n, ex.threadCount(), 4, 4096, 1u << 20);
        std::vector<Range> task_range(taskCount(n, grain));
        ex.parallelFor(n, grain, [&](std::size_t begin, std::size_t end) {
            const BoxZ first = boxOf(in, begin);
            Range r{{first.x0, first.y0, first.z0}, {first.x1, first.y1, first.z1}};
            for (std::size_t i = begin; i < end; ++i) {
                const BoxZ b = boxOf(in, i);
                const float lo[3] = {b.x0, b.y0, b.z0}, hi[3] = {b.x1, b.y1, b.z1};
                for (int a = 0; a < 3; ++a) r.lo[a] = std::min(r.lo[a], lo[a]), r.hi[a] = std::max(r.hi[a], hi[a]);
            }
            task_range[begin / grain] = r;
        });
        range = task_range[0];
        for (const Range& r : task_range) {
            for (int a = 0; a < 3; ++a) range.lo[a] = std::min(range.lo[a], r.lo[a]), range.hi[a] = std::max(range.hi[a], r.hi[a]);
        }
    }

    // Slabs per axis: cells of kGridCellExtent(X) median boxes, at most one cell per box
    // (shrunk alike on all axes), then coarser while the sample says boxes would be listed
    // too often (on the axis whose boxes span most slabs).
    const std::size_t step = std::max<std::size_t>(1, n / kGridSampleSize);
    double extent[3], slabs[3];
    {
        std::vector<float> sizes[3];
        for (std::size_t i = 0; i < n; i += step) {
            const BoxZ b = boxOf(in, i);
            sizes[0].push_back(b.x1 - b.x0);
            sizes[1].push_back(b.y1 - b.y0);
            sizes[2].push_back(b.z1 - b.z0);
        }
        double product = 1;
        for (int a = 0; a < 3; ++a) {
            extent[a] = double(range.hi[a] - range.lo[a]);  // as the slab map computes it, in float
            const double cell = (a == 0 ? kGridCellExtentX : kGridCellExtent) * medianOf(sizes[a]);
            slabs[a] = !(extent[a] > 0) ? 1.0 : std::clamp(cell > 0 ? std::ceil(extent[a] / cell) : kGridMaxSlabs, 1.0, kGridMaxSlabs);
            product *= slabs[a];
        }
        const double max_cells = double(n);
        if (product > max_cells) {
            const double f = std::cbrt(max_cells / product);
            for (double& s : slabs) s = std::max(1.0, std::floor(s * f));
        }
    }
    const auto setAxes = [&] {
        for (int a = 0; a < 3; ++a) {
            Axis& axis = axis_[a];
            // A range too small for a float scale (denormal extents) gets one slab.
            const double scale = extent[a] > 0 ? slabs[a] / extent[a] : 0;
            if (!(scale < 1e30)) slabs[a] = 1;
            axis.origin = range.lo[a];
            axis.last = static_cast<std::uint32_t>(slabs[a]) - 1;
            axis.last_slab = static_cast<float>(axis.last);
            axis.scale = slabs[a] > 1 ? static_cast<float>(scale) : 0.0f;
        }
    };
    const auto coarsen = [&](const double span[3]) {
        int axis = -1;
        for (int a = 0; a < 3; ++a) {
            if (slabs[a] > 1 && (axis < 0 || span[a] > span[axis])) axis = a;
        }
        if (axis < 0) return false;
        slabs[axis] = std::ceil(slabs[axis] / 2);
        return true;
    };
    setAxes();
    for (;;) {
        double listings = 0, span[3] = {0, 0, 0};
        std::size_t sampled = 0;
        for (std::size_t i = 0; i < n; i += step, ++sampled) {
            const BoxZ b = boxOf(in, i);
            const double sx = axis_[0](b.x1) - axis_[0](b.x0) + 1, sy = axis_[1](b.y1) - axis_[1](b.y0) + 1,
                         sz = axis_[2](b.z1) - axis_[2](b.z0) + 1;
            listings += sx * sy * sz;
            span[0] += sx, span[1] += sy, span[2] += sz;
        }
        if (listings <= kGridMaxListingsPerBox * double(sampled) || !coarsen(span)) break;
        setAxes();
    }
    // The sample can miss a few huge boxes: the exact count decides (coarser until it fits;
    // a 1 x 1 x 1 grid always does).
    const std::size_t max_cell_listings = kGridHardListingsPerBox * n + 1024;
    while (!listInTiles(in, ex, max_cell_listings)) {
        const double span[3] = {slabs[0], slabs[1], slabs[2]};
        if (!coarsen(span)) break;
        setAxes();
    }
}

bool GridSweep::listInTiles(const SweepInput& in, Executor& ex, std::size_t max_cell_listings) {
    const std::size_t n = in.count;
    // Tiles: cubes of 2^s cells a side, about n / kGridBoxesPerTile of them (a surface
    // crosses a cube of k^3 cells in about k^2 of them), at most kGridMaxTileCells cells each.
    {
        const double target = std::clamp<double>(double(n) / kGridBoxesPerTile, 1, kGridMaxTiles);
        const double side = std::max(1.0, std::cbrt(double(cellCount()) / target));
        std::uint32_t shift = 0;
        while (shift < 5 && double(2u << shift) <= side) ++shift;
        for (int a = 0; a < 3; ++a) {
            std::uint32_t sa = shift;
            while (sa > 0 && (1u << (sa - 1)) >= axis_[a].count()) --sa;  // no wider than the axis
            tile_shift_[a] = sa;
            tiles_[a] = ((axis_[a].count() - 1) >> sa) + 1;
        }
    }
    const std::size_t tiles = std::size_t{tiles_[0]} * tiles_[1] * tiles_[2];
    const std::size_t grain = grainFor(n, ex.threadCount(), 2, kGridMinListGrain, std::size_t(1) << 30);
    const std::size_t tasks = taskCount(n, grain);
    const auto forTiles = [&](const CellRange& r, auto&& f) {
        const std::uint32_t x0 = r.lo[0] >> tile_shift_[0], x1 = r.hi[0] >> tile_shift_[0];
        const std::uint32_t y0 = r.lo[1] >> tile_shift_[1], y1 = r.hi[1] >> tile_shift_[1];
        const std::uint32_t z0 = r.lo[2] >> tile_shift_[2], z1 = r.hi[2] >> tile_shift_[2];
        for (std::uint32_t tz = z0; tz <= z1; ++tz) {
            for (std::uint32_t ty = y0; ty <= y1; ++ty) {
                const std::size_t row = (std::size_t{tz} * tiles_[1] + ty) * tiles_[0];
                for (std::uint32_t tx = x0; tx <= x1; ++tx) f(row + tx);
            }
        }
    };
    const bool uniform_self = !in.options || in.options->self_collision.empty();
    const std::uint32_t default_self = (!in.options || in.options->default_self_collision) ? 8u : 0u;
    const auto entryOf = [&](std::size_t i) {
        const BoxZ b = boxOf(in, i);
        const std::uint32_t object = in.object[i];
        const std::uint32_t self = uniform_self ? default_self : (in.options->selfCollides(object) ? 8u : 0u);
        return Entry{b.x0, b.x1, b.y0, b.y1, b.z0, b.z1, (static_cast<std::uint32_t>(i) << 4) | self, object};
    };

    // Per task and tile, the boxes listed; per task, the cell listings (to bound them).
    counts_.resize(tasks * tiles);
    std::vector<std::size_t> cell_listings(tasks, 0);
    ex.parallelFor(n, grain, [&](std::size_t begin, std::size_t end) {
        std::uint32_t* count = &counts_[(begin / grain) * tiles];
        std::fill(count, count + tiles, 0u);
        std::size_t listed = 0;
        for (std::size_t i = begin; i < end; ++i) {
            const CellRange r = cellsOf(boxOf(in, i));
            listed += std::size_t{r.hi[0] - r.lo[0] + 1} * (r.hi[1] - r.lo[1] + 1) * (r.hi[2] - r.lo[2] + 1);
            forTiles(r, [&](std::size_t t) { ++count[t]; });
        }
        cell_listings[begin / grain] = listed;
    });
    std::size_t total_cell_listings = 0;
    for (const std::size_t c : cell_listings) total_cell_listings += c;
    if (total_cell_listings > max_cell_listings && cellCount() > 1) return false;
    // Exclusive prefix sums, tile-major and task-minor, so each tile lists its boxes in
    // slot order: tile totals in parallel, a scan over tiles, the offsets in parallel.
    tile_begin_.resize(tiles + 1);
    const std::size_t tile_grain = std::max<std::size_t>(256, tiles / (std::size_t{ex.threadCount()} * 4));
    ex.parallelFor(tiles, tile_grain, [&](std::size_t first, std::size_t last) {
        for (std::size_t t = first; t < last; ++t) {
            std::uint64_t sum = 0;
            for (std::size_t k = 0; k < tasks; ++k) sum += counts_[k * tiles + t];
            tile_begin_[t] = static_cast<std::uint32_t>(std::min<std::uint64_t>(sum, std::numeric_limits<std::uint32_t>::max()));
        }
    });
    std::uint64_t total = 0;
    for (std::size_t t = 0; t < tiles; ++t) {
        const std::uint64_t here = tile_begin_[t];
        tile_begin_[t] = static_cast<std::uint32_t>(std::min<std::uint64_t>(total, std::numeric_limits<std::uint32_t>::max()));
        total += here;
    }
    if (total > std::numeric_limits<std::uint32_t>::max() - 1) return false;
    tile_begin_[tiles] = static_cast<std::uint32_t>(total);
    ex.parallelFor(tiles, tile_grain, [&](std::size_t first, std::size_t last) {
        for (std::size_t t = first; t < last; ++t) {
            std::uint32_t offset = tile_begin_[t];
            for (std::size_t k = 0; k < tasks; ++k) {
                const std::uint32_t here = counts_[k * tiles + t];
                counts_[k * tiles + t] = offset;
                offset += here;
            }
        }
    });
    tile_count_ = tiles;
    entry_count_ = total;
    entries_.resize(total);
    ex.parallelFor(n, grain, [&](std::size_t begin, std::size_t end) {
        std::uint32_t* next = &counts_[(begin / grain) * tiles];
        for (std::size_t i = begin; i < end; ++i) {
            const Entry e = entryOf(i);
            forTiles(cellsOf(e), [&](std::size_t t) { entries_[next[t]++] = e; });
        }
    });
    return true;
}

void GridSweep::fillTile(std::size_t tile, TileCells& out) const {
    out.begin.assign(1, 0);
    out.entries.clear();
    const Entry* const list = entries_.data() + tile_begin_[tile];
    const std::size_t listed = tile_begin_[tile + 1] - tile_begin_[tile];
    // A tile of one object that does not self-collide has no pair: skip it at once.
    {
        bool any = false;
        for (std::size_t k = 1; k < listed && !any; ++k) any = list[k].object != list[0].object;
        if (listed < 2 || (!any && (list[0].slot_flags & 8) == 0)) return;
    }
    std::uint32_t base[3], size[3];
    {
        std::size_t t = tile;
        for (int a = 0; a < 3; ++a) {
            const std::uint32_t index = static_cast<std::uint32_t>(t % tiles_[a]);
            t /= tiles_[a];
            base[a] = index << tile_shift_[a];
            size[a] = std::min(1u << tile_shift_[a], axis_[a].count() - base[a]);
        }
    }
    const std::size_t cells = std::size_t{size[0]} * size[1] * size[2];
    out.count.assign(cells, 0);
    out.state.assign(cells, kEmpty);
    out.first_object.resize(cells);
    out.ranges.resize(listed);
    // Each entry's cells within this tile, as local ranges, and its starts bits there
    // (cell index x fastest, then y, then z).
    const auto forCells = [&](const CellRange& r, auto&& f) {
        for (std::uint32_t cz = r.lo[2]; cz <= r.hi[2]; ++cz) {
            for (std::uint32_t cy = r.lo[1]; cy <= r.hi[1]; ++cy) {
                const std::size_t row = (std::size_t{cz} * size[1] + cy) * size[0];
                for (std::uint32_t cx = r.lo[0]; cx <= r.hi[0]; ++cx) f(row + cx);
            }
        }
    };
    // Count, and note which cells hold one object only and whether it self-collides.
    for (std::size_t k = 0; k < listed; ++k) {
        const Entry& e = list[k];
        const CellRange global = cellsOf(e);
        CellRange& r = out.ranges[k];
        for (int a = 0; a < 3; ++a) {
            r.lo[a] = std::max(global.lo[a], base[a]) - base[a];
            r.hi[a] = std::min(global.hi[a], base[a] + size[a] - 1) - base[a];
        }
        // The starts bits live in the high bits of lo[0] (below 2^5 cells per axis).
        const std::uint32_t starts = (global.lo[0] >= base[0] ? 1u : 0u) | (global.lo[1] >= base[1] ? 2u : 0u) |
                                     (global.lo[2] >= base[2] ? 4u : 0u);
        r.lo[0] |= starts << 16;
        const std::uint8_t self = (e.slot_flags & 8) ? kSelf : 0;
        CellRange clipped = r;
        clipped.lo[0] &= 0xffff;
        forCells(clipped, [&](std::size_t c) {
            const std::uint32_t first = out.count[c]++ == 0 ? e.object : out.first_object[c];
            out.first_object[c] = first;
            out.state[c] = static_cast<std::uint8_t>(out.state[c] | self | (first != e.object ? kMixed : 0));
        });
    }
    // Active cells: two boxes or more, of two objects or of a self-colliding one. Their
    // positions replace the counts (inactive cells get the marker kSkip).
    constexpr std::uint32_t kSkip = std::numeric_limits<std::uint32_t>::max();
    std::uint32_t total = 0;
    for (std::size_t c = 0; c < cells; ++c) {
        const std::uint32_t here = out.count[c];
        if (here >= 2 && (out.state[c] & (kMixed | kSelf))) {
            out.count[c] = total;
            total += here;
            out.begin.push_back(total);
        } else {
            out.count[c] = kSkip;
        }
    }
    out.entries.resize(total);
    for (std::size_t k = 0; k < listed; ++k) {
        const Entry& e = list[k];
        CellRange r = out.ranges[k];
        // An entry starts in a cell along an axis in the first cell of its range, if that
        // is its global first cell (not clipped by the tile).
        const std::uint32_t starts = r.lo[0] >> 16;
        r.lo[0] &= 0xffff;
        for (std::uint32_t cz = r.lo[2]; cz <= r.hi[2]; ++cz) {
            const std::uint32_t starts_z = (cz == r.lo[2] && (starts & 4)) ? 4u : 0u;
            for (std::uint32_t cy = r.lo[1]; cy <= r.hi[1]; ++cy) {
                const std::uint32_t starts_yz = starts_z | ((cy == r.lo[1] && (starts & 2)) ? 2u : 0u);
                const std::size_t row = (std::size_t{cz} * size[1] + cy) * size[0];
                for (std::uint32_t cx = r.lo[0]; cx <= r.hi[0]; ++cx) {
                    std::uint32_t& next = out.count[row + cx];
                    if (next == kSkip) continue;
                    Entry& o = out.entries[next++];
                    o = e;
                    o.slot_flags |= starts_yz | ((cx == r.lo[0] && (starts & 1)) ? 1u : 0u);
                }
            }
        }
    }
}

void GridSweep::build(std::span<const CandidateTriangle> in_candidates, Executor* executor) {
    SweepInput in;
    in.count = in_candidates.size();
    if (!in_candidates.empty()) {
        in.box = {reinterpret_cast<const BoxZ*>(&in_candidates[0].box[0]), sizeof(CandidateTriangle)};
        in.object = {&in_candidates[0].object, sizeof(CandidateTriangle)};
    }
    build(in, executor);
}

std::vector<IndexPair> sweepAndPrunePairs(std::span<const CandidateTriangle> in_candidates, Executor* executor) {
    GridSweep sweep;
    sweep.build(in_candidates, executor);
    std::vector<IndexPair> pairs;
    GridSweep::TileCells cells;
    sweep.sweepTiles(0, sweep.tileCount(), cells, [&](std::uint32_t i, std::uint32_t j) { pairs.push_back({i, j}); });
    std::sort(pairs.begin(), pairs.end());
    return pairs;
}

}  // namespace vkcollide::narrow
