#version 460
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
// The exact triangle-triangle test and its predicates alone, for their unit tests
// (tests/gpu/exact_tritri_tests.cpp), one case per invocation:
//  mode 0 (pairs, 24 words: a's 9 floats, b's 9 floats, a's 3 indices, b's 3 indices):
//    bit 0 exactTrianglesIntersect(a, b), bit 1 exactNeighbours, bits 8.. the number of
//    exact fallbacks the decision ran (saturated at 2^24 - 1);
//  mode 1 (predicates, 12 words: points a, b, c, d): two bits (sign + 1) each, from bit 0:
//    orient3d(a,b,c,d), orient3dExact(a,b,c,d), the plane (a,b,c)'s side of d,
//    orient2d(a.xy,b.xy,c.xy), orient2dExact(same), orient2d(b.yz,c.yz,d.yz),
//    orient2dExact(same); bit 14 the plane's certainlyNotCollinear; bits 16.. the exact
//    fallbacks of the filtered predicates (the first, third, fourth and sixth);
//  mode 2 (rounding, 12 words: doubles a, b, x, a float's value f, then the CPU's a / b and
//    sqrt(x); 13 words out): roundedQuotient(a, b), roundedSqrt(x), the two stepped to from
//    5 ulps off the CPU's values (the correction alone), the driver's own a / b and sqrt(x),
//    as doubles' bits, then roundedFloatBits(f);
//  mode 3 (the steps of the rounding, 8 words: doubles a, b, c, h; 16 words out): TwoSum(a, b),
//    Veltkamp's split of a, TwoProduct(a, b) (two doubles each), the signs (+1) of
//    roundedQuotientSide and roundedRootSide at the midpoint c + h, then fma(a, b, -a * b) (the
//    product's error where the driver's fma is fused; for the record: Vulkan does not promise it).
#include "cells/exact_predicates.glsl.inc"
#include "cells/tritri_exact.glsl.inc"
#include "cells/rounded_fp64.glsl.inc"
layout(local_size_x = 64) in;

layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer ExactCasesRef { uint w[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) writeonly buffer ExactResultsRef { uint r[]; };
layout(push_constant, scalar) uniform ExactPush {
    ExactCasesRef cases;
    ExactResultsRef results;
    uint count;
    uint mode;
} pc;

vec3 point(uint base) {
    return uintBitsToFloat(uvec3(pc.cases.w[base], pc.cases.w[base + 1u], pc.cases.w[base + 2u]));
}

uint signBits(int s, uint shift) { return uint(s + 1) << shift; }

// A double in two input words (low first), and one written to two result words.
double caseDouble(uint word) { return packDouble2x32(uvec2(pc.cases.w[word], pc.cases.w[word + 1u])); }
void putDouble(uint word, double v) {
    uvec2 u = unpackDouble2x32(v);
    pc.results.r[word] = u.x;
    pc.results.r[word + 1u] = u.y;
}

void main() {
    uint id = gl_GlobalInvocationID.x;
    if (id >= pc.count) return;
    if (pc.mode == 0u) {
        uint base = 24u * id;
        vec3 a[3], b[3];
        for (uint k = 0u; k < 3u; ++k) {
            a[k] = point(base + 3u * k);
            b[k] = point(base + 9u + 3u * k);
        }
        uvec3 index_a = uvec3(pc.cases.w[base + 18u], pc.cases.w[base + 19u], pc.cases.w[base + 20u]);
        uvec3 index_b = uvec3(pc.cases.w[base + 21u], pc.cases.w[base + 22u], pc.cases.w[base + 23u]);
        bool hit = exactTrianglesIntersect(a, b);
        uint fallbacks = min(exactFallbacks, 0xffffffu);
        pc.results.r[id] = (hit ? 1u : 0u) | (exactNeighbours(index_a, a, index_b, b) ? 2u : 0u) | (fallbacks << 8);
        return;
    }
    if (pc.mode == 2u) {
        uint base = 12u * id, out_base = 13u * id;
        double a = caseDouble(base), b = caseDouble(base + 2u), x = caseDouble(base + 4u), f = caseDouble(base + 6u);
        double q_cpu = caseDouble(base + 8u), s_cpu = caseDouble(base + 10u);
        double q_off = abs(q_cpu), s_off = s_cpu;
        for (int k = 0; k < 5; ++k) {
            q_off = roundedNextUp(q_off);
            s_off = roundedNextDown(s_off);
        }
        double q_far = roundedNearest(0u, abs(a), abs(b), q_off);
        if ((a < 0.0lf) != (b < 0.0lf)) q_far = -q_far;
        double v[6] = double[6](roundedQuotient(a, b), roundedSqrt(x), q_far, roundedNearest(1u, x, 0.0lf, s_off), a / b, sqrt(x));
        for (uint k = 0u; k < 6u; ++k) putDouble(out_base + 2u * k, v[k]);
        pc.results.r[out_base + 12u] = roundedFloatBits(f);
        return;
    }
    if (pc.mode == 3u) {
        uint base = 8u * id, out_base = 16u * id;
        double a = caseDouble(base), b = caseDouble(base + 2u), c = caseDouble(base + 4u), h = caseDouble(base + 6u);
        double v[6];
        exactTwoSum(a, b, v[0], v[1]);
        exactSplit(a, v[2], v[3]);
        exactTwoProduct(a, b, v[4], v[5]);
        for (uint k = 0u; k < 6u; ++k) putDouble(out_base + 2u * k, v[k]);
        pc.results.r[out_base + 12u] = uint(roundedQuotientSide(a, b, c, h > 0.0lf) + 1);  // the midpoint c + h
        pc.results.r[out_base + 13u] = uint(roundedRootSide(a, c, h > 0.0lf) + 1);
        precise double product = a * b;
        precise double fused_error = fma(a, b, -product);
        putDouble(out_base + 14u, fused_error);
        return;
    }
    uint base = 12u * id;
    vec3 a = point(base), b = point(base + 3u), c = point(base + 6u), d = point(base + 9u);
    uint r = signBits(exactOrient3d(a, b, c, d), 0u);
    ExactPlane plane = exactPlane(exactDouble3(a), exactDouble3(b), exactDouble3(c));
    r |= signBits(exactPlaneSide(plane, exactDouble3(d)), 4u);
    r |= signBits(exactOrient2d(a.xy, b.xy, c.xy), 6u);
    r |= signBits(exactOrient2d(b.yz, c.yz, d.yz), 10u);
    uint fallbacks = min(exactFallbacks, 0xffffu);
    r |= signBits(exactOrient3dExact(a, b, c, d), 2u);
    r |= signBits(exactOrient2dExact(a.xy, b.xy, c.xy), 8u);
    r |= signBits(exactOrient2dExact(b.yz, c.yz, d.yz), 12u);
    r |= exactPlaneCertainlyNotCollinear(plane) ? (1u << 14) : 0u;
    pc.results.r[id] = r | (fallbacks << 16);
}
