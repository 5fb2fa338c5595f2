#version 460
#extension GL_GOOGLE_include_directive : require
// Resets the per-ray peeling state; rays with no fragment are done at once, and so are
// rays marked kCountThin by reduce_max (a thin triangle touches them, or they are deeper
// than kMaxRayFragments): those collide. Step 1: the keys were written by a count pass that
// did peeling step 0; leave them.
#include "common/common.glsl.inc"
layout(local_size_x = kGroupSize) in;
#include "common/dispatch.glsl.inc"

void main() {
    Frame f = frame();
    uint p = globalIndex();
    if (p >= f.resolution * f.resolution) return;
    PixelState st;
    st.last_front = 0ul;
    st.last_back = ~0ul;
    st.peeled = 0u;
    uint c = UintsRef(f.counts).v[p];
    st.flags = (c & kCountThin) != 0u ? (kRayCollision | kRayDone) : (c == 0u ? kRayDone : 0u);
    StatesRef(f.state).s[p] = st;
    if (pc.step != 0u) return;  // the keys already hold peeling step 0 (compute sampling)
    Uint64sRef(f.front_keys).v[p] = ~0ul;
    Uint64sRef(f.back_keys).v[p] = 0ul;
}
