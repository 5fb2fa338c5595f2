#version 460
#extension GL_GOOGLE_include_directive : require
// Cell pair stage, indirect dispatch arguments (one invocation), from the counters the
// previous pass left in the header; nothing to do (0 workgroups) once the run failed.
//   step 0, after setup: big-triangle work items (count and fill);
//   step 1, after the scan and before each later sweep chunk: the sweep's next chunk (one
//   workgroup per kCellsEntryChunk entries of it, whole ones) and its deep items, from
//   where the last chunk ended (0 after the header's clear), at most
//   CellsParams.sweep_work comparisons (a deep item counts kCellsGroupSize entries of a
//   sorted cell); whether more are left into the header (sweep_pending); none once the
//   comparisons passed the budget;
//   step 2 + k, after the sweep: every candidate (passes after the pair pass) and the pair
//   pass's chunk k (one invocation per candidate in it); the chunks so far into the header.
//   Nothing while sweep chunks are pending: the candidates are not all written yet. The
//   chunk's exact queue starts empty;
//   step kCellsArgsStepExact, after the pair pass's chunk: the exact pass over the
//   candidates it queued.
#include "cells_common.glsl.inc"
layout(local_size_x = 1) in;

uint groupsFor(uint n) { return (n + kCellsGroupSize - 1u) / kCellsGroupSize; }

void main() {
    CellsParams P = params();
    CellsHeader h = cellsHeader(P).h;
    bool failed = h.flags != 0u;
    if (pc.step == kCellsArgsStepExact) {
        writeDispatch(P, kCellsArgsExact, failed ? 0u : groupsFor(min(h.exact_queued, P.exact_queue_capacity)));
    } else if (pc.step == 0u) {
        writeDispatch(P, kCellsArgsBig, failed ? 0u : min(h.items, P.item_capacity));
    } else if (pc.step == 1u) {
        // A candidate overflow still sweeps on: the count sizes the rerun's buffer. The
        // comparisons grow while huge cells are swept: past the budget no chunk follows.
        if (h.comparisons > comparisonBudget(P)) {
            raiseFlag(P, kCellsOverBudget);
            h.flags |= kCellsOverBudget;
        }
        bool stop = (h.flags & ~kCellsOverflowCandidates) != 0u;
        uint entries = stop ? 0u : min(h.entries, P.entry_capacity), items = stop ? 0u : min(h.deep_items, P.deep_capacity);
        uint e0 = min(h.sweep_entries_end, entries), i0 = min(h.sweep_items_end, items);
        uint e1 = entries, i1 = items;
        if (P.sweep_work != ~0u) {
            uint deepest = max(h.max_cell, 1u);
            // Whole chunks: the shallow sweep's tiles are the cells that begin in one.
            uint chunk_entries = max(kCellsEntryChunk, P.sweep_work / min(deepest, kCellsSmallCell));
            e1 = e0 + min(entries - e0, chunk_entries - chunk_entries % kCellsEntryChunk);
            i1 = i0 + min(items - i0, max(1u, P.sweep_work / (kCellsGroupSize * min(deepest, kCellsDeepShared))));
        }
        CellsHeaderRef hr = cellsHeader(P);
        hr.h.sweep_entries_begin = e0;
        hr.h.sweep_entries_end = e1;
        hr.h.sweep_items_begin = i0;
        hr.h.sweep_items_end = i1;
        hr.h.sweep_pending = e1 < entries || i1 < items ? 1u : 0u;
        writeDispatch(P, kCellsArgsSweep, (e1 - e0 + kCellsEntryChunk - 1u) / kCellsEntryChunk);  // a tile each
        writeDispatch(P, kCellsArgsDeep, i1 - i0);
        writeDispatch(P, kCellsArgsSort, h.huge_cells > 0u ? i1 - i0 : 0u);
    } else {
        uint total = failed || h.sweep_pending != 0u ? 0u : uint(min(h.candidates, uint64_t(P.candidate_capacity)));
        uint first = (pc.step - 2u) * P.pair_chunk;  // at most total + pair_chunk < 2^32
        uint n = total > first ? min(total - first, P.pair_chunk) : 0u;
        writeDispatch(P, kCellsArgsPairs, groupsFor(total));
        writeDispatch(P, kCellsArgsPairChunk, groupsFor(n));
        if (!failed && h.sweep_pending == 0u) cellsHeader(P).h.pairs_done = first + n;
        cellsHeader(P).h.exact_queued = 0u;
    }
}
