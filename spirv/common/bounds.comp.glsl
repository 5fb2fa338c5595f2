#version 460
#extension GL_GOOGLE_include_directive : require
// Auto fit, step 1: extent of the objects' vertices along the projection basis. Counts the
// vertices with a subnormal coordinate: arithmetic flushes them to zero, so a scene made
// of them reads as a point (the host names that instead of sampling nothing).
// One dispatch covers a batch of objects (pc.object: the first, pc.step: how many), one
// invocation per vertex of the batch: one dispatch for a scene of hundreds of objects
// instead of one each (each cost the host about a microsecond to record and the GPU a
// dispatch). Each workgroup reduces its vertices' extent in shared memory and adds it
// with one atomic per field: every vertex's own atomics on the header's words serialised
// (0.18 ms for the 1.3M vertices of deep-blobs on an H100, where reading them takes 10 us).
#include "common.glsl.inc"
layout(local_size_x = kGroupSize) in;
#include "dispatch.glsl.inc"

// The workgroup's extent: min keys (0-2), max keys (3-5), subnormal count (6), reduced
// together in log2(kGroupSize) steps of one barrier each.
shared uint s_fields[7][kGroupSize];

void main() {
    Frame f = frame();
    ObjectsRef objects = ObjectsRef(f.objects);
    uint first = pc.object, last = pc.object + pc.step - 1u;
    ObjectGpu end = objects.o[last];
    uint i = globalIndex();
    // Every invocation reaches the reductions (they hold barriers); one past the batch
    // contributes the neutral values.
    bool live = i < end.vertex_base + end.vertex_count;
    uint subnormal = 0u;
    uvec3 lo_keys = uvec3(0xFFFFFFFFu), hi_keys = uvec3(0u);
    if (live) {
        // The last object of the batch whose first vertex is at most i (an empty object
        // shares its base with the next one, which is then the one found).
        uint lo = first, hi = last;
        while (lo < hi) {
            uint mid = (lo + hi + 1u) / 2u;
            if (objects.o[mid].vertex_base <= i) lo = mid; else hi = mid - 1u;
        }
        ObjectGpu o = objects.o[lo];
        vec3 p = fetchPosition(o, i - o.vertex_base);
        vec3 w = toWorld(o, p);
        // Magnitude bits in [1, 0x7FFFFF]: a subnormal (0 wraps past the bound).
        subnormal = any(lessThan((floatBitsToUint(p) & 0x7FFFFFFFu) - 1u, uvec3(0x7FFFFFu))) ? 1u : 0u;
        for (uint axis = 0u; axis < 3u; ++axis) lo_keys[axis] = hi_keys[axis] = orderedFromFloat(dot(basisRow(f, axis), w));
    }
    const uint me = gl_LocalInvocationIndex;
    for (uint axis = 0u; axis < 3u; ++axis) {
        s_fields[axis][me] = lo_keys[axis];
        s_fields[3u + axis][me] = hi_keys[axis];
    }
    s_fields[6][me] = subnormal;
    barrier();
    for (uint stride = kGroupSize / 2u; stride > 0u; stride >>= 1) {
        if (me < stride) {
            for (uint axis = 0u; axis < 3u; ++axis) {
                s_fields[axis][me] = min(s_fields[axis][me], s_fields[axis][me + stride]);
                s_fields[3u + axis][me] = max(s_fields[3u + axis][me], s_fields[3u + axis][me + stride]);
            }
            s_fields[6][me] += s_fields[6][me + stride];
        }
        barrier();
    }
    if (me != 0u) return;
    subnormal = s_fields[6][0];
    for (uint axis = 0u; axis < 3u; ++axis) {
        lo_keys[axis] = s_fields[axis][0];
        hi_keys[axis] = s_fields[3u + axis][0];
    }
    HeaderRef h = HeaderRef(f.header);
    if (subnormal != 0u) atomicAdd(h.h.subnormal_vertices, subnormal);
    for (uint axis = 0u; axis < 3u; ++axis) {
        atomicMin(h.h.bounds[axis], lo_keys[axis]);
        atomicMax(h.h.bounds[3u + axis], hi_keys[axis]);
    }
}
