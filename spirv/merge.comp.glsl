#version 460
#extension GL_GOOGLE_include_directive : require
// Ray merging: texel (x, y) of level l is the union of its four children at level l-1.
#include "common.glsl.inc"
layout(local_size_x = kGroupSize) in;
#include "dispatch.glsl.inc"

void main() {
    Frame f = frame();
    uint size = f.resolution >> pc.level;
    uint i = globalIndex();
    if (i >= size * size) return;
    uint x = i % size, y = i / size, child = size * 2u;
    Vec4sRef b = Vec4sRef(f.bundles);
    uint src = f.level_offset[pc.level - 1u];
    vec4 u = boxUnion(boxUnion(b.v[src + (2u * y) * child + 2u * x], b.v[src + (2u * y) * child + 2u * x + 1u]),
                      boxUnion(b.v[src + (2u * y + 1u) * child + 2u * x], b.v[src + (2u * y + 1u) * child + 2u * x + 1u]));
    b.v[f.level_offset[pc.level] + i] = u;
}
