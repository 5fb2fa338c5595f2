#include "contacts/contact_grid.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace vkcollide::passes {
namespace {

double dot3(const std::array<float, 3>& a, const std::array<double, 3>& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

}  // namespace

float orderedToFloat(std::uint32_t u) {
    const std::uint32_t bits = (u & 0x80000000u) ? (u & 0x7FFFFFFFu) : ~u;
    float f;
    std::memcpy(&f, &bits, sizeof f);
    return f;
}

ContactCandidates findContactCandidates(std::span<const std::array<float, 6>> boxes, std::span<const std::uint8_t> closed,
                                        const std::function<bool(std::uint32_t, std::uint32_t)>& may_collide) {
    std::vector<std::uint32_t> order;
    for (std::uint32_t i = 0; i < boxes.size(); ++i)
        if (closed[i] && boxes[i][0] <= boxes[i][3] && boxes[i][1] <= boxes[i][4] && boxes[i][2] <= boxes[i][5]) order.push_back(i);
    std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return boxes[a][0] < boxes[b][0] || (boxes[a][0] == boxes[b][0] && a < b); });
    ContactCandidates out;
    for (std::size_t i = 0; i < order.size(); ++i) {
        const auto& bi = boxes[order[i]];
        for (std::size_t j = i + 1; j < order.size() && boxes[order[j]][0] <= bi[3]; ++j) {
            const auto& bj = boxes[order[j]];
            if (bj[1] > bi[4] || bi[1] > bj[4] || bj[2] > bi[5] || bi[2] > bj[5]) continue;
            const std::uint32_t a = std::min(order[i], order[j]), b = std::max(order[i], order[j]);
            if (may_collide && !may_collide(a, b)) continue;
            out.pairs.push_back({a, b});
        }
    }
    std::sort(out.pairs.begin(), out.pairs.end());
    out.region = {INFINITY, INFINITY, INFINITY, -INFINITY, -INFINITY, -INFINITY};
    for (const auto& [a, b] : out.pairs) {
        std::array<double, 3> mid{};
        for (int k = 0; k < 3; ++k) {
            const double lo = std::max(boxes[a][k], boxes[b][k]), hi = std::min(boxes[a][3 + k], boxes[b][3 + k]);
            out.region[k] = std::min(out.region[k], lo);
            out.region[3 + k] = std::max(out.region[3 + k], hi);
            mid[k] = 0.5 * (lo + hi);
        }
        out.middles.push_back(mid);
    }
    return out;
}

ContactGrid fitContactGrid(const std::array<float, 3>& direction, const std::array<double, 6>& region, std::uint32_t resolution) {
    ContactGrid g;
    g.basis = projectionBasis(direction);
    const std::array<float, 3>* axes[3] = {&g.basis.u, &g.basis.v, &g.basis.d};
    std::array<double, 3> lo{INFINITY, INFINITY, INFINITY}, hi{-INFINITY, -INFINITY, -INFINITY};
    double magnitude = 0;
    for (int c = 0; c < 8; ++c) {
        const std::array<double, 3> p{region[(c & 1) ? 3 : 0], region[(c & 2) ? 4 : 1], region[(c & 4) ? 5 : 2]};
        for (int k = 0; k < 3; ++k) {
            const double x = dot3(*axes[k], p);
            lo[k] = std::min(lo[k], x);
            hi[k] = std::max(hi[k], x);
            magnitude = std::max(magnitude, std::fabs(x));
        }
    }
    // A flat overlap (boxes touching on a face) still gets a grid a few ulps wide.
    const double floor_extent = std::max(magnitude * 1e-6, 1e-30);
    const double extent = std::max({hi[0] - lo[0], hi[1] - lo[1], floor_extent});
    g.h = extent / resolution;
    g.width = std::clamp<std::uint32_t>(static_cast<std::uint32_t>(std::ceil((hi[0] - lo[0]) / g.h)), 1u, resolution);
    g.height = std::clamp<std::uint32_t>(static_cast<std::uint32_t>(std::ceil((hi[1] - lo[1]) / g.h)), 1u, resolution);
    g.origin = {0.5 * (lo[0] + hi[0]) - 0.5 * g.width * g.h, 0.5 * (lo[1] + hi[1]) - 0.5 * g.height * g.h, 0.5 * (lo[2] + hi[2])};
    g.depth_pixels = std::max((hi[2] - lo[2]) / g.h, 1.0);
    return g;
}

