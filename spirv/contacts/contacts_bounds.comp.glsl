#version 460
#extension GL_GOOGLE_include_directive : require
// Contact stage, submission 1 (one invocation per triangle): the world box of every active
// object (closed objects), as ordered floats, so that the host can pick the object pairs
// whose boxes overlap and fit the grid to where they overlap.
#include "contacts_common.glsl.inc"
layout(local_size_x = kContactsGroupSize) in;

void main() {
    ContactsParams P = params();
    uint t = globalIndex();
    if (t >= P.triangle_count) return;
    uint o = objectOf(P, t);
    if (UintsRef(P.object_active).v[o] == 0u) return;
    ObjectGpu obj = ObjectsRef(P.objects).o[o];
    uint local_tri = t - obj.triangle_base;
    vec3 lo = vec3(3.0e38), hi = vec3(-3.0e38);
    for (uint k = 0u; k < 3u; ++k) {
        vec3 w = toWorld(obj, fetchPosition(obj, fetchIndex(obj, 3u * local_tri + k)));
        lo = min(lo, w);
        hi = max(hi, w);
    }
    // Minima of every object first, then maxima (each half cleared by one fill).
    UintsRef bmin = UintsRef(P.bounds + uint64_t(o) * 12ul);
    UintsRef bmax = UintsRef(P.bounds + uint64_t(P.object_count + o) * 12ul);
    for (uint k = 0u; k < 3u; ++k) {
        atomicMin(bmin.v[k], orderedFromFloat(lo[k]));
        atomicMax(bmax.v[k], orderedFromFloat(hi[k]));
    }
}
