#version 460
#extension GL_GOOGLE_include_directive : require
// Ray merging: texel (x, y) of level l is the union of its four children at level l-1
// (with depth-aware separation also their depth intervals: (x, y, depth) boxes).
#include "common/common.glsl.inc"
#include "depth.glsl.inc"
layout(local_size_x = kGroupSize) in;
#include "common/dispatch.glsl.inc"

void main() {
    Frame f = frame();
    uint size = f.resolution >> pc.level;
    uint i = globalIndex();
    if (i >= size * size) return;
    uint x = i % size, y = i / size, child = size * 2u;
    uint src = f.level_offset[pc.level - 1u];
    uint c00 = src + (2u * y) * child + 2u * x, c10 = c00 + 1u, c01 = c00 + child, c11 = c01 + 1u;
    Vec4sRef b = Vec4sRef(f.bundles);
    b.v[f.level_offset[pc.level] + i] = boxUnion(boxUnion(b.v[c00], b.v[c10]), boxUnion(b.v[c01], b.v[c11]));
    if (f.depth_aware != 0u) {
        Vec2sRef d = Vec2sRef(f.bundle_depth);
        d.v[f.level_offset[pc.level] + i] = depthUnion(depthUnion(d.v[c00], d.v[c10]), depthUnion(d.v[c01], d.v[c11]));
    }
}
