#version 460
#extension GL_GOOGLE_include_directive : require
// Compute sampling, depth complexity: what count.frag does, per covered sample. With
// fragment lists the count so far is the key's slot in its ray's list (the first
// list_layers are stored). With fuse_first_step it also does peeling step 0, which takes
// every fragment of the ray (no key is peeled yet, only empty rays are done): the nearest
// (and farthest) key.
#include "csample.glsl.inc"

void visit(Frame f, uint p, uint64_t key) {
    uint64_t before = atomicAdd(Uint64sRef(f.ray_fragments).v[p], (uint(key) & kKeyOpen) != 0u ? (1ul << 32) : 1ul);
    CsFrame cs = CsFrameRef(f.compute_sampling).c;
    // Both counts are below 2^30 (one fragment per triangle), so the sum fits.
    uint slot = (uint(before) & kFragmentsClosedMask) + uint(before >> 32);
    if (slot < cs.list_layers) {
        uint64_t pixels = uint64_t(f.resolution) * uint64_t(f.resolution);
        Uint64sRef(cs.fragments + 8ul * (uint64_t(slot) * pixels + uint64_t(p))).v[0] = key;
    }
    if (cs.fuse_first_step != 0u) {
        atomicMin(Uint64sRef(f.front_keys).v[p], key);
        if (f.dual != 0u) atomicMax(Uint64sRef(f.back_keys).v[p], key);
    }
}

#include "csample_draw.glsl.inc"
