#version 460
#extension GL_GOOGLE_include_directive : require
// Object sampling: vertices pulled from the object's buffers (any stride, 16/32-bit
// indices), transformed to sampling space; one invocation per triangle corner.
//
// Coverage (pc.coverage, see broadphase.h): a thin triangle (projected inradius below half
// a pixel diagonal) may cover no pixel centre, so the rays cannot resolve it. With
// kCoverageDilate it is replaced by a triangle that contains every pixel it touches and
// flagged (v_thin): the fragment shaders make those rays collision rays. The two
// kCoverage*Thin modes split the draw for a conservatively rasterising pipeline.
#include "common/common.glsl.inc"
layout(location = 0) flat out uint v_key_low;
layout(location = 1) flat out uint v_thin;

// Projected inradius in pixels: twice the area over the perimeter (0 for zero area).
float inradiusPx(vec2 a, vec2 b, vec2 c) {
    float twice_area = abs((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x));
    float perimeter = length(b - a) + length(c - b) + length(a - c);
    return perimeter > 0.0 ? twice_area / perimeter : 0.0;
}

// Corner `corner` of a triangle that contains the thin triangle p[0..2] (pixels) grown by
// half a pixel diagonal in every direction: the rectangle around it, aligned with its
// longest edge, sits in the corner of a right triangle twice its width and height. The
// winding follows the original's.
vec2 dilatedCorner(vec2 p[3], uint corner) {
    uint e = 0u;
    float best = -1.0;
    for (uint i = 0u; i < 3u; ++i) {
        float l = length(p[(i + 1u) % 3u] - p[i]);
        if (l > best) { best = l; e = i; }
    }
    vec2 o = p[e];
    vec2 t = best > 1e-6 ? (p[(e + 1u) % 3u] - o) / best : vec2(1.0, 0.0);
    vec2 n = vec2(-t.y, t.x);
    vec2 lo = vec2(0.0), hi = vec2(0.0);
    for (uint i = 0u; i < 3u; ++i) {
        vec2 local = vec2(dot(p[i] - o, t), dot(p[i] - o, n));
        lo = min(lo, local);
        hi = max(hi, local);
    }
    lo -= vec2(kThinInradiusPx);
    hi += vec2(kThinInradiusPx);
    vec2 origin = o + t * lo.x + n * lo.y;
    vec2 along = t * (2.0 * (hi.x - lo.x)), across = n * (2.0 * (hi.y - lo.y));
    float winding = (p[1].x - p[0].x) * (p[2].y - p[0].y) - (p[1].y - p[0].y) * (p[2].x - p[0].x);
    if (winding < 0.0) { vec2 s = along; along = across; across = s; }
    return corner == 0u ? origin : (corner == 1u ? origin + along : origin + across);
}

void main() {
    Frame f = frame();
    ObjectGpu o = ObjectsRef(f.objects).o[pc.object];
    Projection pr = ProjectionRef(f.projection).p;
    uint tri = uint(gl_VertexIndex) / 3u;
    uint corner = uint(gl_VertexIndex) % 3u;
    v_key_low = ((o.triangle_base + tri) & kKeyTriangleMask) | ((o.flags & kObjectOpen) != 0u ? kKeyOpen : 0u);
    v_thin = 0u;
    if (pc.coverage == kCoverageCentre) {
        vec3 s = toSampling(pr, toWorld(o, fetchPosition(o, fetchIndex(o, uint(gl_VertexIndex)))));
        gl_Position = vec4(s.xy * 2.0 - 1.0, s.z, 1.0);
        return;
    }
    // Every corner invocation computes the same verdict from the same three vertices.
    vec3 s[3];
    vec2 px[3];
    float n = float(f.resolution);
    for (uint c = 0u; c < 3u; ++c) {
        s[c] = toSampling(pr, toWorld(o, fetchPosition(o, fetchIndex(o, tri * 3u + c))));
        px[c] = s[c].xy * n;
    }
    bool thin = inradiusPx(px[0], px[1], px[2]) < kThinInradiusPx;
    const vec4 culled = vec4(-4.0, -4.0, 0.5, 1.0);  // all three corners outside the view: no fragment
    if ((pc.coverage == kCoverageSkipThin && thin) || (pc.coverage == kCoverageOnlyThin && !thin)) {
        gl_Position = culled;
        return;
    }
    if (!thin) {
        gl_Position = vec4(s[corner].xy * 2.0 - 1.0, s[corner].z, 1.0);
        return;
    }
    v_thin = 1u;
    if (pc.coverage == kCoverageOnlyThin) {  // the pipeline overestimates: the triangle as it is
        gl_Position = vec4(s[corner].xy * 2.0 - 1.0, s[corner].z, 1.0);
        return;
    }
    // The flag decides, not the depth: one depth inside the sampled range, unless the whole
    // triangle lies outside it (then it is clipped, as without dilation).
    float zmin = min(s[0].z, min(s[1].z, s[2].z)), zmax = max(s[0].z, max(s[1].z, s[2].z));
    float z = (zmax < 0.0 || zmin > 1.0) ? zmin : clamp(0.5 * (zmin + zmax), 0.0, 1.0);
    vec2 d = dilatedCorner(px, corner) / n;
    gl_Position = vec4(d * 2.0 - 1.0, z, 1.0);
}
