#version 460
#extension GL_GOOGLE_include_directive : require
// Cell pair stage, indirect dispatch arguments (one invocation), from the counters the
// previous pass left in the header; nothing to do (0 workgroups) once the run failed.
//   step 0, after setup: big-triangle work items (count and fill);
//   step 1, after the scan: the sweep (one invocation per entry) and the deep cells;
//   step 2 + k, after the sweep: every candidate (passes after the pair pass) and the pair
//   pass's chunk k (one invocation per candidate in it); the chunks so far into the header.
#include "cells_common.glsl.inc"
layout(local_size_x = 1) in;

uint groupsFor(uint n) { return (n + kCellsGroupSize - 1u) / kCellsGroupSize; }

void main() {
    CellsParams P = params();
    CellsHeader h = cellsHeader(P).h;
    bool failed = h.flags != 0u;
    if (pc.step == 0u) {
        writeDispatch(P, kCellsArgsBig, failed ? 0u : min(h.items, P.item_capacity));
    } else if (pc.step == 1u) {
        writeDispatch(P, kCellsArgsSweep, failed ? 0u : groupsFor(h.entries));
        writeDispatch(P, kCellsArgsDeep, failed ? 0u : min(h.deep_items, P.deep_capacity));
    } else {
        uint total = failed ? 0u : uint(min(h.candidates, uint64_t(P.candidate_capacity)));
        uint first = (pc.step - 2u) * P.pair_chunk;  // at most total + pair_chunk < 2^32
        uint n = total > first ? min(total - first, P.pair_chunk) : 0u;
        writeDispatch(P, kCellsArgsPairs, groupsFor(total));
        writeDispatch(P, kCellsArgsPairChunk, groupsFor(n));
        if (!failed) cellsHeader(P).h.pairs_done = first + n;
    }
}
