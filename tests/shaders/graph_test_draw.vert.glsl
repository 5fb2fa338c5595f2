#version 460
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
// Foundation check: a screen-space rectangle drawn as two triangles sharing a diagonal.
layout(push_constant) uniform Push {
    vec4 rect;    // x0, y0, x1, y1 in pixels
    vec2 extent;  // framebuffer size in pixels
    uint64_t counter;  // unused here; shared layout with the fragment shader
} pc;

void main() {
    const vec2 corners[6] = vec2[](vec2(0, 0), vec2(1, 0), vec2(1, 1), vec2(0, 0), vec2(1, 1), vec2(0, 1));
    vec2 c = corners[gl_VertexIndex];
    vec2 p = mix(pc.rect.xy, pc.rect.zw, c);
    gl_Position = vec4(p / pc.extent * 2.0 - 1.0, 0.5, 1.0);
}
