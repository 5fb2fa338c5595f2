#version 460
#extension GL_GOOGLE_include_directive : require
// Compute sampling, depth complexity: what count.frag does, per covered sample. With
// fuse_first_step it also does peeling step 0, which takes every fragment of the ray (no
// key is peeled yet and only empty rays are done): the nearest (and farthest) key.
#include "csample.glsl.inc"

void visit(Frame f, uint p, uint64_t key) {
    atomicAdd(UintsRef(f.counts).v[p], (uint(key) & kKeyOpen) != 0u ? kOpenCountUnit : 1u);
    if (CsFrameRef(f.compute_sampling).c.fuse_first_step != 0u) {
        atomicMin(Uint64sRef(f.front_keys).v[p], key);
        if (f.dual != 0u) atomicMax(Uint64sRef(f.back_keys).v[p], key);
    }
}

#include "csample_draw.glsl.inc"
