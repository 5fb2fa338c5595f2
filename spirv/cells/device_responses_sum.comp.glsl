#version 460
#extension GL_GOOGLE_include_directive : require
// Device responses, the arithmetic (after device_responses.comp's bookkeeping; both listed
// there): one invocation per triangle in a pair (R.responders, dispatched indirectly), equal
// to the CPU's responses (src/narrow/responses.cpp) to the bit. Unit normals and lengths use
// correctly rounded division and square root (rounded_fp64.glsl.inc), the directions are
// rounded to float through the bits; docs/exact_gpu.md, "Responses on the GPU", has the
// argument. Steps (Push.step):
//   0  per responder: its triangle's unit normal (normals[t]);
//   1  per responder r: the response, its terms in ascending partner order, written at r.
#include "cells_common.glsl.inc"
#include "device_responses.glsl.inc"
#include "exact_predicates.glsl.inc"
#include "rounded_fp64.glsl.inc"
#include "response_math.glsl.inc"
layout(local_size_x = kCellsGroupSize) in;

layout(buffer_reference, scalar, buffer_reference_align = 4) writeonly buffer DeviceResponsesRef { DeviceResponse r[]; };
layout(buffer_reference, scalar, buffer_reference_align = 8) buffer DoublesRef { double v[]; };

dvec3 loadNormal(DoublesRef normals, uint t) { return dvec3(normals.v[3u * t], normals.v[3u * t + 1u], normals.v[3u * t + 2u]); }

void main() {
    DeviceResponsesParams R = DeviceResponsesParamsRef(pc.frame).p;
    DevicePairsParams D = DevicePairsParamsRef(R.pairs).p;
    CellsParams P = CellsParamsRef(D.cells).p;
    uint r = globalIndex();
    if (skipped(D) || r >= pairsHeader(D).h.responses) return;  // the dispatch is rounded up to whole groups
    uint t = UintsRef(R.responders).v[r];
    DoublesRef normals = DoublesRef(R.normals);
    if (pc.step == 0u) {
        dvec3 n = unitNormal(CellsGeometryRef(P.geometry).g[t]);
        normals.v[3u * t] = n.x;
        normals.v[3u * t + 1u] = n.y;
        normals.v[3u * t + 2u] = n.z;
        return;
    }
    UintsRef partners = UintsRef(D.partners), lower = UintsRef(R.lower);
    uint higher_n = UintsRef(D.counts).v[t], higher_base = UintsRef(D.offsets).v[t];
    uint lower_n = UintsRef(R.lower_counts).v[t], lower_base = UintsRef(R.lower_offsets).v[t];
    dvec3 n = loadNormal(normals, t);
    dvec3 sum = dvec3(0.0lf);
    for (uint j = 0u; j < lower_n; ++j) addTerm(sum, loadNormal(normals, lower.v[lower_base + j]), n);
    for (uint j = 0u; j < higher_n; ++j) addTerm(sum, loadNormal(normals, partners.v[higher_base + j]), n);
    uvec3 direction = responseDirection(sum);
    uint object = CellsTrianglesRef(P.triangles).t[t].key & kCellsKeyObject;
    DeviceResponse out_r;
    out_r.object = UintsRef(D.object_ids).v[object];
    out_r.triangle = t - ObjectsRef(P.objects).o[object].triangle_base;
    out_r.direction[0] = direction.x;
    out_r.direction[1] = direction.y;
    out_r.direction[2] = direction.z;
    out_r.partner_count = lower_n + higher_n;
    DeviceResponsesRef(R.responses).r[r] = out_r;
}
