#version 460
#extension GL_GOOGLE_include_directive : require
// Collision rays -> level 0 of the ray-bundle mipmap (each ray's pixel box, normalised).
// A ray still unfinished after the last recorded step has more fragments than the layer
// cap allows: it is marked colliding (conservative).
#include "common.glsl.inc"
layout(local_size_x = kGroupSize) in;
#include "dispatch.glsl.inc"

void main() {
    Frame f = frame();
    uint p = globalIndex();
    uint n = f.resolution;
    if (p >= n * n) return;
    PixelState st = StatesRef(f.state).s[p];
    bool collision = (st.flags & kRayCollision) != 0u || (st.flags & kRayDone) == 0u;
    vec4 box = kEmptyBox;
    if (collision) {
        vec2 xy = vec2(float(p % n), float(p / n));
        box = vec4(xy / float(n), (xy + 1.0) / float(n));
        atomicAdd(HeaderRef(f.header).h.collision_rays, 1u);
    }
    Vec4sRef(f.bundles).v[p] = box;
    if (f.ray_image != 0ul) UintsRef(f.ray_image).v[p] = collision ? 1u : 0u;
}
