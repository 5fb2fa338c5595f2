#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
// Proximity pass (src/proximity/proximity_stage.cpp, docs/proximity.md): after the cell
// stage ran with every triangle grown by half the distance d (CellsParams.proximity_pad)
// and the sweep keeping neighbours (keep_neighbours), every candidate triangle pair in its
// canonical cell (the pair pass marked the others) is examined here, one invocation each
// (the pair pass's own dispatch): the vertices each triangle owns against the other
// triangle, and the edges each owns against the other's owned edges
// (ProximityParams.owned: a vertex's or an edge's lowest triangle owns it, so each
// primitive pair is examined once), in double on the CPU's
// world vertices. A pair is written when its computed distance is at most d plus its error
// bound (flagged kProximityInBand when within the bound of d). One object's primitives
// that share a vertex index or a bit-identical world vertex are neighbours, left out.
// Steps (Push.step): 0 per candidate; 1 one invocation: the header's count and flags.
#include "cells/cells_common.glsl.inc"
#include "cells/cells_geometry.glsl.inc"
#include "cells/cells_candidate.glsl.inc"
#include "proximity.h"
#include "proximity_distance.glsl.inc"
layout(local_size_x = kCellsGroupSize) in;

layout(buffer_reference, scalar, buffer_reference_align = 8) readonly buffer ProximityParamsRef { ProximityParams p; };
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer ProximityHeaderRef { ProximityHeader h; };
layout(buffer_reference, scalar, buffer_reference_align = 4) writeonly buffer ProximityRecordsRef { ProximityRecord r[]; };

ProximityParams qparams() { return ProximityParamsRef(pc.frame).p; }
ProximityHeaderRef qheader(ProximityParams Q) { return ProximityHeaderRef(Q.header); }

uint ownedMask(ProximityParams Q, uint t) { return (UintsRef(Q.owned).v[t >> 2] >> ((t & 3u) * 8u)) & 0xFFu; }

bool sameBits(vec3 a, vec3 b) { return all(equal(floatBitsToUint(a), floatBitsToUint(b))); }

// One side of a candidate: object, its id, the triangle within it, indices and world vertices.
struct Side {
    uint object;
    uint id;
    uint triangle;
    uvec3 index;
    vec3 w[3];
    uint owned;
};

Side sideOf(ProximityParams Q, CellsParams P, uint t, uint key) {
    Side s;
    s.object = key & kCellsKeyObject;
    ObjectGpu obj = ObjectsRef(P.objects).o[s.object];
    s.id = UintsRef(Q.object_ids).v[s.object];
    s.triangle = t - obj.triangle_base;
    CellsGeometry g = CellsGeometryRef(P.geometry).g[t];
    s.index = uvec3(g.index[0], g.index[1], g.index[2]);
    worldTriangle(g, s.w);
    s.owned = ownedMask(Q, t);
    return s;
}

bool within(ProximityParams Q, Nearest n) { return n.distance <= Q.distance + n.band; }

ProximityRecord recordOf(ProximityParams Q, uint kind, uint id_a, uvec2 a, uint id_b, uvec2 b, Nearest n) {
    ProximityRecord r;
    r.kind = kind;
    r.flags = n.distance > Q.distance - n.band ? kProximityInBand : 0u;
    r.object_a = id_a;
    r.object_b = id_b;
    r.a0 = a.x;
    r.a1 = a.y;
    r.b0 = b.x;
    r.b1 = b.y;
    r.distance = float(n.distance);
    r.weight_a = float(n.s);
    r.weights_b[0] = float(n.wb.x);
    r.weights_b[1] = float(n.wb.y);
    r.weights_b[2] = float(n.wb.z);
    dvec3 d = n.pa - n.pb;
    double len = length(d);
    vec3 nrm = len > 0.0 ? vec3(d / len) : vec3(0.0, 0.0, 1.0);
    r.normal[0] = nrm.x;
    r.normal[1] = nrm.y;
    r.normal[2] = nrm.z;
    return r;
}

