#version 460
#extension GL_GOOGLE_include_directive : require
// The one pass of few pairs, its responses (after small_sort.comp; cells.h,
// src/broad/cells/small_sort.hpp): one invocation per responder, dispatched indirectly over
// as many workgroups as there are responders (small_sort.comp wrote the count: none where it
// skipped), so that the double arithmetic runs across the GPU. Equal to the CPU's responses
// to the bit (response_math.glsl.inc). Steps (Push.step):
//   0  responder r's unit normal (normals[r]);
//   1  responder r's response: its run of ends in ascending partner order, each end's
//      partner already its responder's number, summed as the CPU sums; written at r.
#include "cells_common.glsl.inc"
#include "small_sort.glsl.inc"
layout(local_size_x = kCellsGroupSize) in;

dvec3 loadNormal(DoublesRef normals, uint r) { return dvec3(normals.v[3u * r], normals.v[3u * r + 1u], normals.v[3u * r + 2u]); }

void main() {
    SmallSortParams S = SmallSortParamsRef(pc.frame).p;
    CellsParams P = CellsParamsRef(S.cells).p;
    const uint r = globalIndex();
    if (r >= SmallSortHeaderRef(S.header).h.responses) return;  // the dispatch is rounded up to whole groups
    DoublesRef normals = DoublesRef(S.normals);
    if (pc.step == 0u) {
        dvec3 n = unitNormal(CellsGeometryRef(P.geometry).g[UintsRef(S.responders).v[r]]);
        normals.v[3u * r] = n.x;
        normals.v[3u * r + 1u] = n.y;
        normals.v[3u * r + 2u] = n.z;
        return;
    }
    Uvec2sRef ends = Uvec2sRef(S.ends);
    UintsRef run_begin = UintsRef(S.run_begin);
    const uint first = run_begin.v[r], last = run_begin.v[r + 1u];
    const dvec3 n = loadNormal(normals, r);
    dvec3 sum = dvec3(0.0lf);
    for (uint e = first; e < last; ++e) addTerm(sum, loadNormal(normals, ends.v[e].y), n);
    const uvec3 direction = responseDirection(sum);
    const uint t = UintsRef(S.responders).v[r];
    const uint object = CellsTrianglesRef(P.triangles).t[t].key & kCellsKeyObject;  // the run's object index: the host result's
    DeviceResponse out_r;
    out_r.object = object;
    out_r.triangle = t - ObjectsRef(P.objects).o[object].triangle_base;
    out_r.direction[0] = direction.x;
    out_r.direction[1] = direction.y;
    out_r.direction[2] = direction.z;
    out_r.partner_count = last - first;
    DeviceResponsesRef(S.responses).r[r] = out_r;
}
