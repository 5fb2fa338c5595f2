#version 460
#extension GL_GOOGLE_include_directive : require
// After a peeling step: checks the fragments just peeled against the ray's rules.
// Closed surfaces: facing must alternate, front first (from the back: back first).
// Open surfaces: two consecutive fragments within the depth epsilon collide, and so does
// an open fragment inside a closed object (odd closed parity before it): a sheet that
// enters a solid crosses its surface, however thin the band where the depths are close.
// Closed surfaces touching (depth-epsilon policy, docs/stability.md): a back face followed
// by a front face within closed_epsilon (leaving one closed surface and entering the next
// across a gap that small) collide; at 0 only the key order decides ties.
// A ray is done when every fragment counted by the depth-complexity pass was peeled.
//
// Depth-aware separation (f.depth_aware): a collision ray is not done at its first
// collision but peeled to its end, and every pair of consecutive fragments of every ray
// is tested: a near pair (nearHull) grows the ray's interval in bundle_depth level 0
// (kRayNear says it holds one). finalize keeps the intervals of collision rays and of the
// rays next to them.
#include "common/common.glsl.inc"
#include "depth.glsl.inc"
layout(local_size_x = kGroupSize) in;
#include "common/dispatch.glsl.inc"

float keyDepth(uint64_t k) { return uintBitsToFloat(uint(k >> 32)); }
bool keyOpen(uint64_t k) { return (uint(k) & kKeyOpen) != 0u; }
bool keyBack(uint64_t k) { return (uint(k) & kKeyBackFacing) != 0u; }

bool tooClose(uint64_t a, uint64_t b, float eps) {
    return (keyOpen(a) || keyOpen(b)) && abs(keyDepth(a) - keyDepth(b)) <= eps;
}

bool touching(uint64_t earlier, uint64_t later, float eps) {
    return eps > 0.0 && !keyOpen(earlier) && !keyOpen(later) && keyBack(earlier) && !keyBack(later) &&
           keyDepth(later) - keyDepth(earlier) <= eps;
}

// Whether triangles ta and tb of one object are neighbours: a common vertex index or a
// bit-identical position (the narrow phase's rule: such pairs are never tested).
bool neighbours(ObjectGpu o, uint ta, uint tb) {
    for (uint i = 0u; i < 3u; ++i) {
        uint ia = fetchIndex(o, ta * 3u + i);
        uvec3 pa = floatBitsToUint(fetchPosition(o, ia));
        for (uint j = 0u; j < 3u; ++j) {
            uint ib = fetchIndex(o, tb * 3u + j);
            if (ia == ib || all(equal(pa, floatBitsToUint(fetchPosition(o, ib))))) return true;
        }
    }
    return false;
}

// Unit normal of a triangle of `o` in object space (0 for zero area).
vec3 normalOf(ObjectGpu o, uint t) {
    vec3 p0 = fetchPosition(o, fetchIndex(o, t * 3u)), p1 = fetchPosition(o, fetchIndex(o, t * 3u + 1u));
    vec3 p2 = fetchPosition(o, fetchIndex(o, t * 3u + 2u));
    vec3 n = cross(p1 - p0, p2 - p0);
    float l = length(n);
    return l > 0.0 ? n / l : vec3(0.0);
}

// The depths a triangle's surface can take near ray p: its plane within kNearReachPx of
// the ray (its depth at the ray's sample plus or minus `slope` over that distance), and
// its own depth range within kNearRangePx of the ray (its vertices, where the neighbours
// that share them start: curvature beyond the plane). `slope` may be capped. The depth
// comes from the plane, not the fragment, so both sampling backends give the same bits.
vec2 nearWindow(Frame f, uint p, uint tri, float slope) {
    TriangleBounds t = TriBoundsRef(f.tri_bounds).b[tri];
    vec2 sample_px = vec2(float(p % f.resolution), float(p / f.resolution)) + 0.5;
    float z = t.plane + t.dzdx * sample_px.x + t.dzdy * sample_px.y;
    float plane = slope * kNearReachPx + kFragmentDepthPad, range = slope * kNearRangePx;
    return vec2(min(z - plane, max(t.zmin, z - range)), max(z + plane, min(t.zmax, z + range)));
}

