#version 460
#extension GL_GOOGLE_include_directive : require
// Cell pair stage, sweep of the shallow cells (one invocation per entry of a cell with at
// most kCellsSmallCell entries): the entry pairs with every entry of its cell that starts
// after it -- by (zlo, entry index), so each pair is taken once -- no later than it ends,
// whose objects may collide and that is not its neighbour (one object, a shared vertex
// index). A pass counts, one atomic per subgroup reserves, a second pass writes
// (a < b, cell). Deeper cells: cells_deep.comp.
#include "cells_common.glsl.inc"
layout(local_size_x = kCellsGroupSize) in;

void main() {
    CellsParams P = params();
    uint e = globalIndex();
    uint total = min(cellsHeader(P).h.entries, P.entry_capacity);
    CellsEntriesRef entries = CellsEntriesRef(P.entries);
    uint begin = 0u, end = 0u, cell = 0u, n = 0u, neighbours = 0u;
    CellsEntry me;
    uvec3 mine = uvec3(~0u);
    if (e < total) {
        cell = UintsRef(P.entry_cells).v[e];
        // Never with matching count and fill passes; a guard, so a bug cannot read out of bounds.
        if (cell >= P.cell_count) {
            atomicOr(cellsHeader(P).h.flags, kCellsInconsistent);
            cell = 0u;
        }
        begin = UintsRef(P.offsets).v[cell];
        end = UintsRef(P.offsets).v[cell + 1u];
        if (end - begin > kCellsSmallCell) end = begin;
        me = entries.e[e];
        if ((me.key & kCellsKeySelf) != 0u) mine = triangleIndices(P, me.triangle);
    }
    for (uint j = begin; j < end; ++j) {
        CellsEntry o = entries.e[j];
        bool after = o.zlo > me.zlo || (o.zlo == me.zlo && j > e);
        if (after && o.zlo <= me.zhi && sweepPair(P, me.key, mine, o.key, o.triangle, neighbours)) ++n;
    }
    subgroupCount(headerField(P, kHeaderNeighbours), neighbours);
    subgroupCount(headerField(P, kHeaderCandidateCells), markCandidateCell(P, cell, n));
    // n < 2^19: the scan let the sweep run, so no cell holds more than 2^19 entries
    // (kCellsComparisonsPerBudget * budget < 2^37 pairs); totals stay far below 2^32.
    uint64_t slot = subgroupAppend64(headerField(P, kHeaderCandidates), n);
    if (n == 0u) return;
    if (slot >= uint64_t(P.candidate_capacity)) {  // none fits: the run is void, skip the second scan
        raiseFlag(P, kCellsOverflowCandidates);
        return;
    }
    CellsCandidatesRef out_pairs = CellsCandidatesRef(P.candidates);
    for (uint j = begin; j < end; ++j) {
        CellsEntry o = entries.e[j];
        bool after = o.zlo > me.zlo || (o.zlo == me.zlo && j > e);
        if (after && o.zlo <= me.zhi && sweepPair(P, me.key, mine, o.key, o.triangle, neighbours)) {
            if (slot < uint64_t(P.candidate_capacity)) {
                CellsCandidate c;
                c.a = min(me.triangle, o.triangle);
                c.b = max(me.triangle, o.triangle);
                c.cell = cell;
                out_pairs.c[uint(slot)] = c;
            } else {
                atomicOr(cellsHeader(P).h.flags, kCellsOverflowCandidates);
            }
            ++slot;
        }
    }
}
