#version 460
#extension GL_GOOGLE_include_directive : require
// Cell pair stage, indirect dispatch arguments (one invocation), from the counters the
// previous pass left in the header; nothing to do (0 workgroups) once the run failed.
//   step 0, after setup: big-triangle work items (count and fill);
//   step 1, after the scan: the sweep (one invocation per entry) and the deep cells;
//   step 2, after the sweep: the pair pass (one invocation per candidate).
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
        writeDispatch(P, kCellsArgsPairs, failed ? 0u : groupsFor(uint(min(h.candidates, uint64_t(P.candidate_capacity)))));
    }
}
