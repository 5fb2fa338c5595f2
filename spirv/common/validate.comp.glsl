#version 460
#extension GL_GOOGLE_include_directive : require
// Input check for geometry that lives only on the GPU (the host checks its own meshes):
// every index below the vertex count, every position of a triangle finite and, after the
// object's transform, within the sampling range (+-kMaxWorldCoordinate: beyond it the
// projection needs subnormal floats, and a product may overflow). Counts the triangles
// that fail and keeps one of each kind so the host can name it.
#include "common.glsl.inc"
layout(local_size_x = kGroupSize) in;
#include "dispatch.glsl.inc"

void main() {
    Frame f = frame();
    ObjectGpu o = ObjectsRef(f.objects).o[pc.object];
    uint t = globalIndex();
    if (t >= o.triangle_count) return;
    HeaderRef h = HeaderRef(f.header);
    bool bad_index = false, bad_vertex = false;
    for (uint c = 0u; c < 3u; ++c) {
        uint i = fetchRawIndex(o, t * 3u + c);
        if (i >= o.vertex_count) {
            bad_index = true;
        } else {
            vec3 p = fetchPosition(o, i);
            vec3 w = toWorld(o, p);
            // NaN fails the last test too; the first two say why in the shader.
            if (any(isnan(p)) || any(isinf(p)) || !all(lessThanEqual(abs(w), vec3(kMaxWorldCoordinate)))) bad_vertex = true;
        }
    }
    if (bad_index && atomicAdd(h.h.bad_index_count, 1u) == 0u) {
        h.h.bad_index_object = pc.object;
        h.h.bad_index_triangle = t;
    }
    if (bad_vertex && atomicAdd(h.h.bad_vertex_count, 1u) == 0u) {
        h.h.bad_vertex_object = pc.object;
        h.h.bad_vertex_triangle = t;
    }
}
