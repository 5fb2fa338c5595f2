#version 460
#extension GL_GOOGLE_include_directive : require
// Auto fit, step 1: extent of the objects' vertices along the projection basis. Counts the
// vertices with a subnormal coordinate: arithmetic flushes them to zero, so a scene made
// of them reads as a point (the host names that instead of sampling nothing).
// One dispatch covers a batch of objects (pc.object: the first, pc.step: how many), one
// invocation per vertex of the batch: one dispatch for a scene of hundreds of objects
// instead of one each (each cost the host about a microsecond to record and the GPU a
// dispatch).
#include "common.glsl.inc"
layout(local_size_x = kGroupSize) in;
#include "dispatch.glsl.inc"

void main() {
    Frame f = frame();
    ObjectsRef objects = ObjectsRef(f.objects);
    uint first = pc.object, last = pc.object + pc.step - 1u;
    ObjectGpu end = objects.o[last];
    uint i = globalIndex();
    if (i >= end.vertex_base + end.vertex_count) return;
    // The last object of the batch whose first vertex is at most i (an empty object shares
    // its base with the next one, which is then the one found).
    uint lo = first, hi = last;
    while (lo < hi) {
        uint mid = (lo + hi + 1u) / 2u;
        if (objects.o[mid].vertex_base <= i) lo = mid; else hi = mid - 1u;
    }
    ObjectGpu o = objects.o[lo];
    i -= o.vertex_base;
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
