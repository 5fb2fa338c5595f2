#version 460
#extension GL_GOOGLE_include_directive : require
// Object sampling: vertices pulled from the object's buffers (any stride, 16/32-bit
// indices), transformed to sampling space; one invocation per triangle corner.
#include "common.glsl.inc"
layout(location = 0) flat out uint v_key_low;

void main() {
    Frame f = frame();
    ObjectGpu o = ObjectsRef(f.objects).o[pc.object];
    uint tri = uint(gl_VertexIndex) / 3u;
    uint vi = fetchIndex(o, uint(gl_VertexIndex));
    vec3 s = toSampling(ProjectionRef(f.projection).p, toWorld(o, fetchPosition(o, vi)));
    gl_Position = vec4(s.xy * 2.0 - 1.0, s.z, 1.0);
    v_key_low = ((o.triangle_base + tri) & kKeyTriangleMask) | ((o.flags & kObjectOpen) != 0u ? kKeyOpen : 0u);
}
