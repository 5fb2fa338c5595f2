#version 460
#extension GL_GOOGLE_include_directive : require
// Compute sampling with fragment lists, when some ray had more keys than the count pass
// stored: every covered sample stores its key in its ray's list again (at most depth
// complexity slots: the same samples were counted). The fill counts start at 0 (step 0
// of csample_args). Rays deeper than the list holds (more than kMaxRayFragments
// fragments: collision rays, never picked) store only what fits.
#include "csample.glsl.inc"

void visit(Frame f, uint p, uint64_t key) {
    CsFrame cs = CsFrameRef(f.compute_sampling).c;
    uint slot = atomicAdd(UintsRef(cs.fill).v[p], 1u);
    if (slot >= cs.list_capacity) return;
    uint64_t pixels = uint64_t(f.resolution) * uint64_t(f.resolution);
    Uint64sRef(cs.fragments + 8ul * (uint64_t(slot) * pixels + uint64_t(p))).v[0] = key;
}

#include "csample_draw.glsl.inc"
