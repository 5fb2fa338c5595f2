#version 460
#extension GL_GOOGLE_include_directive : require
// Exclusive prefix sum of `count` uints at scratch[0..count) into scratch[count..2count),
// by one workgroup: each invocation sums a contiguous chunk, the chunk sums are scanned
// in shared memory, then each chunk is written out. Also records the total (the number
// of records) and the largest input (the paper's M, the longest packed row).
#include "common/common.glsl.inc"
#include "common/workgroup.glsl.inc"
layout(local_size_x = kGroupSize) in;

void main() {
    Frame f = frame();
    uint count = pc.step;  // number of rows or blocks
    UintsRef scratch = UintsRef(f.scratch);
    uint chunk = (count + kGroupSize - 1u) / kGroupSize;
    uint begin = min(gl_LocalInvocationIndex * chunk, count), end = min(begin + chunk, count);
    uint sum = 0u, biggest = 0u;
    for (uint i = begin; i < end; ++i) {
        uint v = scratch.v[i];
        sum += v;
        biggest = max(biggest, v);
    }
    uint most = groupReduceMax(biggest);
    uint inclusive = groupInclusiveScan(sum);
    uint running = inclusive - sum;
    for (uint i = begin; i < end; ++i) {
        uint v = scratch.v[i];
        scratch.v[count + i] = running;
        running += v;
    }
    if (gl_LocalInvocationIndex == kGroupSize - 1u) {
        HeaderRef h = HeaderRef(f.header);
        h.h.record_count = inclusive;
        h.h.max_row_count = most;
    }
}
