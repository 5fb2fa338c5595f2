#version 460
#extension GL_GOOGLE_include_directive : require
// Paper packing, counting: the sparse result seen as a texture of kPackRowWidth columns;
// non-empty texels per row by a log-step reduce-add. scratch[0 .. rows) = row counts.
#include "common.glsl.inc"
layout(local_size_x = kPackRowWidth) in;
shared uint s_sum[kPackRowWidth];

void main() {
    Frame f = frame();
    uint row = gl_WorkGroupID.x;
    uint t = row * kPackRowWidth + gl_LocalInvocationIndex;
    s_sum[gl_LocalInvocationIndex] = (t < f.triangle_count && !boxEmpty(Vec4sRef(f.sparse).v[t])) ? 1u : 0u;
    barrier();
    for (uint stride = kPackRowWidth / 2u; stride > 0u; stride >>= 1) {
        if (gl_LocalInvocationIndex < stride) s_sum[gl_LocalInvocationIndex] += s_sum[gl_LocalInvocationIndex + stride];
        barrier();
    }
    if (gl_LocalInvocationIndex == 0u) UintsRef(f.scratch).v[row] = s_sum[0];
}
