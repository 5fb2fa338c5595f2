#version 460
#extension GL_GOOGLE_include_directive : require
// Few pairs sorted in one pass (PairSort::Auto below kGpuPairSortFrom; cells.h,
// src/broad/cells/small_sort.hpp): one workgroup takes the exact run's survivors (global
// ids a < b, unsorted, a rare pair twice) and writes what the host result needs, equal to
// the CPU narrow phase's to the bit: the distinct pairs in (a, b) order and every colliding
// triangle's response in triangle order. The device-pairs passes do the same for any count
// in some twenty dispatches over every triangle; at a few thousand pairs their fixed costs
// outweigh the work, and the host's sort costs about 50 ns a pair.
//   1. the survivors as (a, b) keys in shared memory, bitonic-sorted, repeats dropped
//      (marked, scanned): the pairs, A, in `pairs`;
//   2. the same pairs as (b, a) keys, sorted: B (in shared memory);
//   3. every pair's two ends (triangle, partner): A's (a, b) and B's (b, a), merged by rank
//      (an end's place is its index in its own list plus the number of the other list's
//      keys below it; no key is in both, since A's partners are above their triangle and
//      B's below) into `ends`, ascending: each triangle's partners in ascending order,
//      the CPU's order of a response's terms;
//   4. each run of one triangle in `ends` is a responder: numbered by a scan, its triangle
//      and its run's first end written (`responders`, `run_begin`), and the indirect
//      dispatch of the responses over them (`args`);
//   5. each end's partner replaced by its responder's number (a binary search over the
//      responders, kept in shared memory).
// small_sort_respond.comp then computes the unit normals and the responses, one invocation
// per responder, over as many workgroups as they need: the double arithmetic spread over
// the GPU, not one multiprocessor.
// The survivors must fit kSmallSortPairs and the run be complete; otherwise (or with a
// survivor out of range) the header says kSmallSortSkipped, and the host sorts them. Every
// loop is bounded by kSmallSortPairs, so llvmpipe's loop limit never ends one.
#include "cells_common.glsl.inc"
#include "small_sort.glsl.inc"
layout(local_size_x = kSmallSortGroupSize) in;

// The whole shared memory of a 32 KiB device: the keys, and between sorts a scan's scratch.
shared uvec2 s_keys[kSmallSortPairs];

const uvec2 kNoKey = uvec2(0xFFFFFFFFu);           // padding: above every key
const uvec2 kBadKey = uvec2(0xFFFFFFFFu, 0xFFFFFFFEu);  // a survivor out of range: below the padding only

bool below(uvec2 x, uvec2 y) { return x.x < y.x || (x.x == y.x && x.y < y.y); }

uint roundUpPow2(uint n) { return n <= 2u ? 2u : 1u << uint(findMSB(n - 1u) + 1); }

// s_keys[0, n) ascending; n a power of two. Every invocation calls it (barriers).
void bitonicSort(uint n) {
    for (uint k = 2u; k <= n; k <<= 1) {
        for (uint j = k >> 1; j > 0u; j >>= 1) {
            for (uint c = gl_LocalInvocationIndex; c < n / 2u; c += kSmallSortGroupSize) {
                uint i = 2u * j * (c / j) + c % j, l = i + j;  // each exchange once: i below l
                uvec2 x = s_keys[i], y = s_keys[l];
                if (((i & k) == 0u) == below(y, x)) {  // ascending where bit k of i is clear
                    s_keys[i] = y;
                    s_keys[l] = x;
                }
            }
            barrier();
        }
    }
}

// Exclusive prefix sum over the invocations in index order, with the total; s_keys[0,
// kSmallSortGroupSize).x as scratch (its keys must have been read). Every invocation calls it.
uint groupExclusiveAdd(uint value, out uint total) {
    const uint i = gl_LocalInvocationIndex;
    s_keys[i].x = value;
    barrier();
    for (uint stride = 1u; stride < kSmallSortGroupSize; stride <<= 1) {
        uint add = i >= stride ? s_keys[i - stride].x : 0u;
        barrier();
        s_keys[i].x += add;
        barrier();
    }
    uint inclusive = s_keys[i].x;
    total = s_keys[kSmallSortGroupSize - 1u].x;
    barrier();
    return inclusive - value;
}

// How many of list[0, n) lie below `key` (list ascending).
uint rankInShared(uvec2 key, uint n) {
    uint lo = 0u, hi = n;
    while (lo < hi) {
        uint mid = (lo + hi) >> 1;
        if (below(s_keys[mid], key)) lo = mid + 1u;
        else hi = mid;
    }
    return lo;
}
uint rankInList(KeysRef list, uvec2 key, uint n) {
    uint lo = 0u, hi = n;
    while (lo < hi) {
        uint mid = (lo + hi) >> 1;
        if (below(list.v[mid], key)) lo = mid + 1u;
        else hi = mid;
    }
    return lo;
}

// Step 4 on: responder r's triangle, two to a key of s_keys (8,192 at most).
void setResponder(uint r, uint t) {
    if ((r & 1u) == 0u) s_keys[r >> 1].x = t;
    else s_keys[r >> 1].y = t;
}
uint responder(uint r) { return (r & 1u) == 0u ? s_keys[r >> 1].x : s_keys[r >> 1].y; }
// The number of responder `t` among the `count` (ascending).
uint responderOf(uint t, uint count) {
    uint lo = 0u, hi = count;
    while (lo < hi) {
        uint mid = (lo + hi) >> 1;
        if (responder(mid) < t) lo = mid + 1u;
        else hi = mid;
    }
    return lo;
}

