#version 460
#extension GL_GOOGLE_include_directive : require
// Cell pair stage, sort of the huge cells (more than kCellsDeepShared entries): one
// workgroup per cell, over the deep items of the sweep's chunk (the item of chunk 0 of a
// huge cell sorts it; every other item returns). The cell's entries are sorted in place,
// in global memory, by (object, zlo, copy hash, triangle) with a bitonic network; then
//   - coincident copies: entries of one self-testing object whose triangles have the same
//     three local positions (bit for bit, in any order) sit next to each other, and each
//     sorted position gets the end of its run of copies (CellsParams.sorted .y). Copies
//     share every vertex position, so they are neighbours, never a pair, and the sweep
//     skips them at once: a pile of k copies costs k, not k^2 (not with proximity, which
//     keeps neighbours: there every entry is its own group);
//   - runs: the first sorted position of each object's entries, then k (.x), as the
//     shared-memory sort of cells_deep.comp makes them;
//   - the budget: k times the runs (each entry visits every run) is added to the
//     comparisons; past the budget kCellsOverBudget stops the sweep.
// cells_deep.comp then sweeps the sorted cell in chunks of kCellsGroupSize entries.
#define CELLS_NO_FLOAT64 1
#include "cells_common.glsl.inc"
#include "common/workgroup.glsl.inc"
layout(local_size_x = kCellsGroupSize) in;

// The sort writes what other invocations of the workgroup read after a barrier.
layout(buffer_reference, scalar, buffer_reference_align = 16) coherent buffer SortEntriesRef { CellsEntry e[]; };
layout(buffer_reference, scalar, buffer_reference_align = 8) coherent buffer SortAuxRef { uvec2 v[]; };

void workgroupSync() {
    memoryBarrierBuffer();
    barrier();
}

uint objectOf(CellsParams P, CellsEntry en) { return triangleKeyOf(P, en.key) & kCellsKeyObject; }

// The sort's order; `ha`, `hb`: the copy hashes.
bool before(CellsParams P, CellsEntry a, uint ha, CellsEntry b, uint hb) {
    uint oa = objectOf(P, a), ob = objectOf(P, b);
    if (oa != ob) return oa < ob;
    if (a.zlo != b.zlo) return a.zlo < b.zlo;
    if (ha != hb) return ha < hb;
    return a.triangle < b.triangle;
}

// The triangle's three local positions as bits, sorted (copies may list them in any order).
void localCorners(CellsParams P, uint triangle, uint key, out uvec3 c[3]) {
    ObjectGpu obj = ObjectsRef(P.objects).o[key & kCellsKeyObject];
    uvec3 index = triangleIndices(P, triangle);
    for (uint k = 0u; k < 3u; ++k) c[k] = floatBitsToUint(fetchPosition(obj, index[k]));
    bool swapped = true;
    for (uint pass = 0u; pass < 2u && swapped; ++pass) {
        swapped = false;
        for (uint k = 0u; k < 2u; ++k) {
            uvec3 a = c[k], b = c[k + 1u];
            bool greater = a.x != b.x ? a.x > b.x : (a.y != b.y ? a.y > b.y : a.z > b.z);
            if (greater) {
                c[k] = b;
                c[k + 1u] = a;
                swapped = true;
            }
        }
    }
}

uint mix(uint h, uint v) {
    h ^= v * 0xcc9e2d51u;
    h = (h << 13) | (h >> 19);
    return h * 5u + 0xe6546b64u;
}

// 0: the entry is never grouped (its object does not test itself, or proximity keeps
// neighbours); else a hash of its corners, odd.
uint copyHash(CellsParams P, CellsEntry en) {
    uint key = triangleKeyOf(P, en.key);
    if ((key & kCellsKeySelf) == 0u || P.keep_neighbours != 0u) return 0u;
    uvec3 c[3];
    localCorners(P, en.triangle, key, c);
    uint h = 0x811c9dc5u;
    for (uint k = 0u; k < 3u; ++k) h = mix(mix(mix(h, c[k].x), c[k].y), c[k].z);
    h ^= h >> 16;
    h *= 0x85ebca6bu;
    h ^= h >> 13;
    return h | 1u;
}

