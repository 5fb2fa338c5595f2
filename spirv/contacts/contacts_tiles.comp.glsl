#version 460
#extension GL_GOOGLE_include_directive : require
// Contact stage, submission 2, pass 2 (one workgroup per work item, indirect): the 8x8
// tiles of a work item of a big triangle's pixel box (one, or contactTilesPerItem past
// kContactsMaxTriangleItems items), one invocation per pixel of a tile. Step 1 (one invocation)
// writes this pass's indirect arguments from the item count first.
#include "contacts_common.glsl.inc"
layout(local_size_x = kContactsGroupSize) in;

void main() {
    ContactsParams P = params();
    ContactsHeaderRef hdr = contactsHeader(P);
    if (pc.step == 1u) {
        if (gl_GlobalInvocationID.x != 0u) return;
        uint groups = hdr.h.flags != 0u ? 0u : min(hdr.h.item_count, P.item_capacity);
        UintsRef args = UintsRef(P.args);
        uint x = min(groups, P.max_groups_x);
        args.v[0] = x;
        args.v[1] = x == 0u ? 0u : (groups + x - 1u) / x;
        args.v[2] = 1u;
        return;
    }
    uint item = groupIndex();
    if (item >= min(hdr.h.item_count, P.item_capacity)) return;
    uvec2 it = CtUvec2sRef(P.items).v[item];
    CtTriangle c = CtTrianglesRef(P.triangles).t[it.x];
    uint w = uint(c.box[2] - c.box[0] + 1), h = uint(c.box[3] - c.box[1] + 1);
    uint tiles_x = (w + kContactsTile - 1u) / kContactsTile;
    uint tiles = tiles_x * ((h + kContactsTile - 1u) / kContactsTile);
    uint per_item = contactTilesPerItem(tiles);  // as the setup pass counted
    uint first = it.y * per_item, last = min(first + per_item, tiles);
    for (uint tile = first; tile < last; ++tile) {
        int px = c.box[0] + int((tile % tiles_x) * kContactsTile + gl_LocalInvocationIndex % kContactsTile);
        int py = c.box[1] + int((tile / tiles_x) * kContactsTile + gl_LocalInvocationIndex / kContactsTile);
        if (px > c.box[2] || py > c.box[3]) continue;
        drawPixel(P, it.x, c, px, py);
    }
}