void store(ProximityParams Q, uint slot, ProximityRecord r) {
    if (slot < Q.capacity) ProximityRecordsRef(Q.records).r[slot] = r;
}

// A touching pair has no direction between its closest points: the triangle's normal
// (vertex-triangle) or the edges' common normal (edge-edge), else +z. Encoded as a
// displacement of pa that recordOf() normalises; the distance stays 0.
void fallbackNormal(inout Nearest n, dvec3 u, dvec3 v) {
    if (n.distance > 0.0) return;
    dvec3 c = cross(u, v);
    double len = length(c);
    n.pa = n.pb + (len > 0.0 ? c / len : dvec3(0.0, 0.0, 1.0));
}

bool vertexNeighbours(Side v, uint k, Side t) {
    return any(equal(t.index, uvec3(v.index[k]))) || sameBits(v.w[k], t.w[0]) || sameBits(v.w[k], t.w[1]) ||
           sameBits(v.w[k], t.w[2]);
}

// Vertex k of `v` against the triangle of `t`.
Nearest vertexTriangle(Side v, uint k, Side t) {
    dvec3 a = dvec3(t.w[0]), b = dvec3(t.w[1]), c = dvec3(t.w[2]);
    Nearest n = pointTriangle(dvec3(v.w[k]), a, b, c);
    fallbackNormal(n, b - a, c - a);
    return n;
}
ProximityRecord vertexRecord(ProximityParams Q, Side v, uint k, Side t) {
    return recordOf(Q, kProximityVertexTriangle, v.id, uvec2(v.index[k], ~0u), t.id, uvec2(t.triangle, ~0u), vertexTriangle(v, k, t));
}

// Edge i of `x` and edge j of `y`, each from its lower vertex index, the lower (id,
// vertices) first as edge a: the record is the same whichever triangle pair finds it.
struct EdgePair {
    uint id_a, id_b;
    uvec2 a, b;
    vec3 pa, qa, pb, qb;
};
EdgePair edgePair(Side x, uint i, Side y, uint j) {
    uint i1 = i == 2u ? 0u : i + 1u, j1 = j == 2u ? 0u : j + 1u;
    EdgePair e;
    bool fx = x.index[i] > x.index[i1], fy = y.index[j] > y.index[j1];
    uvec2 ex = fx ? uvec2(x.index[i1], x.index[i]) : uvec2(x.index[i], x.index[i1]);
    uvec2 ey = fy ? uvec2(y.index[j1], y.index[j]) : uvec2(y.index[j], y.index[j1]);
    vec3 px = fx ? x.w[i1] : x.w[i], qx = fx ? x.w[i] : x.w[i1];
    vec3 py = fy ? y.w[j1] : y.w[j], qy = fy ? y.w[j] : y.w[j1];
    bool swap = y.id < x.id || (y.id == x.id && (ey.x < ex.x || (ey.x == ex.x && ey.y < ex.y)));
    e.id_a = swap ? y.id : x.id;
    e.id_b = swap ? x.id : y.id;
    e.a = swap ? ey : ex;
    e.b = swap ? ex : ey;
    e.pa = swap ? py : px;
    e.qa = swap ? qy : qx;
    e.pb = swap ? px : py;
    e.qb = swap ? qx : qy;
    return e;
}
bool edgeNeighbours(EdgePair e) {
    return e.a.x == e.b.x || e.a.x == e.b.y || e.a.y == e.b.x || e.a.y == e.b.y || sameBits(e.pa, e.pb) ||
           sameBits(e.pa, e.qb) || sameBits(e.qa, e.pb) || sameBits(e.qa, e.qb);
}
Nearest edgeEdge(EdgePair e) {
    dvec3 p1 = dvec3(e.pa), q1 = dvec3(e.qa), p2 = dvec3(e.pb), q2 = dvec3(e.qb);
    Nearest n = segmentSegment(p1, q1, p2, q2);
    fallbackNormal(n, q1 - p1, q2 - p2);
    return n;
}

