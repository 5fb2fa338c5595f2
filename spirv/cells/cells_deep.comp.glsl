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
// of such a cell's pairs) reads shared memory. Huge cells (deeper) come sorted in global
// memory by cells_deep_sort.comp, in chunks of kCellsGroupSize sorted entries, swept the
// same way (hugeChunk). Every deep cell drops the pairs an earlier cell keeps where the cell to the
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

// Between a deep sweep's two passes: its counts into the header and this invocation's slots
// for its n candidates. Every invocation of the subgroup still running calls it (subgroup
// operations). False: nothing to write (none found, or none fits: the overflow is flagged
// and the second pass skipped).
bool reserveCandidates(CellsParams P, uint cell, uint n, uint neighbours, uint repeats, out uint64_t out_slot) {
    subgroupCount(headerField(P, kHeaderNeighbours), neighbours);
    subgroupCount64(headerField(P, kHeaderRepeats), repeats);
    subgroupCount(headerField(P, kHeaderCandidateCells), markCandidateCell(P, cell, n));
    out_slot = subgroupAppend64(headerField(P, kHeaderCandidates), n);
    if (n == 0u) return false;
    if (out_slot >= uint64_t(P.candidate_capacity)) {
        raiseFlag(P, kCellsOverflowCandidates);
        return false;
    }
    return true;
}

// A pair of the deep sweeps that overlaps in depth and whose boxes meet, and may collide:
// a neighbour (one object, a shared vertex index) or a repeat (cells_sweep.glsl.inc's
// keptHere) is counted on the first pass, any other counted, then written on the second.
void takeOverlapping(CellsParams P, uint pass, bool neighbour, bool dedupe, CellsTriangle mine_t, uint my_triangle,
                     CellsEntry other, uint cell, inout uint n, inout uint neighbours, inout uint repeats, inout uint64_t out_slot) {
    if (neighbour) {
        if (pass == 0u) ++neighbours;
    } else if (!keptHere(P, dedupe, mine_t, other, cell)) {
        if (pass == 0u) ++repeats;
    } else if (pass == 0u) {
        ++n;
    } else {
        emitCandidate(P, out_slot, my_triangle, other.triangle, cell);
    }
}

// The loop guard (CellsParams.loop_guard): `iterations` counts a subgroup's loop iterations
// as a device that limits them does -- a loop runs as long as its longest invocation, so
// each visit of a run adds the subgroup's largest count (`mine`: this invocation's search
// steps and visits there, 0 where it skipped the run). Every invocation of the subgroup
// still in the loop over runs calls it once per run; true once past the guard, after
// raising kCellsLoopLimit (the run then fails naming it).
bool pastLoopGuard(CellsParams P, inout uint iterations, uint mine) {
    if (P.loop_guard == ~0u) return false;
    iterations += subgroupMax(mine) + 1u;
    if (iterations <= P.loop_guard) return false;
    if (subgroupElect()) raiseFlag(P, kCellsLoopLimit);
    return true;
}

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
    uint n = 0u, neighbours = 0u, repeats = 0u, iterations = 0u;
    bool cut = false;
    for (uint pass = 0u; pass < 2u && !cut; ++pass) {
        uint64_t out_slot = 0ul;
        if (pass == 1u && !reserveCandidates(P, cell, n, neighbours, repeats, out_slot)) return;
        for (uint p = tid; p < k; p += kCellsGroupSize) {
            uint a = s_order[p];
            CellsEntry me = CellsEntriesRef(P.entries).e[begin + a];  // its zhi and triangle: read once, not kept in shared memory
            CellsTriangle mine_t;
            if (dedupe) mine_t = CellsTrianglesRef(P.triangles).t[me.triangle];
            uint box = boxOf(P, me.key);
            uvec3 mine = (s_key[a] & kCellsKeySelf) != 0u ? s_index[a] : uvec3(~0u);
            for (uint r = 0u; r < runs && !cut; ++r) {
                uint first = s_runs[r], end = s_runs[r + 1u], steps = 0u;
                if (!mayCollide(P, s_key[a], s_key[s_order[first]])) end = first;  // skipped
                // First position of the run after `a` in (zlo, index) order.
                uint lo = first, hi = end;
                while (lo < hi) {
                    ++steps;
                    uint mid = (lo + hi) / 2u;
                    if (sweepBefore(a, s_order[mid]) || a == s_order[mid]) hi = mid; else lo = mid + 1u;
                }
                if (lo < end && s_order[lo] == a) ++lo;
                for (uint q = lo; q < end; ++q) {
                    ++steps;
                    uint b = s_order[q];
                    if (s_zlo[b] > me.zhi) break;
                    // Boxes within the cell: the entry's key from global memory, only for pairs
                    // that meet in depth.
                    CellsEntry other = CellsEntriesRef(P.entries).e[begin + b];
                    if (!subBoxesMeet(box, boxOf(P, other.key))) continue;
                    // sweepPair's rule, the indices from shared memory.
                    if (!mayCollide(P, s_key[a], s_key[b])) continue;
                    bool neighbour = s_key[a] == s_key[b] && P.keep_neighbours == 0u && shareIndex(mine, s_index[b]);
                    takeOverlapping(P, pass, neighbour, dedupe, mine_t, me.triangle, other, cell, n, neighbours, repeats, out_slot);
                }
                cut = pastLoopGuard(P, iterations, steps);
            }
            if (cut) break;
        }
    }
}