// Whether sorted neighbours a and b are copies: same object, hash and depth interval, and
// the same local corners (a hash says nothing for sure).
bool copies(CellsParams P, CellsEntry a, uint ha, CellsEntry b, uint hb) {
    if (ha == 0u || ha != hb || a.zlo != b.zlo || a.zhi != b.zhi) return false;
    uint key = triangleKeyOf(P, a.key);
    if (key != triangleKeyOf(P, b.key)) return false;
    uvec3 ca[3], cb[3];
    localCorners(P, a.triangle, key, ca);
    localCorners(P, b.triangle, key, cb);
    return ca[0] == cb[0] && ca[1] == cb[1] && ca[2] == cb[2];
}

// Compares positions lo < hi of the cell and swaps them out of order (ascending).
void exchange(CellsParams P, SortEntriesRef E, SortAuxRef A, uint lo, uint hi) {
    CellsEntry a = E.e[lo], b = E.e[hi];
    uint ha = A.v[lo].x, hb = A.v[hi].x;
    if (before(P, b, hb, a, ha)) {
        E.e[lo] = b;
        E.e[hi] = a;
        A.v[lo].x = hb;
        A.v[hi].x = ha;
    }
}

// Exchange x of a step of the network over k entries: the first step of a span compares
// mirrored positions (flip), the others positions `stride` apart; positions past k (the
// largest) never move.
void exchangeAt(CellsParams P, SortEntriesRef E, SortAuxRef A, uint x, uint span, uint stride, bool flip, uint k) {
    uint lo, hi;
    if (flip) {
        uint half_span = span >> 1, base = (x / half_span) * span, offset = x % half_span;
        lo = base + offset;
        hi = base + span - 1u - offset;
    } else {
        lo = 2u * stride * (x / stride) + (x % stride);
        hi = lo + stride;
    }
    if (hi < k) exchange(P, E, A, lo, hi);
}

// Whether sorted position p starts an object's run.
bool startsRun(CellsParams P, SortEntriesRef E, uint p) { return p == 0u || objectOf(P, E.e[p]) != objectOf(P, E.e[p - 1u]); }

shared uint s_first[kCellsGroupSize];  // each invocation's first start of a run of copies, or k

