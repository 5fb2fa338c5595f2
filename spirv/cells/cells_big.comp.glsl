#version 460
#extension GL_GOOGLE_include_directive : require
// Cell pair stage, big triangles (one workgroup per work item (triangle, chunk)): the
// chunk's kCellsChunkCells cells of the triangle's clamped box, row-major, one per
// invocation at a time. Push.step 0 counts footprints (after cells_setup), 1 fills them
// (after the scan).
#include "cells_common.glsl.inc"
#include "cells_geometry.glsl.inc"
#include "cells_fill.glsl.inc"
layout(local_size_x = kCellsGroupSize) in;

void main() {
    CellsParams P = params();
    uint item = groupIndex();
    if (item >= min(cellsHeader(P).h.items, P.item_capacity) || runFailed(P)) return;
    uvec2 work = Uvec2sRef(P.big_items).v[item];
    CellsTriangle tri = CellsTrianglesRef(P.triangles).t[work.x];
    uvec4 r = cellsRange(tri);
    uint width = r.z - r.x + 1u, cells = width * (r.w - r.y + 1u);
    uint begin = work.y * kCellsChunkCells, end = min(begin + kCellsChunkCells, cells);
    vec4 box = paddedBox(tri);
    for (uint c = begin + gl_LocalInvocationIndex; c < end; c += kCellsGroupSize) {
        uint i = r.x + c % width, j = r.y + c / width;
        if (pc.step == 0u) {
            if (cellsCovers(tri, i, j, P.resolution)) atomicAdd(UintsRef(P.counts).v[j * P.resolution + i], 1u);
        } else {
            fillCell(P, tri, box, work.x, i, j);
        }
    }
}
