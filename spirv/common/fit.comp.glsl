#version 460
#extension GL_GOOGLE_include_directive : require
// Auto fit, step 2: the orthographic projection that maps the scene's extent to the
// square image (with a margin) and its depth range to [kDepthNear, kDepthNear + kDepthSpan].
// The host repeats it (broad/projection.cpp, fitProjection); tests check they agree.
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
        pr.row[axis] = vec4(basisRow(f, axis) / size, -origin[axis] / size);
    }
    pr.row[2] = vec4(basisRow(f, 2u) * (kDepthSpan / depth), kDepthNear - kDepthSpan * lo.z / depth);
    pr.world_to_depth = kDepthSpan / depth;
    pr.open_epsilon = f.open_epsilon_world * pr.world_to_depth;
    pr.closed_epsilon = f.closed_epsilon_world * pr.world_to_depth;
    pr.pad1 = 0u;
    ProjectionRef(f.projection).p = pr;
}
