#version 460
#extension GL_GOOGLE_include_directive : require
// Compute sampling. Step 0 (one invocation per pixel): clears the counters before setup
// and, when the count pass also does peeling step 0, the ray's keys as peel_init would.
// Step 2 (one invocation per pixel): clears the gather pass's fill counts.
// Step 1 (one invocation): turns the counters into the indirect dispatch of the draw
// passes (x at most kCsMaxGroupsX, rows in y) and copies the list sizes to the header.
#include "csample.glsl.inc"
layout(local_size_x = kGroupSize) in;
#include "common/dispatch.glsl.inc"

void main() {
    Frame f = frame();
    CsFrame cs = csFrame(f);
    CsCountersRef counters = CsCountersRef(cs.counters);
    uint p = globalIndex();
    if (pc.step == 2u) {  // before a gather pass: its fill counts
        if (p < f.resolution * f.resolution) UintsRef(cs.fill).v[p] = 0u;
        return;
    }
    if (pc.step == 0u && cs.fuse_first_step != 0u && p < f.resolution * f.resolution) {
        Uint64sRef(f.front_keys).v[p] = ~0ul;
        Uint64sRef(f.back_keys).v[p] = 0ul;
    }
    if (p != 0u) return;
    if (pc.step == 0u) {
        CsCounters zero;
        zero.small_count = 0u;
        zero.big_count = 0u;
        zero.item_count = 0u;
        zero.tiles_per_item = 1u;
        zero.small_groups = 0u;
        zero.total_groups = 0u;
        zero.pad0 = 0u;
        zero.pad1 = 0u;
        zero.tiles = 0ul;
        counters.c = zero;
        return;
    }
    uint small_groups = (counters.c.small_count + kCsGroupSize - 1u) / kCsGroupSize;
    uint total = small_groups + counters.c.item_count;
    counters.c.small_groups = small_groups;
    counters.c.total_groups = total;
    uint x = min(total, kCsMaxGroupsX);
    Uvec3Ref(cs.args).v = uvec3(x, x == 0u ? 1u : (total + x - 1u) / x, 1u);
    HeaderRef h = HeaderRef(f.header);
    h.h.cs_small = counters.c.small_count;
    h.h.cs_big = counters.c.big_count;
    h.h.cs_items = counters.c.item_count;
}
