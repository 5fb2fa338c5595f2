#version 460
#extension GL_GOOGLE_include_directive : require
// Compute sampling, triangle setup (one invocation per triangle of one object): the same
// vertex transform as sample.vert, the viewport transform, snapping to the device's
// sub-pixel grid, facing, the pixel box and the depth plane. Small triangles go to the
// one-invocation list, big ones to the tiled list.
#include "csample.glsl.inc"
layout(local_size_x = kGroupSize) in;

void main() {
    Frame f = frame();
    ObjectGpu o = ObjectsRef(f.objects).o[pc.object];
    uint t = gl_GlobalInvocationID.x;
    if (t >= o.triangle_count) return;
    CsFrame cs = csFrame(f);
    Projection pr = ProjectionRef(f.projection).p;
    const float half_n = 0.5 * float(f.resolution);
    const float unit = float(1u << cs.subpixel_bits);
    // Positions past this many pixels from the origin are clamped (the raster path clips
    // them at its guard band instead); differences of snapped coordinates then fit 31 bits.
    const float limit = float(1u << (29u - cs.subpixel_bits));

    precise vec2 w[3];
    float z[3];
    ivec2 q[3];
    for (uint c = 0u; c < 3u; ++c) {
        uint vi = fetchIndex(o, 3u * t + c);
        vec3 s = toSampling(pr, toWorld(o, fetchPosition(o, vi)));
        // gl_Position = (s.xy * 2 - 1, s.z, 1); viewport (0, 0, N, N), depth [0, 1].
        // Both steps are exact up to one rounding each, fused or not.
        precise vec2 ndc = s.xy * 2.0 - 1.0;
        w[c] = ndc * half_n + half_n;
        z[c] = s.z;
        // Sample of pixel i at i + 0.5: snap (w - 0.5) to the grid, round to nearest even.
        precise vec2 g = (w[c] - 0.5) * unit;
        q[c] = ivec2(roundEven(clamp(g, vec2(-limit * unit), vec2(limit * unit))));
    }
    CsTriangle tri;
    tri.box_lo = 1u;
    tri.box_hi = 0u;
    // Signed area (twice) of the snapped triangle; Vulkan's a = -area/2 in these
    // coordinates, so with counter-clockwise front faces area > 0 is back-facing.
    int64_t area = int64_t(q[1].x - q[0].x) * int64_t(q[2].y - q[0].y) - int64_t(q[2].x - q[0].x) * int64_t(q[1].y - q[0].y);
    bool back = area > 0l;
    if (area < 0l) {
        ivec2 tq = q[1];
        q[1] = q[2];
        q[2] = tq;
    }
    ivec2 lo = min(q[0], min(q[1], q[2])), hi = max(q[0], max(q[1], q[2]));
    // Pixels whose sample lies in [lo, hi]: ceil(lo / unit) .. floor(hi / unit).
    int shift = int(cs.subpixel_bits);
    ivec2 p0 = max((lo + ivec2(int(unit) - 1)) >> shift, ivec2(0));
    ivec2 p1 = min(hi >> shift, ivec2(int(f.resolution) - 1));
    uint id = o.triangle_base + t;
    if (area != 0l && all(lessThanEqual(p0, p1))) {
        tri.box_lo = uint(p0.x) | (uint(p0.y) << 16);
        tri.box_hi = uint(p1.x) | (uint(p1.y) << 16);
        // Depth plane through the unsnapped window positions (as the interpolation of
        // gl_FragCoord.z); snapped ones if those are degenerate in float.
        vec2 e1 = w[1] - w[0], e2 = w[2] - w[0];
        float det = e1.x * e2.y - e2.x * e1.y;
        vec2 base = w[0];
        if (det == 0.0 || isinf(det) || isnan(det)) {
            // q was reordered; the plane only needs any consistent vertex order.
            vec2 a = vec2(q[0]) / unit + 0.5, b = vec2(q[1]) / unit + 0.5, c = vec2(q[2]) / unit + 0.5;
            e1 = b - a;
            e2 = c - a;
            det = e1.x * e2.y - e2.x * e1.y;
            base = a;
            // The z values must follow the same order as a, b, c.
            if (area < 0l) {
                float tz = z[1];
                z[1] = z[2];
                z[2] = tz;
            }
        }
        float dz1 = z[1] - z[0], dz2 = z[2] - z[0];
        tri.dzdx = (dz1 * e2.y - dz2 * e1.y) / det;
        tri.dzdy = (e1.x * dz2 - e2.x * dz1) / det;
        tri.z = z[0] + tri.dzdx * (float(p0.x) + 0.5 - base.x) + tri.dzdy * (float(p0.y) + 0.5 - base.y);
    }
    tri.x[0] = q[0].x; tri.x[1] = q[1].x; tri.x[2] = q[2].x;
    tri.y[0] = q[0].y; tri.y[1] = q[1].y; tri.y[2] = q[2].y;
    tri.key_low = (id & kKeyTriangleMask) | ((o.flags & kObjectOpen) != 0u ? kKeyOpen : 0u) | (back ? kKeyBackFacing : 0u);
    CsTrianglesRef(cs.triangles).t[id] = tri;
    if (tri.box_lo > tri.box_hi) return;  // no sample inside the image can be covered

    CsCountersRef counters = CsCountersRef(cs.counters);
    uvec2 box = uvec2(p1 - p0) + 1u;
    ivec2 extent = hi - lo;
    if (box.x * box.y <= cs.small_box && extent.x <= int(kCsSmallExtent) && extent.y <= int(kCsSmallExtent)) {
        UintsRef(cs.small).v[atomicAdd(counters.c.small_count, 1u)] = id;
    } else {
        UintsRef(cs.big).v[atomicAdd(counters.c.big_count, 1u)] = id;
        uvec2 tiles = (box + kCsTile - 1u) / kCsTile;
        atomicAdd(counters.c.tiles, uint64_t(tiles.x * tiles.y));
    }
}