void main() {
    CellsParams P = params();
    const uint tid = gl_LocalInvocationIndex;
    uint item = cellsHeader(P).h.sweep_items_begin + groupIndex();  // the deep sweep's items (cells_args.comp)
    if (item >= min(cellsHeader(P).h.sweep_items_end, min(cellsHeader(P).h.deep_items, P.deep_capacity))) return;  // whole workgroup
    uvec2 work = Uvec2sRef(P.deep_items).v[item];
    if (work.y != 0u) return;  // a shared-memory cell (kCellsSorted) or a later chunk
    uint begin = UintsRef(P.offsets).v[work.x], k = UintsRef(P.offsets).v[work.x + 1u] - begin;
    uint size = 1u;
    while (size < k) size <<= 1;
    // Where the device ends long loops silently (llvmpipe), a cell too deep to sort within
    // its count fails by name instead (the scan flags it first: a guard here too).
    if (hugeSortIterations(k) > P.loop_guard) {
        if (tid == 0u) raiseFlag(P, kCellsLoopLimit);
        return;
    }
    // The entries and their slots of `sorted` from the cell's first entry.
    SortEntriesRef E = SortEntriesRef(P.entries + uint64_t(begin) * 16ul);
    SortAuxRef A = SortAuxRef(P.sorted + uint64_t(begin) * 8ul);

    for (uint x = tid; x < k; x += kCellsGroupSize) A.v[x].x = copyHash(P, E.e[x]);
    workgroupSync();
    // Bitonic sort of any k, kCellsSortExchangesPerIteration exchanges per loop iteration (each
    // iteration counts against a loop guard, the exchanges do not).
    const uint half_size = size / 2u, stride_x = kCellsSortExchangesPerIteration * kCellsGroupSize;
    for (uint span = 2u; span <= size; span <<= 1) {
        for (uint stride = span >> 1; stride > 0u; stride >>= 1) {
            const bool flip = stride == span >> 1;
            for (uint x = tid; x < half_size; x += stride_x) {
                exchangeAt(P, E, A, x, span, stride, flip, k);
                if (x + kCellsGroupSize < half_size) exchangeAt(P, E, A, x + kCellsGroupSize, span, stride, flip, k);
                if (x + 2u * kCellsGroupSize < half_size) exchangeAt(P, E, A, x + 2u * kCellsGroupSize, span, stride, flip, k);
                if (x + 3u * kCellsGroupSize < half_size) exchangeAt(P, E, A, x + 3u * kCellsGroupSize, span, stride, flip, k);
                if (x + 4u * kCellsGroupSize < half_size) exchangeAt(P, E, A, x + 4u * kCellsGroupSize, span, stride, flip, k);
                if (x + 5u * kCellsGroupSize < half_size) exchangeAt(P, E, A, x + 5u * kCellsGroupSize, span, stride, flip, k);
                if (x + 6u * kCellsGroupSize < half_size) exchangeAt(P, E, A, x + 6u * kCellsGroupSize, span, stride, flip, k);
                if (x + 7u * kCellsGroupSize < half_size) exchangeAt(P, E, A, x + 7u * kCellsGroupSize, span, stride, flip, k);
            }
            workgroupSync();
        }
    }

    // Each invocation takes a stretch of positions. Copies: .y marks where a run of copies
    // starts (1) or goes on (0); each invocation finds the first start after its stretch
    // (s_first), walks its stretch backwards writing each position's end of copies to .x
    // (the hashes are done), and .y takes it.
    const uint per = (k + kCellsGroupSize - 1u) / kCellsGroupSize;
    const uint first = min(tid * per, k), last = min(first + per, k);
    uint my_first = k;
    for (uint x = first; x < last; ++x) {
        bool start = x == 0u || !copies(P, E.e[x - 1u], A.v[x - 1u].x, E.e[x], A.v[x].x);
        A.v[x].y = start ? 1u : 0u;
        if (start && my_first == k) my_first = x;
    }
    s_first[tid] = my_first;
    workgroupSync();
    uint end = k;
    for (uint t = tid + 1u; t < kCellsGroupSize; ++t) {
        if (s_first[t] < k) {
            end = s_first[t];
            break;
        }
    }
    for (uint x = last; x > first; --x) {
        A.v[x - 1u].x = end;
        if (A.v[x - 1u].y != 0u) end = x - 1u;
    }
    workgroupSync();
    for (uint x = first; x < last; ++x) A.v[x].y = A.v[x].x;
    workgroupSync();

    // Runs: each invocation counts the object changes in its stretch, a workgroup scan gives
    // its slots, and .x takes the run starts, then k.
    uint starts = 0u;
    for (uint p = first; p < last; ++p)
        if (startsRun(P, E, p)) ++starts;
    uint slot = groupInclusiveScan(starts) - starts;
    uint runs = groupReduceAdd(starts);
    for (uint p = first; p < last; ++p)
        if (startsRun(P, E, p)) A.v[slot++].x = p;
    if (tid == 0u) {
        if (runs < k) A.v[runs].x = k;
        uint64_t total = atomicAdd(Uint64sRef(headerField(P, kHeaderComparisons)).v[0], uint64_t(k) * uint64_t(runs));
        if (total + uint64_t(k) * uint64_t(runs) > comparisonBudget(P)) raiseFlag(P, kCellsOverBudget);
    }
}
