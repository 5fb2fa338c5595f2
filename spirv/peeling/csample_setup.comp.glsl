#version 460
#extension GL_GOOGLE_include_directive : require
// Compute sampling, triangle setup (one invocation per triangle of the scene): the same
// vertex transform as sample.vert, the viewport transform, snapping to the device's
// sub-pixel grid, facing, the pixel box and the depth plane. Small triangles go to the
// one-invocation list, big ones to the tiled list.
#include "csample.glsl.inc"
layout(local_size_x = kGroupSize) in;
#include "common/dispatch.glsl.inc"

// List sizes of this workgroup, then its first entries in the global lists.
shared uint s_small, s_big, s_tiles;

CsTriangle setupTriangle(Frame f, CsFrame cs, uint id, out uint tiles, out bool small) {
    ObjectGpu o = ObjectsRef(f.objects).o[objectOfTriangle(f, id)];
    uint t = id - o.triangle_base;
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
    tri.z = 0.0;
    tri.dzdx = 0.0;
    tri.dzdy = 0.0;
    // Signed area (twice) of the snapped triangle; Vulkan's a = -area/2 in these
    // coordinates, so with counter-clockwise front faces area > 0 is back-facing.
    int64_t area = int64_t(q[1].x - q[0].x) * int64_t(q[2].y - q[0].y) - int64_t(q[2].x - q[0].x) * int64_t(q[1].y - q[0].y);
    bool back = area > 0l;
    if (area < 0l) {
        ivec2 tq = q[1];
        q[1] = q[2];
        q[2] = tq;
        // Keep the (unsnapped) positions and depths in the same order.
        vec2 tw = w[1];
        w[1] = w[2];
        w[2] = tw;
        float tz = z[1];
        z[1] = z[2];
        z[2] = tz;
    }
    ivec2 lo = min(q[0], min(q[1], q[2])), hi = max(q[0], max(q[1], q[2]));
    // Pixels whose sample lies in [lo, hi]: ceil(lo / unit) .. floor(hi / unit).
    int shift = int(cs.subpixel_bits);
    ivec2 p0 = max((lo + ivec2(int(unit) - 1)) >> shift, ivec2(0));
    ivec2 p1 = min(hi >> shift, ivec2(int(f.resolution) - 1));
    if (area != 0l && all(lessThanEqual(p0, p1))) {
        tri.box_lo = uint(p0.x) | (uint(p0.y) << 16);
        tri.box_hi = uint(p1.x) | (uint(p1.y) << 16);
        // Depth plane through the snapped window positions (the rasterizer's triangle) or,
        // where the device interpolates from the unsnapped ones (llvmpipe), through those;
        // snapped ones as well if the unsnapped ones are degenerate in float.
        vec2 e1 = w[1] - w[0], e2 = w[2] - w[0];
        float det = e1.x * e2.y - e2.x * e1.y;
        vec2 base = w[0];
        if (cs.depth_snapped != 0u || det == 0.0 || isinf(det) || isnan(det)) {
            vec2 a = vec2(q[0]) / unit + 0.5, b = vec2(q[1]) / unit + 0.5, c = vec2(q[2]) / unit + 0.5;
            e1 = b - a;
            e2 = c - a;
            det = e1.x * e2.y - e2.x * e1.y;
            base = a;
        }
        float dz1 = z[1] - z[0], dz2 = z[2] - z[0];
        tri.dzdx = (dz1 * e2.y - dz2 * e1.y) / det;
        tri.dzdy = (e1.x * dz2 - e2.x * dz1) / det;
        tri.z = z[0] + tri.dzdx * (float(p0.x) + 0.5 - base.x) + tri.dzdy * (float(p0.y) + 0.5 - base.y);
    }
    tri.x[0] = q[0].x; tri.x[1] = q[1].x; tri.x[2] = q[2].x;
    tri.y[0] = q[0].y; tri.y[1] = q[1].y; tri.y[2] = q[2].y;
    tri.key_low = (id & kKeyTriangleMask) | ((o.flags & kObjectOpen) != 0u ? kKeyOpen : 0u) | (back ? kKeyBackFacing : 0u);

    uvec2 box = uvec2(p1 - p0) + 1u;
    ivec2 extent = hi - lo;
    small = box.x * box.y <= cs.small_box && extent.x <= int(kCsSmallExtent) && extent.y <= int(kCsSmallExtent);
    uvec2 tile_counts = (box + kCsTile - 1u) / kCsTile;
    tiles = tile_counts.x * tile_counts.y;
    return tri;
}

void main() {
    Frame f = frame();
    CsFrame cs = csFrame(f);
    uint id = globalIndex();
    if (gl_LocalInvocationIndex == 0u) {
        s_small = 0u;
        s_big = 0u;
        s_tiles = 0u;
    }
    barrier();
    bool is_small = false, is_big = false;
    uint tiles = 0u;
    if (id < f.triangle_count) {
        bool small;
        CsTriangle tri = setupTriangle(f, cs, id, tiles, small);
        CsTrianglesRef(cs.triangles).t[id] = tri;
        // Culled triangles (no sample inside the image) join neither list.
        bool live = tri.box_lo <= tri.box_hi;
        is_small = live && small;
        is_big = live && !small;
    }
    // Appends: one shared atomic per subgroup, one global atomic per workgroup and list (a
    // million atomics on one counter would serialise). A workgroup's tiles fit 32 bits:
    // at most 2^22 per triangle (16384^2 pixels).
    uvec4 small_ballot = subgroupBallot(is_small), big_ballot = subgroupBallot(is_big);
    uint sub_tiles = subgroupAdd(is_big ? tiles : 0u);
    uint small_off = 0u, big_off = 0u;
    if (subgroupElect()) {
        small_off = atomicAdd(s_small, subgroupBallotBitCount(small_ballot));
        big_off = atomicAdd(s_big, subgroupBallotBitCount(big_ballot));
        atomicAdd(s_tiles, sub_tiles);
    }
    small_off = subgroupBroadcastFirst(small_off) + subgroupBallotExclusiveBitCount(small_ballot);
    big_off = subgroupBroadcastFirst(big_off) + subgroupBallotExclusiveBitCount(big_ballot);
    barrier();
    if (gl_LocalInvocationIndex == 0u) {
        CsCountersRef counters = CsCountersRef(cs.counters);
        s_small = s_small != 0u ? atomicAdd(counters.c.small_count, s_small) : 0u;
        s_big = s_big != 0u ? atomicAdd(counters.c.big_count, s_big) : 0u;
        if (s_tiles != 0u) atomicAdd(counters.c.tiles, uint64_t(s_tiles));
    }
    barrier();
    if (is_small) UintsRef(cs.small).v[s_small + small_off] = id;
    if (is_big) UintsRef(cs.big).v[s_big + big_off] = id;
}
