#version 460
#extension GL_GOOGLE_include_directive : require
// Contact stage, submission 2, pass 3 (one invocation per ray). The ray's fragments are
// sorted by depth (in place), then walked front to back keeping how often the ray has
// entered each closed object: between two fragments every pair of objects the ray is
// inside at once overlaps. Step 0 sums per object pair (a < b): overlap length (the
// volume in pixel-area units), its first moments, and the boundary of the intersection
// volume: a fragment of A's surface while inside B adds A's unit normal times its area
// per pixel (1 / |cos|), one of B's surface inside A subtracts B's, so the sum points from
// A into B. Step 1, with the sums complete, takes the overlap's extent along the pair's
// normal (min and max of dot(normal, p) over the overlap intervals' ends).
// Per ray, sums stay in registers for up to kContactsRayPairs pairs; then lanes that hold
// the same pair add them with subgroup operations and one lane adds them to the table
// (fixed point: 64-bit integer atomics, exact and order-independent).
//
// One invocation sorts and walks a whole ray: up to n (n - 1) / 2 sort steps for n
// fragments. llvmpipe ends a shader invocation's loops once their iterations together pass
// 65,535, without an error (DeviceInfo::loop_iteration_limit); there P.loop_guard bounds
// them (below that limit; ~0 elsewhere): the sort's before it starts (a loop runs as long
// as its longest lane, so a subgroup sorts in at most m (m + 1) / 2 iterations for its
// longest list m), the walk's as it goes (every iteration of the subgroup's is one of some
// lane's, so at most their sum). Past the guard the run fails by name (kContactsLoopLimit)
// instead of ending its loops early.
#include "contacts_common.glsl.inc"
layout(local_size_x = kContactsGroupSize) in;

// Local sums of one pair: step 0 uses all kSumCount; step 1 uses 0 (min) and 1 (max).
int slot_of[kContactsRayPairs];
float acc[kContactsRayPairs][kSumCount];
vec3 axis_of[kContactsRayPairs];  // step 1: the pair's unit normal (grid space)
bool axis_ok[kContactsRayPairs];
uint local_count = 0u;
uint steps = 0u;  // this lane's loop iterations in the walk

int64_t toFixed(ContactsParams P, float x) { return int64_t(roundEven(x * P.fixed_scale)); }

// Whether the pair of table slot `slot` has a normal to measure along (step 1).
bool pairAxis(ContactsParams P, int slot, out vec3 axis) {
    ContactsTableRef table = ContactsTableRef(P.table);
    vec3 s = vec3(float(table.e[slot].sums[kSumNormal]), float(table.e[slot].sums[kSumNormal + 1u]),
                  float(table.e[slot].sums[kSumNormal + 2u]));
    float area = float(table.e[slot].sums[kSumArea]);
    float len = length(s);
    axis = len > 0.0 ? s / len : vec3(0.0, 0.0, 1.0);
    // A closed boundary sums to zero (one object inside the other): no normal.
    return len > 1.0e-3 * area && len > 0.0;
}

// Index of the local sums of table slot `slot` (-1: none free).
int localOf(ContactsParams P, int slot, uint step) {
    for (uint k = 0u; k < local_count; ++k) {
        ++steps;
        if (slot_of[k] == slot) return int(k);
    }
    if (local_count == kContactsRayPairs) return -1;
    uint k = local_count++;
    slot_of[k] = slot;
    steps += kSumCount;
    for (uint f = 0u; f < kSumCount; ++f) acc[k][f] = 0.0;
    if (step == 1u) {
        acc[k][0] = 3.0e38;
        acc[k][1] = -3.0e38;
        axis_ok[k] = pairAxis(P, slot, axis_of[k]);
    }
    return int(k);
}

// Step 0: adds `v` to field f of a pair (local sums, or straight to the table).
void addSum(ContactsParams P, int slot, int local, uint f, float v) {
    if (local >= 0) acc[local][f] += v;
    else atomicAdd(ContactsTableRef(P.table).e[slot].sums[f], toFixed(P, v));
}

