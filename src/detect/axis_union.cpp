#include "detect/axis_union.hpp"

#include <algorithm>
#include <cmath>

#include "broad/projection.hpp"

namespace vkcollide::passes {

std::array<double, 6> keptWorldBox(const CandidateTriangle& c, const gpu::Projection& projection) {
    const std::array<double, 6> kept = samplingBoxToWorld(projection, {c.box[0], c.box[1], c.zmin}, {c.box[2], c.box[3], c.zmax});
    const double pad = gpu::kKeptBoxPad * imageWidth(projection);
    std::array<double, 6> out;
    for (int w = 0; w < 3; ++w) {
        double t_lo = INFINITY, t_hi = -INFINITY;
        for (const Float3& v : c.v) {
            const double x = w == 0 ? v.x : (w == 1 ? v.y : v.z);
            t_lo = std::min(t_lo, x), t_hi = std::max(t_hi, x);
        }
        out[w] = std::max(kept[w] - pad, t_lo);
        out[w + 3] = std::min(kept[w + 3] + pad, t_hi);
        if (!(out[w] <= out[w + 3])) out[w] = t_lo, out[w + 3] = t_hi;  // rounding only: keep the triangle's box
    }
    return out;
}

std::vector<CandidateTriangle> uniteAxes(std::span<const BroadPhaseResult> runs) {
    struct Entry {
        const CandidateTriangle* record;
        std::array<double, 6> box;
    };
    std::vector<Entry> all;
    for (const auto& run : runs)
        for (const CandidateTriangle& c : run.records) all.push_back({&c, keptWorldBox(c, run.projection)});
    std::sort(all.begin(), all.end(), [](const Entry& a, const Entry& b) {
        return a.record->object != b.record->object ? a.record->object < b.record->object : a.record->triangle < b.record->triangle;
    });
    // Outward to float: boxes that touch in double still touch.
    auto down = [](double x) { const float f = static_cast<float>(x); return double(f) > x ? std::nextafter(f, -INFINITY) : f; };
    auto up = [](double x) { const float f = static_cast<float>(x); return double(f) < x ? std::nextafter(f, INFINITY) : f; };
    std::vector<CandidateTriangle> out;
    for (std::size_t i = 0; i < all.size();) {
        std::array<double, 6> box = all[i].box;
        std::size_t j = i + 1;
        for (; j < all.size() && all[j].record->object == all[i].record->object && all[j].record->triangle == all[i].record->triangle; ++j)
            for (int w = 0; w < 3; ++w) box[w] = std::min(box[w], all[j].box[w]), box[w + 3] = std::max(box[w + 3], all[j].box[w + 3]);
        CandidateTriangle c = *all[i].record;
        c.box[0] = down(box[0]), c.box[1] = down(box[1]), c.box[2] = up(box[3]), c.box[3] = up(box[4]);
        c.zmin = down(box[2]), c.zmax = up(box[5]);
        out.push_back(c);
        i = j;
    }
    return out;
}

}  // namespace vkcollide::passes
