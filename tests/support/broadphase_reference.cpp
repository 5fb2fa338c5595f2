#include "support/broadphase_reference.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

#include "broad/projection.hpp"

namespace vkcollide::test {
namespace {

constexpr double kEdgeAmbiguity = 1e-3;   // pixels
constexpr float kDepthAmbiguity = 1e-6f;  // normalised depth
constexpr std::uint32_t kBack = 0x80000000u, kOpen = 0x40000000u;

constexpr float kHuge = 3.4e38f;
// Near tests and silhouette tests this close to their thresholds may round either way.
constexpr float kNearAmbiguity = 1e-5f;  // relative to the windows' slopes
constexpr float kCosAmbiguity = 1e-4f;

// A bundle: screen box and (depth-aware) depth interval; lo > hi is empty.
struct Box {
    float x0 = 1, y0 = 1, x1 = 0, y1 = 0;
    float z0 = kHuge, z1 = -kHuge;
    bool empty() const { return x0 > x1 || y0 > y1; }
};
Box unite(Box a, Box b) {
    return {std::min(a.x0, b.x0), std::min(a.y0, b.y0), std::max(a.x1, b.x1), std::max(a.y1, b.y1), std::min(a.z0, b.z0), std::max(a.z1, b.z1)};
}
using Interval = std::array<float, 2>;
constexpr Interval kNone{kHuge, -kHuge};
bool none(Interval d) { return d[0] > d[1]; }
Interval unite(Interval a, Interval b) { return {std::min(a[0], b[0]), std::max(a[1], b[1])}; }

float dot4(const float* row, Float3 p) { return row[0] * p.x + row[1] * p.y + row[2] * p.z + row[3]; }

// What the triangle-bounds pass computes for one triangle (tri_bounds.comp.glsl).
struct TriangleInfo {
    std::uint32_t object = 0, local = 0;
    float lo[2], hi[2];  // sampling-space box
    float zmin, zmax;    // padded depth range
    float slope;         // depth per pixel of its plane (3.4e38: degenerate)
    float plane, dzdx, dzdy;  // z = plane + dzdx * x + dzdy * y, pixel units
    bool thin = false;        // projected inradius below kThinInradiusPx
    float px[3][2];           // corners in pixel coordinates
    float det = 0;            // twice the projected area, pixel units
    Float3 normal;       // unit normal (world = object space here)
};

TriangleInfo triangleInfo(const HostMesh& m, std::uint32_t t, const float* rows, std::uint32_t n) {
    TriangleInfo ti;
    float s[3][3], magnitude = 0;
    for (int c = 0; c < 3; ++c) {
        const Float3 p = m.positions[m.indices[t * 3 + c]];
        for (int a = 0; a < 3; ++a) s[c][a] = dot4(rows + 4 * a, p);
        magnitude = std::max(magnitude, std::fabs(rows[8]) * std::fabs(p.x) + std::fabs(rows[9]) * std::fabs(p.y) +
                                            std::fabs(rows[10]) * std::fabs(p.z) + std::fabs(rows[11]));
    }
    for (int a = 0; a < 2; ++a) {
        ti.lo[a] = std::min({s[0][a], s[1][a], s[2][a]});
        ti.hi[a] = std::max({s[0][a], s[1][a], s[2][a]});
    }
    const float pad = magnitude * gpu::kDepthRoundingPad;
    ti.zmin = std::min({s[0][2], s[1][2], s[2][2]}) - pad;
    ti.zmax = std::max({s[0][2], s[1][2], s[2][2]}) + pad;
    const float p0x = s[0][0] * float(n), p0y = s[0][1] * float(n);
    const float e1x = s[1][0] * float(n) - p0x, e1y = s[1][1] * float(n) - p0y;
    const float e2x = s[2][0] * float(n) - p0x, e2y = s[2][1] * float(n) - p0y;
    const float dz1 = s[1][2] - s[0][2], dz2 = s[2][2] - s[0][2];
    const float det = e1x * e2y - e2x * e1y;
    const float gx = (dz1 * e2y - dz2 * e1y) / det, gy = (e1x * dz2 - e2x * dz1) / det;
    const bool planar = det != 0 && std::fabs(gx) + std::fabs(gy) < kHuge;
    ti.slope = planar ? std::fabs(gx) + std::fabs(gy) : kHuge;
    ti.dzdx = planar ? gx : 0, ti.dzdy = planar ? gy : 0;
    ti.plane = s[0][2] - ti.dzdx * p0x - ti.dzdy * p0y;
    const float perimeter = std::sqrt(e1x * e1x + e1y * e1y) + std::sqrt(e2x * e2x + e2y * e2y) +
                            std::sqrt((e2x - e1x) * (e2x - e1x) + (e2y - e1y) * (e2y - e1y));
    ti.thin = std::fabs(det) < gpu::kThinInradiusPx * perimeter;
    ti.det = det;
    ti.px[0][0] = p0x, ti.px[0][1] = p0y, ti.px[1][0] = p0x + e1x, ti.px[1][1] = p0y + e1y, ti.px[2][0] = p0x + e2x, ti.px[2][1] = p0y + e2y;
    const Float3 a = m.positions[m.indices[t * 3]], b = m.positions[m.indices[t * 3 + 1]], c = m.positions[m.indices[t * 3 + 2]];
    const float ux = b.x - a.x, uy = b.y - a.y, uz = b.z - a.z, vx = c.x - a.x, vy = c.y - a.y, vz = c.z - a.z;
    const float nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, nz = ux * vy - uy * vx, l = std::sqrt(nx * nx + ny * ny + nz * nz);
    ti.normal = l > 0 ? Float3{nx / l, ny / l, nz / l} : Float3{};
    return ti;
}

// A triangle's window on the ray through pixel (x, y) (classify.comp.glsl, nearWindow).
Interval window(std::uint32_t x, std::uint32_t y, const TriangleInfo& t, float slope) {
    const float z = t.plane + t.dzdx * (float(x) + 0.5f) + t.dzdy * (float(y) + 0.5f);
    const float plane = slope * gpu::kNearReachPx + gpu::kFragmentDepthPad, range = slope * gpu::kNearRangePx;
    return {std::min(z - plane, std::max(t.zmin, z - range)), std::max(z + plane, std::min(t.zmax, z + range))};
}

// tri_bounds.comp.glsl, splat: the rays near an edge-on triangle's longest edge get its
// range; rays within kSplatAmbiguity px of the marked ranges' ends are ambiguous.
constexpr float kSplatAmbiguity = 1e-3f;
void splat(const TriangleInfo& t, std::uint32_t n, std::vector<Interval>& io_edge, std::vector<std::uint8_t>& io_ambiguous) {
    const float e1[2] = {t.px[1][0] - t.px[0][0], t.px[1][1] - t.px[0][1]}, e2[2] = {t.px[2][0] - t.px[0][0], t.px[2][1] - t.px[0][1]};
    auto len = [](float x, float y) { return std::sqrt(x * x + y * y); };
    const float* a = t.px[0];
    const float* c = t.px[1];
    float longest = len(e1[0], e1[1]);
    if (len(e2[0], e2[1]) > longest) c = t.px[2], longest = len(e2[0], e2[1]);
    if (len(e2[0] - e1[0], e2[1] - e1[1]) > longest) a = t.px[1], c = t.px[2], longest = len(e2[0] - e1[0], e2[1] - e1[1]);
    const float d = (longest > 0 ? std::fabs(t.det) / longest : 0.0f) + gpu::kNearReachPx;
    const int row0 = std::max(int(std::ceil(std::min(a[1], c[1]) - d - 0.5f)), 0);
    const int row1 = std::min(int(std::floor(std::max(a[1], c[1]) + d - 0.5f)), int(n) - 1);
    for (int j = row0; j <= row1; ++j) {
        const float yc = float(j) + 0.5f, dy = c[1] - a[1];
        float t0 = 0, t1 = 1;
        if (std::fabs(dy) > 1e-6f) {
            const float ta = (yc - d - a[1]) / dy, tb = (yc + d - a[1]) / dy;
            t0 = std::clamp(std::min(ta, tb), 0.0f, 1.0f), t1 = std::clamp(std::max(ta, tb), 0.0f, 1.0f);
        }
        const float x0 = a[0] + (c[0] - a[0]) * t0, x1 = a[0] + (c[0] - a[0]) * t1;
        const float xl = std::min(x0, x1) - d - 0.5f, xh = std::max(x0, x1) + d - 0.5f;
        const int col0 = std::max(int(std::ceil(xl)), 0), col1 = std::min(int(std::floor(xh)), int(n) - 1);
        for (int i = std::max(col0 - 1, 0); i <= std::min(col1 + 1, int(n) - 1); ++i) {
            const std::size_t pix = std::size_t(j) * n + i;
            if (std::fabs(float(i) - xl) < kSplatAmbiguity || std::fabs(float(i) - xh) < kSplatAmbiguity) io_ambiguous[pix] = 1;
            if (i >= col0 && i <= col1) io_edge[pix] = unite(io_edge[pix], Interval{t.zmin, t.zmax});
        }
        // The first and last rows may round either way: their neighbours are ambiguous too.
        const float top = std::min(a[1], c[1]) - d - 0.5f, bottom = std::max(a[1], c[1]) + d - 0.5f;
        const bool edge_row = std::fabs(top - std::round(top)) < kSplatAmbiguity || std::fabs(bottom - std::round(bottom)) < kSplatAmbiguity;
        for (int row = j - 1; edge_row && row <= j + 1; ++row)
            if (row >= 0 && row < int(n))
                for (int i = std::max(col0 - 1, 0); i <= std::min(col1 + 1, int(n) - 1); ++i) io_ambiguous[std::size_t(row) * n + i] = 1;
    }
}

bool neighbours(const HostMesh& m, std::uint32_t ta, std::uint32_t tb) {
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            const std::uint32_t ia = m.indices[ta * 3 + i], ib = m.indices[tb * 3 + j];
            const Float3 pa = m.positions[ia], pb = m.positions[ib];
            if (ia == ib || (std::bit_cast<std::uint32_t>(pa.x) == std::bit_cast<std::uint32_t>(pb.x) &&
                             std::bit_cast<std::uint32_t>(pa.y) == std::bit_cast<std::uint32_t>(pb.y) &&
                             std::bit_cast<std::uint32_t>(pa.z) == std::bit_cast<std::uint32_t>(pb.z)))
                return true;
        }
    return false;
}

}  // namespace

