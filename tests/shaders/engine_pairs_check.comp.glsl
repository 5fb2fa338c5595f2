#version 460
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
// The engine's own reader of vkcollide's device pairs in tests/api/engine_loop_tests.cpp
// (DetectSettings::reliable.device_pairs): submitted after the world's signal, it reads the header
// and the pairs through their device addresses and writes what the host checks against
// DetectResult::pairs: out[0] count, [1] flags, [2] needed, [3] an order-sensitive checksum
// (the sum over i of mix(i, pair i)), [4] the pairs between two different objects; with the
// responses (reliable.device_responses; address 0 without) [5] their count, [6] the same
// checksum over them (mixResponse, their float bits as they are).
layout(local_size_x = 64) in;
struct Pair {
    uint object_a, triangle_a, object_b, triangle_b;
};
struct Response {
    uint object, triangle;
    uint direction[3];
    uint partner_count;
};
layout(buffer_reference, scalar) readonly buffer Pairs { Pair p[]; };
layout(buffer_reference, scalar) readonly buffer Responses { Response r[]; };
layout(buffer_reference, scalar) readonly buffer Header { uint count, needed, flags, capacity, responses, response_capacity; };
layout(buffer_reference, scalar) buffer Out { uint v[]; };
layout(push_constant, scalar) uniform Push {
    Pairs pairs;
    Header header;
    Out out_values;
    Responses responses;
} pc;

// The same on the host (engine_loop_tests.cpp, mix()).
uint mixPair(uint i, Pair p) {
    uint h = i * 0x9E3779B1u;
    h ^= p.object_a * 0x85EBCA6Bu;
    h ^= p.triangle_a * 0xC2B2AE35u;
    h ^= p.object_b * 0x27D4EB2Fu;
    h ^= p.triangle_b * 0x165667B1u;
    return h ^ (h >> 15);
}

uint mixResponse(uint i, Response r) {
    uint h = i * 0x9E3779B1u;
    h ^= r.object * 0x85EBCA6Bu;
    h ^= r.triangle * 0xC2B2AE35u;
    h ^= r.direction[0] * 0x27D4EB2Fu;
    h ^= r.direction[1] * 0x165667B1u;
    h ^= r.direction[2] * 0xD3A2646Cu;
    h ^= r.partner_count * 0xFD7046C5u;
    return h ^ (h >> 15);
}

void main() {
    uint count = pc.header.count;
    if (gl_GlobalInvocationID.x == 0u) {
        pc.out_values.v[0] = count;
        pc.out_values.v[1] = pc.header.flags;
        pc.out_values.v[2] = pc.header.needed;
    }
    uint sum = 0u, cross = 0u;
    for (uint i = gl_GlobalInvocationID.x; i < count; i += gl_NumWorkGroups.x * 64u) {
        Pair p = pc.pairs.p[i];
        sum += mixPair(i, p);
        if (p.object_a != p.object_b) ++cross;
    }
    atomicAdd(pc.out_values.v[3], sum);
    atomicAdd(pc.out_values.v[4], cross);
    if (uint64_t(pc.responses) == 0ul) return;
    uint responses = pc.header.responses, response_sum = 0u;
    if (gl_GlobalInvocationID.x == 0u) pc.out_values.v[5] = responses;
    for (uint i = gl_GlobalInvocationID.x; i < responses; i += gl_NumWorkGroups.x * 64u) response_sum += mixResponse(i, pc.responses.r[i]);
    atomicAdd(pc.out_values.v[6], response_sum);
}
