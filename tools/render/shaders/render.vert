#version 460
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_GOOGLE_include_directive : require
#include "render.h"

// Pulls the three corners of its triangle (a non-indexed draw of 3 vertices per
// triangle), so the flat normal and the highlight bit are known per vertex.
layout(push_constant, scalar) uniform Push {
    FrameParams frame;
    DrawParams draw;
};

layout(location = 0) flat out vec3 out_colour;

vec3 corner(uint triangle, uint k) {
    uint i = draw.indices.u[triangle * 3 + k];
    uint b = draw.first_float + i * draw.stride_floats;
    vec4 p = vec4(draw.vertices.f[b], draw.vertices.f[b + 1], draw.vertices.f[b + 2], 1.0);
    return vec3(dot(draw.model[0], p), dot(draw.model[1], p), dot(draw.model[2], p));
}

void main() {
    uint triangle = uint(gl_VertexIndex) / 3;
    uint k = uint(gl_VertexIndex) % 3;
    vec3 w0 = corner(triangle, 0), w1 = corner(triangle, 1), w2 = corner(triangle, 2);
    vec3 n = cross(w1 - w0, w2 - w0);
    float len = length(n);
    n = len > 0.0 ? n / len : vec3(0.0, 1.0, 0.0);
    bool hot = ((draw.highlights.u[triangle >> 5] >> (triangle & 31u)) & 1u) != 0u;
    vec3 base = hot ? frame.highlight.rgb : draw.colour.rgb;
    // Two-sided: open surfaces (cloth) show their back faces.
    float diffuse = abs(dot(n, frame.light.xyz));
    out_colour = base * (0.28 + 0.72 * diffuse);
    vec3 w = k == 0 ? w0 : (k == 1 ? w1 : w2);
    gl_Position = frame.view_proj * vec4(w, 1.0);
}
