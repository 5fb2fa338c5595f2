#version 460
#extension GL_GOOGLE_include_directive : require
// Cell pair stage, fill (one invocation per triangle with a small clamped box), each
// footprint taking its own slot: the form for CPU implementations (CellStageSettings::
// FillSlots::PerFootprint), where cells_fill.comp's table costs more than it saves.
#include "cells_common.glsl.inc"
#include "cells_geometry.glsl.inc"
#include "cells_fill.glsl.inc"
layout(local_size_x = kCellsGroupSize) in;

void main() {
    CellsParams P = params();
    uint t = globalIndex();
    if (t >= P.triangle_count || runFailed(P)) return;
    CellsTriangle tri = CellsTrianglesRef(P.triangles).t[t];
    uvec4 r = cellsRange(tri);
    if ((r.z - r.x + 1u) * (r.w - r.y + 1u) <= kCellsSmallBox) fillPerFootprint(P, tri, t, r);
}