// Whether two boxes (of points held exactly in double) are farther apart than d along some
// axis, with room for rounding: no pair of their points is then within d (the pass skips
// them before any distance). The margin covers the differences' rounding at the magnitudes.
bool boxesApart(dvec3 lo_a, dvec3 hi_a, dvec3 lo_b, dvec3 hi_b, double d) {
    dvec3 gap = max(lo_b - hi_a, lo_a - hi_b);
    double scale = max(maxAbs(lo_a), max(maxAbs(hi_a), max(maxAbs(lo_b), maxAbs(hi_b))));
    return max(gap.x, max(gap.y, gap.z)) > d + kProximityErrorUnits * kProximityU * scale;
}
void boxOf(Side s, out dvec3 lo, out dvec3 hi) {
    lo = dvec3(min(s.w[0], min(s.w[1], s.w[2])));
    hi = dvec3(max(s.w[0], max(s.w[1], s.w[2])));
}

// Header fields (ProximityHeader, 4-byte words) for the subgroup helpers.
const uint kProxNeeded = 1u, kProxPairsTested = 4u, kProxDistances = 5u, kProxNeighbours = 6u, kProxInBand = 7u;
uint64_t qfield(ProximityParams Q, uint word) { return Q.header + uint64_t(word) * 4ul; }

