#version 460
#extension GL_EXT_buffer_reference : require
// The transfer-queue probe's fill: out[i] = i * 2654435761u (session65_transfer_queue_probe.cpp).
layout(local_size_x = 256) in;
layout(buffer_reference, std430) buffer Words { uint v[]; };
layout(push_constant) uniform Push { Words out_words; uint count; uint iterations; } pc;
void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i < pc.count) pc.out_words.v[i] = i * 2654435761u;
}
