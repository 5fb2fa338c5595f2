// Mesh transforms and statistics.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include "vkcollide/scene.hpp"

namespace vkcollide {
namespace {

Result<void> applyAffine(HostMesh& io_mesh, const float (&m)[12]) {
    for (const float value : m)
        if (!std::isfinite(value)) return Error(ErrorCode::InvalidArgument, "transformMesh: non-finite matrix entry");
    // Into a copy first, so a failure leaves the mesh as it was.
    std::vector<Float3> moved(io_mesh.positions.size());
    constexpr double kFloatMax = std::numeric_limits<float>::max();
    for (std::size_t i = 0; i < moved.size(); ++i) {
        const Float3& p = io_mesh.positions[i];
        double out[3];
        for (int row = 0; row < 3; ++row) {
            out[row] = double{m[4 * row]} * p.x + double{m[4 * row + 1]} * p.y + double{m[4 * row + 2]} * p.z +
                       double{m[4 * row + 3]};
            if (!(std::fabs(out[row]) <= kFloatMax))
                return Error(ErrorCode::InvalidArgument, "transformMesh: '" + io_mesh.name + "' vertex " +
                                                             std::to_string(i) + " leaves the float range");
        }
        moved[i] = Float3{static_cast<float>(out[0]), static_cast<float>(out[1]), static_cast<float>(out[2])};
    }
    io_mesh.positions = std::move(moved);

    const double det = double{m[0]} * (double{m[5]} * m[10] - double{m[6]} * m[9]) -
                       double{m[1]} * (double{m[4]} * m[10] - double{m[6]} * m[8]) +
                       double{m[2]} * (double{m[4]} * m[9] - double{m[5]} * m[8]);
    // A mirror turns counter-clockwise into clockwise; swapping two corners restores
    // outward winding.
    if (det < 0.0)
        for (std::size_t t = 0; t + 2 < io_mesh.indices.size(); t += 3) std::swap(io_mesh.indices[t + 1], io_mesh.indices[t + 2]);
    return {};
}

}  // namespace

Result<void> transformMesh(HostMesh& io_mesh, const Transform3x4& transform) {
    float m[12];
    std::copy(transform.begin(), transform.end(), m);
    return applyAffine(io_mesh, m);
}

Result<void> transformMesh(HostMesh& io_mesh, const Transform4x4& transform) {
    if (transform[12] != 0.0f || transform[13] != 0.0f || transform[14] != 0.0f || transform[15] != 1.0f)
        return Error(ErrorCode::InvalidArgument, "transformMesh: the last row of a 4x4 transform must be (0, 0, 0, 1)");
    float m[12];
    std::copy(transform.begin(), transform.begin() + 12, m);
    return applyAffine(io_mesh, m);
}

Result<MeshStats> computeMeshStats(const HostMesh& mesh) {
    const std::size_t vertex_total = mesh.positions.size();
    if (mesh.indices.empty() || mesh.indices.size() % 3 != 0)
        return Error(ErrorCode::InvalidMesh, "mesh '" + mesh.name + "': index count " +
                                                 std::to_string(mesh.indices.size()) +
                                                 " is not a positive multiple of three");
    for (std::size_t i = 0; i < mesh.indices.size(); ++i)
        if (mesh.indices[i] >= vertex_total)
            return Error(ErrorCode::InvalidMesh, "mesh '" + mesh.name + "': index " + std::to_string(i) + " = " +
                                                     std::to_string(mesh.indices[i]) + " is out of range (" +
                                                     std::to_string(vertex_total) + " vertices)");

    MeshStats stats;
    stats.triangle_count = mesh.triangleCount();
    std::vector<bool> used(vertex_total, false);
    constexpr float kInf = std::numeric_limits<float>::infinity();
    stats.bounds_min = Float3{kInf, kInf, kInf};
    stats.bounds_max = Float3{-kInf, -kInf, -kInf};

    // Directed edges as ((min << 32) | max, from < to); sorting brings all uses of an
    // undirected edge together so they can be counted and their directions compared.
    std::vector<std::pair<std::uint64_t, bool>> edges;
    edges.reserve(mesh.indices.size());
    for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
        const std::uint32_t tri[3] = {mesh.indices[t], mesh.indices[t + 1], mesh.indices[t + 2]};
        const Float3& a = mesh.positions[tri[0]];
        const Float3& b = mesh.positions[tri[1]];
        const Float3& c = mesh.positions[tri[2]];
        const double ab[3] = {double{b.x} - a.x, double{b.y} - a.y, double{b.z} - a.z};
        const double ac[3] = {double{c.x} - a.x, double{c.y} - a.y, double{c.z} - a.z};
        const double n[3] = {ab[1] * ac[2] - ab[2] * ac[1], ab[2] * ac[0] - ab[0] * ac[2], ab[0] * ac[1] - ab[1] * ac[0]};
        stats.surface_area += 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        // det(a, b, c) / 6 = a . (b x c) / 6: the tetrahedron with the origin.
        stats.signed_volume += (double{a.x} * (double{b.y} * c.z - double{b.z} * c.y) -
                                double{a.y} * (double{b.x} * c.z - double{b.z} * c.x) +
                                double{a.z} * (double{b.x} * c.y - double{b.y} * c.x)) /
                               6.0;
        if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2]) ++stats.degenerate_triangles;
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t from = tri[k];
            const std::uint32_t to = tri[(k + 1) % 3];
            used[from] = true;
            if (from == to) continue;
            const std::uint64_t lo = std::min(from, to), hi = std::max(from, to);
            edges.emplace_back((lo << 32) | hi, from < to);
        }
    }
    for (std::size_t v = 0; v < vertex_total; ++v) {
        if (!used[v]) continue;
        ++stats.vertex_count;
        const Float3& p = mesh.positions[v];
        stats.bounds_min = Float3{std::min(stats.bounds_min.x, p.x), std::min(stats.bounds_min.y, p.y),
                                  std::min(stats.bounds_min.z, p.z)};
        stats.bounds_max = Float3{std::max(stats.bounds_max.x, p.x), std::max(stats.bounds_max.y, p.y),
                                  std::max(stats.bounds_max.z, p.z)};
    }

    std::sort(edges.begin(), edges.end());
    for (std::size_t i = 0; i < edges.size();) {
        std::size_t j = i;
        std::size_t forward = 0;
        while (j < edges.size() && edges[j].first == edges[i].first) forward += edges[j++].second ? 1u : 0u;
        const std::size_t uses = j - i;
        ++stats.edge_count;
        if (uses == 1) ++stats.boundary_edges;
        if (uses >= 3) ++stats.non_manifold_edges;
        if (uses == 2 && forward != 1) ++stats.misoriented_edges;
        i = j;
    }
    stats.euler_characteristic = static_cast<std::int64_t>(stats.vertex_count) -
                                 static_cast<std::int64_t>(stats.edge_count) +
                                 static_cast<std::int64_t>(stats.triangle_count);
    stats.closed = stats.boundary_edges == 0 && stats.non_manifold_edges == 0 && stats.misoriented_edges == 0 &&
                   stats.degenerate_triangles == 0;
    return stats;
}

}  // namespace vkcollide
