#include "api/mesh_checks.hpp"

#include <algorithm>
#include <vector>

namespace vkcollide::mesh_checks {

std::uint64_t boundaryEdges(std::span<const std::uint32_t> indices) {
    std::vector<std::uint64_t> edges;
    edges.reserve(indices.size());
    for (std::size_t t = 0; t + 2 < indices.size(); t += 3)
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t a = indices[t + k], b = indices[t + (k + 1) % 3];
            if (a != b) edges.push_back(std::uint64_t{std::min(a, b)} << 32 | std::max(a, b));
        }
    std::sort(edges.begin(), edges.end());
    std::uint64_t once = 0;
    for (std::size_t i = 0; i < edges.size();) {
        std::size_t j = i + 1;
        while (j < edges.size() && edges[j] == edges[i]) ++j;
        once += j - i == 1 ? 1 : 0;
        i = j;
    }
    return once;
}

double signedVolume6(Executor& executor, std::span<const Float3> positions, std::span<const std::uint32_t> indices) {
    const std::size_t triangles = indices.size() / 3;
    if (triangles == 0) return 0;
    const std::size_t runs = (triangles + kVolumeChunk - 1) / kVolumeChunk;
    std::vector<double> sums(runs, 0.0);
    // About the first vertex: coordinates far from the origin would cancel in the sum.
    const Float3 o = positions[indices[0]];
    auto body = [&](std::size_t begin, std::size_t end) {
        for (std::size_t r = begin; r < end; ++r) {
            double sum = 0;
            for (std::size_t t = r * kVolumeChunk, last = std::min(triangles, (r + 1) * kVolumeChunk); t < last; ++t) {
                const Float3 &a = positions[indices[3 * t]], &b = positions[indices[3 * t + 1]], &c = positions[indices[3 * t + 2]];
                const double ax = double(a.x) - o.x, ay = double(a.y) - o.y, az = double(a.z) - o.z;
                const double bx = double(b.x) - o.x, by = double(b.y) - o.y, bz = double(b.z) - o.z;
                const double cx = double(c.x) - o.x, cy = double(c.y) - o.y, cz = double(c.z) - o.z;
                sum += ax * (by * cz - bz * cy) + ay * (bz * cx - bx * cz) + az * (bx * cy - by * cx);
            }
            sums[r] = sum;
        }
    };
    executor.parallelFor(runs, 1, body);
    double total = 0;
    for (double s : sums) total += s;
    return total;
}

double determinant(const Transform3x4& t) {
    const double a = t[0], b = t[1], c = t[2], d = t[4], e = t[5], f = t[6], g = t[8], h = t[9], i = t[10];
    return a * (e * i - f * h) - b * (d * i - f * g) + c * (d * h - e * g);
}

std::string describe(bool inside_out, std::uint64_t boundary_edges) {
    if (boundary_edges > 0)
        return "declared closed but has " + std::to_string(boundary_edges) + (boundary_edges == 1 ? " boundary edge" : " boundary edges") +
               " (edges of one triangle only: holes), so inside and outside are not defined; declare it open "
               "(ObjectOptions::open) or close it";
    if (inside_out)
        return "declared closed but inside out (its enclosed volume is negative: the triangles' counter-clockwise sides face "
               "inwards), so contact volumes are 0 and peeling finds collision rays where it is not touched; reverse its "
               "triangles' winding";
    return "";
}

}  // namespace vkcollide::mesh_checks
