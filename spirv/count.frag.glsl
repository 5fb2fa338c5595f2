#version 460
#extension GL_GOOGLE_include_directive : require
// Depth complexity: fragments per ray, closed and open surfaces counted apart.
#include "common.glsl.inc"
layout(location = 0) flat in uint v_key_low;

void main() {
    Frame f = frame();
    uint p = rayIndex(f, gl_FragCoord.xy);
    atomicAdd(UintsRef(f.counts).v[p], (v_key_low & kKeyOpen) != 0u ? kOpenCountUnit : 1u);
}
