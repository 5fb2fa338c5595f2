#version 460
#extension GL_GOOGLE_include_directive : require
// Primitive separation: each triangle takes its screen box, the coarsest-needed mip level
// (a texel at least as large as the box, refined while the corners stay neighbours one
// level finer), unites the bundles under its four corners and keeps that union
// intersected with its own box. No bundle: the empty box.
#include "common.glsl.inc"
layout(local_size_x = kGroupSize) in;
#include "dispatch.glsl.inc"

void main() {
    Frame f = frame();
    ObjectGpu o = ObjectsRef(f.objects).o[pc.object];
    uint t = globalIndex();
    if (t >= o.triangle_count) return;
    Projection pr = ProjectionRef(f.projection).p;
    vec2 lo = vec2(3.4e38), hi = vec2(-3.4e38);
    for (uint c = 0u; c < 3u; ++c) {
        vec2 s = toSampling(pr, toWorld(o, fetchPosition(o, fetchIndex(o, t * 3u + c)))).xy;
        lo = min(lo, s);
        hi = max(hi, s);
    }
    vec4 tri_box = vec4(lo, hi);
    float n = float(f.resolution);
    vec4 kept = kEmptyBox;
    if (!(hi.x < 0.0 || hi.y < 0.0 || lo.x > 1.0 || lo.y > 1.0)) {
        float extent = max(hi.x - lo.x, hi.y - lo.y) * n;
        uint level = 0u;
        while (level + 1u < f.levels && float(1u << level) < extent) ++level;
        ivec4 texel;
        for (;;) {
            int size = int(f.resolution >> level);
            texel = clamp(ivec4(floor(tri_box * n / float(1u << level))), ivec4(0), ivec4(size - 1));
            if (level == 0u) break;
            int finer = int(f.resolution >> (level - 1u));
            ivec4 t2 = clamp(ivec4(floor(tri_box * n / float(1u << (level - 1u)))), ivec4(0), ivec4(finer - 1));
            if (t2.z - t2.x > 1 || t2.w - t2.y > 1) break;
            --level;
        }
        int size = int(f.resolution >> level);
        Vec4sRef b = Vec4sRef(f.bundles);
        uint base = f.level_offset[level];
        vec4 u = boxUnion(boxUnion(b.v[base + uint(texel.y * size + texel.x)], b.v[base + uint(texel.y * size + texel.z)]),
                          boxUnion(b.v[base + uint(texel.w * size + texel.x)], b.v[base + uint(texel.w * size + texel.z)]));
        if (!boxEmpty(u)) {
            vec4 k = vec4(max(u.xy, tri_box.xy), min(u.zw, tri_box.zw));
            if (!boxEmpty(k)) kept = k;
        }
    }
    Vec4sRef(f.sparse).v[o.triangle_base + t] = kept;
}
