// The cell stage's counters (docs/reliable.md; the stage is src/broad/cells/): in the
// seam, so that the broad phase's result (BroadPhaseResult::cells) carries them without the
// stage's Vulkan types and the contract (broad_phase_types.hpp) includes no method's room.
#pragma once

#include <cstdint>

namespace vkcollide::passes {

struct CellStageStats {
    std::uint64_t entries = 0;        // footprints: (triangle, cell) pairs
    std::uint64_t box_cells = 0;      // cells of the footprint boxes (>= entries; the budget's first count)
    // The sweep's comparisons (the budget's second count): pairs of footprints sharing a
    // cell, in huge cells the sort's work, k per object in the cell and the pairs visited.
    std::uint64_t comparisons = 0;
    std::uint64_t big_triangles = 0;  // triangles counted and filled in work items
    std::uint64_t items = 0;
    std::uint64_t deep_cells = 0;     // cells with more than kCellsSmallCell entries
    std::uint64_t huge_cells = 0;     // of those, with more than kCellsDeepShared: sorted in global memory
    std::uint64_t max_cell = 0;       // most entries in one cell
    std::uint64_t candidate_cells = 0;  // cells where the sweep found at least one candidate
    std::uint64_t candidates = 0;     // pairs the sweep wrote (with duplicates across cells)
    // Overlapping pairs the sweep found but did not write, as repeats (not their canonical
    // cell) in the cells where it checks (CellsParams::sweep_dedupe entries or more). With
    // `candidates`: what the budget counts.
    std::uint64_t repeats = 0;
    std::uint64_t neighbours = 0;     // left out by the sweep (not candidates): one object, shared vertex index
    std::uint64_t duplicates = 0;     // dropped: not the pair's canonical cell (an earlier cell qualifies, or
                                      // their unquantised boxes are apart in this one)
    std::uint64_t filtered = 0;       // dropped: proved disjoint by the filter
    std::uint64_t survivors = 0;
    std::uint64_t gpu_triangles = 0;  // triangles of download objects in a survivor, written with their vertices
    std::uint64_t host_duplicates = 0;  // survivors kept twice (canonical scan out of budget), removed (run() only)
    std::uint32_t runs = 0;           // runs this call took (1 without overflow)
    std::uint32_t sweep_chunks = 0;   // submissions the last run's sweep took (CellStageSettings::sweep_work)
    std::uint32_t pair_chunks = 0;    // and its pair pass (CellStageSettings::pair_chunk)
    bool filter_ran = false;
    bool exact_ran = false;  // the pair pass decided exactly: survivors intersect
    std::uint64_t exact_tests = 0;  // candidates the exact test decided
    std::uint64_t exact_neighbours = 0;  // of those, left out as neighbours (bit-identical vertex)
    bool exact_queued = false;  // the exact decision ran as the exact pass (CellStageSettings::exact_pass)
};

}  // namespace vkcollide::passes
