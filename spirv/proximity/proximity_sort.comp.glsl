#version 460
#extension GL_GOOGLE_include_directive : require
// Proximity records into the result's order on the GPU (src/proximity/proximity_stage.cpp):
// (kind, object_a, a0, a1, object_b, b0, b1), so that the device buffer and the host result
// agree and a GPU solver reads them in a deterministic order. The order comes from the data
// alone: atomics only place a record in its bucket (kind, object_a, a0: one per kind and
// vertex of the run), and each bucket is then sorted by (a1, object_b, b0, b1).
// Steps (Push.step), each after a barrier:
//   0  per record: counts[bucket] += 1
//   1-3  exclusive scan of counts over the buckets into offsets (counts reset to 0)
//   4  per record: order[offsets[bucket] + cursor] = record
//   5  per bucket: its records sorted
//   6  per slot: sorted[slot] = records[order[slot]]
// Nothing runs when the pass failed or overflowed (the host grows and runs it again).
#include "cells/cells_common.glsl.inc"
#include "proximity.h"
#include "common/workgroup.glsl.inc"
#include "cells/block_scan.glsl.inc"
layout(local_size_x = kCellsGroupSize) in;

layout(buffer_reference, scalar, buffer_reference_align = 8) readonly buffer ProximityParamsRef { ProximityParams p; };
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer ProximityHeaderRef { ProximityHeader h; };
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer ProximityRecordsRef { ProximityRecord r[]; };

ProximityParams qparams() { return ProximityParamsRef(pc.frame).p; }

bool usable(ProximityParams Q) { return ProximityHeaderRef(Q.header).h.flags == 0u; }
uint recordCount(ProximityParams Q) { return ProximityHeaderRef(Q.header).h.count; }

// The run object whose id is `id` (ids ascend with the run's objects).
uint objectOfId(ProximityParams Q, uint id) {
    UintsRef ids = UintsRef(Q.object_ids);
    uint lo = 0u, hi = Q.object_count - 1u;
    while (lo < hi) {
        uint mid = (lo + hi) / 2u;
        if (ids.v[mid] < id) lo = mid + 1u; else hi = mid;
    }
    return lo;
}

uint bucketOf(ProximityParams Q, ProximityRecord r) {
    uint base = UintsRef(Q.vertex_base).v[objectOfId(Q, r.object_a)];
    return (r.kind == kProximityEdgeEdge ? Q.bucket_count / 2u : 0u) + base + r.a0;
}

// The order within a bucket: (a1, object_b, b0, b1) as (a1, run vertex of b0, run vertex
// of b1) -- run vertices grow with (object, vertex) -- with the record's index.
// Vertex-triangle: (object_b, b0) as the run triangle of b0.
uvec4 sortKey(ProximityParams Q, ProximityRecord r, uint index) {
    uint run = objectOfId(Q, r.object_b);
    if (r.kind == kProximityVertexTriangle) {
        uint first = ObjectsRef(CellsParamsRef(Q.cells).p.objects).o[run].triangle_base;
        return uvec4(0u, first + r.b0, 0u, index);
    }
    uint base = UintsRef(Q.vertex_base).v[run];
    return uvec4(r.a1, base + r.b0, base + r.b1, index);
}
bool after(uvec4 x, uvec4 y) {
    if (x.x != y.x) return x.x > y.x;
    if (x.y != y.y) return x.y > y.y;
    return x.z > y.z;
}

void siftDown(Uvec4sRef o, uint base, uint root, uint n) {
    uvec4 v = o.v[base + root];
    for (;;) {
        uint child = 2u * root + 1u;
        if (child >= n) break;
        if (child + 1u < n && after(o.v[base + child + 1u], o.v[base + child])) ++child;
        uvec4 c = o.v[base + child];
        if (!after(c, v)) break;
        o.v[base + root] = c;
        root = child;
    }
    o.v[base + root] = v;
}

void sortBucket(Uvec4sRef o, uint base, uint n) {
    if (n <= kProximityInsertionSort) {
        for (uint i = 1u; i < n; ++i) {
            uvec4 v = o.v[base + i];
            uint j = i;
            for (; j > 0u && after(o.v[base + j - 1u], v); --j) o.v[base + j] = o.v[base + j - 1u];
            o.v[base + j] = v;
        }
        return;
    }
    for (uint i = n / 2u; i-- > 0u;) siftDown(o, base, i, n);
    for (uint end = n - 1u; end > 0u; --end) {
        uvec4 top = o.v[base];
        o.v[base] = o.v[base + end];
        o.v[base + end] = top;
        siftDown(o, base, 0u, end);
    }
}

// The scan's three steps over counts[0, bucket_count).
void scan(ProximityParams Q, uint step) {
    if (!usable(Q)) return;  // uniform: written by an earlier pass
    blockScan(step - 1u, UintsRef(Q.counts), UintsRef(Q.block_sums), UintsRef(Q.offsets), Q.bucket_count, Q.block_count, true);
}

void main() {
    ProximityParams Q = qparams();
    if (pc.step >= 1u && pc.step <= 3u) {
        scan(Q, pc.step);
        return;
    }
    if (!usable(Q)) return;
    ProximityRecordsRef R = ProximityRecordsRef(Q.records);
    UintsRef counts = UintsRef(Q.counts), offsets = UintsRef(Q.offsets);
    Uvec4sRef order = Uvec4sRef(Q.order);
    uint id = globalIndex();
    if (pc.step == 5u) {
        if (id >= Q.bucket_count) return;
        uint base = offsets.v[id], n = offsets.v[id + 1u] - base;
        // A device that ends long loops silently (CellsParams.loop_guard): a bucket its
        // invocation cannot sort fails the pass by name instead of leaving it out of order.
        if (!bucketSortFits(CellsParamsRef(Q.cells).p, n, kProximityInsertionSort, 0u)) {
            atomicOr(ProximityHeaderRef(Q.header).h.flags, kProximityLoopLimit);
            return;
        }
        if (n > 1u) sortBucket(order, base, n);
        return;
    }
    if (id >= recordCount(Q)) return;
    if (pc.step == 0u) {
        atomicAdd(counts.v[bucketOf(Q, R.r[id])], 1u);
    } else if (pc.step == 4u) {
        ProximityRecord r = R.r[id];
        uint b = bucketOf(Q, r);
        order.v[offsets.v[b] + atomicAdd(counts.v[b], 1u)] = sortKey(Q, r, id);
    } else {
        ProximityRecordsRef(Q.sorted).r[id] = R.r[order.v[id].w];
    }
}