void overlap(ContactsParams P, uint step, uint a, uint b, vec2 xy, float z0, float z1) {
    int slot = findPair(P, min(a, b), max(a, b), steps);
    if (slot < 0) return;
    int local = localOf(P, slot, step);
    if (step == 0u) {
        float len = z1 - z0;
        addSum(P, slot, local, kSumVolume, len);
        addSum(P, slot, local, kSumMoment, len * xy.x);
        addSum(P, slot, local, kSumMoment + 1u, len * xy.y);
        addSum(P, slot, local, kSumMoment + 2u, len * 0.5 * (z0 + z1));
        return;
    }
    vec3 axis;
    bool ok;
    if (local >= 0) {
        axis = axis_of[local];
        ok = axis_ok[local];
    } else {
        ok = pairAxis(P, slot, axis);
    }
    if (!ok) return;
    float e0 = dot(axis, vec3(xy, z0)), e1 = dot(axis, vec3(xy, z1));
    float lo = min(e0, e1), hi = max(e0, e1);
    if (local >= 0) {
        acc[local][0] = min(acc[local][0], lo);
        acc[local][1] = max(acc[local][1], hi);
    } else {
        atomicMin(ContactsTableRef(P.table).e[slot].extent_min, orderedFromFloat(lo));
        atomicMax(ContactsTableRef(P.table).e[slot].extent_max, orderedFromFloat(hi));
    }
}

// Boundary of the intersection volume: triangle `c` of object `o`, inside object `other`.
void boundary(ContactsParams P, uint o, uint other, CtTriangle c) {
    int slot = findPair(P, min(o, other), max(o, other), steps);
    if (slot < 0) return;
    int local = localOf(P, slot, 0u);
    float sign = o < other ? 1.0 : -1.0;
    steps += 3u;
    for (uint k = 0u; k < 3u; ++k) addSum(P, slot, local, kSumNormal + k, sign * c.n[k] * c.weight);
    addSum(P, slot, local, kSumArea, c.weight);
}

// Lanes holding the same pair add their sums, one atomic per field per subgroup. Every
// lane of the subgroup calls it (uniform control flow).
void flush(ContactsParams P, uint step) {
    ContactsTableRef table = ContactsTableRef(P.table);
    uint next = 0u;
    for (;;) {
        bool has = next < local_count;
        if (subgroupBallotBitCount(subgroupBallot(has)) == 0u) break;  // ballot: no vote extension needed
        uint mine = has ? uint(slot_of[next]) : 0xFFFFFFFFu;
        uint target = subgroupMin(mine);
        bool take = has && mine == target;
        if (step == 0u) {
            for (uint f = 0u; f < kSumCount; ++f) {
                float total = subgroupAdd(take ? acc[next][f] : 0.0);
                if (subgroupElect() && total != 0.0) atomicAdd(table.e[target].sums[f], toFixed(P, total));
            }
        } else {
            float lo = subgroupMin(take ? acc[next][0] : 3.0e38);
            float hi = subgroupMax(take ? acc[next][1] : -3.0e38);
            if (subgroupElect()) {
                if (lo <= hi) {
                    atomicMin(table.e[target].extent_min, orderedFromFloat(lo));
                    atomicMax(table.e[target].extent_max, orderedFromFloat(hi));
                }
            }
        }
        if (take) ++next;
    }
}

