#include "support/broadphase_reference.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

#include "passes/projection.hpp"

namespace vkcollide::test {
namespace {

constexpr double kEdgeAmbiguity = 1e-3;   // pixels
constexpr float kDepthAmbiguity = 1e-6f;  // normalised depth
constexpr std::uint32_t kBack = 0x80000000u, kOpen = 0x40000000u;

struct Box {
    float x0 = 1, y0 = 1, x1 = 0, y1 = 0;
    bool empty() const { return x0 > x1 || y0 > y1; }
};
Box unite(Box a, Box b) { return {std::min(a.x0, b.x0), std::min(a.y0, b.y0), std::max(a.x1, b.x1), std::max(a.y1, b.y1)}; }

float dot4(const float* row, Float3 p) { return row[0] * p.x + row[1] * p.y + row[2] * p.z + row[3]; }

}  // namespace

std::size_t ReferenceResult::ambiguousCount() const {
    return static_cast<std::size_t>(std::count(ambiguous.begin(), ambiguous.end(), std::uint8_t(1)));
}

ReferenceResult referenceBroadPhase(const std::vector<ReferenceObject>& objects, const passes::BroadPhaseSettings& s,
                                    std::uint32_t layers, const std::vector<std::uint8_t>* gpu_rays) {
    const std::uint32_t n = s.resolution;
    const gpu::Projection proj = passes::regionProjection(passes::projectionBasis(s.direction), *s.region, s.open_epsilon, 0);
    float rows[12];
    for (int a = 0; a < 3; ++a) rows[a * 4] = proj.row[a].x, rows[a * 4 + 1] = proj.row[a].y, rows[a * 4 + 2] = proj.row[a].z, rows[a * 4 + 3] = proj.row[a].w;
    const float eps = proj.open_epsilon;
    ReferenceResult out;
    out.rays.assign(std::size_t(n) * n, 0);
    out.ambiguous.assign(std::size_t(n) * n, 0);

    // Pass 1: rasterise every triangle (pixel centres, 8-bit sub-pixel snapping, top-left
    // rule), give each fragment the GPU's 64-bit key, sort each ray, apply the rules.
    std::vector<std::vector<std::uint64_t>> frags(std::size_t(n) * n);
    std::uint32_t tri_base = 0;
    for (const ReferenceObject& obj : objects) {
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
    for (std::size_t pix = 0; pix < frags.size(); ++pix) {
        auto& f = frags[pix];
        out.depth_complexity = std::max(out.depth_complexity, std::uint32_t(f.size()));
        if (f.empty()) continue;
        std::sort(f.begin(), f.end());
        auto depth = [](std::uint64_t k) { return std::bit_cast<float>(std::uint32_t(k >> 32)); };
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
        if (peeled < f.size()) collide = true;  // beyond the layer cap: conservative
        out.rays[pix] = collide ? 1 : 0;
    }
    for (auto r : out.rays) out.collision_rays += r;

    // Pass 2: the ray-bundle mipmap.
    const std::vector<std::uint8_t>& rays = gpu_rays ? *gpu_rays : out.rays;
    std::vector<std::vector<Box>> mip;
    mip.emplace_back(std::size_t(n) * n);
    for (std::uint32_t py = 0; py < n; ++py)
        for (std::uint32_t px = 0; px < n; ++px)
            if (rays[std::size_t(py) * n + px])
                mip[0][std::size_t(py) * n + px] = {float(px) / float(n), float(py) / float(n), float(px + 1) / float(n),
                                                    float(py + 1) / float(n)};
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
    std::uint32_t obj_index = 0;
    for (const ReferenceObject& obj : objects) {
        const HostMesh& m = *obj.mesh;
        for (std::uint32_t t = 0; t < m.triangleCount(); ++t) {
            float lo[2] = {std::numeric_limits<float>::max(), std::numeric_limits<float>::max()};
            float hi[2] = {-lo[0], -lo[1]};
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
                const float sx = dot4(rows, p), sy = dot4(rows + 4, p), sz = dot4(rows + 8, p);
                lo[0] = std::min(lo[0], sx), lo[1] = std::min(lo[1], sy);
                hi[0] = std::max(hi[0], sx), hi[1] = std::max(hi[1], sy);
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
            const std::size_t size = n >> level;
            const auto& L = mip[level];
            Box u = unite(unite(L[tx[1] * size + tx[0]], L[tx[1] * size + tx[2]]), unite(L[tx[3] * size + tx[0]], L[tx[3] * size + tx[2]]));
            if (u.empty()) continue;
            Box k{std::max(u.x0, lo[0]), std::max(u.y0, lo[1]), std::min(u.x1, hi[0]), std::min(u.y1, hi[1])};
            if (k.empty()) continue;
            rec.box[0] = k.x0, rec.box[1] = k.y0, rec.box[2] = k.x1, rec.box[3] = k.y1;
            out.records.push_back(rec);
        }
        ++obj_index;
    }
    return out;
}

}  // namespace vkcollide::test
