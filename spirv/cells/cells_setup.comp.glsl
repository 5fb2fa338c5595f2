#version 460
#extension GL_GOOGLE_include_directive : require
// Cell pair stage, pass 1 (one invocation per triangle): input checks, world and sampling
// coordinates with their error bounds, the CellsTriangle and CellsGeometry records, then
// the footprint count: a triangle with a small clamped box adds 1 to every cell it may
// touch; a bigger one is queued as work items for cells_big.comp.
#include "cells_common.glsl.inc"
#include "cells_geometry.glsl.inc"
layout(local_size_x = kCellsGroupSize) in;

const float kTinyWorld = 7.52316384526264e-37;  // 2^-120: denormals flushed to zero, world or sampling units
const float kClampSampling = 1.2676506002282294e30;  // 2^100: far beyond the grid, keeps N * x finite

uint objectOf(CellsParams P, uint tri) {
    ObjectsRef objects = ObjectsRef(P.objects);
    uint lo = 0u, hi = P.object_count - 1u;
    while (lo < hi) {
        uint mid = (lo + hi + 1u) / 2u;
        if (objects.o[mid].triangle_base <= tri) lo = mid; else hi = mid - 1u;
    }
    return lo;
}

// Finite with magnitude below 2^62 (decided on the bits: reliable even where a device
// does not preserve infinities and NaNs).
bool moderate(float x) { return ((floatBitsToUint(x) >> 23) & 0xFFu) < kCellsMaxExponentBits; }
bool moderate(vec4 v) { return moderate(v.x) && moderate(v.y) && moderate(v.z) && moderate(v.w); }
bool moderate(vec3 v) { return moderate(v.x) && moderate(v.y) && moderate(v.z); }

// The projection as the stage uses it. Any affine map is a valid projection
// (docs/reliable.md: the grid and the depth only decide speed), and every later pass reads
// the triangles the setup wrote, so all see the same map. A row with an entry of 2^62 or
// more (the fit's rows are 1 / extent: a scene narrower than about 2^-62 across the grid,
// or thinner than that in depth) is scaled by a power of two to below 2^62 (exact, or
// where an entry becomes subnormal another affine map). A row with a non-finite entry
// (the fit divided by a subnormal extent) becomes 0: every triangle then shares that
// coordinate. A scaled or zero depth row changes no footprint and widens depth intervals
// (more candidates); scaled or zero x or y rows put the scene into the first cells
// (correct, as slow as one cell). The host refuses a non-finite projection it is given.
uint exponentBits(float x) { return (floatBitsToUint(x) >> 23) & 0xFFu; }
vec4 stageRow(vec4 row) {
    uint top = max(max(exponentBits(row.x), exponentBits(row.y)), max(exponentBits(row.z), exponentBits(row.w)));
    if (top == 0xFFu) return vec4(0.0);
    if (top < kCellsMaxExponentBits) return row;
    uint shift = top - kCellsMaxExponentBits + 1u;  // at most 66: 2^-shift is a normal float
    precise vec4 scaled = row * uintBitsToFloat((127u - shift) << 23);
    return scaled;
}

// One row of an affine map, evaluated in a fixed order.
float affineRow(vec4 row, vec3 p) {
    precise float r = ((row.x * p.x + row.y * p.y) + row.z * p.z) + row.w;
    return r;
}
// Bound on the rounding of affineRow (4 roundings per term) plus denormals, for inputs
// that are themselves uncertain by `input_error` per coordinate.
float affineError(vec4 row, vec3 p, float input_error) {
    precise float s = abs(row.x * p.x) + abs(row.y * p.y) + abs(row.z * p.z) + abs(row.w);
    precise float a = abs(row.x) + abs(row.y) + abs(row.z);
    precise float e = a * input_error + 6.0 * kU * s + kTinyWorld * (a + 1.0);
    return e * (1.0 + 8.0 * kU);
}

