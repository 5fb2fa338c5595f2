// More closed shapes for the benchmark scenes: icosphere and frustum (cylinder, cone).
#include <cmath>
#include <numbers>
#include <string>

#include "scene/mesh_building.hpp"
#include "vkcollide/scene.hpp"

namespace vkcollide {
namespace {

using mesh_building::invalid;
using mesh_building::kPi;
using mesh_building::pushTriangle;

bool isFinite(float value) { return std::isfinite(value); }

Float3 scaledTo(const Float3& p, double radius) {
    const double n = std::sqrt(double{p.x} * p.x + double{p.y} * p.y + double{p.z} * p.z);
    return {static_cast<float>(radius * p.x / n), static_cast<float>(radius * p.y / n), static_cast<float>(radius * p.z / n)};
}

}  // namespace

Result<HostMesh> icosphere(float radius, std::uint32_t levels) {
    if (!isFinite(radius) || !(radius > 0.0f)) return invalid("icosphere: radius must be positive and finite");
    if (levels > 12) return invalid("icosphere: needs levels <= 12");
    HostMesh mesh;
    mesh.name = "icosphere";
    const double g = (1.0 + std::sqrt(5.0)) / 2.0;
    const double corners[12][3] = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0}, {0, -1, g}, {0, 1, g},
                                   {0, -1, -g}, {0, 1, -g}, {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
    for (const auto& c : corners)
        mesh.positions.push_back(scaledTo({static_cast<float>(c[0]), static_cast<float>(c[1]), static_cast<float>(c[2])}, radius));
    // The classic face list; each face is counter-clockwise seen from outside (its normal
    // points along its centroid, which tests/scene checks through the signed volume).
    const std::uint32_t faces[20][3] = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                                        {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                                        {3, 8, 9},  {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
    for (const auto& f : faces) pushTriangle(mesh, f[0], f[1], f[2]);
    // One level at a time, pushing the new midpoints out: the triangles stay nearly equal.
    for (std::uint32_t l = 0; l < levels; ++l) {
        Result<HostMesh> finer = subdivide(mesh, 1);
        if (!finer) return finer.error();
        mesh = std::move(*finer);
        for (Float3& p : mesh.positions) p = scaledTo(p, radius);
    }
    mesh.name = "icosphere";
    return mesh;
}

Result<HostMesh> frustum(float radius_bottom, float radius_top, float height, std::uint32_t segments, std::uint32_t stacks) {
    if (!isFinite(radius_bottom) || !isFinite(radius_top) || !isFinite(height) || !(radius_bottom > 0.0f) ||
        !(radius_top >= 0.0f) || !(height > 0.0f))
        return invalid("frustum: needs finite radius_bottom > 0, radius_top >= 0 and height > 0");
    if (segments < 3 || stacks < 1) return invalid("frustum: needs segments >= 3 and stacks >= 1");
    const bool cone = radius_top == 0.0f;
    const std::uint64_t triangles = 2ull * segments * stacks + (cone ? 0ull : 2ull * segments);
    if (triangles > kMaxGeneratedTriangles) return invalid("frustum: " + std::to_string(triangles) + " triangles exceed the limit");

    HostMesh mesh;
    mesh.name = cone ? "cone" : "frustum";
    // Rings 0..stacks (the last one is the apex of a cone, not a ring).
    const std::uint32_t rings = cone ? stacks : stacks + 1;
    for (std::uint32_t k = 0; k < rings; ++k) {
        const double f = static_cast<double>(k) / stacks;
        const double r = radius_bottom + (radius_top - radius_bottom) * f;
        const double z = height * (f - 0.5);
        for (std::uint32_t j = 0; j < segments; ++j) {
            const double phi = 2.0 * kPi * j / segments;
            mesh.positions.push_back({static_cast<float>(r * std::cos(phi)), static_cast<float>(r * std::sin(phi)), static_cast<float>(z)});
        }
    }
    const auto at = [segments](std::uint32_t k, std::uint32_t j) { return k * segments + j % segments; };
    const auto bottom = static_cast<std::uint32_t>(mesh.positions.size());
    mesh.positions.push_back({0.0f, 0.0f, -0.5f * height});
    const auto top = static_cast<std::uint32_t>(mesh.positions.size());
    mesh.positions.push_back({0.0f, 0.0f, 0.5f * height});
    // Seen from outside the azimuth grows to the right and k upwards, so (k, j), (k, j+1),
    // (k+1, j+1), (k+1, j) is counter-clockwise.
    for (std::uint32_t k = 0; k + 1 < rings; ++k)
        for (std::uint32_t j = 0; j < segments; ++j) {
            pushTriangle(mesh, at(k, j), at(k, j + 1), at(k + 1, j + 1));
            pushTriangle(mesh, at(k, j), at(k + 1, j + 1), at(k + 1, j));
        }
    for (std::uint32_t j = 0; j < segments; ++j) {
        pushTriangle(mesh, bottom, at(0, j + 1), at(0, j));  // faces -Z
        if (cone) pushTriangle(mesh, at(rings - 1, j), at(rings - 1, j + 1), top);
        else pushTriangle(mesh, top, at(rings - 1, j), at(rings - 1, j + 1));  // faces +Z
    }
    return mesh;
}

}  // namespace vkcollide
