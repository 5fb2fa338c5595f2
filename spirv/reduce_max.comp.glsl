#version 460
#extension GL_GOOGLE_include_directive : require
// Depth complexity of the scene: log-step reduce-max of the per-ray fragment counts
// within each workgroup, then one atomicMax per workgroup; the counts' sum likewise.
#include "common.glsl.inc"
#include "workgroup.glsl.inc"
layout(local_size_x = kGroupSize) in;

void main() {
    Frame f = frame();
    uint i = gl_GlobalInvocationID.x;
    uint n = f.resolution * f.resolution;
    uint c = i < n ? UintsRef(f.counts).v[i] : 0u;
    // Rays flagged by a thin triangle are collision rays without peeling.
    uint most = groupReduceMax((c & kCountThin) != 0u ? 0u : (c & kCountClosedMask) + (c >> 16));
    uint sum = groupReduceAdd((c & kCountClosedMask) + (c >> 16));
    if (gl_LocalInvocationIndex == 0u) {
        atomicMax(HeaderRef(f.header).h.depth_complexity, most);
        atomicAdd(HeaderRef(f.header).h.fragments, uint64_t(sum));
    }
}