void main() {
    CellsParams P = params();
    uint t = globalIndex();
    bool live = t < P.triangle_count;
    uint big_chunks = 0u;
    uint bad = 0u;
    uint bbox_cells = 0u;
    CellsTriangle tri;
    if (live) {
        uint o = objectOf(P, t);
        ObjectGpu obj = ObjectsRef(P.objects).o[o];
        uint local_tri = t - obj.triangle_base;
        uint self = P.object_flags != 0ul && (UintsRef(P.object_flags).v[o] & kCellsObjectSelf) != 0u ? kCellsKeySelf : 0u;
        uint index[3];
        vec3 p[3];
        for (uint k = 0u; k < 3u; ++k) {
            uint raw = fetchRawIndex(obj, 3u * local_tri + k);
            if (raw >= obj.vertex_count) bad |= kCellsBadIndex;
            index[k] = min(raw, obj.vertex_count - 1u);
            p[k] = fetchPosition(obj, index[k]);
            if (!moderate(p[k])) bad |= kCellsBadPosition;
        }
        if (!moderate(obj.model[0]) || !moderate(obj.model[1]) || !moderate(obj.model[2])) bad |= kCellsBadPosition;
        Projection pr = ProjectionRef(P.projection).p;
        for (uint r = 0u; r < 3u; ++r) pr.row[r] = stageRow(pr.row[r]);
        // Bad input: every later pass is skipped and the host reports the error.
        if (bad != 0u) p[0] = p[1] = p[2] = vec3(0.0);

        // World coordinates as this GPU computes them, and how far they may be from the
        // CPU's (M * p in double, rounded once to float): both are within 6u of the
        // magnitudes that make them up.
        vec3 w[3];
        float eps = 0.0;
        for (uint k = 0u; k < 3u; ++k) {
            w[k] = vec3(affineRow(obj.model[0], p[k]), affineRow(obj.model[1], p[k]), affineRow(obj.model[2], p[k]));
            eps = max(eps, max(affineError(obj.model[0], p[k], 0.0),
                               max(affineError(obj.model[1], p[k], 0.0), affineError(obj.model[2], p[k], 0.0))));
            if (bad == 0u && !(maxOf3(abs(w[k].x), abs(w[k].y), abs(w[k].z)) < 4.611686018427388e18)) bad |= kCellsBadWorld;
        }
        if (bad != 0u) w[0] = w[1] = w[2] = vec3(0.0);

        CellsGeometry geo;
        for (uint k = 0u; k < 3u; ++k) {
            geo.v[3u * k] = w[k].x;
            geo.v[3u * k + 1u] = w[k].y;
            geo.v[3u * k + 2u] = w[k].z;
            geo.index[k] = index[k];
        }
        geo.eps = eps;
        CellsGeometryRef(P.geometry).g[t] = geo;

        // Sampling coordinates: x, y in cell units, z in sampling depth, each with the
        // bound on its distance from the exact image of the CPU's world position.
        float n = float(P.resolution);
        float pad = 0.0, ez = 0.0;
        // Proximity grows every triangle by proximity_pad world units along each axis: an
        // uncertainty of the world vertices like eps (docs/proximity.md).
        precise float eps_s = P.proximity_pad > 0.0 ? (eps + P.proximity_pad) * (1.0 + 2.0 * kU) : eps;
        bool far = false;
        for (uint k = 0u; k < 3u; ++k) {
            precise float sx = affineRow(pr.row[0], w[k]), sy = affineRow(pr.row[1], w[k]), sz = affineRow(pr.row[2], w[k]);
            float ex = affineError(pr.row[0], w[k], eps_s), ey = affineError(pr.row[1], w[k], eps_s);
            precise float cx = clamp(sx, -kClampSampling, kClampSampling) * n;
            precise float cy = clamp(sy, -kClampSampling, kClampSampling) * n;
            precise float px = (ex * n) * (1.0 + 8.0 * kU) + 2.0 * kU * abs(cx) + kTiny;
            precise float py = (ey * n) * (1.0 + 8.0 * kU) + 2.0 * kU * abs(cy) + kTiny;
            tri.x[k] = cx;
            tri.y[k] = cy;
            tri.z[k] = sz;
            pad = max(pad, max(px, py));
            ez = max(ez, affineError(pr.row[2], w[k], eps_s));
            far = far || !(abs(cx) <= kFar && abs(cy) <= kFar && abs(sz) <= kFar);
        }
        tri.pad = pad;
        tri.ez = ez;
        tri.zmin = padDown(minOf3(tri.z[0], tri.z[1], tri.z[2]), ez);
        tri.zmax = padUp(maxOf3(tri.z[0], tri.z[1], tri.z[2]), ez);
        tri.key = o | self;

        // The depth plane z = z0 + gx (x - x0) + gy (y - y0), where the projected area is
        // clearly non-zero (relative error of A below 1/16) and the slope bounded.
        tri.mode = far ? 0u : kCellsEdges;
        tri.gx = tri.gy = tri.egx = tri.egy = 0.0;
        if (!far) {
            precise float e1x = tri.x[1] - tri.x[0], e1y = tri.y[1] - tri.y[0], e1z = tri.z[1] - tri.z[0];
            precise float e2x = tri.x[2] - tri.x[0], e2y = tri.y[2] - tri.y[0], e2z = tri.z[2] - tri.z[0];
            precise float area = e1x * e2y - e2x * e1y;
            precise float err_area = 8.0 * kU * (abs(e1x * e2y) + abs(e2x * e1y)) + kTiny;
            precise float nx = e1z * e2y - e2z * e1y, ny = e1x * e2z - e2x * e1z;
            precise float err_nx = 8.0 * kU * (abs(e1z * e2y) + abs(e2z * e1y)) + kTiny;
            precise float err_ny = 8.0 * kU * (abs(e1x * e2z) + abs(e2x * e1z)) + kTiny;
            precise float limit = kFar * abs(area);
            if (abs(area) > 16.0 * err_area && abs(nx) <= limit && abs(ny) <= limit) {
                precise float gx = nx / area, gy = ny / area;
                tri.gx = gx;
                tri.gy = gy;
                precise float egx = 1.125 * (err_nx + abs(gx) * err_area) / abs(area) + 8.0 * kU * abs(gx) + kTiny;
                precise float egy = 1.125 * (err_ny + abs(gy) * err_area) / abs(area) + 8.0 * kU * abs(gy) + kTiny;
                tri.egx = egx;
                tri.egy = egy;
                tri.mode |= kCellsPlane;
            }
        }

        // Clamped footprint box: cells [i, i+1] that meet [xmin - pad, xmax + pad]; a
        // value exactly on a cell border takes both cells.
        precise vec4 cells = floor(paddedBox(tri));  // x lo, y lo, x hi, y hi
        float last = n - 1.0;
        uvec4 range = uvec4(clamp(cells, vec4(0.0), vec4(last)));
        tri.cells_lo = range.x | (range.y << 16);
        tri.cells_hi = range.z | (range.w << 16);
        CellsTrianglesRef(P.triangles).t[t] = tri;

        bbox_cells = (range.z - range.x + 1u) * (range.w - range.y + 1u);
        if (bad != 0u) {
            atomicOr(cellsHeader(P).h.flags, bad);
            atomicMin(cellsHeader(P).h.bad_triangle, t);
            live = false;
        } else if (bbox_cells > kCellsSmallBox) {
            big_chunks = (bbox_cells + kCellsChunkCells - 1u) / kCellsChunkCells;
            live = false;
        }
    }

    // The budget: every footprint box cell, summed without wrapping (a lane's is below
    // 2^28, so each 16-bit half sums below 2^32 over a subgroup). The subgroup that passes
    // the budget flags the run; its footprints are still counted below (small triangles:
    // at most kCellsSmallBox each), but nothing after this pass runs.
    uint64_t boxes = (uint64_t(subgroupAdd(bad == 0u ? bbox_cells >> 16 : 0u)) << 16) +
                     uint64_t(subgroupAdd(bad == 0u ? bbox_cells & 0xFFFFu : 0u));
    if (subgroupElect() && boxes > 0ul) {
        uint64_t before = atomicAdd(Uint64sRef(headerField(P, kHeaderBoxCells)).v[0], boxes);
        if (before + boxes > uint64_t(P.budget)) raiseFlag(P, kCellsOverBudget);
    }

    // Big triangles: work items (t, chunk), one atomic per subgroup.
    uint first = subgroupAppend(headerField(P, kHeaderItems), big_chunks);
    subgroupCount(headerField(P, kHeaderBigTriangles), big_chunks > 0u ? 1u : 0u);
    for (uint c = 0u; c < big_chunks; ++c) {
        if (first + c < P.item_capacity) Uvec2sRef(P.big_items).v[first + c] = uvec2(t, c);
        else atomicOr(cellsHeader(P).h.flags, kCellsOverflowItems);
    }
    if (!live) return;

    uvec4 r = cellsRange(tri);
    UintsRef counts = UintsRef(P.counts);
    for (uint j = r.y; j <= r.w; ++j)
        for (uint i = r.x; i <= r.z; ++i)
            if (cellsCovers(tri, i, j, P.resolution)) atomicAdd(counts.v[j * P.resolution + i], 1u);
}
