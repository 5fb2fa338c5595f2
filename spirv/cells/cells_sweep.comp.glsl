#version 460
#extension GL_GOOGLE_include_directive : require
// Cell pair stage, sweep of the shallow cells (one invocation per entry of a cell with at
// most kCellsSmallCell entries): each entry scanned against its cell (cells_sweep.glsl.inc).
// Deeper cells: cells_deep.comp.
// The canonical-cell rule needs no double precision (cells_candidate.glsl.inc).
#define CELLS_NO_FLOAT64 1
#include "cells_common.glsl.inc"
#include "cells_geometry.glsl.inc"
#include "cells_candidate.glsl.inc"
#include "cells_sweep.glsl.inc"
layout(local_size_x = kCellsGroupSize) in;

void main() {
    CellsParams P = params();
    // This chunk's entries (cells_args.comp, step 1).
    uint e = cellsHeader(P).h.sweep_entries_begin + globalIndex();
    uint total = min(cellsHeader(P).h.sweep_entries_end, min(cellsHeader(P).h.entries, P.entry_capacity));
    uint begin = 0u, end = 0u, cell = 0u;
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
        me = CellsEntriesRef(P.entries).e[e];
        if ((triangleKeyOf(P, me.key) & kCellsKeySelf) != 0u) mine = triangleIndices(P, me.triangle);
    }
    sweepEntry(P, cell, e, me, mine, begin, end, end - begin >= P.sweep_dedupe);
}
