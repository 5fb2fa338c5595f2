#version 460
#extension GL_GOOGLE_include_directive : require
// Cell pair stage, sweep of the deep cells (one workgroup per work item). A cell of at most
// kCellsDeepShared entries (chunk kCellsSorted) is loaded into shared memory and sorted by
// (object, zlo, index) with a bitonic network, which cuts it into one run per object. Each
// entry then visits the runs of the objects it may collide with (its own only when that
// object tests itself, skipping neighbours that share a vertex index), finds by binary search the first entry after it in (zlo, index)
// order and pairs with the following ones until one starts beyond its zhi. So a cell
// where one object piles up (silhouettes, fans of slivers around a vertex) costs no more
// than its pairs and a binary search per run, not its entries squared; the vertex indices
// of self-colliding objects' entries are loaded with the cell, so the neighbour rule (most
// of such a cell's pairs) reads shared memory. Deeper cells come
// in chunks of kCellsGroupSize entries, each entry scanning the whole cell as the shallow
// sweep does. Every deep cell drops the pairs an earlier cell keeps where the cell to the
// left or below shows it (repeatsHere, kCellsSweepDedupe): a pile repeats its pairs in
// every cell it covers.
// The canonical-cell rule needs no double precision (cells_candidate.glsl.inc).
#define CELLS_NO_FLOAT64 1
#include "cells_common.glsl.inc"
#include "cells_geometry.glsl.inc"
#include "cells_candidate.glsl.inc"
#include "cells_sweep.glsl.inc"
#include "common/workgroup.glsl.inc"
layout(local_size_x = kCellsGroupSize) in;

shared float s_zlo[kCellsDeepShared];
shared uint s_key[kCellsDeepShared];
shared uint s_order[kCellsDeepShared];
shared uint s_runs[kCellsDeepShared + 1];  // first sorted position of each object's run, then k
shared uvec3 s_index[kCellsDeepShared];  // vertex indices of entries whose object tests itself (neighbour rule)

const float kFloatMax = 3.4028234663852886e38;

uint objectOf(uint a) { return s_key[a] & kCellsKeyObject; }
// (zlo, index) order, the sweep's.
bool sweepBefore(uint a, uint b) { return s_zlo[a] < s_zlo[b] || (s_zlo[a] == s_zlo[b] && a < b); }
// (object, zlo, index) order, the sort's.
bool orderedBefore(uint a, uint b) { return objectOf(a) < objectOf(b) || (objectOf(a) == objectOf(b) && sweepBefore(a, b)); }

