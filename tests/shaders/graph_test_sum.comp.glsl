#version 460
#extension GL_EXT_buffer_reference : require
// Sums an R32_UINT storage image into a counter.
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0, r32ui) uniform readonly uimage2D image;
layout(buffer_reference, std430) buffer Counter { uint value; };
layout(push_constant) uniform Push { Counter sum; } pc;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, imageSize(image)))) return;
    uint v = imageLoad(image, p).x;
    if (v != 0u) atomicAdd(pc.sum.value, v);
}
