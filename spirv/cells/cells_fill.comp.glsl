#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
// Cell pair stage, fill (one invocation per triangle with a small clamped box): writes an
// entry (triangle, key, depth interval) into every cell the count pass counted it in.
// Big triangles are filled by cells_big.comp. The form for GPUs (CellStageSettings::
// FillSlots::PerCell); cells_fill_per_footprint.comp is the other.
//
// A workgroup whose footprints crowd into few cells takes its slots per cell, not per
// footprint: it counts them per cell in a table in shared memory (cells_table.glsl.inc),
// takes each cell's slots with one atomic and places the footprints from there, so a
// cell's footprints from one workgroup land in consecutive slots, written together. Where
// they are spread out, the table would only add its steps (and overflow): each footprint
// takes its slot alone. Crowded: the workgroup's footprint boxes' cells, summed, reach
// twice the cells of the box around them all. Meshes whose index order follows the
// surface crowd; a mesh listing its triangles in scattered order does not.
#include "cells_common.glsl.inc"
#include "cells_geometry.glsl.inc"
#include "cells_fill.glsl.inc"
layout(local_size_x = kCellsGroupSize) in;

#include "cells_table.glsl.inc"
shared uint s_next[kTable];  // the next of the workgroup's slots in the cell to hand out
shared uint s_box[5];        // the workgroup's cells: x lo, y lo, x hi, y hi; footprint box cells summed

void main() {
    CellsParams P = params();
    uint t = globalIndex();
    tableClear();
    for (uint q = gl_LocalInvocationIndex; q < kTable; q += kCellsGroupSize) s_next[q] = 0u;
    if (gl_LocalInvocationIndex == 0u) s_box = uint[5](0xFFFFFFFFu, 0xFFFFFFFFu, 0u, 0u, 0u);
    bool live = t < P.triangle_count && !runFailed(P);
    CellsTriangle tri;
    uvec4 r = uvec4(1u, 1u, 0u, 0u);  // no cells
    uint box_cells = 0u;
    if (live) {
        tri = CellsTrianglesRef(P.triangles).t[t];
        r = cellsRange(tri);
        box_cells = (r.z - r.x + 1u) * (r.w - r.y + 1u);
        if (box_cells > kCellsSmallBox) r = uvec4(1u, 1u, 0u, 0u), box_cells = 0u;
    }
    barrier();
    bool mine = r.x <= r.z;
    uvec4 lo = subgroupMin(mine ? r : uvec4(0xFFFFFFFFu)), hi = subgroupMax(mine ? r : uvec4(0u));
    uint cells = subgroupAdd(box_cells);  // at most 64 per invocation
    if (subgroupElect() && cells > 0u) {
        atomicMin(s_box[0], lo.x);
        atomicMin(s_box[1], lo.y);
        atomicMax(s_box[2], hi.z);
        atomicMax(s_box[3], hi.w);
        atomicAdd(s_box[4], cells);
    }
    barrier();
    // Crowded: the footprint boxes' cells, summed, at least twice the cells around them all
    // (below 2^29: cells below 2^28).
    bool crowded = s_box[4] > 0u && (s_box[2] - s_box[0] + 1u) * (s_box[3] - s_box[1] + 1u) * 2u <= s_box[4];
    if (!crowded) {  // uniform: every invocation read the same words
        if (mine) fillPerFootprint(P, tri, t, r);
        return;
    }

    // The workgroup's footprints per cell.
    for (uint j = r.y; j <= r.w; ++j)
        for (uint i = r.x; i <= r.z; ++i)
            if (cellsCovers(tri, i, j, P.resolution)) {
                uint h = tableInsert(j * P.resolution + i);
                if (h != kMissing) atomicAdd(s_first[h], 1u);
            }
    barrier();

    // One atomic per cell of the table for the workgroup's slots there, the invocation's
    // places all read first so that their atomics are in flight together.
    const uint kPlaces = kTable / kCellsGroupSize;
    uint place_cell[kPlaces], place_count[kPlaces];
    [[unroll]] for (uint k = 0u; k < kPlaces; ++k) {
        place_cell[k] = s_cell[gl_LocalInvocationIndex + k * kCellsGroupSize];
        place_count[k] = s_first[gl_LocalInvocationIndex + k * kCellsGroupSize];
    }
    [[unroll]] for (uint k = 0u; k < kPlaces; ++k)
        if (place_cell[k] != kEmpty) s_first[gl_LocalInvocationIndex + k * kCellsGroupSize] = takeSlots(P, place_cell[k], place_count[k]);
    barrier();

    if (!mine) return;
    vec4 box = paddedBox(tri);
    CellsEntriesRef entries = CellsEntriesRef(P.entries);
    for (uint j = r.y; j <= r.w; ++j)
        for (uint i = r.x; i <= r.z; ++i) {
            uint h = tablePlace(j * P.resolution + i);
            if (h == kMissing) {
                fillCell(P, tri, box, t, i, j);
            } else if (s_first[h] != kCellsNoSlot && cellsCovers(tri, i, j, P.resolution)) {
                entries.e[s_first[h] + atomicAdd(s_next[h], 1u)] = cellsEntry(P, tri, box, t, i, j);  // its cell: written by the scan
            }
        }
}
