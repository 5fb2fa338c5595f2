#version 460
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_scalar_block_layout : require
// The engine's own deformation in tests/api/engine_loop_tests.cpp: out[i] = rest[i] * scale
// + offset. `precise` keeps the multiply and the add separately rounded (no fused
// multiply-add), so the host forms the same positions bit for bit for its reference.
layout(local_size_x = 64) in;
layout(buffer_reference, scalar) readonly buffer Rest { vec3 p[]; };
layout(buffer_reference, scalar) writeonly buffer Out { vec3 p[]; };
layout(push_constant, scalar) uniform Push {
    Rest rest;
    Out out_positions;
    vec3 offset;
    float scale;
    uint count;
} pc;

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= pc.count) return;
    precise vec3 p = pc.rest.p[i] * pc.scale + pc.offset;
    pc.out_positions.p[i] = p;
}
