#version 460
#extension GL_GOOGLE_include_directive : require
// Cell pair stage, scan of the per-cell footprint counts into entry offsets, in three
// steps (Push.step) with a barrier between them:
//   0: one workgroup per block of kCellsScanBlock cells: the block's sum, the deepest cell,
//      what the sweep will compare in its cells (sweepComparisons);
//   1: one workgroup: exclusive scan of the block sums (in place), the total, checked
//      against the entry capacity (overflow: flag, and every later pass does nothing), and
//      the comparisons checked against the budget (kCellsOverBudget: the same);
//   2: one workgroup per block: each cell's offset, its count reset to 0 (the fill's
//      cursor), work items for cells deeper than kCellsSmallCell (huge cells need
//      CellsParams.sorted up to their end: kCellsOverflowSorted), and the cell of every
//      kCellsEntryChunk-th entry (chunk_cells, written by the invocation whose cell holds
//      it), from which the sweep finds each entry's cell: the fill stored every entry's,
//      one scattered 4-byte word a footprint, 0.45 of its 1.57 ms on deep-blobs (H100).
#include "cells_common.glsl.inc"
#include "common/workgroup.glsl.inc"
layout(local_size_x = kCellsGroupSize) in;

const uint kPerInvocation = kCellsScanBlock / kCellsGroupSize;

// Sum over the workgroup in 64 bits (the comparisons of a block may pass 2^32).
shared uint64_t s_wide[kCellsGroupSize];
uint64_t groupReduceAdd64(uint64_t value) {
    const uint i = gl_LocalInvocationIndex;
    s_wide[i] = value;
    barrier();
    for (uint stride = kCellsGroupSize / 2u; stride > 0u; stride >>= 1) {
        if (i < stride) s_wide[i] += s_wide[i + stride];
        barrier();
    }
    return s_wide[0];
}

// What the sweep compares in a cell of k entries, as far as the count tells: every two
// entries up to kCellsDeepShared (and beyond kCellsHugeMax: refused); a huge cell's sort (a bitonic network of L (L + 1) / 2
// steps of k / 2 exchanges, L = ceil(log2 k)) -- its sort and sweep add the rest.
uint64_t sweepComparisons(uint k) {
    if (k <= kCellsDeepShared || k > kCellsHugeMax) return k > 1u ? uint64_t(k) * uint64_t(k - 1u) / 2ul : 0ul;
    uint steps = uint(findMSB(k - 1u)) + 1u;
    return uint64_t(k) * uint64_t(steps * (steps + 1u)) / 4ul;
}

