#version 460
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_buffer_reference : require
// Writes 1 to the attachment and counts fragments, so a double-covered pixel on the
// shared diagonal shows up as a count above the pixel area.
layout(buffer_reference, std430) buffer Counter { uint value; };
layout(push_constant) uniform Push {
    vec4 rect;
    vec2 extent;
    Counter counter;
} pc;
layout(location = 0) out uint out_value;

void main() {
    atomicAdd(pc.counter.value, 1u);
    out_value = 1u;
}
