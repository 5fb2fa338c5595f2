#version 460
#extension GL_GOOGLE_include_directive : require
// Cell pair stage, sweep of the deep cells (one workgroup per work item). A cell of at most
// kCellsDeepShared entries (chunk kCellsSorted) is loaded into shared memory and sorted by
// (zlo, index) with a bitonic network; each entry then pairs with the ones after it in that
// order until one starts beyond its zhi. Deeper cells come in chunks of kCellsGroupSize
// entries, each entry scanning the whole cell as the shallow sweep does.
#include "cells_common.glsl.inc"
layout(local_size_x = kCellsGroupSize) in;

shared float s_zlo[kCellsDeepShared];
shared float s_zhi[kCellsDeepShared];
shared uint s_key[kCellsDeepShared];
shared uint s_tri[kCellsDeepShared];
shared uint s_order[kCellsDeepShared];

const float kFloatMax = 3.4028234663852886e38;

bool orderedBefore(uint a, uint b) { return s_zlo[a] < s_zlo[b] || (s_zlo[a] == s_zlo[b] && a < b); }

void emit(CellsParams P, inout uint slot, uint ta, uint tb, uint cell) {
    if (slot < P.candidate_capacity) {
        CellsCandidate c;
        c.a = min(ta, tb);
        c.b = max(ta, tb);
        c.cell = cell;
        CellsCandidatesRef(P.candidates).c[slot] = c;
    } else {
        atomicOr(cellsHeader(P).h.flags, kCellsOverflowCandidates);
    }
    ++slot;
}

void sortedCell(CellsParams P, uint cell, uint begin, uint k) {
    const uint tid = gl_LocalInvocationIndex;
    uint size = 1u;
    while (size < k) size <<= 1;
    for (uint x = tid; x < size; x += kCellsGroupSize) {
        if (x < k) {
            CellsEntry en = CellsEntriesRef(P.entries).e[begin + x];
            s_zlo[x] = en.zlo;
            s_zhi[x] = en.zhi;
            s_key[x] = en.key;
            s_tri[x] = en.triangle;
        } else {
            s_zlo[x] = kFloatMax;  // padding sorts last (ties broken by index >= k)
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
    uint n = 0u;
    for (uint p = tid; p < k; p += kCellsGroupSize) {
        uint a = s_order[p];
        for (uint q = p + 1u; q < k; ++q) {
            uint b = s_order[q];
            if (s_zlo[b] > s_zhi[a]) break;
            if (mayCollide(P, s_key[a], s_key[b])) ++n;
        }
    }
    uint slot = subgroupAppend(headerField(P, kHeaderCandidates), n);
    if (n == 0u) return;
    for (uint p = tid; p < k; p += kCellsGroupSize) {
        uint a = s_order[p];
        for (uint q = p + 1u; q < k; ++q) {
            uint b = s_order[q];
            if (s_zlo[b] > s_zhi[a]) break;
            if (mayCollide(P, s_key[a], s_key[b])) emit(P, slot, s_tri[a], s_tri[b], cell);
        }
    }
}

void chunkOfCell(CellsParams P, uint cell, uint begin, uint end, uint chunk) {
    CellsEntriesRef entries = CellsEntriesRef(P.entries);
    uint e = begin + chunk * kCellsGroupSize + gl_LocalInvocationIndex;
    uint stop = e < end ? end : begin;
    CellsEntry me;
    if (e < end) me = entries.e[e];
    uint n = 0u;
    for (uint j = begin; j < stop; ++j) {
        CellsEntry o = entries.e[j];
        bool after = o.zlo > me.zlo || (o.zlo == me.zlo && j > e);
        if (after && o.zlo <= me.zhi && mayCollide(P, me.key, o.key)) ++n;
    }
    uint slot = subgroupAppend(headerField(P, kHeaderCandidates), n);
    if (n == 0u) return;
    for (uint j = begin; j < stop; ++j) {
        CellsEntry o = entries.e[j];
        bool after = o.zlo > me.zlo || (o.zlo == me.zlo && j > e);
        if (after && o.zlo <= me.zhi && mayCollide(P, me.key, o.key)) emit(P, slot, me.triangle, o.triangle, cell);
    }
}

void main() {
    CellsParams P = params();
    uint item = groupIndex();
    if (item >= min(cellsHeader(P).h.deep_items, P.deep_capacity)) return;  // whole workgroup
    uvec2 work = Uvec2sRef(P.deep_items).v[item];
    uint begin = UintsRef(P.offsets).v[work.x], end = UintsRef(P.offsets).v[work.x + 1u];
    if (work.y == kCellsSorted) sortedCell(P, work.x, begin, end - begin);
    else chunkOfCell(P, work.x, begin, end, work.y);
}