void writeGridParams(const ContactGrid& g, std::uint32_t layers, gpu::ContactsParams& p) {
    const std::array<float, 3>* axes[3] = {&g.basis.u, &g.basis.v, &g.basis.d};
    for (int k = 0; k < 3; ++k)
        p.grid[k] = {static_cast<float>((*axes[k])[0] / g.h), static_cast<float>((*axes[k])[1] / g.h),
                     static_cast<float>((*axes[k])[2] / g.h), static_cast<float>(-g.origin[k] / g.h)};
    p.width = g.width;
    p.height = g.height;
    // Largest sum a pair can reach (grid units): its volume, first moments (centred) and
    // boundary sums, with a factor 4 to spare; the scale is the largest power of two that
    // keeps it below 2^62 (at most 2^24: finer than the float sums it adds).
    const double rays = double(g.width) * g.height, d = g.depth_pixels + 2;
    const double moments = rays * d * 0.5 * std::max({double(g.width), double(g.height), d});
    const double bound = 4 * std::max({rays * d, moments, rays * layers * double(gpu::kContactMaxWeight), 1.0});
    p.fixed_scale = static_cast<float>(std::exp2(std::clamp(std::floor(std::log2(std::exp2(62.0) / bound)), -40.0, 24.0)));
}

bool contactFromSums(const gpu::ContactsPair& s, const ContactGrid& g, float fixed_scale, StageContact& out) {
    const double inv = 1.0 / fixed_scale;
    const double volume = double(s.sums[gpu::kSumVolume]) * inv;
    if (!(volume > 0)) return false;
    const std::array<float, 3>* axes[3] = {&g.basis.u, &g.basis.v, &g.basis.d};
    const std::array<double, 3> centre{double(s.sums[gpu::kSumMoment]) * inv / volume + 0.5 * g.width,
                                       double(s.sums[gpu::kSumMoment + 1]) * inv / volume + 0.5 * g.height,
                                       double(s.sums[gpu::kSumMoment + 2]) * inv / volume};
    std::array<double, 3> n_grid{};
    for (int k = 0; k < 3; ++k) n_grid[k] = double(s.sums[gpu::kSumNormal + k]) * inv;
    const double area = double(s.sums[gpu::kSumArea]) * inv;
    const double len = std::sqrt(n_grid[0] * n_grid[0] + n_grid[1] * n_grid[1] + n_grid[2] * n_grid[2]);
    out.volume = volume * g.h * g.h * g.h;
    out.point = {};
    out.normal = {};
    for (int k = 0; k < 3; ++k)
        for (int c = 0; c < 3; ++c) out.point[c] += (*axes[k])[c] * (centre[k] * g.h + g.origin[k]);
    // The shaders' rule (contacts_walk.comp, pairAxis): a boundary whose normals cancel
    // (one object inside the other) has no normal.
    out.depth = 0;
    if (len > 1e-3 * area && len > 0) {
        for (int k = 0; k < 3; ++k)
            for (int c = 0; c < 3; ++c) out.normal[c] += (*axes[k])[c] * n_grid[k] / len;
        const float lo = orderedToFloat(s.extent_min), hi = orderedToFloat(s.extent_max);
        if (lo <= hi) out.depth = (double(hi) - double(lo)) * g.h;
    }
    return true;
}

}  // namespace vkcollide::passes