void main() {
    ContactsParams P = params();
    uint step = pc.step;
    ContactsHeaderRef hdr = contactsHeader(P);
    uint ray = globalIndex();
    bool live = ray < P.width * P.height && hdr.h.flags == 0u;
    uint n = live ? min(UintsRef(P.counts).v[ray], P.layers) : 0u;
    // The sort's iterations in this subgroup, at most (step 1: none).
    const bool guarded = P.loop_guard != 0xFFFFFFFFu;
    uint64_t longest = uint64_t(subgroupMax(n));
    uint64_t bound = step == 0u ? longest * (longest + 1ul) / 2ul : 0ul;
    if (guarded && bound > uint64_t(P.loop_guard)) {
        if (subgroupElect()) {
            atomicOr(hdr.h.flags, kContactsLoopLimit);
            atomicMax(hdr.h.max_fragments, uint(longest));  // for the error
        }
        n = 0u;
    }
    // This ray's list (ray-major).
    CtUvec2sRef entries = CtUvec2sRef(P.entries + uint64_t(live ? ray : 0u) * uint64_t(P.layers) * 8ul);
    const uint base = 0u;
    // Sort by (depth, triangle): insertion sort in place (lists are short); step 1 finds
    // them sorted.
    if (step == 0u) {
        for (uint i = 1u; i < n; ++i) {
            uvec2 e = entries.v[base + i];
            float z = uintBitsToFloat(e.x);
            uint j = i;
            while (j > 0u) {
                uvec2 prev = entries.v[base + j - 1u];
                float pz = uintBitsToFloat(prev.x);
                if (pz < z || (pz == z && prev.y <= e.y)) break;
                entries.v[base + j] = prev;
                --j;
            }
            entries.v[base + j] = e;
        }
    }
    vec2 xy = vec2(float(ray % max(P.width, 1u)) + 0.5 - 0.5 * float(P.width), float(ray / max(P.width, 1u)) + 0.5 - 0.5 * float(P.height));
    uint inside_obj[kContactsMaxInside];
    int inside_count[kContactsMaxInside];
    uint n_inside = 0u;
    bool nested = false, any_overlap = false;
    float prev_z = 0.0;
    CtTrianglesRef tris = CtTrianglesRef(P.triangles);
    for (uint i = 0u; i < n; ++i) {
        ++steps;
        uvec2 e = entries.v[base + i];
        float z = uintBitsToFloat(e.x);
        CtTriangle c = tris.t[e.y];
        uint o = c.key & kCtKeyObject;
        // The interval since the last fragment, for every pair inside both.
        if (i > 0u && z > prev_z)
            for (uint p = 0u; p < n_inside; ++p) {
                ++steps;
                if (inside_count[p] <= 0) continue;
                for (uint q = p + 1u; q < n_inside; ++q) {
                    ++steps;
                    if (inside_count[q] <= 0) continue;
                    overlap(P, step, inside_obj[p], inside_obj[q], xy, prev_z, z);
                    any_overlap = true;
                }
            }
        // This fragment bounds the intersection volume where the ray is inside another object.
        int at = -1;
        for (uint p = 0u; p < n_inside; ++p) {
            ++steps;
            if (inside_obj[p] == o) at = int(p);
            else if (step == 0u && inside_count[p] > 0) boundary(P, o, inside_obj[p], c);
        }
        int delta = (c.key & kCtKeyEntering) != 0u ? 1 : -1;
        if (at >= 0) {
            inside_count[at] += delta;
            if (inside_count[at] == 0) {
                --n_inside;
                inside_obj[at] = inside_obj[n_inside];
                inside_count[at] = inside_count[n_inside];
            }
        } else if (n_inside < kContactsMaxInside) {
            inside_obj[n_inside] = o;
            inside_count[n_inside] = delta;
            ++n_inside;
        } else {
            nested = true;
        }
        prev_z = z;
    }
    // The walk's iterations: every subgroup iteration is one of some lane's. (flush() adds
    // at most (kContactsRayPairs + 1) (kSumCount + 1) per lane: the guard's margin.)
    if (guarded && bound + uint64_t(subgroupAdd(steps)) > uint64_t(P.loop_guard) && subgroupElect()) {
        atomicOr(hdr.h.flags, kContactsLoopLimit);
        atomicMax(hdr.h.max_fragments, uint(longest));
    }
    flush(P, step);
    if (step == 0u) {
        uint nested_rays = subgroupAdd(nested ? 1u : 0u), overlap_rays = subgroupAdd(any_overlap ? 1u : 0u);
        uint fragments = subgroupAdd(n);
        if (subgroupElect()) {
            if (nested_rays > 0u) atomicAdd(hdr.h.nested_rays, nested_rays);
            if (overlap_rays > 0u) atomicAdd(hdr.h.overlap_rays, overlap_rays);
            if (fragments > 0u) atomicAdd(hdr.h.fragments, fragments);
        }
    }
}
