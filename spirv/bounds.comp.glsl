#version 460
#extension GL_GOOGLE_include_directive : require
// Auto fit, step 1: extent of one object's vertices along the projection basis. Counts the
// vertices with a subnormal coordinate: arithmetic flushes them to zero, so a scene made
// of them reads as a point (the host names that instead of sampling nothing).
#include "common.glsl.inc"
layout(local_size_x = kGroupSize) in;
#include "dispatch.glsl.inc"

void main() {
    Frame f = frame();
    ObjectGpu o = ObjectsRef(f.objects).o[pc.object];
    uint i = globalIndex();
    if (i >= o.vertex_count) return;
    vec3 p = fetchPosition(o, i);
    vec3 w = toWorld(o, p);
    HeaderRef h = HeaderRef(f.header);
    // Magnitude bits in [1, 0x7FFFFF]: a subnormal (0 wraps past the bound).
    if (any(lessThan((floatBitsToUint(p) & 0x7FFFFFFFu) - 1u, uvec3(0x7FFFFFu)))) atomicAdd(h.h.subnormal_vertices, 1u);
    for (uint axis = 0u; axis < 3u; ++axis) {
        uint key = orderedFromFloat(dot(basisRow(f, axis), w));
        atomicMin(h.h.bounds[axis], key);
        atomicMax(h.h.bounds[3u + axis], key);
    }
}