// Chunk `chunk` of a huge cell, which cells_deep_sort.comp sorted in place (entries by
// (object, zlo, copy hash, triangle); CellsParams.sorted: its runs in .x, each position's
// end of coincident copies in .y): kCellsGroupSize sorted positions, each visiting the
// runs as sortedCell does. In its own run an entry starts after its copies (neighbours:
// they share every vertex position); in another run at the first entry not below its zlo,
// and of entries with its zlo takes those of a higher triangle id (the other takes the
// rest), so each pair is taken once. The pairs it visits count as comparisons.
const uint kVisitsPerCount = 4096u;  // visits an invocation adds to the comparisons at a time

void hugeChunk(CellsParams P, uint cell, uint begin, uint k, uint chunk) {
    CellsEntriesRef E = CellsEntriesRef(P.entries + uint64_t(begin) * 16ul);
    Uvec2sRef A = Uvec2sRef(P.sorted + uint64_t(begin) * 8ul);
    const uint p = chunk * kCellsGroupSize + gl_LocalInvocationIndex;
    const bool mine_valid = p < k;
    CellsEntry me;
    uint my_key = 0u, box = 0u, skip_to = 0u;
    uvec3 mine = uvec3(~0u);
    if (mine_valid) {
        me = E.e[p];
        my_key = triangleKeyOf(P, me.key);
        box = boxOf(P, me.key);
        if ((my_key & kCellsKeySelf) != 0u) mine = triangleIndices(P, me.triangle);
        skip_to = A.v[p].y;
    }
    // k is the workgroup's: the subgroup operation runs in all of it or none.
    const bool dedupe = k >= P.sweep_dedupe && repeatChecksWithinBudget(P);  // for both passes
    CellsTriangle mine_t;
    if (dedupe && mine_valid) mine_t = CellsTrianglesRef(P.triangles).t[me.triangle];
    uint n = 0u, neighbours = 0u, repeats = 0u, visits = 0u, iterations = 0u;
    bool cut = false;
    for (uint pass = 0u; pass < 2u && !cut; ++pass) {
        uint64_t out_slot = 0ul;
        if (pass == 1u) {
            if (visits > 0u) atomicAdd(Uint64sRef(headerField(P, kHeaderComparisons)).v[0], uint64_t(visits));
            if (!reserveCandidates(P, cell, n, neighbours, repeats, out_slot)) return;
        }
        if (!mine_valid) continue;
        for (uint r = 0u; r < k && !cut; ++r) {
            uint first = A.v[r].x;
            if (first >= k) break;
            uint end = r + 1u < k ? A.v[r + 1u].x : k, steps = 0u;
            if (!mayCollide(P, my_key, triangleKeyOf(P, E.e[first].key))) end = first;  // skipped
            const bool own = first <= p && p < end;
            uint q = skip_to;
            if (!own) {  // first position of the run with zlo not below mine
                uint lo = first, hi = end;
                while (lo < hi) {
                    ++steps;
                    uint mid = (lo + hi) / 2u;
                    if (E.e[mid].zlo < me.zlo) lo = mid + 1u; else hi = mid;
                }
                q = lo;
            }
            for (; q < end; ++q) {
                ++steps;
                CellsEntry other = E.e[q];
                if (other.zlo > me.zhi) break;
                if (!own && other.zlo == me.zlo && other.triangle < me.triangle) continue;
                if (pass == 0u && ++visits == kVisitsPerCount) {
                    // The budget bounds the visits as they happen: a huge cell's pairs are
                    // known only here (a fan of neighbours around a vertex visits k^2).
                    visits = 0u;
                    uint64_t total = atomicAdd(Uint64sRef(headerField(P, kHeaderComparisons)).v[0], uint64_t(kVisitsPerCount));
                    if (total + uint64_t(kVisitsPerCount) > comparisonBudget(P)) {
                        raiseFlag(P, kCellsOverBudget);
                        cut = true;
                        break;
                    }
                }
                if (!subBoxesMeet(box, boxOf(P, other.key))) continue;
                bool neighbour = own && P.keep_neighbours == 0u && shareIndex(mine, triangleIndices(P, other.triangle));
                takeOverlapping(P, pass, neighbour, dedupe, mine_t, me.triangle, other, cell, n, neighbours, repeats, out_slot);
            }
            if (pastLoopGuard(P, iterations, steps)) cut = true;
        }
    }
}

void main() {
    CellsParams P = params();
    uint item = cellsHeader(P).h.sweep_items_begin + groupIndex();  // this chunk's items (cells_args.comp)
    if (item >= min(cellsHeader(P).h.sweep_items_end, min(cellsHeader(P).h.deep_items, P.deep_capacity))) return;  // whole workgroup
    uvec2 work = Uvec2sRef(P.deep_items).v[item];
    uint begin = UintsRef(P.offsets).v[work.x], end = UintsRef(P.offsets).v[work.x + 1u];
    if (work.y == kCellsSorted) sortedCell(P, work.x, begin, end - begin);
    else if ((cellsHeader(P).h.flags & kCellsOverBudget) == 0u) hugeChunk(P, work.x, begin, end - begin, work.y);  // the sort's count
}
