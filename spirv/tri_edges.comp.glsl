#version 460
#extension GL_GOOGLE_include_directive : require
// Depth-aware separation, after triangle-bounds: each triangle gets the depth range of the
// edge-on triangles that share one of its vertices (vertex_depth: ordered floats, the
// minimum inverted, zero where none), so that a fragment's window can reach a surface no
// ray sees (classify.comp.glsl, nearWindow). Push.step: the object's first vertex.
#include "common.glsl.inc"
#include "depth.glsl.inc"
layout(local_size_x = kGroupSize) in;

void main() {
    Frame f = frame();
    ObjectGpu o = ObjectsRef(f.objects).o[pc.object];
    uint t = gl_GlobalInvocationID.x;
    if (t >= o.triangle_count) return;
    UintsRef vd = UintsRef(f.vertex_depth);
    uint lo = 0u, hi = 0u;
    for (uint c = 0u; c < 3u; ++c) {
        uint v = pc.step + fetchIndex(o, t * 3u + c);
        lo = max(lo, vd.v[2u * v]);
        hi = max(hi, vd.v[2u * v + 1u]);
    }
    if (hi == 0u) return;  // no edge-on neighbour (triangle-bounds wrote the empty range)
    TriBoundsRef b = TriBoundsRef(f.tri_bounds);
    b.b[o.triangle_base + t].edge_lo = floatFromOrdered(~lo);
    b.b[o.triangle_base + t].edge_hi = floatFromOrdered(hi);
}
