#version 460
#extension GL_GOOGLE_include_directive : require
// Cell pair stage, the exact pass (needs shaderFloat64): one invocation per candidate the
// pair pass queued in this chunk (CellsParams.exact_queue: canonical, not proved disjoint
// by the filter). It makes the CPU narrow phase's decision on the CPU's world vertices
// (docs/exact_gpu.md): a pair of one object with a bit-identical world vertex is
// neighbours (the sweep already left out a shared vertex index), else the exact test
// (tritri_exact.glsl.inc) decides. Survivors, the intersecting pairs, are written as the
// pair pass writes its own (cells_survivors.glsl.inc).
#include "cells_common.glsl.inc"
#include "cells_geometry.glsl.inc"
#include "cells_candidate.glsl.inc"
#include "exact_predicates.glsl.inc"
#include "tritri_exact.glsl.inc"
#include "cells_survivors.glsl.inc"
layout(local_size_x = kCellsGroupSize) in;

void main() {
    CellsParams P = params();
    uint id = globalIndex();
    uint total = min(cellsHeader(P).h.exact_queued, P.exact_queue_capacity);
    bool keep = false;
    uint tested = 0u, neighbour = 0u;
    uvec2 c = uvec2(0u);
    uint key_a = 0u, key_b = 0u;
    if (id < total) {
        c = Uvec2sRef(P.exact_queue).v[id];
        CellsTrianglesRef tris = CellsTrianglesRef(P.triangles);
        key_a = tris.t[c.x].key;
        key_b = tris.t[c.y].key;
        CellsGeometryRef geo = CellsGeometryRef(P.geometry);
        CellsGeometry ga = geo.g[c.x], gb = geo.g[c.y];
        vec3 wa[3], wb[3];
        worldTriangle(ga, wa);
        worldTriangle(gb, wb);
        tested = 1u;
        // One object's triangles reach here only when it collides with itself and they
        // share no vertex index (the sweep's half of the rule); a bit-identical world
        // vertex is the rest.
        if ((key_a & kCellsKeyObject) == (key_b & kCellsKeyObject) &&
            exactNeighbours(uvec3(ga.index[0], ga.index[1], ga.index[2]), wa, uvec3(gb.index[0], gb.index[1], gb.index[2]), wb)) {
            neighbour = 1u;
        } else {
            keep = exactTrianglesIntersect(wa, wb);
        }
    }
    subgroupCount(headerField(P, kHeaderExactTests), tested);
    subgroupCount(headerField(P, kHeaderExactNeighbours), neighbour);
    writeSurvivor(P, keep, c.x, c.y, key_a, key_b);
}
