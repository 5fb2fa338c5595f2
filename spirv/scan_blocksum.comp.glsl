#version 460
#extension GL_GOOGLE_include_directive : require
// Scan compaction, step 1: surviving triangles per block of kGroupSize (log-step add).
#include "common.glsl.inc"
layout(local_size_x = kGroupSize) in;
shared uint s_sum[kGroupSize];

void main() {
    Frame f = frame();
    uint t = gl_GlobalInvocationID.x;
    s_sum[gl_LocalInvocationIndex] = (t < f.triangle_count && !boxEmpty(Vec4sRef(f.sparse).v[t])) ? 1u : 0u;
    barrier();
    for (uint stride = kGroupSize / 2u; stride > 0u; stride >>= 1) {
        if (gl_LocalInvocationIndex < stride) s_sum[gl_LocalInvocationIndex] += s_sum[gl_LocalInvocationIndex + stride];
        barrier();
    }
    if (gl_LocalInvocationIndex == 0u) UintsRef(f.scratch).v[gl_WorkGroupID.x] = s_sum[0];
}
