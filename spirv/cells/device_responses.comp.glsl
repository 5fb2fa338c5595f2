#version 460
#extension GL_GOOGLE_include_directive : require
// Device responses (DetectSettings::reliable.device_responses): every colliding triangle's
// TriangleResponse from the device pairs' buckets (device_pairs.comp: each triangle's higher
// partners, sorted, repeats dropped), equal to the CPU's (src/narrow/responses.cpp) to the
// bit. The CPU sums n_partner - n_self over a triangle's partners in the sorted pairs'
// order: its lower partners ascending, then its higher ones ascending, i.e. every partner
// ascending. So the lower partners are bucketed too (by the higher id) and sorted, and each
// triangle sums in that order; unit normals and lengths use correctly rounded division and
// square root (rounded_fp64.glsl.inc), the directions are rounded to float through the bits.
// Steps (Push.step), each after a barrier, all after the device pairs' passes:
//   0     per triangle a: lower_counts[b] += 1 for each higher partner b;
//   1-3   an exclusive scan (block_scan.glsl.inc): Push.level 0, lower_counts into
//         lower_offsets (the counts reset: the scatter's cursor); level 1, marks into
//         positions, the total is the header's `responses`;
//   4     per triangle a: lower[lower_offsets[b] + cursor] = a for each higher partner b;
//   5     per triangle: its lower bucket sorted; marks = in a pair; its unit normal;
//   6     per marked triangle: the response, written at positions[t].
// Order: 0, scan level 0, 4, 5, scan level 1, 6.
// Every pass is proportional to the triangles (and their partners).
#include "cells_common.glsl.inc"
#include "common/workgroup.glsl.inc"
#include "block_scan.glsl.inc"
#include "bucket_sort.glsl.inc"
#include "exact_predicates.glsl.inc"
#include "rounded_fp64.glsl.inc"
layout(local_size_x = kCellsGroupSize) in;

layout(buffer_reference, scalar, buffer_reference_align = 8) readonly buffer DeviceResponsesParamsRef { DeviceResponsesParams p; };
layout(buffer_reference, scalar, buffer_reference_align = 8) readonly buffer DevicePairsParamsRef { DevicePairsParams p; };
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer DevicePairsHeaderRef { DevicePairsHeader h; };
layout(buffer_reference, scalar, buffer_reference_align = 4) writeonly buffer DeviceResponsesRef { DeviceResponse r[]; };
layout(buffer_reference, scalar, buffer_reference_align = 8) buffer DoublesRef { double v[]; };

DevicePairsHeaderRef pairsHeader(DevicePairsParams D) { return DevicePairsHeaderRef(D.header); }
// A run the device pairs could not sort (incomplete, or a bucket past the loop limit): no
// responses. Uniform: written by earlier passes.
bool skipped(DevicePairsParams D) { return (pairsHeader(D).h.flags & (kDevicePairsIncomplete | kDevicePairsLoopLimit)) != 0u; }

dvec3 loadNormal(DoublesRef normals, uint t) { return dvec3(normals.v[3u * t], normals.v[3u * t + 1u], normals.v[3u * t + 2u]); }

// The CPU's unitNormal(): the cross product of the edges from the first vertex, in double
// from the world vertices (exactly: through the float bits), divided by its length; zero for
// a zero-area triangle. `precise`: the CPU's operations in its order, none fused.
dvec3 unitNormal(CellsGeometry g) {
    dvec3 v0 = dvec3(exactDouble(g.v[0]), exactDouble(g.v[1]), exactDouble(g.v[2]));
    dvec3 v1 = dvec3(exactDouble(g.v[3]), exactDouble(g.v[4]), exactDouble(g.v[5]));
    dvec3 v2 = dvec3(exactDouble(g.v[6]), exactDouble(g.v[7]), exactDouble(g.v[8]));
    precise double ux = v1.x - v0.x, uy = v1.y - v0.y, uz = v1.z - v0.z;
    precise double vx = v2.x - v0.x, vy = v2.y - v0.y, vz = v2.z - v0.z;
    precise double nx = uy * vz - uz * vy;
    precise double ny = uz * vx - ux * vz;
    precise double nz = ux * vy - uy * vx;
    precise double length2 = nx * nx + ny * ny + nz * nz;
    if (!(length2 > 0.0lf)) return dvec3(0.0lf);
    double length = roundedSqrt(length2);
    return dvec3(roundedQuotient(nx, length), roundedQuotient(ny, length), roundedQuotient(nz, length));
}

