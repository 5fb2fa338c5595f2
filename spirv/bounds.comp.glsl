#version 460
#extension GL_GOOGLE_include_directive : require
// Auto fit, step 1: extent of one object's vertices along the projection basis.
#include "common.glsl.inc"
layout(local_size_x = kGroupSize) in;
#include "dispatch.glsl.inc"

void main() {
    Frame f = frame();
    ObjectGpu o = ObjectsRef(f.objects).o[pc.object];
    uint i = globalIndex();
    if (i >= o.vertex_count) return;
    vec3 w = toWorld(o, fetchPosition(o, i));
    HeaderRef h = HeaderRef(f.header);
    for (uint axis = 0u; axis < 3u; ++axis) {
        uint key = orderedFromFloat(dot(basisRow(f, axis), w));
        atomicMin(h.h.bounds[axis], key);
        atomicMax(h.h.bounds[3u + axis], key);
    }
}