void main() {
    ProximityParams Q = qparams();
    CellsParams P = CellsParamsRef(Q.cells).p;
    if (pc.step == 1u) {
        ProximityHeaderRef H = qheader(Q);
        H.h.capacity = Q.capacity;
        if (!runComplete(P)) {  // failed, or chunks left: the candidates are not all decided
            H.h.flags = kProximityIncomplete;
            H.h.count = 0u;
        } else {
            H.h.flags = H.h.needed > Q.capacity ? kProximityOverflow : 0u;
            H.h.count = min(H.h.needed, Q.capacity);
        }
        // The sort's per-record dispatches: none unless the records are complete.
        uint groups = H.h.flags == 0u ? (H.h.count + kCellsGroupSize - 1u) / kCellsGroupSize : 0u;
        uint x = min(groups, Q.max_groups_x);
        UintsRef args = UintsRef(Q.args);
        args.v[0] = x;
        args.v[1] = x == 0u ? 1u : (groups + x - 1u) / x;
        args.v[2] = 1u;
        return;
    }
    // A failed run (an overflow, bad input) is repeated or reported by the host.
    if (cellsHeader(P).h.flags != 0u) return;
    uint id = globalIndex();
    uint total = uint(min(cellsHeader(P).h.candidates, uint64_t(P.candidate_capacity)));
    bool live = id < total;
    CellsCandidate c = CellsCandidate(0u, 0u, 0u);
    if (live) {
        c = CellsCandidatesRef(P.candidates).c[id];
        // The pair pass marked the candidates outside their canonical cell (kCellsNotCanonical);
        // other bad ones it flags.
        live = c.b < P.triangle_count && c.cell < P.cell_count;
    }
    CellsTrianglesRef tris = CellsTrianglesRef(P.triangles);
    // First every owned primitive pair's distance, a bit per pair within d (bits 0-2: a's
    // vertices against b, 3-5: b's against a, 6-14: a's edge i against b's edge j at
    // 6 + 3 i + j); then one slot range per subgroup and the records written.
    uint within_mask = 0u, distances = 0u, neighbours = 0u, in_band = 0u;
    Side a, b;
    bool same = false;
    if (live) {
        a = sideOf(Q, P, c.a, tris.t[c.a].key);
        b = sideOf(Q, P, c.b, tris.t[c.b].key);
        same = a.object == b.object;
        dvec3 lo_a, hi_a, lo_b, hi_b;
        boxOf(a, lo_a, hi_a);
        boxOf(b, lo_b, hi_b);
        // Triangles farther apart than d (their cells were near only in projection).
        if (boxesApart(lo_a, hi_a, lo_b, hi_b, Q.distance)) {
            a.owned = 0u;
            b.owned = 0u;
        }
        // Owned primitives far from the other triangle's box need no distance either.
        [[unroll]] for (uint k = 0u; k < 3u; ++k) {
            if (boxesApart(dvec3(a.w[k]), dvec3(a.w[k]), lo_b, hi_b, Q.distance)) a.owned &= ~(1u << k);
            if (boxesApart(dvec3(b.w[k]), dvec3(b.w[k]), lo_a, hi_a, Q.distance)) b.owned &= ~(1u << k);
        }
        [[unroll]] for (uint k = 0u; k < 3u; ++k) {
            if ((a.owned & (1u << k)) != 0u) {
                if (same && vertexNeighbours(a, k, b)) {
                    ++neighbours;
                } else if (!screenedPointTriangle(a.w[k], b.w[0], b.w[1], b.w[2], Q.distance)) {
                    ++distances;
                    Nearest n = vertexTriangle(a, k, b);
                    if (within(Q, n)) within_mask |= 1u << k;
                    if (within(Q, n) && n.distance > Q.distance - n.band) ++in_band;
                }
            }
            if ((b.owned & (1u << k)) != 0u) {
                if (same && vertexNeighbours(b, k, a)) {
                    ++neighbours;
                } else if (!screenedPointTriangle(b.w[k], a.w[0], a.w[1], a.w[2], Q.distance)) {
                    ++distances;
                    Nearest n = vertexTriangle(b, k, a);
                    if (within(Q, n)) within_mask |= 8u << k;
                    if (within(Q, n) && n.distance > Q.distance - n.band) ++in_band;
                }
            }
        }
        [[unroll]] for (uint i = 0u; i < 3u; ++i) {
            if ((a.owned & (8u << i)) == 0u) continue;
            uint i1 = i == 2u ? 0u : i + 1u;
            dvec3 lo_e = dvec3(min(a.w[i], a.w[i1])), hi_e = dvec3(max(a.w[i], a.w[i1]));
            if (boxesApart(lo_e, hi_e, lo_b, hi_b, Q.distance)) continue;
            [[unroll]] for (uint j = 0u; j < 3u; ++j) {
                if ((b.owned & (8u << j)) == 0u) continue;
                uint j1 = j == 2u ? 0u : j + 1u;
                if (boxesApart(lo_e, hi_e, dvec3(min(b.w[j], b.w[j1])), dvec3(max(b.w[j], b.w[j1])), Q.distance)) continue;
                EdgePair e = edgePair(a, i, b, j);
                if (same && edgeNeighbours(e)) {
                    ++neighbours;
                    continue;
                }
                if (screenedSegmentSegment(e.pa, e.qa, e.pb, e.qb, Q.distance)) continue;
                ++distances;
                Nearest n = edgeEdge(e);
                if (within(Q, n)) within_mask |= 64u << (3u * i + j);
                if (within(Q, n) && n.distance > Q.distance - n.band) ++in_band;
            }
        }
    }
    subgroupCount(qfield(Q, kProxPairsTested), live ? 1u : 0u);
    subgroupCount(qfield(Q, kProxDistances), distances);
    subgroupCount(qfield(Q, kProxNeighbours), neighbours);
    subgroupCount(qfield(Q, kProxInBand), in_band);
    uint slot = subgroupAppend(qfield(Q, kProxNeeded), bitCount(within_mask));
    if (within_mask == 0u) return;
    // The records, recomputed for the few primitive pairs within d.
    [[unroll]] for (uint k = 0u; k < 3u; ++k) {
        if ((within_mask & (1u << k)) != 0u) store(Q, slot++, vertexRecord(Q, a, k, b));
        if ((within_mask & (8u << k)) != 0u) store(Q, slot++, vertexRecord(Q, b, k, a));
    }
    [[unroll]] for (uint i = 0u; i < 3u; ++i)
        [[unroll]] for (uint j = 0u; j < 3u; ++j)
            if ((within_mask & (64u << (3u * i + j))) != 0u) {
                EdgePair e = edgePair(a, i, b, j);
                store(Q, slot++, recordOf(Q, kProximityEdgeEdge, e.id_a, e.a, e.id_b, e.b, edgeEdge(e)));
            }
}
