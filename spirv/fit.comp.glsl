#version 460
#extension GL_GOOGLE_include_directive : require
// Auto fit, step 2: the orthographic projection that maps the scene's extent to the
// square image (with a margin) and its depth range to [0.05, 0.95].
#include "common.glsl.inc"
layout(local_size_x = 1) in;

void main() {
    Frame f = frame();
    Header h = HeaderRef(f.header).h;
    vec3 lo = vec3(floatFromOrdered(h.bounds[0]), floatFromOrdered(h.bounds[1]), floatFromOrdered(h.bounds[2]));
    vec3 hi = vec3(floatFromOrdered(h.bounds[3]), floatFromOrdered(h.bounds[4]), floatFromOrdered(h.bounds[5]));
    float size = max(hi.x - lo.x, hi.y - lo.y);
    if (!(size > 0.0)) size = 1.0;
    size *= 1.0 + 2.0 * f.fit_margin;
    vec2 origin = 0.5 * (lo.xy + hi.xy) - vec2(0.5 * size);
    float depth = hi.z - lo.z;
    if (!(depth > 0.0)) depth = 1.0;
    Projection pr;
    for (uint axis = 0u; axis < 2u; ++axis) {
        vec3 b = vec3(f.direction_basis[axis * 3u], f.direction_basis[axis * 3u + 1u], f.direction_basis[axis * 3u + 2u]);
        pr.row[axis] = vec4(b / size, -origin[axis] / size);
    }
    vec3 d = vec3(f.direction_basis[6], f.direction_basis[7], f.direction_basis[8]);
    pr.row[2] = vec4(d * (0.9 / depth), 0.05 - 0.9 * lo.z / depth);
    pr.world_to_depth = 0.9 / depth;
    pr.open_epsilon = f.open_epsilon_world * pr.world_to_depth;
    pr.pad0 = 0u;
    pr.pad1 = 0u;
    ProjectionRef(f.projection).p = pr;
}
