#version 460
#extension GL_GOOGLE_include_directive : require
// Depth complexity: fragments per ray, closed and open surfaces counted apart.
#include "common.glsl.inc"
layout(location = 0) flat in uint v_key_low;
layout(location = 1) flat in uint v_thin;  // counted like any fragment (peel.frag acts on it)

void main() {
    Frame f = frame();
    uint p = rayIndex(f, gl_FragCoord.xy);
    if (v_thin > 1u) return;  // never (0 or 1): keeps the input that sample.vert writes
    atomicAdd(UintsRef(f.counts).v[p], (v_key_low & kKeyOpen) != 0u ? kOpenCountUnit : 1u);
}