// Consecutive fragments a and b of one ray are a near pair when their triangles may
// collide (different objects, or one self-colliding object and not neighbours) and their
// windows overlap: the two surfaces can meet that close to the ray. The ray's interval
// then grows by both windows. Two triangles of one object facing within 30 degrees of
// each other have their slopes capped (kSelfSlopeCap): the object's own silhouettes put
// a front and a back triangle next to each other on grazing rays, so steep that their
// windows would always overlap. Empty when not a near pair.
vec2 nearHull(Frame f, uint p, uint64_t a, uint64_t b) {
    uint ta = uint(a) & kKeyTriangleMask, tb = uint(b) & kKeyTriangleMask;
    TriBoundsRef bounds = TriBoundsRef(f.tri_bounds);
    float sa = bounds.b[ta].slope, sb = bounds.b[tb].slope;
    vec2 wa = nearWindow(f, p, ta, sa), wb = nearWindow(f, p, tb, sb);
    if (depthEmpty(depthIntersect(wa, wb))) return kEmptyDepth;  // capping only narrows them
    uint oa = objectOfTriangle(f, ta), ob = objectOfTriangle(f, tb);
    if (oa == ob) {
        ObjectGpu o = ObjectsRef(f.objects).o[oa];
        uint la = ta - o.triangle_base, lb = tb - o.triangle_base;
        if ((o.flags & kObjectSelfCollide) == 0u || neighbours(o, la, lb)) return kEmptyDepth;
        if (dot(normalOf(o, la), normalOf(o, lb)) > kSilhouetteCos) {
            float cap = kSelfSlopeCap * levelSlope(f);
            wa = nearWindow(f, p, ta, min(sa, cap));
            wb = nearWindow(f, p, tb, min(sb, cap));
            if (depthEmpty(depthIntersect(wa, wb))) return kEmptyDepth;
        }
    }
    return depthUnion(wa, wb);
}

void addNear(Frame f, uint p, inout uint flags, uint64_t a, uint64_t b) {
    vec2 hull = nearHull(f, p, a, b);
    if (depthEmpty(hull)) return;
    Vec2sRef acc = Vec2sRef(f.bundle_depth);
    acc.v[p] = (flags & kRayNear) != 0u ? depthUnion(acc.v[p], hull) : hull;
    flags |= kRayNear;
}

void main() {
    Frame f = frame();
    uint p = globalIndex();
    if (p >= f.resolution * f.resolution) return;
    StatesRef states = StatesRef(f.state);
    PixelState st = states.s[p];
    if ((st.flags & kRayDone) != 0u) return;
    float eps = ProjectionRef(f.projection).p.open_epsilon;
    float closed_eps = ProjectionRef(f.projection).p.closed_epsilon;
    uint counts = UintsRef(f.counts).v[p];
    uint closed_total = counts & kCountClosedMask;
    uint total = closed_total + (counts >> 16);
    uint n_front = st.peeled & 0xFFFFu, n_back = st.peeled >> 16;
    bool collide = false;
    bool depth_aware = f.depth_aware != 0u;

    uint64_t kf = Uint64sRef(f.front_keys).v[p];
    Uint64sRef(f.front_keys).v[p] = ~0ul;
    if (kf != ~0ul) {
        if (!keyOpen(kf)) {
            bool expect_back = (st.flags & kParityFront) != 0u;
            if (keyBack(kf) != expect_back) collide = true;
            st.flags ^= kParityFront;
        } else if ((st.flags & kParityFront) != 0u) {
            collide = true;
        }
        if (n_front > 0u && (tooClose(st.last_front, kf, eps) || touching(st.last_front, kf, closed_eps))) collide = true;
        if (depth_aware && n_front > 0u) addNear(f, p, st.flags, st.last_front, kf);
        st.last_front = kf;
        ++n_front;
    }
    bool met_in_middle = false;
    if (f.dual != 0u) {
        uint64_t kb = Uint64sRef(f.back_keys).v[p];
        Uint64sRef(f.back_keys).v[p] = 0ul;
        if (kb != 0ul) {
            if (!keyOpen(kb)) {
                bool expect_back = (st.flags & kParityBack) == 0u;
                if (keyBack(kb) != expect_back) collide = true;
                st.flags ^= kParityBack;
            } else if ((st.flags & kParityBack) != 0u) {
                collide = true;
            }
            if (n_back > 0u && (tooClose(kb, st.last_back, eps) || touching(kb, st.last_back, closed_eps))) collide = true;
            if (depth_aware && n_back > 0u) addNear(f, p, st.flags, kb, st.last_back);
            if (kb == kf) {
                met_in_middle = true;  // the same fragment, counted once (by the front)
            } else {
                st.last_back = kb;
                ++n_back;
            }
        }
    }
    if (n_front + n_back >= total) {
        st.flags |= kRayDone;
        if ((closed_total & 1u) != 0u) collide = true;  // a closed ray must enter and leave
        bool join = f.dual != 0u && !met_in_middle && n_front > 0u && n_back > 0u;
        if (join && (tooClose(st.last_front, st.last_back, eps) || touching(st.last_front, st.last_back, closed_eps)))
            collide = true;
        if (depth_aware && join) addNear(f, p, st.flags, st.last_front, st.last_back);
    }
    // Depth-aware: a collision ray goes on until it is done (every near pair found).
    if (collide) st.flags |= kRayCollision | (depth_aware ? 0u : kRayDone);
    st.peeled = n_front | (n_back << 16);
    states.s[p] = st;
}
