#version 460
#extension GL_GOOGLE_include_directive : require
// Depth complexity: fragments per ray, closed and open surfaces counted apart, in 64 bits
// (kFragments* in broadphase.h: no count can overflow). A fragment of a thin triangle
// (sample.vert) is not counted: it flags its ray, which peel_init marks colliding, so the
// ray needs no peeling.
#include "common/common.glsl.inc"
layout(location = 0) flat in uint v_key_low;
layout(location = 1) flat in uint v_thin;

void main() {
    Frame f = frame();
    uint p = rayIndex(f, gl_FragCoord.xy);
    Uint64sRef counts = Uint64sRef(f.ray_fragments);
    if (v_thin != 0u) {
        atomicOr(counts.v[p], uint64_t(kFragmentsThin));
        return;
    }
    atomicAdd(counts.v[p], (v_key_low & kKeyOpen) != 0u ? (1ul << 32) : 1ul);
}
