#version 460
#extension GL_GOOGLE_include_directive : require
// Scan compaction, step 1: surviving triangles per block of kGroupSize (log-step add).
#include "common/common.glsl.inc"
#include "common/workgroup.glsl.inc"
layout(local_size_x = kGroupSize) in;
#include "common/dispatch.glsl.inc"

void main() {
    Frame f = frame();
    uint block = groupIndex();
    if (block >= f.pack_blocks) return;  // past the last block (whole workgroups)
    uint t = globalIndex();
    uint sum = groupReduceAdd((t < f.triangle_count && !boxEmpty(Vec4sRef(f.sparse).v[t])) ? 1u : 0u);
    if (gl_LocalInvocationIndex == 0u) UintsRef(f.scratch).v[block] = sum;
}
