#version 460
#extension GL_GOOGLE_include_directive : require
// Paper packing, counting: the sparse result seen as a texture of kPackRowWidth columns
// (one workgroup per row; kPackRowWidth == kGroupSize); non-empty texels per row by a
// log-step reduce-add. scratch[0 .. rows) = row counts.
#include "common/common.glsl.inc"
#include "common/workgroup.glsl.inc"
layout(local_size_x = kPackRowWidth) in;
#include "common/dispatch.glsl.inc"

void main() {
    Frame f = frame();
    uint row = groupIndex();
    if (row >= f.pack_rows) return;  // past the last row (whole workgroups)
    uint t = row * kPackRowWidth + gl_LocalInvocationIndex;
    uint sum = groupReduceAdd((t < f.triangle_count && !boxEmpty(Vec4sRef(f.sparse).v[t])) ? 1u : 0u);
    if (gl_LocalInvocationIndex == 0u) UintsRef(f.scratch).v[row] = sum;
}
