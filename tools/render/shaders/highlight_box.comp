#version 460
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_GOOGLE_include_directive : require
#include "render.h"

// The world box of one draw's colliding triangles, merged into BoxWords by atomics, so a
// picture can be aimed at the contact whatever holds the vertices (the engine's GPU
// meshes included: the host never sees those).
layout(local_size_x = 64) in;
layout(push_constant, scalar) uniform Push {
    DrawParams draw;
    BoxWords box;
    uint triangles;
};

vec3 corner(uint triangle, uint k) {
    uint i = draw.indices.u[triangle * 3 + k];
    uint b = draw.first_float + i * draw.stride_floats;
    vec4 p = vec4(draw.vertices.f[b], draw.vertices.f[b + 1], draw.vertices.f[b + 2], 1.0);
    return vec3(dot(draw.model[0], p), dot(draw.model[1], p), dot(draw.model[2], p));
}

// A float as a uint that orders as the float does (negative ones reversed below positive).
uint ordered(float f) {
    uint u = floatBitsToUint(f);
    return (u & 0x80000000u) != 0u ? ~u : u | 0x80000000u;
}

void main() {
    uint t = gl_GlobalInvocationID.x;
    if (t >= triangles || ((draw.highlights.u[t >> 5] >> (t & 31u)) & 1u) == 0u) return;
    for (uint k = 0; k < 3; ++k) {
        vec3 p = corner(t, k);
        if (any(isnan(p)) || any(isinf(p))) continue;
        for (int a = 0; a < 3; ++a) {
            atomicMin(box.v[a], ordered(p[a]));
            atomicMax(box.v[a + 3], ordered(p[a]));
        }
    }
}
