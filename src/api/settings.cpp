// Automatic settings: what the world knows about its scene on the host (object boxes and
// typical edge lengths) turned into a direction, a resolution, an open epsilon and a
// coverage, with a note saying how each was chosen. The tunables are in spirv/config.h.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "api/world_impl.hpp"
#include "broadphase.h"
#include "vk/device.hpp"

namespace vkcollide {
namespace {

using gpu::kFallbackResolution;
using gpu::kMaxAutoResolution;
using gpu::kMinAutoResolution;
using gpu::kOpenEpsilonPerEdge;
using gpu::kPixelsPerEdge;

// Largest factor by which the transform stretches a length (row norms bound it).
float maxScale(const Transform3x4& t) {
    float s = 0;
    for (int r = 0; r < 3; ++r) s = std::max(s, std::sqrt(t[r * 4] * t[r * 4] + t[r * 4 + 1] * t[r * 4 + 1] + t[r * 4 + 2] * t[r * 4 + 2]));
    return s;
}

std::uint32_t nextPowerOfTwo(double x) {
    std::uint32_t p = 1;
    while (p < x && p < (1u << 30)) p *= 2;
    return p;
}

}  // namespace

// A host mesh's object-space box and mean edge length.
void CollisionWorld::Impl::measureHost(Object& o, std::span<const Float3> positions, std::span<const std::uint32_t> indices) {
    float lo[3] = {positions[0].x, positions[0].y, positions[0].z}, hi[3] = {lo[0], lo[1], lo[2]};
    for (const Float3& p : positions) {
        const float c[3] = {p.x, p.y, p.z};
        for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], c[a]), hi[a] = std::max(hi[a], c[a]);
    }
    o.box = {lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]};
    double sum = 0;
    auto dist = [&](std::uint32_t a, std::uint32_t b) {
        const Float3 &p = positions[a], &q = positions[b];
        return std::sqrt(double(p.x - q.x) * (p.x - q.x) + double(p.y - q.y) * (p.y - q.y) + double(p.z - q.z) * (p.z - q.z));
    };
    for (std::size_t t = 0; t + 2 < indices.size(); t += 3)
        sum += dist(indices[t], indices[t + 1]) + dist(indices[t + 1], indices[t + 2]) + dist(indices[t + 2], indices[t]);
    o.edge_length = indices.empty() ? 0.0f : static_cast<float>(sum / double(indices.size()));
}

// Fills every automatic field from the host's knowledge of the scene: the world box of
// the host meshes, the typical edge length of every object that has one.
DetectSettings CollisionWorld::Impl::resolve(const DetectSettings& in, std::string* note) const {
    DetectSettings s = in;
    float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    double edge_weighted = 0, edge_triangles = 0, open_edge = 0, open_triangles = 0;
    bool any_box = false;
    for (const Object& o : objects) {
        if (!o.alive) continue;
        const Transform3x4& t = o.options.transform;
        if (o.host) {
            for (int c = 0; c < 8; ++c) {
                const float p[3] = {o.box[(c & 1) ? 3 : 0], o.box[(c & 2) ? 4 : 1], o.box[(c & 4) ? 5 : 2]};
                for (int r = 0; r < 3; ++r) {
                    const float x = t[r * 4] * p[0] + t[r * 4 + 1] * p[1] + t[r * 4 + 2] * p[2] + t[r * 4 + 3];
                    lo[r] = std::min(lo[r], x), hi[r] = std::max(hi[r], x);
                }
            }
            any_box = true;
        }
        if (o.edge_length > 0) {
            const double e = double(o.edge_length) * maxScale(t), n = o.gpu.triangle_count;
            edge_weighted += e * n, edge_triangles += n;
            if (o.options.open) open_edge += e * n, open_triangles += n;
        }
    }
    std::string why;
    if (!s.direction) {
        if (any_box) {
            int thin = 0;
            for (int a = 1; a < 3; ++a)
                if (hi[a] - lo[a] < hi[thin] - lo[thin]) thin = a;
            std::array<float, 3> d{0, 0, 0};
            d[thin] = 1;
            s.direction = d;
            why += std::string("direction ") + "xyz"[thin] + " (the scene's thinnest axis)";
        } else {
            s.direction = std::array<float, 3>{0, 0, 1};
            why += "direction z (no host geometry to measure)";
        }
    }
    const double typical_edge = edge_triangles > 0 ? edge_weighted / edge_triangles : 0;
    if (!s.resolution) {
        // Extent across the image: the box's widest extent perpendicular to the direction.
        const auto& d = *s.direction;
        const double dl = std::sqrt(double(d[0]) * d[0] + double(d[1]) * d[1] + double(d[2]) * d[2]);
        double extent = 0;
        if (any_box) {
            const double size[3] = {hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]};
            for (int a = 0; a < 3; ++a) extent = std::max(extent, size[a] * std::sqrt(std::max(0.0, 1.0 - (d[a] / dl) * (d[a] / dl))));
            if (s.region) {
                const auto& r = *s.region;
                extent = std::max({double(r[3] - r[0]), double(r[4] - r[1]), double(r[5] - r[2])});
            }
        }
        if (extent > 0 && typical_edge > 0) {
            const double want = kPixelsPerEdge * extent / typical_edge;
            s.resolution = std::clamp(nextPowerOfTwo(want), kMinAutoResolution, kMaxAutoResolution);
            char buf[160];
            std::snprintf(buf, sizeof buf, "resolution %u (extent %.4g / typical edge %.4g x %.0f px per edge)", *s.resolution, extent,
                          typical_edge, kPixelsPerEdge);
            why += (why.empty() ? "" : "; ") + std::string(buf);
        } else {
            s.resolution = kFallbackResolution;
            why += std::string(why.empty() ? "" : "; ") + "resolution " + std::to_string(kFallbackResolution) +
                   " (no host geometry or edge length to measure)";
        }
    }
    if (!s.open_epsilon) {
        s.open_epsilon = open_triangles > 0 ? static_cast<float>(kOpenEpsilonPerEdge * open_edge / open_triangles) : 0.0f;
        if (open_triangles > 0) why += (why.empty() ? "" : "; ") + std::string("open epsilon half the open objects' typical edge");
    }
    if (s.coverage == Coverage::Best) {
        s.coverage = context->device().conservative_rasterization ? Coverage::Conservative : Coverage::Dilate;
        why += (why.empty() ? "" : "; ") + std::string(s.coverage == Coverage::Conservative
                                                           ? "coverage conservative (the device rasterises conservatively)"
                                                           : "coverage dilate (no conservative rasterisation on this device)");
    }
    if (note) *note = why;
    return s;
}

}  // namespace vkcollide
