// Midpoint subdivision. Edges are numbered by sorting their (min, max) vertex keys rather
// than hashing them: on a million-triangle mesh the sort is several times faster than an
// unordered_map and needs no rehashing.
#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include "vkcollide/scene.hpp"

namespace vkcollide {
namespace {

// One round: every triangle (a, b, c) becomes (a, ab, ca), (ab, b, bc), (ca, bc, c),
// (ab, bc, ca), all wound like the original.
HostMesh subdivideOnce(const HostMesh& in) {
    const std::size_t triangles = in.triangleCount();
    // Directed edge k of triangle t (from corner k to corner k + 1), keyed undirected.
    std::vector<std::pair<std::uint64_t, std::uint32_t>> edges(3 * triangles);
    for (std::size_t t = 0; t < triangles; ++t)
        for (std::size_t k = 0; k < 3; ++k) {
            const std::uint64_t a = in.indices[3 * t + k], b = in.indices[3 * t + (k + 1) % 3];
            edges[3 * t + k] = {(std::min(a, b) << 32) | std::max(a, b), static_cast<std::uint32_t>(3 * t + k)};
        }
    std::sort(edges.begin(), edges.end());
    HostMesh out;
    out.name = in.name;
    out.positions = in.positions;
    std::vector<std::uint32_t> midpoint(3 * triangles);
    for (std::size_t i = 0; i < edges.size();) {
        const std::uint64_t key = edges[i].first;
        const auto a = static_cast<std::uint32_t>(key >> 32), b = static_cast<std::uint32_t>(key & 0xffffffffu);
        const Float3 &pa = in.positions[a], &pb = in.positions[b];
        const auto vertex = static_cast<std::uint32_t>(out.positions.size());
        // In double, from the unordered pair: both triangles of the edge get the same point.
        out.positions.push_back({static_cast<float>(0.5 * (double{pa.x} + pb.x)), static_cast<float>(0.5 * (double{pa.y} + pb.y)),
                                 static_cast<float>(0.5 * (double{pa.z} + pb.z))});
        for (; i < edges.size() && edges[i].first == key; ++i) midpoint[edges[i].second] = vertex;
    }
    out.indices.resize(12 * triangles);
    for (std::size_t t = 0; t < triangles; ++t) {
        const std::uint32_t a = in.indices[3 * t], b = in.indices[3 * t + 1], c = in.indices[3 * t + 2];
        const std::uint32_t ab = midpoint[3 * t], bc = midpoint[3 * t + 1], ca = midpoint[3 * t + 2];
        const std::uint32_t tri[12] = {a, ab, ca, ab, b, bc, ca, bc, c, ab, bc, ca};
        std::copy(std::begin(tri), std::end(tri), out.indices.begin() + static_cast<std::ptrdiff_t>(12 * t));
    }
    return out;
}

}  // namespace

Result<HostMesh> subdivide(const HostMesh& mesh, std::uint32_t levels) {
    if (Result<void> ok = validateMesh(mesh); !ok) return ok.error();
    std::uint64_t triangles = mesh.triangleCount();
    for (std::uint32_t l = 0; l < levels; ++l) {
        triangles *= 4;
        if (triangles > kMaxGeneratedTriangles)
            return Error(ErrorCode::InvalidArgument, "subdivide: '" + mesh.name + "' at " + std::to_string(levels) +
                                                         " levels exceeds the limit of " +
                                                         std::to_string(kMaxGeneratedTriangles) + " triangles");
    }
    HostMesh out = mesh;
    for (std::uint32_t l = 0; l < levels; ++l) out = subdivideOnce(out);
    return out;
}

}  // namespace vkcollide