std::size_t ReferenceResult::ambiguousCount() const {
    return static_cast<std::size_t>(std::count(ambiguous.begin(), ambiguous.end(), std::uint8_t(1)));
}

ReferenceResult referenceBroadPhase(const std::vector<BroadPhaseObject>& objects, const passes::BroadPhaseSettings& s, std::uint32_t layers,
                                    const GpuRays& gpu) {
    const std::uint32_t n = s.resolution;
    const bool depth_aware = s.depth_aware;
    const gpu::Projection proj = passes::regionProjection(passes::projectionBasis(s.direction), *s.region, s.open_epsilon, 0);
    float rows[12];
    for (int a = 0; a < 3; ++a) rows[a * 4] = proj.row[a].x, rows[a * 4 + 1] = proj.row[a].y, rows[a * 4 + 2] = proj.row[a].z, rows[a * 4 + 3] = proj.row[a].w;
    const float eps = proj.open_epsilon;
    ReferenceResult out;
    out.rays.assign(std::size_t(n) * n, 0);
    out.ambiguous.assign(std::size_t(n) * n, 0);
    out.ray_depth.assign(depth_aware ? std::size_t(n) * n : 0, kNone);

    // Every triangle's bounds, in global order (the triangle-bounds pass); edge-on triangles
    // (thin and steep) leave their range at the rays near them.
    const float level_slope = std::sqrt(rows[8] * rows[8] + rows[9] * rows[9] + rows[10] * rows[10]) /
                              (float(n) * std::min(std::sqrt(rows[0] * rows[0] + rows[1] * rows[1] + rows[2] * rows[2]),
                                                   std::sqrt(rows[4] * rows[4] + rows[5] * rows[5] + rows[6] * rows[6])));
    std::vector<TriangleInfo> tris;
    std::vector<Interval> edge(depth_aware ? std::size_t(n) * n : 0, kNone);
    for (std::uint32_t o = 0; o < objects.size(); ++o) {
        const HostMesh& m = *objects[o].mesh;
        for (std::uint32_t t = 0; t < m.triangleCount(); ++t) {
            tris.push_back(triangleInfo(m, t, rows, n));
            TriangleInfo& ti = tris.back();
            ti.object = o, ti.local = t;
            if (depth_aware && ti.thin && ti.slope > gpu::kEdgeOnSlope * level_slope) splat(ti, n, edge, out.ambiguous);
        }
    }

    // Pass 1: rasterise every triangle (pixel centres, 8-bit sub-pixel snapping, top-left
    // rule), give each fragment the GPU's 64-bit key, sort each ray, apply the rules.
    std::vector<std::vector<std::uint64_t>> frags(std::size_t(n) * n);
    std::uint32_t tri_base = 0;
    for (const BroadPhaseObject& obj : objects) {
        const HostMesh& m = *obj.mesh;
        for (std::uint32_t t = 0; t < m.triangleCount(); ++t) {
            double x[3], y[3];
            float z[3];
            for (int c = 0; c < 3; ++c) {
                Float3 p = m.positions[m.indices[t * 3 + c]];
                float sx = dot4(rows, p), sy = dot4(rows + 4, p);
                z[c] = dot4(rows + 8, p);
                // Viewport transform of (s*2-1), then snapping to 1/256 pixel.
                x[c] = std::round(double((sx * 2.0f - 1.0f) * 0.5f * float(n) + 0.5f * float(n)) * 256.0) / 256.0;
                y[c] = std::round(double((sy * 2.0f - 1.0f) * 0.5f * float(n) + 0.5f * float(n)) * 256.0) / 256.0;
            }
            const double area = (x[1] - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[1] - y[0]);
            if (area == 0) continue;
            const bool back = -0.5 * area <= 0;  // Vulkan: a = -1/2 * shoelace; CCW front means a > 0
            const double sign = area > 0 ? 1.0 : -1.0;
            const std::uint32_t low = ((tri_base + t) & 0x3FFFFFFFu) | (obj.open ? kOpen : 0u) | (back ? kBack : 0u);
            int px0 = std::max(0, int(std::floor(std::min({x[0], x[1], x[2]}) - 0.5)));
            int px1 = std::min(int(n) - 1, int(std::ceil(std::max({x[0], x[1], x[2]}))));
            int py0 = std::max(0, int(std::floor(std::min({y[0], y[1], y[2]}) - 0.5)));
            int py1 = std::min(int(n) - 1, int(std::ceil(std::max({y[0], y[1], y[2]}))));
            for (int py = py0; py <= py1; ++py)
                for (int px = px0; px <= px1; ++px) {
                    const double cx = px + 0.5, cy = py + 0.5;
                    double w[3];
                    bool inside = true, near = false;
                    for (int e = 0; e < 3; ++e) {
                        const int a = (e + 1) % 3, b = (e + 2) % 3;  // edge opposite vertex e
                        double ex = x[b] - x[a], ey = y[b] - y[a];
                        double val = sign * (ex * (cy - y[a]) - ey * (cx - x[a]));
                        w[e] = val;
                        double len = std::sqrt(ex * ex + ey * ey);
                        if (std::fabs(val) < kEdgeAmbiguity * len) near = true;
                        if (val < 0) inside = false;
                    }
                    const std::size_t pix = std::size_t(py) * n + px;
                    if (near) out.ambiguous[pix] = 1;
                    if (!inside) continue;
                    double sum = w[0] + w[1] + w[2];
                    float depth = float((w[0] * z[0] + w[1] * z[1] + w[2] * z[2]) / sum);
                    frags[pix].push_back((std::uint64_t(std::bit_cast<std::uint32_t>(depth)) << 32) | low);
                }
        }
        tri_base += static_cast<std::uint32_t>(m.triangleCount());
    }
    auto depth = [](std::uint64_t k) { return std::bit_cast<float>(std::uint32_t(k >> 32)); };
    // Depth-aware: whether consecutive fragments a, b are a near pair, and their windows.
    auto nearHull = [&](std::size_t pix, std::uint64_t a, std::uint64_t b, std::uint8_t& io_ambiguous) -> Interval {
        const std::uint32_t px = std::uint32_t(pix % n), py = std::uint32_t(pix / n);
        const TriangleInfo &ta = tris[std::uint32_t(a) & 0x3FFFFFFFu], &tb = tris[std::uint32_t(b) & 0x3FFFFFFFu];
        auto overlap = [](Interval x, Interval y) { return std::min(x[1], y[1]) - std::max(x[0], y[0]); };
        Interval wa = window(px, py, ta, ta.slope), wb = window(px, py, tb, tb.slope);
        // GPU and CPU windows differ by rounding: of the depths (absolute) and of the planes
        // in pixel units (relative to the slopes).
        const float rounding = kNearAmbiguity * (std::min(ta.slope, 1.0f) + std::min(tb.slope, 1.0f)) * (gpu::kNearRangePx + 1.0f) + 5e-7f;
        float o = overlap(wa, wb);
        if (std::fabs(o) < rounding) io_ambiguous = 1;
        if (o < 0) return kNone;
        if (ta.object == tb.object) {
            const BroadPhaseObject& obj = objects[ta.object];
            if (!obj.self_collision || neighbours(*obj.mesh, ta.local, tb.local)) return kNone;
            const float cosine = ta.normal.x * tb.normal.x + ta.normal.y * tb.normal.y + ta.normal.z * tb.normal.z;
            if (std::fabs(cosine - gpu::kSilhouetteCos) < kCosAmbiguity) io_ambiguous = 1;
            if (cosine > gpu::kSilhouetteCos) {
                const float cap = gpu::kSelfSlopeCap * level_slope;
                wa = window(px, py, ta, std::min(ta.slope, cap)), wb = window(px, py, tb, std::min(tb.slope, cap));
                o = overlap(wa, wb);
                if (std::fabs(o) < rounding) io_ambiguous = 1;
                if (o < 0) return kNone;
            }
        }
        return unite(wa, wb);
    };
    std::vector<Interval> near(depth_aware ? frags.size() : 0, kNone);
    std::vector<std::uint8_t> unknown(frags.size(), 0);
    for (std::size_t pix = 0; pix < frags.size(); ++pix) {
        auto& f = frags[pix];
        out.depth_complexity = std::max(out.depth_complexity, std::uint32_t(f.size()));
        if (f.empty()) continue;
        std::sort(f.begin(), f.end());
        for (std::size_t i = 1; i < f.size(); ++i)
            if (std::fabs(depth(f[i]) - depth(f[i - 1])) < kDepthAmbiguity) out.ambiguous[pix] = 1;
        bool collide = false;
        std::uint32_t parity = 0, closed = 0;
        const std::size_t peeled = std::min<std::size_t>(f.size(), layers);
        for (std::size_t i = 0; i < peeled && !collide; ++i) {
            const std::uint32_t lowk = std::uint32_t(f[i]);
            if (!(lowk & kOpen)) {
                if (((lowk & kBack) != 0) != (parity != 0)) collide = true;
                parity ^= 1;
            } else if (parity) {
                collide = true;  // an open surface inside a closed one
            }
            if (i > 0 && ((lowk | std::uint32_t(f[i - 1])) & kOpen) && std::fabs(depth(f[i]) - depth(f[i - 1])) <= eps)
                collide = true;
        }
        for (std::uint64_t k : f) closed += (std::uint32_t(k) & kOpen) ? 0 : 1;
        if (!collide && peeled == f.size() && (closed & 1)) collide = true;
        if (peeled < f.size()) collide = true, unknown[pix] = 1;  // beyond the layer cap: conservative
        out.rays[pix] = collide ? 1 : 0;
        // Depth-aware: every consecutive pair of a fully peeled ray.
        if (depth_aware && peeled == f.size())
            for (std::size_t i = 1; i < f.size(); ++i) near[pix] = unite(near[pix], nearHull(pix, f[i - 1], f[i], out.ambiguous[pix]));
    }
    for (auto r : out.rays) out.collision_rays += r;

    // Depth-aware: each ray's interval (finalize.comp.glsl): every depth for a collision ray
    // beyond the cap; its near pairs' windows if it or a ray next to it collides.
    for (std::size_t pix = 0; depth_aware && pix < frags.size(); ++pix) {
        const std::uint32_t x = std::uint32_t(pix % n), y = std::uint32_t(pix / n);
        bool beside = false;
        for (std::uint32_t j = std::max(y, 1u) - 1; j <= std::min(y + 1, n - 1); ++j)
            for (std::uint32_t i = std::max(x, 1u) - 1; i <= std::min(x + 1, n - 1); ++i) beside = beside || out.rays[std::size_t(j) * n + i];
        if (out.rays[pix] && unknown[pix]) out.ray_depth[pix] = {-kHuge, kHuge};
        else if (beside) out.ray_depth[pix] = unite(near[pix], edge[pix]);
    }

    // Pass 2: the ray-bundle mipmap.
    const std::vector<std::uint8_t>& rays = gpu.rays ? *gpu.rays : out.rays;
    const std::vector<Interval>& ray_depth = gpu.depth ? *gpu.depth : out.ray_depth;
    std::vector<std::vector<Box>> mip;
    mip.emplace_back(std::size_t(n) * n);
    for (std::uint32_t py = 0; py < n; ++py)
        for (std::uint32_t px = 0; px < n; ++px) {
            const std::size_t pix = std::size_t(py) * n + px;
            if (depth_aware ? none(ray_depth[pix]) : !rays[pix]) continue;
            // A near interval holds within kNearReachPx of the ray's sample.
            const float grow = depth_aware && ray_depth[pix][1] < kHuge ? gpu::kNearReachPx - 0.5f : 0.0f;
            Box& b = mip[0][pix];
            b = {(float(px) - grow) / float(n), (float(py) - grow) / float(n), (float(px) + 1.0f + grow) / float(n),
                 (float(py) + 1.0f + grow) / float(n)};
            if (depth_aware) b.z0 = ray_depth[pix][0], b.z1 = ray_depth[pix][1];
        }
    for (std::uint32_t size = n / 2; size >= 1; size /= 2) {
        const auto& prev = mip.back();
        std::vector<Box> level(std::size_t(size) * size);
        for (std::uint32_t y = 0; y < size; ++y)
            for (std::uint32_t x = 0; x < size; ++x) {
                const std::size_t c = size * 2;
                level[y * size + x] = unite(unite(prev[2 * y * c + 2 * x], prev[2 * y * c + 2 * x + 1]),
                                            unite(prev[(2 * y + 1) * c + 2 * x], prev[(2 * y + 1) * c + 2 * x + 1]));
            }
        mip.push_back(std::move(level));
    }

    // Pass 3 and 4: separation, then the surviving triangles in global order.
    std::uint32_t global = 0;
    for (std::uint32_t obj_index = 0; obj_index < objects.size(); ++obj_index) {
        const HostMesh& m = *objects[obj_index].mesh;
        for (std::uint32_t t = 0; t < m.triangleCount(); ++t, ++global) {
            const TriangleInfo& ti = tris[global];
            const float* lo = ti.lo;
            const float* hi = ti.hi;
            CandidateTriangle rec{};
            rec.object = obj_index;
            rec.triangle = t;
            rec.zmin = std::numeric_limits<float>::max();
            rec.zmax = -rec.zmin;
            for (int c = 0; c < 3; ++c) {
                const std::uint32_t vi = m.indices[t * 3 + c];
                const Float3 p = m.positions[vi];
                rec.vertex_index[c] = vi;
                rec.v[c] = p;
                const float sz = dot4(rows + 8, p);
                rec.zmin = std::min(rec.zmin, sz), rec.zmax = std::max(rec.zmax, sz);
            }
            if (hi[0] < 0 || hi[1] < 0 || lo[0] > 1 || lo[1] > 1) continue;
            const float extent = std::max(hi[0] - lo[0], hi[1] - lo[1]) * float(n);
            std::uint32_t level = 0;
            while (level + 1 < mip.size() && float(1u << level) < extent) ++level;
            auto texels = [&](std::uint32_t l) {
                const int size = int(n >> l);
                const float scale = float(n) / float(1u << l);
                auto cl = [&](float v) { return std::clamp(int(std::floor(v * scale)), 0, size - 1); };
                return std::array<int, 4>{cl(lo[0]), cl(lo[1]), cl(hi[0]), cl(hi[1])};
            };
            std::array<int, 4> tx = texels(level);
            while (level > 0) {
                auto finer = texels(level - 1);
                if (finer[2] - finer[0] > 1 || finer[3] - finer[1] > 1) break;
                --level;
                tx = finer;
            }
            Box k;
            if (depth_aware) {
                // Each texel one level finer on its own; kept if one meets the triangle's box
                // in all three axes, as the union of those under its box (separate.comp.glsl).
                const std::uint32_t fine = level > gpu::kSeparationRefine ? level - gpu::kSeparationRefine : 0;
                const float grow = (gpu::kNearReachPx - 0.5f) / float(n);
                const int fsize = int(n >> fine);
                const float fscale = float(n) / float(1u << fine);
                auto fcl = [&](float v) { return std::clamp(int(std::floor(v * fscale)), 0, fsize - 1); };
                const std::array<int, 4> ft{fcl(lo[0] - grow), fcl(lo[1] - grow), fcl(hi[0] + grow), fcl(hi[1] + grow)};
                const std::size_t size = n >> fine;
                Box u;
                bool meets = false;
                for (int y = ft[1]; y <= ft[3]; ++y)
                    for (int x = ft[0]; x <= ft[2]; ++x) {
                        const Box& bb = mip[fine][std::size_t(y) * size + x];
                        if (bb.empty() || bb.x0 > hi[0] || bb.x1 < lo[0] || bb.y0 > hi[1] || bb.y1 < lo[1]) continue;
                        meets = meets || std::max(ti.zmin, bb.z0) <= std::min(ti.zmax, bb.z1);
                        u = unite(u, bb);
                    }
                if (!meets) continue;
                k = {std::max(u.x0, lo[0]), std::max(u.y0, lo[1]), std::min(u.x1, hi[0]), std::min(u.y1, hi[1]),
                     std::max(u.z0, ti.zmin), std::min(u.z1, ti.zmax)};
                rec.zmin = k.z0, rec.zmax = k.z1;
            } else {
                const std::size_t size = n >> level;
                const auto& L = mip[level];
                Box u = unite(unite(L[tx[1] * size + tx[0]], L[tx[1] * size + tx[2]]), unite(L[tx[3] * size + tx[0]], L[tx[3] * size + tx[2]]));
                if (u.empty()) continue;
                k = {std::max(u.x0, lo[0]), std::max(u.y0, lo[1]), std::min(u.x1, hi[0]), std::min(u.y1, hi[1])};
            }
            if (k.empty()) continue;
            rec.box[0] = k.x0, rec.box[1] = k.y0, rec.box[2] = k.x1, rec.box[3] = k.y1;
            out.records.push_back(rec);
        }
    }
    return out;
}

}  // namespace vkcollide::test
