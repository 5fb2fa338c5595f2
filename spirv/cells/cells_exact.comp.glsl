#version 460
#extension GL_GOOGLE_include_directive : require
// Cell pair stage, the exact pass (needs shaderFloat64): one invocation per candidate the
// pair pass queued in this chunk (CellsParams.exact_queue: canonical, not proved disjoint
// by the filter), decided exactly (cells_exact_decision.glsl.inc); the survivors, the
// intersecting pairs, are written as the pair pass writes its own (cells_survivors.glsl.inc).
#include "cells_common.glsl.inc"
#include "cells_geometry.glsl.inc"
#include "cells_candidate.glsl.inc"
#include "cells_exact_decision.glsl.inc"
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
        tested = 1u;
        CellsGeometryRef geo = CellsGeometryRef(P.geometry);
        keep = exactDecision(geo.g[c.x], geo.g[c.y], key_a, key_b, neighbour);
    }
    subgroupCount(headerField(P, kHeaderExactTests), tested);
    subgroupCount(headerField(P, kHeaderExactNeighbours), neighbour);
    writeSurvivor(P, keep, c.x, c.y, key_a, key_b);
}
