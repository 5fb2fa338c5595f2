#version 460
#extension GL_GOOGLE_include_directive : require
// Depth-aware separation, before the peeling: each triangle's sampling-space box (x, y:
// as separation computes it) and depth range, the depth range padded by a bound on the
// rounding of its vertex depths (kDepthRoundingPad), so that two triangles with a common
// point get overlapping ranges whatever the order of the arithmetic, and its plane in
// pixel units (gradient and slope). classify reads the planes and ranges of the
// fragments it compares; separate reads box and range. An edge-on triangle (thin: it may
// cover no pixel centre, and steeper than kEdgeOnSlope: its surface too may be invisible)
// also leaves its range at its three vertices (vertex_depth, Push.step: the object's
// first vertex there), for tri_edges to hand to its neighbours.
#include "common.glsl.inc"
#include "depth.glsl.inc"
layout(local_size_x = kGroupSize) in;

void main() {
    Frame f = frame();
    ObjectGpu o = ObjectsRef(f.objects).o[pc.object];
    uint t = gl_GlobalInvocationID.x;
    if (t >= o.triangle_count) return;
    Projection pr = ProjectionRef(f.projection).p;
    vec3 lo = vec3(3.4e38), hi = vec3(-3.4e38);
    float magnitude = 0.0;
    vec3 s[3];
    uint vi[3];
    for (uint c = 0u; c < 3u; ++c) {
        vi[c] = fetchIndex(o, t * 3u + c);
        vec3 w = toWorld(o, fetchPosition(o, vi[c]));
        s[c] = toSampling(pr, w);
        lo = min(lo, s[c]);
        hi = max(hi, s[c]);
        magnitude = max(magnitude, dot(abs(pr.row[2].xyz), abs(w)) + abs(pr.row[2].w));
    }
    float pad = magnitude * kDepthRoundingPad;
    // The plane's depth gradient per pixel (a degenerate projection: no bound).
    float n = float(f.resolution);
    vec2 p0 = s[0].xy * n, e1 = s[1].xy * n - p0, e2 = s[2].xy * n - p0;
    float dz1 = s[1].z - s[0].z, dz2 = s[2].z - s[0].z;
    float det = e1.x * e2.y - e2.x * e1.y;
    vec2 grad = vec2(dz1 * e2.y - dz2 * e1.y, e1.x * dz2 - e2.x * dz1) / det;
    bool planar = det != 0.0 && abs(grad.x) + abs(grad.y) < 3.4e38;  // false for inf and NaN
    TriangleBounds b;
    b.box = vec4(lo.xy, hi.xy);
    b.zmin = lo.z - pad;
    b.zmax = hi.z + pad;
    b.slope = planar ? abs(grad.x) + abs(grad.y) : 3.4e38;
    b.dzdx = planar ? grad.x : 0.0;
    b.dzdy = planar ? grad.y : 0.0;
    b.plane = s[0].z - b.dzdx * p0.x - b.dzdy * p0.y;
    b.edge_lo = 3.4e38;
    b.edge_hi = -3.4e38;
    TriBoundsRef(f.tri_bounds).b[o.triangle_base + t] = b;
    // Thin: projected inradius (twice the area over the perimeter) below kThinInradiusPx.
    float perimeter = length(e1) + length(e2) + length(e2 - e1);
    bool thin = abs(det) < kThinInradiusPx * perimeter;
    if (thin && b.slope > kEdgeOnSlope * levelSlope(f)) {
        UintsRef vd = UintsRef(f.vertex_depth);
        for (uint c = 0u; c < 3u; ++c) {
            uint v = pc.step + vi[c];
            atomicMax(vd.v[2u * v], ~orderedFromFloat(b.zmin));
            atomicMax(vd.v[2u * v + 1u], orderedFromFloat(b.zmax));
        }
    }
}
