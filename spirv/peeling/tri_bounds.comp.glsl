#version 460
#extension GL_GOOGLE_include_directive : require
// Depth-aware separation, before the peeling: each triangle's sampling-space box (x, y:
// as separation computes it) and depth range, the depth range padded by a bound on the
// rounding of its vertex depths (kDepthRoundingPad), so that two triangles with a common
// point get overlapping ranges whatever the order of the arithmetic, and its plane in
// pixel units (gradient and slope). classify reads the planes and ranges of the
// fragments it compares; separate reads box and range. An edge-on triangle (thin: it may
// cover no pixel centre, and steeper than kEdgeOnSlope: its surface too may be invisible
// to every ray, a box's side seen along it) leaves its depth range at every ray within
// kNearReachPx of it (edge_depth), which finalize adds to the ray's interval.
#include "common/common.glsl.inc"
#include "depth.glsl.inc"
layout(local_size_x = kGroupSize) in;
#include "common/dispatch.glsl.inc"

// Every ray whose sample lies within d pixels of the segment a-b (pixel coordinates), and a
// few more, gets [zlo, zhi]: per row of rays, the x range of the part of the segment
// within d of the row's height, widened by d. About (4 d + 2) x the segment's pixels in
// x and y: up to some 48,000 loop iterations across a 4096^2 image, twice that at 8192^2,
// and a subgroup runs each loop as long as its longest lane. Returns false where a loop
// ended before its range did, which only a device that ends long loops silently does
// (llvmpipe past 65,535 iterations in one invocation): then rays near the segment lack
// the depth, and the run must fail (kLoopLimitSplat). Each loop counts its iterations:
// nothing a compiler can equate with the range without knowing about that limit.
bool splat(Frame f, vec2 a, vec2 b, float d, float zlo, float zhi) {
    int n = int(f.resolution);
    UintsRef ed = UintsRef(f.edge_depth);
    uint lo_key = ~orderedFromFloat(zlo), hi_key = orderedFromFloat(zhi);
    int row0 = max(int(ceil(min(a.y, b.y) - d - 0.5)), 0), row1 = min(int(floor(max(a.y, b.y) + d - 0.5)), n - 1);
    int rows_done = 0;
    for (int j = row0; j <= row1; ++j) {
        ++rows_done;
        float yc = float(j) + 0.5, dy = b.y - a.y;
        float t0 = 0.0, t1 = 1.0;
        if (abs(dy) > 1e-6) {
            float ta = (yc - d - a.y) / dy, tb = (yc + d - a.y) / dy;
            t0 = clamp(min(ta, tb), 0.0, 1.0);
            t1 = clamp(max(ta, tb), 0.0, 1.0);
        }
        float x0 = a.x + (b.x - a.x) * t0, x1 = a.x + (b.x - a.x) * t1;
        int col0 = max(int(ceil(min(x0, x1) - d - 0.5)), 0), col1 = min(int(floor(max(x0, x1) + d - 0.5)), n - 1);
        int cols_done = 0;
        for (int i = col0; i <= col1; ++i) {
            ++cols_done;
            uint p = uint(j * n + i);
            atomicMax(ed.v[2u * p], lo_key);
            atomicMax(ed.v[2u * p + 1u], hi_key);
        }
        if (cols_done < col1 - col0 + 1) return false;
    }
    return rows_done >= row1 - row0 + 1;
}

void main() {
    Frame f = frame();
    ObjectGpu o = ObjectsRef(f.objects).o[pc.object];
    uint t = globalIndex();
    if (t >= o.triangle_count) return;
    Projection pr = ProjectionRef(f.projection).p;
    vec3 lo = vec3(3.4e38), hi = vec3(-3.4e38);
    float magnitude = 0.0;
    vec3 s[3];
    for (uint c = 0u; c < 3u; ++c) {
        vec3 w = toWorld(o, fetchPosition(o, fetchIndex(o, t * 3u + c)));
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
    TriBoundsRef(f.tri_bounds).b[o.triangle_base + t] = b;
    // Thin: projected inradius (twice the area over the perimeter) below kThinInradiusPx.
    float perimeter = length(e1) + length(e2) + length(e2 - e1);
    bool thin = abs(det) < kThinInradiusPx * perimeter;
    if (thin && b.slope > kEdgeOnSlope * levelSlope(f)) {
        // Along its longest edge, as far as its third corner lies from it plus the reach.
        vec2 p1 = p0 + e1, p2 = p0 + e2;
        vec2 a = p0, c = p1, far = p2;
        float longest = length(e1);
        if (length(e2) > longest) { c = p2; far = p1; longest = length(e2); }
        if (length(e2 - e1) > longest) { a = p1; c = p2; far = p0; longest = length(e2 - e1); }
        float height = longest > 0.0 ? abs(det) / longest : 0.0;
        if (!splat(f, a, c, height + kNearReachPx, b.zmin, b.zmax)) atomicOr(HeaderRef(f.header).h.loop_limit, kLoopLimitSplat);
    }
}
