#version 460
#extension GL_GOOGLE_include_directive : require
// Cell pair stage, fill (one invocation per triangle with a small clamped box): writes an
// entry (triangle, key, depth interval) into every cell the count pass counted it in.
// Big triangles are filled by cells_big.comp.
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
    if ((r.z - r.x + 1u) * (r.w - r.y + 1u) > kCellsSmallBox) return;
    vec4 box = paddedBox(tri);
    for (uint j = r.y; j <= r.w; ++j)
        for (uint i = r.x; i <= r.z; ++i) fillCell(P, tri, box, t, i, j);
}
