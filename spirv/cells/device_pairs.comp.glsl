#version 460
#extension GL_GOOGLE_include_directive : require
// Device pairs (DetectSettings::reliable.device_pairs): the exact run's survivors (global ids
// a < b, unsorted, a rare pair twice) sorted on the GPU into the host result's order, as
// DevicePair records (object ids as the API returns them, triangles within the object).
// Global ids grow with (object, triangle) and run objects with their ids, so that order is
// the order of (a, b). The order comes from the data alone, never from atomics: the
// atomics only place a pair in its lower id's bucket, and each bucket is then sorted.
// Steps (Push.step), each after a barrier:
//   0  one invocation: the header (capacity, flags: Incomplete when the run failed, has
//      chunks left or a mesh failed the GPU input check) and the indirect dispatch over
//      the survivors;
//   1  per survivor: counts[a] += 1;
//   2-4  exclusive scan of counts over triangles (Push.level 0: into offsets, counts reset
//      to 0 as the scatter's cursor; level 1: into out_offsets, the total is `needed`);
//   5  per survivor: partners[offsets[a] + cursor] = b;
//   6  per triangle: its bucket sorted by b, repeats dropped; counts[a] = distinct partners;
//   7  per triangle: its pairs written at out_offsets[a] (those below the capacity), as
//      DevicePair records or, for the host alone (DevicePairsParams.packed), as (a, b).
// Passes 1 and 5 are proportional to the survivors, the others to the triangles.
#include "cells_common.glsl.inc"
#include "common/workgroup.glsl.inc"
#include "block_scan.glsl.inc"
#include "bucket_sort.glsl.inc"
layout(local_size_x = kCellsGroupSize) in;

layout(buffer_reference, scalar, buffer_reference_align = 8) readonly buffer DevicePairsParamsRef { DevicePairsParams p; };
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer DevicePairsHeaderRef { DevicePairsHeader h; };
layout(buffer_reference, scalar, buffer_reference_align = 4) writeonly buffer DevicePairsRef { DevicePair p[]; };

DevicePairsParams dparams() { return DevicePairsParamsRef(pc.frame).p; }
DevicePairsHeaderRef pairsHeader(DevicePairsParams D) { return DevicePairsHeaderRef(D.header); }
bool incomplete(DevicePairsParams D) { return (pairsHeader(D).h.flags & kDevicePairsIncomplete) != 0u; }
uint survivorCount(CellsParams P) { return min(cellsHeader(P).h.survivors, P.survivor_capacity); }

void writeArgs(DevicePairsParams D, uint survivors) {
    uint groups = (survivors + kCellsGroupSize - 1u) / kCellsGroupSize;
    uint x = min(groups, D.max_groups_x);
    UintsRef args = UintsRef(D.args);
    args.v[0] = x;
    args.v[1] = x == 0u ? 1u : (groups + x - 1u) / x;
    args.v[2] = 1u;
}

// The scan's three steps over counts[0, triangle_count) (see the header comment).
void scan(DevicePairsParams D, uint step) {
    if (incomplete(D)) return;  // uniform: written by step 0 in an earlier pass
    UintsRef dst = UintsRef(pc.level == 0u ? D.offsets : D.out_offsets);
    uint total = blockScan(step - 2u, UintsRef(D.counts), UintsRef(D.block_sums), dst, D.triangle_count, D.block_count, pc.level == 0u);
    if (step == 3u && gl_LocalInvocationIndex == 0u && pc.level == 1u) {
        pairsHeader(D).h.needed = total;
        pairsHeader(D).h.count = min(total, D.capacity);
        if (total > D.capacity) atomicOr(pairsHeader(D).h.flags, kDevicePairsOverflow);
    }
}

void main() {
    DevicePairsParams D = dparams();
    CellsParams P = CellsParamsRef(D.cells).p;
    if (pc.step == 0u) {
        if (gl_LocalInvocationIndex != 0u) return;
        // A run whose sweep or pair pass still has chunks to go is incomplete like a failed
        // one (a sweep chunk that found no candidate yet included).
        bool failed = !runComplete(P);
        if (D.fault_header != 0ul) {
            Header f = HeaderRef(D.fault_header).h;
            failed = failed || f.bad_index_count != 0u || f.bad_vertex_count != 0u;
        }
        pairsHeader(D).h = DevicePairsHeader(0u, 0u, failed ? kDevicePairsIncomplete : 0u, D.capacity, 0u, D.response_capacity, 0u, 0u);
        writeArgs(D, failed ? 0u : survivorCount(P));
        return;
    }
    if (pc.step >= 2u && pc.step <= 4u) {
        scan(D, pc.step);
        return;
    }
    UintsRef counts = UintsRef(D.counts), offsets = UintsRef(D.offsets), partners = UintsRef(D.partners);
    uint id = globalIndex();
    if (pc.step == 1u || pc.step == 5u) {  // indirect: no invocations once incomplete
        if (id >= survivorCount(P)) return;
        uvec2 s = Uvec2sRef(P.survivors).v[id];
        if (s.x >= s.y || s.y >= P.triangle_count) {  // the pair pass writes a < b below the count
            atomicOr(pairsHeader(D).h.flags, kDevicePairsIncomplete);
            return;
        }
        if (pc.step == 1u) atomicAdd(counts.v[s.x], 1u);
        else partners.v[offsets.v[s.x] + atomicAdd(counts.v[s.x], 1u)] = s.y;
        return;
    }
    if (id >= D.triangle_count || incomplete(D)) return;
    uint n = counts.v[id];
    if (n == 0u) return;
    uint base = offsets.v[id];
    if (pc.step == 6u) {
        // A device that ends long loops silently (CellsParams.loop_guard): a bucket its
        // invocation cannot sort, then pass over for repeats, fails the run by name.
        if (!bucketSortFits(P, n, kDevicePairsInsertionSort, 1u)) {
            atomicOr(pairsHeader(D).h.flags, kDevicePairsLoopLimit);
            return;
        }
        sortBucket(partners, base, n);
        uint distinct = 1u;
        for (uint i = 1u; i < n; ++i) {
            uint b = partners.v[base + i];
            if (b != partners.v[base + distinct - 1u]) partners.v[base + distinct++] = b;
        }
        counts.v[id] = distinct;
        return;
    }
    // Step 7: the lower triangle's pairs, in order, where they fit.
    uint out_first = UintsRef(D.out_offsets).v[id];
    if (out_first >= D.capacity) return;
    uint last = min(n, D.capacity - out_first);
    if (D.packed != 0u) {  // global ids for the host's result
        Uvec2sRef packed = Uvec2sRef(D.pairs);
        for (uint j = 0u; j < last; ++j) packed.v[out_first + j] = uvec2(id, partners.v[base + j]);
        return;
    }
    CellsTrianglesRef tris = CellsTrianglesRef(P.triangles);
    ObjectsRef objects = ObjectsRef(P.objects);
    UintsRef ids = UintsRef(D.object_ids);
    uint oa = tris.t[id].key & kCellsKeyObject;
    uint ida = ids.v[oa], ta = id - objects.o[oa].triangle_base;
    DevicePairsRef out_pairs = DevicePairsRef(D.pairs);
    for (uint j = 0u; j < last; ++j) {
        uint b = partners.v[base + j];
        uint ob = tris.t[b].key & kCellsKeyObject;
        out_pairs.p[out_first + j] = DevicePair(ida, ta, ids.v[ob], b - objects.o[ob].triangle_base);
    }
}