void main() {
    DeviceResponsesParams R = DeviceResponsesParamsRef(pc.frame).p;
    DevicePairsParams D = DevicePairsParamsRef(R.pairs).p;
    CellsParams P = CellsParamsRef(D.cells).p;
    if (skipped(D)) return;
    if (pc.step >= 1u && pc.step <= 3u) {
        UintsRef dst = UintsRef(pc.level == 0u ? R.lower_offsets : R.positions);
        UintsRef src = UintsRef(pc.level == 0u ? R.lower_counts : R.marks);
        uint total = blockScan(pc.step - 1u, src, UintsRef(D.block_sums), dst, R.triangle_count, R.block_count, pc.level == 0u);
        if (pc.step == 2u && pc.level == 1u && gl_LocalInvocationIndex == 0u) pairsHeader(D).h.responses = total;
        return;
    }
    uint t = globalIndex();
    if (t >= R.triangle_count) return;
    UintsRef counts = UintsRef(D.counts), offsets = UintsRef(D.offsets), partners = UintsRef(D.partners);
    UintsRef lower_counts = UintsRef(R.lower_counts), lower_offsets = UintsRef(R.lower_offsets), lower = UintsRef(R.lower);
    uint higher_n = counts.v[t], higher_base = offsets.v[t];
    if (pc.step == 0u || pc.step == 4u) {
        for (uint j = 0u; j < higher_n; ++j) {
            uint b = partners.v[higher_base + j];
            uint k = atomicAdd(lower_counts.v[b], 1u);
            if (pc.step == 4u) lower.v[lower_offsets.v[b] + k] = t;
        }
        return;
    }
    uint lower_n = lower_counts.v[t], lower_base = lower_offsets.v[t];
    DoublesRef normals = DoublesRef(R.normals);
    if (pc.step == 5u) {
        // A device that ends long loops silently (CellsParams.loop_guard): a bucket its
        // invocation cannot sort, or partners it cannot sum, fails the run by name.
        if (!bucketSortFits(P, lower_n, kDevicePairsInsertionSort, 1u) ||
            (P.loop_guard != ~0u && uint64_t(lower_n) + uint64_t(higher_n) > uint64_t(P.loop_guard))) {
            atomicOr(pairsHeader(D).h.flags, kDevicePairsLoopLimit);
            return;
        }
        sortBucket(lower, lower_base, lower_n);
        bool marked = lower_n + higher_n > 0u;
        UintsRef(R.marks).v[t] = marked ? 1u : 0u;
        if (!marked) return;
        dvec3 n = unitNormal(CellsGeometryRef(P.geometry).g[t]);
        normals.v[3u * t] = n.x;
        normals.v[3u * t + 1u] = n.y;
        normals.v[3u * t + 2u] = n.z;
        return;
    }
    // Step 6: the response, its terms in ascending partner order (the CPU's).
    if (lower_n + higher_n == 0u) return;
    dvec3 n = loadNormal(normals, t);
    precise dvec3 sum = dvec3(0.0lf);
    for (uint j = 0u; j < lower_n; ++j) {
        dvec3 m = loadNormal(normals, lower.v[lower_base + j]);
        sum.x = sum.x + (m.x - n.x);
        sum.y = sum.y + (m.y - n.y);
        sum.z = sum.z + (m.z - n.z);
    }
    for (uint j = 0u; j < higher_n; ++j) {
        dvec3 m = loadNormal(normals, partners.v[higher_base + j]);
        sum.x = sum.x + (m.x - n.x);
        sum.y = sum.y + (m.y - n.y);
        sum.z = sum.z + (m.z - n.z);
    }
    // The CPU's setResponse(): scaled by a power of two (exact) so that no square underflows,
    // the length, each component divided by it and rounded to float.
    uvec3 direction = uvec3(0u);
    if (max(abs(sum.x), max(abs(sum.y), abs(sum.z))) > 0.0lf) {
        double scale = roundedUnitScale(sum);
        precise dvec3 s = sum * scale;
        precise double length2 = s.x * s.x + s.y * s.y + s.z * s.z;
        double length = roundedSqrt(length2);
        direction = uvec3(roundedFloatBits(roundedQuotient(s.x, length)), roundedFloatBits(roundedQuotient(s.y, length)),
                          roundedFloatBits(roundedQuotient(s.z, length)));
    }
    CellsTrianglesRef tris = CellsTrianglesRef(P.triangles);
    ObjectsRef objects = ObjectsRef(P.objects);
    uint object = tris.t[t].key & kCellsKeyObject;
    DeviceResponse r;
    r.object = UintsRef(D.object_ids).v[object];
    r.triangle = t - objects.o[object].triangle_base;
    r.direction[0] = direction.x;
    r.direction[1] = direction.y;
    r.direction[2] = direction.z;
    r.partner_count = lower_n + higher_n;
    DeviceResponsesRef(R.responses).r[UintsRef(R.positions).v[t]] = r;
}