void main() {
    CellsParams P = params();
    if (runFailed(P)) return;  // bad input or too many work items: nothing was counted right
    UintsRef counts = UintsRef(P.counts), offsets = UintsRef(P.offsets), sums = UintsRef(P.block_sums);
    if (pc.step == 1u) {
        uint carry = 0u;
        for (uint base = 0u; base < P.block_count; base += kCellsGroupSize) {
            uint b = base + gl_LocalInvocationIndex;
            uint v = b < P.block_count ? sums.v[b] : 0u;
            uint inclusive = groupInclusiveScan(v);
            if (b < P.block_count) sums.v[b] = carry + inclusive - v;
            carry += groupReduceAdd(v);
        }
        if (gl_LocalInvocationIndex == 0u) {
            cellsHeader(P).h.entries = carry;
            offsets.v[P.cell_count] = carry;
            if (carry > P.entry_capacity) atomicOr(cellsHeader(P).h.flags, kCellsOverflowEntries);
            // Complete: step 0 counted every cell. Beyond the budget the sweep never runs.
            if (Uint64sRef(headerField(P, kHeaderComparisons)).v[0] > comparisonBudget(P)) raiseFlag(P, kCellsOverBudget);
        }
        return;
    }
    uint block = groupIndex();
    if (block >= P.block_count) return;  // whole workgroup: the barriers below stay uniform
    uint first = block * kCellsScanBlock + gl_LocalInvocationIndex * kPerInvocation;
    uint v[kPerInvocation];
    uint sum = 0u, most = 0u;
    for (uint k = 0u; k < kPerInvocation; ++k) {
        v[k] = first + k < P.cell_count ? counts.v[first + k] : 0u;
        sum += v[k];
        most = max(most, v[k]);
    }
    if (pc.step == 0u) {
        // Totals fit in 32 bits: the setup let the scan run, so the footprints are at most
        // the budget's box cells (below 2^31); a cell's pairs need 64.
        uint64_t pairs = 0ul;
        for (uint k = 0u; k < kPerInvocation; ++k) pairs += sweepComparisons(v[k]);
        uint total = groupReduceAdd(sum);
        uint deepest = groupReduceMax(most);
        uint64_t block_pairs = groupReduceAdd64(pairs);
        if (gl_LocalInvocationIndex == 0u) {
            sums.v[block] = total;
            atomicMax(cellsHeader(P).h.max_cell, deepest);
            if (block_pairs > 0ul) atomicAdd(Uint64sRef(headerField(P, kHeaderComparisons)).v[0], block_pairs);
        }
        return;
    }
    uint running = sums.v[block] + groupInclusiveScan(sum) - sum;
    uint items = 0u, deep = 0u, huge = 0u, sorted_end = 0u;
    UintsRef chunk_cells = UintsRef(P.chunk_cells);
    for (uint k = 0u; k < kPerInvocation; ++k) {
        if (first + k >= P.cell_count) break;
        offsets.v[first + k] = running;
        counts.v[first + k] = 0u;
        // The chunks whose first entry is this cell's: each lies in one non-empty cell, so
        // one invocation writes it.
        uint cell_end = min(running + v[k], P.entry_capacity);
        for (uint c = (running + kCellsEntryChunk - 1u) / kCellsEntryChunk; c * kCellsEntryChunk < cell_end; ++c)
            chunk_cells.v[c] = first + k;
        running += v[k];
        if (v[k] > kCellsSmallCell) {
            ++deep;
            items += v[k] <= kCellsDeepShared ? 1u : (v[k] + kCellsGroupSize - 1u) / kCellsGroupSize;
            if (v[k] > kCellsDeepShared) {
                ++huge;
                sorted_end = running;
                // A sort the device would cut short (llvmpipe's loop limit): named now,
                // before the fill.
                if (v[k] <= kCellsHugeMax && hugeSortIterations(v[k]) > P.loop_guard) raiseFlag(P, kCellsLoopLimit);
            }
        }
    }
    if (sorted_end > 0u) {
        atomicMax(cellsHeader(P).h.sorted_need, sorted_end);
        if (sorted_end > P.sorted_capacity) raiseFlag(P, kCellsOverflowSorted);
    }
    subgroupCount(headerField(P, kHeaderDeepCells), deep);
    subgroupCount(headerField(P, kHeaderHugeCells), huge);
    uint slot = subgroupAppend(headerField(P, kHeaderDeepItems), items);
    Uvec2sRef deep_items = Uvec2sRef(P.deep_items);
    for (uint k = 0u; k < kPerInvocation && deep > 0u; ++k) {
        if (first + k >= P.cell_count) break;
        uint n = v[k];
        if (n <= kCellsSmallCell) continue;
        uint parts = n <= kCellsDeepShared ? 1u : (n + kCellsGroupSize - 1u) / kCellsGroupSize;
        for (uint c = 0u; c < parts; ++c, ++slot)
            if (slot < P.deep_capacity) deep_items.v[slot] = uvec2(first + k, parts == 1u ? kCellsSorted : c);
            else atomicOr(cellsHeader(P).h.flags, kCellsInconsistent);  // deep_capacity >= 2 entries / kCellsSmallCell
    }
}
