#version 460
#extension GL_GOOGLE_include_directive : require
// Depth complexity of the scene: log-step reduce-max of the per-ray fragment counts
// within each workgroup, then one atomicMax per workgroup.
#include "common.glsl.inc"
layout(local_size_x = kGroupSize) in;
shared uint s_max[kGroupSize];

void main() {
    Frame f = frame();
    uint i = gl_GlobalInvocationID.x;
    uint n = f.resolution * f.resolution;
    uint c = i < n ? UintsRef(f.counts).v[i] : 0u;
    s_max[gl_LocalInvocationIndex] = (c & 0xFFFFu) + (c >> 16);
    barrier();
    for (uint stride = kGroupSize / 2u; stride > 0u; stride >>= 1) {
        if (gl_LocalInvocationIndex < stride)
            s_max[gl_LocalInvocationIndex] = max(s_max[gl_LocalInvocationIndex], s_max[gl_LocalInvocationIndex + stride]);
        barrier();
    }
    if (gl_LocalInvocationIndex == 0u) atomicMax(HeaderRef(f.header).h.depth_complexity, s_max[0]);
}
