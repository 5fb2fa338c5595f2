#version 460
#extension GL_GOOGLE_include_directive : require
// Collision rays -> level 0 of the ray-bundle mipmap (each ray's pixel box, normalised).
// A ray still unfinished after the last recorded step has more fragments than the layer
// cap allows: it is marked colliding (conservative).
//
// Depth-aware separation (f.depth_aware): bundles are (x, y, depth) boxes. A collision ray
// without fragment information (layer cap exceeded, a thin triangle under coverage) gets
// every depth. Otherwise a ray's box holds its near pairs' windows (classify left them in
// bundle_depth level 0) and the depth ranges of the edge-on triangles near it (no ray
// samples those: triangle-bounds left them in edge_depth) if it is a collision ray or next
// to one: where two surfaces cross between two rows of rays, the rays on one side collide
// while the crossing triangles may be sampled only on the other. A ray with neither gets
// the empty box: it holds no pair for separation to find (collision rays are counted all
// the same, as the paper does). The grown box is the window's reach.
#include "common/common.glsl.inc"
#include "depth.glsl.inc"
layout(local_size_x = kGroupSize) in;
#include "common/dispatch.glsl.inc"

bool collides(PixelState st) { return (st.flags & kRayCollision) != 0u || (st.flags & kRayDone) == 0u; }

// Whether one of the 8 rays around (x, y) is a collision ray.
bool besideCollision(Frame f, uint x, uint y) {
    StatesRef states = StatesRef(f.state);
    uint n = f.resolution;
    for (uint j = max(y, 1u) - 1u; j <= min(y + 1u, n - 1u); ++j)
        for (uint i = max(x, 1u) - 1u; i <= min(x + 1u, n - 1u); ++i)
            if (collides(states.s[j * n + i])) return true;
    return false;
}

void main() {
    Frame f = frame();
    uint p = globalIndex();
    uint n = f.resolution;
    if (p >= n * n) return;
    PixelState st = StatesRef(f.state).s[p];
    bool collision = collides(st);
    if (collision) atomicAdd(HeaderRef(f.header).h.collision_rays, 1u);
    bool bundled = collision;
    vec2 depth = kEmptyDepth;
    if (f.depth_aware != 0u) {
        uvec2 edge = uvec2(UintsRef(f.edge_depth).v[2u * p], UintsRef(f.edge_depth).v[2u * p + 1u]);
        vec2 found = (st.flags & kRayNear) != 0u ? Vec2sRef(f.bundle_depth).v[p] : kEmptyDepth;
        if (edge.y != 0u) found = depthUnion(found, vec2(floatFromOrdered(~edge.x), floatFromOrdered(edge.y)));
        if (collision && ((st.flags & kRayDone) == 0u || (UintsRef(f.counts).v[p] & kCountThin) != 0u)) {
            depth = kAllDepth;
        } else if (!depthEmpty(found) && (collision || besideCollision(f, p % n, p / n))) {
            depth = found;
        }
        bundled = !depthEmpty(depth);
    }
    vec4 box = kEmptyBox;
    if (bundled) {
        // The pixel; a near interval holds for kNearReachPx around the ray's sample.
        vec2 xy = vec2(float(p % n), float(p / n));
        float grow = f.depth_aware != 0u && depth != kAllDepth ? kNearReachPx - 0.5 : 0.0;
        box = vec4((xy - grow) / float(n), (xy + 1.0 + grow) / float(n));
    }
    Vec4sRef(f.bundles).v[p] = box;
    if (f.ray_image != 0ul) UintsRef(f.ray_image).v[p] = collision ? 1u : 0u;
    if (f.depth_aware != 0u) {
        Vec2sRef(f.bundle_depth).v[p] = depth;
        if (f.ray_depth_image != 0ul) Vec2sRef(f.ray_depth_image).v[p] = depth;
    }
}