// Invocation i's share of [0, n): a run of consecutive items (their order follows i).
uvec2 share(uint n) {
    uint per = (n + kSmallSortGroupSize - 1u) / kSmallSortGroupSize;
    uint first = min(gl_LocalInvocationIndex * per, n);
    return uvec2(first, min(first + per, n));
}

void main() {
    SmallSortParams S = SmallSortParamsRef(pc.frame).p;
    CellsParams P = CellsParamsRef(S.cells).p;
    const uint self = gl_LocalInvocationIndex;
    const uint n = min(cellsHeader(P).h.survivors, P.survivor_capacity);
    // Uniform: every invocation reads the same header.
    if (!runComplete(P) || n > kSmallSortPairs) {
        if (self == 0u) {
            SmallSortHeaderRef(S.header).h = SmallSortHeader(kSmallSortSkipped, n, 0u, 0u);
            writeResponseArgs(S, 0u);
        }
        return;
    }

    // 1. The survivors, sorted, repeats dropped.
    const uint m = roundUpPow2(n);
    Uvec2sRef survivors = Uvec2sRef(P.survivors);
    for (uint i = self; i < m; i += kSmallSortGroupSize) {
        uvec2 s = i < n ? survivors.v[i] : kNoKey;
        if (i < n && (s.x >= s.y || s.y >= S.triangle_count)) s = kBadKey;  // the pair pass writes a < b below the count
        s_keys[i] = s;
    }
    barrier();
    bitonicSort(m);
    const bool bad = n > 0u && s_keys[n - 1u] == kBadKey;  // sorted last but the padding
    // Each invocation's share of the sorted keys (at most kSmallSortPairs / group = 4).
    const uvec2 mine = share(m);
    uvec2 keys[kSmallSortPairs / kSmallSortGroupSize];
    uint firsts = 0u, count = 0u;  // bit j: keys[j] is the first of its value
    for (uint i = mine.x; i < mine.y; ++i) {
        uint j = i - mine.x;
        keys[j] = s_keys[i];
        bool first = keys[j].x != 0xFFFFFFFFu && (i == 0u || s_keys[i - 1u] != keys[j]);
        if (first) {
            firsts |= 1u << j;
            ++count;
        }
    }
    barrier();  // every key read: the scan may overwrite them
    uint pairs;
    uint at = groupExclusiveAdd(count, pairs);
    KeysRef A = KeysRef(S.pairs);
    for (uint i = mine.x; i < mine.y; ++i) {
        uint j = i - mine.x;
        if ((firsts & (1u << j)) == 0u) continue;
        A.v[at] = keys[j];
        s_keys[at] = keys[j].yx;  // 2. B: the same pairs as (b, a)
        ++at;
    }
    const uint m2 = roundUpPow2(pairs);
    for (uint i = pairs + self; i < m2; i += kSmallSortGroupSize) s_keys[i] = kNoKey;
    memoryBarrierBuffer();
    barrier();
    bitonicSort(m2);

    // 3. Both lists' ends merged into `ends` by rank.
    KeysRef ends = KeysRef(S.ends);
    for (uint i = self; i < pairs; i += kSmallSortGroupSize) {
        uvec2 a = A.v[i], b = s_keys[i];
        ends.v[i + rankInShared(a, pairs)] = a;
        ends.v[i + rankInList(A, b, pairs)] = b;
    }
    memoryBarrierBuffer();
    barrier();  // B no longer needed: s_keys is the next scan's scratch

    // 4. The responders: each run of one triangle in `ends`, numbered by a scan over the runs'
    // first ends (every partner is a responder too).
    const uint end_count = 2u * pairs;
    const uvec2 runs_in = share(end_count);
    uint heads = 0u;
    for (uint e = runs_in.x; e < runs_in.y; ++e)
        if (e == 0u || ends.v[e].x != ends.v[e - 1u].x) ++heads;
    uint responses;
    const uint first_r = groupExclusiveAdd(heads, responses);  // B is no longer needed: s_keys is its scratch
    UintsRef responders = UintsRef(S.responders), run_begin = UintsRef(S.run_begin);
    for (uint e = runs_in.x, r = first_r; e < runs_in.y; ++e) {
        const uint t = ends.v[e].x;
        if (e > 0u && ends.v[e - 1u].x == t) continue;
        setResponder(r, t);
        responders.v[r] = t;
        run_begin.v[r] = e;
        ++r;
    }
    if (self == 0u) {
        run_begin.v[responses] = end_count;
        writeResponseArgs(S, bad ? 0u : responses);
    }
    barrier();
    // 5. Each end's partner replaced by its responder's number (the partner's id is not read
    // again; each invocation rewrites its own ends only).
    for (uint e = runs_in.x; e < runs_in.y; ++e) ends.v[e].y = responderOf(ends.v[e].y, responses);
    if (self == 0u) SmallSortHeaderRef(S.header).h = SmallSortHeader(bad ? kSmallSortSkipped : kSmallSortDone, n, pairs, responses);
}