void sortedCell(CellsParams P, uint cell, uint begin, uint k) {
    const uint tid = gl_LocalInvocationIndex;
    uint size = 1u;
    while (size < k) size <<= 1;
    for (uint x = tid; x < size; x += kCellsGroupSize) {
        if (x < k) {
            CellsEntry en = CellsEntriesRef(P.entries).e[begin + x];
            s_zlo[x] = en.zlo;
            s_key[x] = triangleKeyOf(P, en.key);
            // Loaded once here, not once per pair: a self-colliding object's deep cell
            // (a pole's fan of slivers) pairs mostly neighbours.
            if ((s_key[x] & kCellsKeySelf) != 0u) s_index[x] = triangleIndices(P, en.triangle);
        } else {
            s_zlo[x] = kFloatMax;  // padding sorts last: the largest object, then index >= k
            s_key[x] = kCellsKeyObject;
        }
        s_order[x] = x;
    }
    barrier();
    for (uint span = 2u; span <= size; span <<= 1) {
        for (uint stride = span >> 1; stride > 0u; stride >>= 1) {
            for (uint x = tid; x < size / 2u; x += kCellsGroupSize) {
                uint lo = 2u * stride * (x / stride) + (x % stride), hi = lo + stride;
                bool ascending = (lo & span) == 0u;
                uint a = s_order[lo], b = s_order[hi];
                if (orderedBefore(b, a) == ascending) {
                    s_order[lo] = b;
                    s_order[hi] = a;
                }
            }
            barrier();
        }
    }
    // Runs: positions where the object changes, compacted in order by a workgroup scan.
    const uint per = kCellsDeepShared / kCellsGroupSize;
    uint starts = 0u;
    for (uint c = 0u; c < per; ++c) {
        uint p = tid * per + c;
        if (p < k && (p == 0u || objectOf(s_order[p]) != objectOf(s_order[p - 1u]))) ++starts;
    }
    uint slot = groupInclusiveScan(starts) - starts;
    uint runs = groupReduceAdd(starts);
    for (uint c = 0u; c < per; ++c) {
        uint p = tid * per + c;
        if (p < k && (p == 0u || objectOf(s_order[p]) != objectOf(s_order[p - 1u]))) s_runs[slot++] = p;
    }
    if (tid == 0u) s_runs[runs] = k;
    barrier();

    // k is the workgroup's: the subgroup operation runs in all of it or none.
    const bool dedupe = k >= P.sweep_dedupe && repeatChecksWithinBudget(P);  // for both passes
    uint n = 0u, neighbours = 0u, repeats = 0u;
    for (uint pass = 0u; pass < 2u; ++pass) {
        uint64_t out_slot = 0ul;
        if (pass == 1u) {
            subgroupCount(headerField(P, kHeaderNeighbours), neighbours);
            subgroupCount64(headerField(P, kHeaderRepeats), repeats);
            subgroupCount(headerField(P, kHeaderCandidateCells), markCandidateCell(P, cell, n));
            out_slot = subgroupAppend64(headerField(P, kHeaderCandidates), n);
            if (n == 0u) return;
            if (out_slot >= uint64_t(P.candidate_capacity)) {  // none fits: skip the second scan
                raiseFlag(P, kCellsOverflowCandidates);
                return;
            }
        }
        for (uint p = tid; p < k; p += kCellsGroupSize) {
            uint a = s_order[p];
            CellsEntry me = CellsEntriesRef(P.entries).e[begin + a];  // its zhi and triangle: read once, not kept in shared memory
            CellsTriangle mine_t;
            if (dedupe) mine_t = CellsTrianglesRef(P.triangles).t[me.triangle];
            uint box = boxOf(P, me.key);
            uvec3 mine = (s_key[a] & kCellsKeySelf) != 0u ? s_index[a] : uvec3(~0u);
            for (uint r = 0u; r < runs; ++r) {
                uint first = s_runs[r], end = s_runs[r + 1u];
                if (!mayCollide(P, s_key[a], s_key[s_order[first]])) continue;
                // First position of the run after `a` in (zlo, index) order.
                uint lo = first, hi = end;
                while (lo < hi) {
                    uint mid = (lo + hi) / 2u;
                    if (sweepBefore(a, s_order[mid]) || a == s_order[mid]) hi = mid; else lo = mid + 1u;
                }
                if (lo < end && s_order[lo] == a) ++lo;
                for (uint q = lo; q < end; ++q) {
                    uint b = s_order[q];
                    if (s_zlo[b] > me.zhi) break;
                    // Boxes within the cell: the entry's key from global memory, only for pairs
                    // that meet in depth.
                    CellsEntry other = CellsEntriesRef(P.entries).e[begin + b];
                    if (!subBoxesMeet(box, boxOf(P, other.key))) continue;
                    // sweepPair's rule, the indices from shared memory.
                    if (!mayCollide(P, s_key[a], s_key[b])) continue;
                    if (s_key[a] == s_key[b] && P.keep_neighbours == 0u && shareIndex(mine, s_index[b])) {
                        if (pass == 0u) ++neighbours;
                        continue;
                    }
                    if (!keptHere(P, dedupe, mine_t, other, cell)) {
                        if (pass == 0u) ++repeats;
                        continue;
                    }
                    if (pass == 0u) ++n;
                    else emitCandidate(P, out_slot, me.triangle, other.triangle, cell);
                }
            }
        }
    }
}

// Chunk `chunk` of a cell deeper than kCellsDeepShared: kCellsGroupSize of its entries,
// each scanned against the whole cell as the shallow sweep does.
void chunkOfCell(CellsParams P, uint cell, uint begin, uint end, uint chunk) {
    uint e = begin + chunk * kCellsGroupSize + gl_LocalInvocationIndex;
    CellsEntry me;
    uvec3 mine = uvec3(~0u);
    if (e < end) {
        me = CellsEntriesRef(P.entries).e[e];
        if ((triangleKeyOf(P, me.key) & kCellsKeySelf) != 0u) mine = triangleIndices(P, me.triangle);
    }
    sweepEntry(P, cell, e, me, mine, begin, e < end ? end : begin, end - begin >= P.sweep_dedupe);
}

void main() {
    CellsParams P = params();
    uint item = cellsHeader(P).h.sweep_items_begin + groupIndex();  // this chunk's items (cells_args.comp)
    if (item >= min(cellsHeader(P).h.sweep_items_end, min(cellsHeader(P).h.deep_items, P.deep_capacity))) return;  // whole workgroup
    uvec2 work = Uvec2sRef(P.deep_items).v[item];
    uint begin = UintsRef(P.offsets).v[work.x], end = UintsRef(P.offsets).v[work.x + 1u];
    if (work.y == kCellsSorted) sortedCell(P, work.x, begin, end - begin);
    else chunkOfCell(P, work.x, begin, end, work.y);
}
