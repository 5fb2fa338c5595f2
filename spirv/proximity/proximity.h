// Data shared by the proximity pass's shader (GLSL) and its host side (C++, src/proximity/):
// the record layout (vkcollide::ProximityPair, include/vkcollide/proximity.hpp), header and
// parameters. docs/proximity.md has the method and why no pair within the distance is
// left out.
#ifndef VKCOLLIDE_PROXIMITY_H
#define VKCOLLIDE_PROXIMITY_H

#include "cells/cells.h"

#ifdef __cplusplus
namespace vkcollide::gpu {
#endif

// ProximityRecord.kind (vkcollide::ProximityKind).
VKC_CONST kProximityVertexTriangle = 0u;
VKC_CONST kProximityEdgeEdge = 1u;
// ProximityRecord.flags (vkcollide::kProximity*).
VKC_CONST kProximityInBand = 1u;  // the computed distance is within its error bound of d: it may be beyond d

// ProximityHeader.flags
VKC_CONST kProximityOverflow = 1u;    // needed > capacity: the records past the capacity were not written
VKC_CONST kProximityIncomplete = 2u;  // the cell stage's run failed or has chunks left (runComplete): count 0
VKC_CONST kProximityLoopLimit = 4u;   // a bucket needs more loop iterations than CellsParams.loop_guard: failed

// Owned primitives of a triangle (ProximityParams.owned, one byte per global triangle):
// bit k: its vertex k (index[k]) is owned by it; bit 3 + k: its edge k (index[k] to
// index[(k + 1) % 3]). A vertex's or edge's owner is the lowest-numbered triangle of its
// object that has it, so every vertex-triangle and edge-edge pair comes from exactly one
// candidate triangle pair: (owner of the vertex, the triangle) or (owners of the two edges).
VKC_CONST kProximityOwnedVertices = 7u;
VKC_CONST kProximityOwnedEdges = 56u;

// One pair within the distance (64 bytes; the public vkcollide::ProximityPair).
struct ProximityRecord {
    uint kind;        // kProximityVertexTriangle or kProximityEdgeEdge
    uint flags;       // kProximityInBand
    uint object_a;    // object ids as the API returns them
    uint object_b;
    uint a0, a1;      // vertex-triangle: the vertex, ~0u; edge-edge: edge a's vertices (a0 < a1)
    uint b0, b1;      // vertex-triangle: the triangle, ~0u; edge-edge: edge b's vertices (b0 < b1)
    float distance;   // world units
    float weight_a;   // edge-edge: closest point of a = (1 - weight_a) a0 + weight_a a1; else 0
    float weights_b[3];  // closest point of b: barycentric on the triangle's vertices in their
                         // index order, or on edge b (1 - t, t, 0)
    float normal[3];  // unit, from b's closest point towards a's
};

struct ProximityHeader {
    uint count;     // records written: min(needed, capacity)
    uint needed;    // pairs found
    uint flags;     // kProximityOverflow, kProximityIncomplete
    uint capacity;  // records the buffer holds
    uint pairs_tested;   // candidate triangle pairs the pass examined (canonical cells only)
    uint distances;      // primitive pairs whose distance was computed
    uint neighbours;     // primitive pairs left out by the neighbour rule
    uint in_band;        // records flagged kProximityInBand
};

struct ProximityParams {
    VKC_ADDRESS(uint64_t) cells;        // CellsParams of the run (candidates, triangles, geometry, objects)
    VKC_ADDRESS(uint64_t) owned;        // uint8[triangle_count] packed in uints (kProximityOwned*)
    VKC_ADDRESS(uint64_t) object_ids;   // uint[object_count]: the id each object has in the result (ascending)
    VKC_ADDRESS(uint64_t) vertex_base;  // uint[object_count]: the vertices of the objects before it
    VKC_ADDRESS(uint64_t) header;       // ProximityHeader
    VKC_ADDRESS(uint64_t) records;      // ProximityRecord[capacity], as the pass found them
    VKC_ADDRESS(uint64_t) sorted;       // ProximityRecord[capacity], in the result's order
    VKC_ADDRESS(uint64_t) order;        // uvec4[capacity]: (sort key, record index), bucketed, then sorted
    VKC_ADDRESS(uint64_t) args;         // VkDispatchIndirectCommand: one invocation per record found
    VKC_ADDRESS(uint64_t) counts;       // uint[bucket_count]: records per bucket, then the cursor
    VKC_ADDRESS(uint64_t) offsets;      // uint[bucket_count + 1]: each bucket's first slot
    VKC_ADDRESS(uint64_t) block_sums;   // uint[block_count]
    double distance;                    // d, world units
    uint capacity;
    uint object_count;
    uint bucket_count;  // 2 x the run's vertices: (kind, object_a, a0)
    uint block_count;   // ceil(bucket_count / kCellsScanBlock)
    uint max_groups_x;
    uint pad;
};
// The sort (proximity_sort.comp): records bucketed by (kind, object_a, a0) -- one bucket per
// kind and vertex of the run -- then each bucket sorted by (a1, object_b, b0, b1) as the key
// (a1, run vertex of b0, run vertex of b1) held beside the record index, insertion sort up to
// this size, heap sort beyond.
VKC_CONST kProximityInsertionSort = 16u;

#ifdef __cplusplus
}  // namespace vkcollide::gpu
#endif
#endif
