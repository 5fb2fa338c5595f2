#version 460
#extension GL_GOOGLE_include_directive : require
// Scan compaction, step 3: each block scans its survivors in shared memory and writes
// them at its offset (from scan_counts), keeping triangle order.
#include "common.glsl.inc"
#include "record.glsl.inc"
layout(local_size_x = kGroupSize) in;
shared uint s_scan[kGroupSize];

void main() {
    Frame f = frame();
    uint t = gl_GlobalInvocationID.x;
    bool keep = t < f.triangle_count && !boxEmpty(Vec4sRef(f.sparse).v[t]);
    uint mine = keep ? 1u : 0u;
    s_scan[gl_LocalInvocationIndex] = mine;
    barrier();
    for (uint stride = 1u; stride < kGroupSize; stride <<= 1) {
        uint add = gl_LocalInvocationIndex >= stride ? s_scan[gl_LocalInvocationIndex - stride] : 0u;
        barrier();
        s_scan[gl_LocalInvocationIndex] += add;
        barrier();
    }
    if (!keep) return;
    uint offset = UintsRef(f.scratch).v[f.pack_blocks + gl_WorkGroupID.x];
    writeRecord(f, offset + s_scan[gl_LocalInvocationIndex] - 1u, t);
}
