#version 460
#extension GL_GOOGLE_include_directive : require
// Compute sampling, one depth-peeling step: what peel.frag does, per covered sample.
#include "csample.glsl.inc"

void visit(Frame f, uint p, uint64_t key) {
    StatesRef states = StatesRef(f.state);
    if ((states.s[p].flags & kRayDone) != 0u) return;
    if (key <= states.s[p].last_front || key >= states.s[p].last_back) return;
    atomicMin(Uint64sRef(f.front_keys).v[p], key);
    if (f.dual != 0u) atomicMax(Uint64sRef(f.back_keys).v[p], key);
}

#include "csample_draw.glsl.inc"
