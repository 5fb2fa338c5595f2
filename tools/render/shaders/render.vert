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
    uint pass;
    float halo_width;
    vec2 image_size;
};

layout(location = 0) flat out vec3 out_colour;

vec3 corner(uint triangle, uint k) {
    uint i = draw.indices.u[triangle * 3 + k];
    uint b = draw.first_float + i * draw.stride_floats;
    vec4 p = vec4(draw.vertices.f[b], draw.vertices.f[b + 1], draw.vertices.f[b + 2], 1.0);
    return vec3(dot(draw.model[0], p), dot(draw.model[1], p), dot(draw.model[2], p));
}

// Outside the depth range: the triangle is clipped away whole.
const vec4 kNowhere = vec4(0.0, 0.0, -1.0, 1.0);
// Colliding triangles whose longest edge on the screen is at most this many halo widths
// are drawn again on top of everything (with the halo); larger ones only in the first pass.
const float kLargestOnTop = 5.0;

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
    if (pass == RENDER_PASS_ALL) return;
    if (!hot) {
        gl_Position = kNowhere;
        return;
    }
    vec4 c0 = frame.view_proj * vec4(w0, 1.0), c1 = frame.view_proj * vec4(w1, 1.0), c2 = frame.view_proj * vec4(w2, 1.0);
    if (c0.w <= 0.0 || c1.w <= 0.0 || c2.w <= 0.0) {
        gl_Position = kNowhere;  // reaches behind the eye: the first pass shows what is seen
        return;
    }
    vec2 half_size = 0.5 * image_size;
    vec2 s0 = c0.xy / c0.w * half_size, s1 = c1.xy / c1.w * half_size, s2 = c2.xy / c2.w * half_size;
    // Large on the screen: the first pass shows it plainly, and on top it would hide the
    // scene behind it (the rigid bunnies' box floor).
    if (max(max(length(s1 - s0), length(s2 - s1)), length(s0 - s2)) > kLargestOnTop * halo_width) {
        gl_Position = kNowhere;
        return;
    }
    if (pass == RENDER_PASS_HOT) return;
    // The halo: each corner moves away from the triangle's centre by the halo's width in
    // pixels, so a colliding triangle smaller than a pixel still shows as a spot.
    out_colour = frame.halo.rgb;
    vec2 centre = (s0 + s1 + s2) / 3.0;
    vec2 here = gl_Position.xy / gl_Position.w * half_size;
    vec2 away = here - centre;
    float d = length(away);
    // A triangle seen edge-on or smaller than rounding: its corners spread in three directions.
    away = d > 1e-6 ? away / d : (k == 0 ? vec2(0.0, -1.0) : (k == 1 ? vec2(0.87, 0.5) : vec2(-0.87, 0.5)));
    vec2 moved = (here + away * halo_width) / half_size;
    gl_Position = vec4(moved * gl_Position.w, gl_Position.z, gl_Position.w);
}
