#version 460
#extension GL_GOOGLE_include_directive : require
// After a peeling step: checks the fragments just peeled against the ray's rules.
// Closed surfaces: facing must alternate, front first (from the back: back first).
// Open surfaces: two consecutive fragments within the depth epsilon collide, and so does
// an open fragment inside a closed object (odd closed parity before it): a sheet that
// enters a solid crosses its surface, however thin the band where the depths are close.
// Closed surfaces touching (depth-epsilon policy, docs/stability.md): a back face followed
// by a front face within closed_epsilon (leaving one closed surface and entering the next
// across a gap that small) collide; at 0 only the key order decides ties.
// A ray is done when every fragment counted by the depth-complexity pass was peeled.
#include "common.glsl.inc"
layout(local_size_x = kGroupSize) in;
#include "dispatch.glsl.inc"

float keyDepth(uint64_t k) { return uintBitsToFloat(uint(k >> 32)); }
bool keyOpen(uint64_t k) { return (uint(k) & kKeyOpen) != 0u; }
bool keyBack(uint64_t k) { return (uint(k) & kKeyBackFacing) != 0u; }

bool tooClose(uint64_t a, uint64_t b, float eps) {
    return (keyOpen(a) || keyOpen(b)) && abs(keyDepth(a) - keyDepth(b)) <= eps;
}

bool touching(uint64_t earlier, uint64_t later, float eps) {
    return eps > 0.0 && !keyOpen(earlier) && !keyOpen(later) && keyBack(earlier) && !keyBack(later) &&
           keyDepth(later) - keyDepth(earlier) <= eps;
}

void main() {
    Frame f = frame();
    uint p = globalIndex();
    if (p >= f.resolution * f.resolution) return;
    StatesRef states = StatesRef(f.state);
    PixelState st = states.s[p];
    if ((st.flags & kRayDone) != 0u) return;
    float eps = ProjectionRef(f.projection).p.open_epsilon;
    float closed_eps = ProjectionRef(f.projection).p.closed_epsilon;
    uint counts = UintsRef(f.counts).v[p];
    uint closed_total = counts & kCountClosedMask;
    uint total = closed_total + (counts >> 16);
    uint n_front = st.peeled & 0xFFFFu, n_back = st.peeled >> 16;
    bool collide = false;

    uint64_t kf = Uint64sRef(f.front_keys).v[p];
    Uint64sRef(f.front_keys).v[p] = ~0ul;
    if (kf != ~0ul) {
        if (!keyOpen(kf)) {
            bool expect_back = (st.flags & kParityFront) != 0u;
            if (keyBack(kf) != expect_back) collide = true;
            st.flags ^= kParityFront;
        } else if ((st.flags & kParityFront) != 0u) {
            collide = true;
        }
        if (n_front > 0u && (tooClose(st.last_front, kf, eps) || touching(st.last_front, kf, closed_eps))) collide = true;
        st.last_front = kf;
        ++n_front;
    }
    bool met_in_middle = false;
    if (f.dual != 0u) {
        uint64_t kb = Uint64sRef(f.back_keys).v[p];
        Uint64sRef(f.back_keys).v[p] = 0ul;
        if (kb != 0ul) {
            if (!keyOpen(kb)) {
                bool expect_back = (st.flags & kParityBack) == 0u;
                if (keyBack(kb) != expect_back) collide = true;
                st.flags ^= kParityBack;
            } else if ((st.flags & kParityBack) != 0u) {
                collide = true;
            }
            if (n_back > 0u && (tooClose(kb, st.last_back, eps) || touching(kb, st.last_back, closed_eps))) collide = true;
            if (kb == kf) {
                met_in_middle = true;  // the same fragment, counted once (by the front)
            } else {
                st.last_back = kb;
                ++n_back;
            }
        }
    }
    if (n_front + n_back >= total) {
        st.flags |= kRayDone;
        if ((closed_total & 1u) != 0u) collide = true;  // a closed ray must enter and leave
        if (f.dual != 0u && !met_in_middle && n_front > 0u && n_back > 0u &&
            (tooClose(st.last_front, st.last_back, eps) || touching(st.last_front, st.last_back, closed_eps)))
            collide = true;
    }
    if (collide) st.flags |= kRayCollision | kRayDone;
    st.peeled = n_front | (n_back << 16);
    states.s[p] = st;
}
