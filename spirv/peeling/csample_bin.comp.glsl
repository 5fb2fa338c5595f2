#version 460
#extension GL_GOOGLE_include_directive : require
// Compute sampling, binning: each tiled triangle gets ceil(tiles / g_i) work items, with
// g_i = triangleTilesPerItem(tiles, tiles_per_item) >= tiles_per_item (so that no triangle
// takes more than kCsMaxTriangleItems items: this loop writes them). tiles_per_item is the
// smallest count that keeps every item within the buffer's capacity:
// sum(ceil(T_i / g_i)) <= sum(ceil(T_i / g)) <= sum(T_i) / g + big_count <= item_capacity.
#include "csample.glsl.inc"
layout(local_size_x = kGroupSize) in;
#include "common/dispatch.glsl.inc"

void main() {
    Frame f = frame();
    CsFrame cs = csFrame(f);
    CsCountersRef counters = CsCountersRef(cs.counters);
    uint i = globalIndex();
    uint big = counters.c.big_count;
    if (groupIndex() * gl_WorkGroupSize.x >= big) return;  // whole workgroups only
    uint64_t budget = uint64_t(cs.item_capacity - big);
    uint64_t total = counters.c.tiles;
    // At most the tiles of the biggest possible triangle (kCsMaxTriangleTiles): then every
    // triangle takes one item, big_count <= item_capacity, and `per` fits 32 bits.
    uint per = uint(clamp((total + budget - 1ul) / budget, 1ul, uint64_t(kCsMaxTriangleTiles)));
    if (i == 0u) counters.c.tiles_per_item = per;
    uint items = 0u, id = 0u;
    if (i < big) {
        id = UintsRef(cs.big).v[i];
        CsTriangle tri = CsTrianglesRef(cs.triangles).t[id];
        uvec2 box = unpackPixel(tri.box_hi) - unpackPixel(tri.box_lo) + 1u;
        uvec2 tiles = (box + kCsTile - 1u) / kCsTile;
        uint count = tiles.x * tiles.y, per_item = triangleTilesPerItem(count, per);
        items = (count + per_item - 1u) / per_item;
    }
    // One atomic per subgroup.
    uint offset = subgroupExclusiveAdd(items), sum = subgroupAdd(items), first = 0u;
    if (subgroupElect()) first = atomicAdd(counters.c.item_count, sum);
    first = subgroupBroadcastFirst(first) + offset;
    Uvec2sRef out_items = Uvec2sRef(cs.items);
    for (uint k = 0u; k < items; ++k) out_items.v[first + k] = uvec2(id, k);
}
