#version 460
#extension GL_GOOGLE_include_directive : require
// Contact stage, submission 2, pass 1 (one invocation per triangle): the triangle in grid
// space (CtTriangle: projected vertices, depth plane, unit normal, boundary weight,
// object and facing); a triangle with a small pixel box is drawn here, a bigger one is
// queued as work items of consecutive 8x8-pixel tiles for contacts_tiles.comp (one tile
// per item, or more past kContactsMaxTriangleItems items). Triangles of
// inactive objects (open, or in no candidate pair) and triangles with no projected area
// are skipped.
#include "contacts_common.glsl.inc"
layout(local_size_x = kContactsGroupSize) in;

// First pixel index whose centre is at or after x, clamped to [0, n] (floats beyond the
// grid never reach the int conversion).
int firstPixel(float x, uint n) { return int(ceil(clamp(x - 0.5, -1.0, float(n)))); }
int lastPixel(float x, uint n) { return int(floor(clamp(x - 0.5, -1.0, float(n)))); }

void main() {
    ContactsParams P = params();
    uint t = globalIndex();
    if (t >= P.triangle_count) return;
    CtTrianglesRef tris = CtTrianglesRef(P.triangles);
    uint o = objectOf(P, t);
    if (UintsRef(P.object_active).v[o] == 0u) {
        tris.t[t].key = kCtSkipped;
        return;
    }
    ObjectGpu obj = ObjectsRef(P.objects).o[o];
    uint local_tri = t - obj.triangle_base;
    vec3 g[3];
    for (uint k = 0u; k < 3u; ++k) g[k] = toGrid(P, toWorld(obj, fetchPosition(obj, fetchIndex(obj, 3u * local_tri + k))));
    // The grid basis is right-handed and isotropic, so the normal's z is the signed
    // projected area (twice): negative where the ray (along +z) enters the object.
    vec3 n = cross(g[1] - g[0], g[2] - g[0]);
    float len = length(n);
    CtTriangle c;
    c.key = kCtSkipped;
    if (n.z == 0.0 || !(len > 0.0) || isinf(len)) {
        tris.t[t].key = kCtSkipped;
        return;
    }
    c.x[0] = g[0].x; c.x[1] = g[1].x; c.x[2] = g[2].x;
    c.y[0] = g[0].y; c.y[1] = g[1].y; c.y[2] = g[2].y;
    c.z0 = g[0].z;
    c.gx = -n.x / n.z;
    c.gy = -n.y / n.z;
    vec3 un = n / len;
    c.n[0] = un.x; c.n[1] = un.y; c.n[2] = un.z;
    c.weight = min(1.0 / abs(un.z), P.max_weight);
    c.key = o | (n.z < 0.0 ? kCtKeyEntering : 0u);
    float x0 = min(g[0].x, min(g[1].x, g[2].x)), x1 = max(g[0].x, max(g[1].x, g[2].x));
    float y0 = min(g[0].y, min(g[1].y, g[2].y)), y1 = max(g[0].y, max(g[1].y, g[2].y));
    int bx0 = max(firstPixel(x0, P.width), 0), bx1 = min(lastPixel(x1, P.width), int(P.width) - 1);
    int by0 = max(firstPixel(y0, P.height), 0), by1 = min(lastPixel(y1, P.height), int(P.height) - 1);
    c.box[0] = bx0; c.box[1] = by0; c.box[2] = bx1; c.box[3] = by1;
    if (bx0 > bx1 || by0 > by1) c.key = kCtSkipped;
    tris.t[t] = c;
    if (c.key == kCtSkipped) return;
    uint w = uint(bx1 - bx0 + 1), h = uint(by1 - by0 + 1);
    if (uint64_t(w) * uint64_t(h) <= uint64_t(kContactsSmallBox)) {
        for (int py = by0; py <= by1; ++py)
            for (int px = bx0; px <= bx1; ++px) drawPixel(P, t, c, px, py);
        return;
    }
    uint tiles = ((w + kContactsTile - 1u) / kContactsTile) * ((h + kContactsTile - 1u) / kContactsTile);
    uint per_item = contactTilesPerItem(tiles), count = (tiles + per_item - 1u) / per_item;
    ContactsHeaderRef hdr = contactsHeader(P);
    uint first = atomicAdd(hdr.h.item_count, count);
    if (uint64_t(first) + uint64_t(count) > uint64_t(P.item_capacity)) {
        atomicOr(hdr.h.flags, kContactsOverflowItems);
        atomicMax(hdr.h.items_needed, first + count);
        return;
    }
    CtUvec2sRef items = CtUvec2sRef(P.items);
    for (uint k = 0u; k < count; ++k) items.v[first + k] = uvec2(t, k);
}
