#version 460
#extension GL_GOOGLE_include_directive : require
// Compute sampling with fragment lists, one peeling step per pixel: over the ray's stored
// keys, the test of peel.frag (skip done rays and keys already peeled from either end),
// then the smallest key (and with dual peeling the largest), as its atomics would leave.
// A ray still to peel has at most depth-complexity keys, all stored (the list holds that
// many layers); the bound on list_capacity only keeps a broken invariant inside the buffer.
#include "csample.glsl.inc"
layout(local_size_x = kGroupSize) in;
#include "common/dispatch.glsl.inc"

void main() {
    Frame f = frame();
    uint p = globalIndex();
    uint pixels = f.resolution * f.resolution;
    if (p >= pixels) return;
    StatesRef states = StatesRef(f.state);
    if ((states.s[p].flags & kRayDone) != 0u) return;
    uint64_t last_front = states.s[p].last_front, last_back = states.s[p].last_back;
    CsFrame cs = csFrame(f);
    uint c = UintsRef(f.counts).v[p];
    uint total = min((c & kCountClosedMask) + (c >> 16), cs.list_capacity);
    uint64_t nearest = ~0ul, farthest = 0ul;
    for (uint k = 0u; k < total; ++k) {
        uint64_t key = Uint64sRef(cs.fragments + 8ul * (uint64_t(k) * uint64_t(pixels) + uint64_t(p))).v[0];
        if (key <= last_front || key >= last_back) continue;
        nearest = min(nearest, key);
        farthest = max(farthest, key);
    }
    Uint64sRef(f.front_keys).v[p] = nearest;
    if (f.dual != 0u) Uint64sRef(f.back_keys).v[p] = farthest;
}
