#version 460
#extension GL_GOOGLE_include_directive : require
// Primitive separation: each triangle takes its screen box, the coarsest-needed mip level
// (a texel at least as large as the box, refined while the corners stay neighbours one
// level finer), unites the bundles under its four corners and keeps that union
// intersected with its own box. No bundle: the empty box.
//
// Depth-aware separation (f.depth_aware): boxes are (x, y, depth): the triangle's box and
// depth range come from the triangle-bounds pass; each bundle under the box at
// kSeparationRefine levels finer is tested on its own, and the triangle is kept where its
// own box meets one in all three axes: the kept box is the union of those, intersected
// with its own; the kept depth range goes to sparse_depth (the record's depth extent).
#include "common/common.glsl.inc"
#include "depth.glsl.inc"
layout(local_size_x = kGroupSize) in;
#include "common/dispatch.glsl.inc"

void main() {
    Frame f = frame();
    ObjectGpu o = ObjectsRef(f.objects).o[pc.object];
    uint t = globalIndex();
    if (t >= o.triangle_count) return;
    bool depth_aware = f.depth_aware != 0u;
    vec4 tri_box;
    vec2 tri_depth = kEmptyDepth;
    if (depth_aware) {
        TriangleBounds tb = TriBoundsRef(f.tri_bounds).b[o.triangle_base + t];
        tri_box = tb.box;
        tri_depth = vec2(tb.zmin, tb.zmax);
    } else {
        Projection pr = ProjectionRef(f.projection).p;
        vec2 lo = vec2(3.4e38), hi = vec2(-3.4e38);
        for (uint c = 0u; c < 3u; ++c) {
            vec2 s = toSampling(pr, toWorld(o, fetchPosition(o, fetchIndex(o, t * 3u + c)))).xy;
            lo = min(lo, s);
            hi = max(hi, s);
        }
        tri_box = vec4(lo, hi);
    }
    vec2 lo = tri_box.xy, hi = tri_box.zw;
    float n = float(f.resolution);
    vec4 kept = kEmptyBox;
    vec2 kept_depth = kEmptyDepth;
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
        if (depth_aware) {
            // (x, y, depth) boxes: each texel of a finer level under the box on its own, so
            // that one bundle's depth cannot stand in for another's. Kept when one of them
            // meets the triangle's box in all three axes; the kept box is then, as in the
            // paper, the union of the bundles under it (those meeting its box in x and y)
            // intersected with its own box, in all three axes.
            // The texels whose cells meet the box grown by the bundles' growth (finalize: a
            // near ray's box reaches kNearReachPx - 0.5 beyond its pixel, into the next cell).
            uint fine = uint(max(int(level) - int(kSeparationRefine), 0));
            int size = int(f.resolution >> fine);
            vec4 reach_box = tri_box + vec4(-1.0, -1.0, 1.0, 1.0) * ((kNearReachPx - 0.5) / n);
            ivec4 tx = clamp(ivec4(floor(reach_box * n / float(1u << fine))), ivec4(0), ivec4(size - 1));
            uint base = f.level_offset[fine];
            Vec4sRef b = Vec4sRef(f.bundles);
            Vec2sRef d = Vec2sRef(f.bundle_depth);
            vec4 u = kEmptyBox;
            vec2 ud = kEmptyDepth;
            bool meets = false;
            for (int y = tx.y; y <= tx.w; ++y)
                for (int x = tx.x; x <= tx.z; ++x) {
                    uint i = base + uint(y * size + x);
                    vec4 bb = b.v[i];
                    if (boxEmpty(bb) || bb.x > hi.x || bb.z < lo.x || bb.y > hi.y || bb.w < lo.y) continue;
                    vec2 bd = d.v[i];
                    meets = meets || !depthEmpty(depthIntersect(tri_depth, bd));
                    u = boxUnion(u, bb);
                    ud = depthUnion(ud, bd);
                }
            if (meets) {
                kept = vec4(max(u.xy, tri_box.xy), min(u.zw, tri_box.zw));
                kept_depth = depthIntersect(tri_depth, ud);
            }
        } else {
            int size = int(f.resolution >> level);
            uint base = f.level_offset[level];
            Vec4sRef b = Vec4sRef(f.bundles);
            vec4 u = boxUnion(boxUnion(b.v[base + uint(texel.y * size + texel.x)], b.v[base + uint(texel.y * size + texel.z)]),
                              boxUnion(b.v[base + uint(texel.w * size + texel.x)], b.v[base + uint(texel.w * size + texel.z)]));
            if (!boxEmpty(u)) {
                vec4 k = vec4(max(u.xy, tri_box.xy), min(u.zw, tri_box.zw));
                if (!boxEmpty(k)) kept = k;
            }
        }
        if (boxEmpty(kept)) kept_depth = kEmptyDepth;
    }
    Vec4sRef(f.sparse).v[o.triangle_base + t] = kept;
    if (depth_aware) Vec2sRef(f.sparse_depth).v[o.triangle_base + t] = kept_depth;
}
