#version 460
#extension GL_EXT_buffer_reference : require
// The transfer-queue probe's compute load: a dependent chain of multiply-adds per invocation,
// so its length scales with `iterations` and it reads no memory.
layout(local_size_x = 256) in;
layout(buffer_reference, std430) buffer Words { uint v[]; };
layout(push_constant) uniform Push { Words out_words; uint count; uint iterations; } pc;
void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= pc.count) return;
    uint x = i;
    for (uint k = 0u; k < pc.iterations; ++k) x = x * 1664525u + 1013904223u;
    pc.out_words.v[i] = x;
}
