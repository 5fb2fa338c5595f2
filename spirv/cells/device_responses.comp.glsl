#version 460
#extension GL_GOOGLE_include_directive : require
// Device responses (DetectSettings::reliable.device_responses, and the host result's
// responses where the GPU sorts its pairs): the bookkeeping passes. From the device pairs'
// buckets (device_pairs.comp: each triangle's higher partners, sorted, repeats dropped) they
// bucket each triangle's lower partners too and list the triangles in a pair, for
// device_responses_sum.comp, which computes the responses over that list alone. The CPU
// (src/narrow/responses.cpp) sums n_partner - n_self over a triangle's partners in the sorted
// pairs' order: its lower partners ascending, then its higher ones ascending, i.e. every
// partner ascending; so the lower buckets are sorted here. Light on registers: every step
// is proportional to the triangles.
// Steps (Push.step), each after a barrier, all after the device pairs' passes:
//   0     per triangle a: lower_counts[b] += 1 for each higher partner b (invocation 0 first
//         zeroes the responders' dispatch, so that a skipped run dispatches none);
//   1-3   an exclusive scan (block_scan.glsl.inc): Push.level 0, lower_counts into
//         lower_offsets (the counts reset: the scatter's cursor); level 1, marks into
//         positions, the total is the header's `responses` and the responders' dispatch;
//   4     per triangle a: lower[lower_offsets[b] + cursor] = a for each higher partner b;
//   5     per triangle: its lower bucket sorted; marks = in a pair;
//   6     per marked triangle: responders[positions[t]] = t.
// Order: 0, scan level 0, 4, 5, scan level 1, 6.
#include "cells_common.glsl.inc"
#include "common/workgroup.glsl.inc"
#include "block_scan.glsl.inc"
#include "bucket_sort.glsl.inc"
#include "device_responses.glsl.inc"
layout(local_size_x = kCellsGroupSize) in;

void main() {
    DeviceResponsesParams R = DeviceResponsesParamsRef(pc.frame).p;
    DevicePairsParams D = DevicePairsParamsRef(R.pairs).p;
    CellsParams P = CellsParamsRef(D.cells).p;
    uint t = globalIndex();
    if (pc.step == 0u && t == 0u) writeResponderArgs(R, 0u);
    if (skipped(D)) return;
    if (pc.step >= 1u && pc.step <= 3u) {
        UintsRef dst = UintsRef(pc.level == 0u ? R.lower_offsets : R.positions);
        UintsRef src = UintsRef(pc.level == 0u ? R.lower_counts : R.marks);
        uint total = blockScan(pc.step - 1u, src, UintsRef(D.block_sums), dst, R.triangle_count, R.block_count, pc.level == 0u);
        if (pc.step == 2u && pc.level == 1u && gl_LocalInvocationIndex == 0u) {
            pairsHeader(D).h.responses = total;
            writeResponderArgs(R, total);
        }
        return;
    }
    if (t >= R.triangle_count) return;
    UintsRef counts = UintsRef(D.counts), offsets = UintsRef(D.offsets), partners = UintsRef(D.partners);
    UintsRef lower_counts = UintsRef(R.lower_counts), lower_offsets = UintsRef(R.lower_offsets), lower = UintsRef(R.lower);
    uint higher_n = counts.v[t], higher_base = offsets.v[t];
    if (pc.step == 0u || pc.step == 4u) {
        for (uint j = 0u; j < higher_n; ++j) {
            uint b = partners.v[higher_base + j];
            uint k = atomicAdd(lower_counts.v[b], 1u);
            if (pc.step == 4u) lower.v[lower_offsets.v[b] + k] = t;
        }
        return;
    }
    uint lower_n = lower_counts.v[t], lower_base = lower_offsets.v[t];
    if (pc.step == 5u) {
        // A device that ends long loops silently (CellsParams.loop_guard): a bucket its
        // invocation cannot sort, or partners it cannot sum, fails the run by name.
        if (!bucketSortFits(P, lower_n, kDevicePairsInsertionSort, 1u) ||
            (P.loop_guard != ~0u && uint64_t(lower_n) + uint64_t(higher_n) > uint64_t(P.loop_guard))) {
            atomicOr(pairsHeader(D).h.flags, kDevicePairsLoopLimit);
            return;
        }
        sortBucket(lower, lower_base, lower_n);
        UintsRef(R.marks).v[t] = lower_n + higher_n > 0u ? 1u : 0u;
        return;
    }
    // Step 6: the list of triangles in a pair, in order.
    if (lower_n + higher_n > 0u) UintsRef(R.responders).v[UintsRef(R.positions).v[t]] = t;
}
