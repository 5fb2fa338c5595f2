#version 460
#extension GL_GOOGLE_include_directive : require
// Depth complexity of the scene, and the per-ray counts the peeling passes read. Per ray:
// the 64-bit fragment counts (kFragments*) become the packed counts (kCount*); a ray that a
// thin triangle touches, or that has more than kMaxRayFragments fragments, is marked with
// kCountThin (a collision ray without peeling). Then a log-step reduce-max of the other
// rays' counts within each workgroup and one atomicMax per workgroup (the depth complexity
// the peeling needs, at most kMaxRayFragments); the fragment sum and the deep rays likewise.
#include "common/common.glsl.inc"
#include "common/workgroup.glsl.inc"
layout(local_size_x = kGroupSize) in;
#include "common/dispatch.glsl.inc"

void main() {
    Frame f = frame();
    uint i = globalIndex();
    uint n = f.resolution * f.resolution;
    uint64_t c = i < n ? Uint64sRef(f.ray_fragments).v[i] : 0ul;
    uint closed = uint(c) & kFragmentsClosedMask, open = uint(c >> 32);
    bool thin = (uint(c) & kFragmentsThin) != 0u;
    uint total = closed + open;  // < 2^31: one fragment per triangle
    bool deep = total > kMaxRayFragments;
    if (i < n) UintsRef(f.counts).v[i] = (thin || deep) ? kCountThin : (closed | (open << 16));
    uint most = groupReduceMax((thin || deep) ? 0u : total);
    // The sum in two halves, each within 32 bits for a workgroup.
    uint sum_low = groupReduceAdd(total & 0xFFFFu);
    uint sum_high = groupReduceAdd(total >> 16);
    uint deep_rays = groupReduceAdd((deep && !thin) ? 1u : 0u);
    if (gl_LocalInvocationIndex == 0u) {
        HeaderRef h = HeaderRef(f.header);
        atomicMax(h.h.depth_complexity, most);
        atomicAdd(h.h.fragments, (uint64_t(sum_high) << 16) + uint64_t(sum_low));
        if (deep_rays != 0u) atomicAdd(h.h.deep_rays, deep_rays);
    }
}
