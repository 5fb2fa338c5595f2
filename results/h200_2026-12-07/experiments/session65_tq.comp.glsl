#version 460
#extension GL_EXT_buffer_reference : require
// The transfer-queue probe's two shaders (session65_transfer_queue_probe.cpp), one source:
//   default    the fill: out[i] = i * 2654435761u
//   -DBUSY     the compute load: a dependent chain of `iterations` multiply-adds per
//              invocation, so its length scales with `iterations` and it reads no memory
layout(local_size_x = 256) in;
layout(buffer_reference, std430) buffer Words { uint v[]; };
layout(push_constant) uniform Push { Words out_words; uint count; uint iterations; } pc;
void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= pc.count) return;
#ifdef BUSY
    uint x = i;
    for (uint k = 0u; k < pc.iterations; ++k) x = x * 1664525u + 1013904223u;
    pc.out_words.v[i] = x;
#else
    pc.out_words.v[i] = i * 2654435761u;
#endif
}
