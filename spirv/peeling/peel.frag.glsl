#version 460
#extension GL_GOOGLE_include_directive : require
// One depth-peeling step. Each fragment has a unique 64-bit key (depth bits, facing,
// open flag, triangle id), so equal depths never merge or hide each other: the nearest
// key above the last one peeled from the front wins an atomicMin, and with dual peeling
// the farthest key below the last one peeled from the back wins an atomicMax. Rays that a
// thin triangle touches were marked colliding by peel_init (docs/stability.md, coverage).
#include "common/common.glsl.inc"
layout(location = 0) flat in uint v_key_low;
layout(location = 1) flat in uint v_thin;  // never set here: peeling passes skip thin triangles

void main() {
    Frame f = frame();
    uint p = rayIndex(f, gl_FragCoord.xy);
    PixelState st = StatesRef(f.state).s[p];
    if ((st.flags & kRayDone) != 0u || v_thin != 0u) return;
    uint low = v_key_low | (gl_FrontFacing ? 0u : kKeyBackFacing);
    uint64_t key = (uint64_t(floatBitsToUint(gl_FragCoord.z)) << 32) | uint64_t(low);
    if (key <= st.last_front || key >= st.last_back) return;
    atomicMin(Uint64sRef(f.front_keys).v[p], key);
    if (f.dual != 0u) atomicMax(Uint64sRef(f.back_keys).v[p], key);
}
