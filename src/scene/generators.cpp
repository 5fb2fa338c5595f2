// Procedural closed meshes and the cloth grid. Each generator states in a comment why
// its triangle order faces outward; tests/scene checks it by signed volume and edges.
#include <cmath>
#include <numbers>
#include <string>
#include <unordered_map>

#include "scene/mesh_building.hpp"
#include "vkcollide/scene.hpp"

namespace vkcollide {
namespace {

using mesh_building::invalid;
using mesh_building::kPi;
using mesh_building::pushTriangle;

bool isPositiveFinite(float value) { return std::isfinite(value) && value > 0.0f; }

Result<void> checkTriangleBudget(const char* generator, std::uint64_t triangles) {
    if (triangles > kMaxGeneratedTriangles)
        return invalid(std::string(generator) + ": " + std::to_string(triangles) + " triangles exceed the limit of " +
                       std::to_string(kMaxGeneratedTriangles));
    return {};
}

Float3 toFloat3(double x, double y, double z) {
    return Float3{static_cast<float>(x), static_cast<float>(y), static_cast<float>(z)};
}

// Quad a, b, c, d (in winding order) as triangles (a, b, c) and (a, c, d).
void pushQuad(HostMesh& io_mesh, std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d) {
    pushTriangle(io_mesh, a, b, c);
    pushTriangle(io_mesh, a, c, d);
}

}  // namespace

Result<HostMesh> uvSphere(float radius, std::uint32_t segments, std::uint32_t rings) {
    if (!isPositiveFinite(radius)) return invalid("uvSphere: radius must be positive and finite");
    if (segments < 3 || rings < 2) return invalid("uvSphere: needs segments >= 3 and rings >= 2");
    if (Result<void> r = checkTriangleBudget("uvSphere", 2ull * segments * (rings - 1ull)); !r) return r.error();

    HostMesh mesh;
    mesh.name = "uv_sphere";
    const std::uint32_t north = 0;
    const std::uint32_t south = 1 + segments * (rings - 1);
    // Ring k (1..rings-1), segment j: polar angle pi*k/rings from +Z, azimuth 2*pi*j/segments.
    const auto ring_vertex = [segments](std::uint32_t k, std::uint32_t j) { return 1 + (k - 1) * segments + j % segments; };
    mesh.positions.reserve(south + 1);
    mesh.positions.push_back(toFloat3(0, 0, radius));
    for (std::uint32_t k = 1; k < rings; ++k) {
        const double theta = kPi * k / rings;
        for (std::uint32_t j = 0; j < segments; ++j) {
            const double phi = 2.0 * kPi * j / segments;
            mesh.positions.push_back(toFloat3(radius * std::sin(theta) * std::cos(phi),
                                              radius * std::sin(theta) * std::sin(phi), radius * std::cos(theta)));
        }
    }
    mesh.positions.push_back(toFloat3(0, 0, -radius));

    // Seen from outside, azimuth grows to the right and k grows downwards, so
    // upper-left, lower-left, lower-right (a_j, b_j, b_j+1) is counter-clockwise.
    mesh.indices.reserve(6ull * segments * (rings - 1));
    for (std::uint32_t j = 0; j < segments; ++j) pushTriangle(mesh, north, ring_vertex(1, j), ring_vertex(1, j + 1));
    for (std::uint32_t k = 1; k + 1 < rings; ++k) {
        for (std::uint32_t j = 0; j < segments; ++j) {
            const std::uint32_t a0 = ring_vertex(k, j), a1 = ring_vertex(k, j + 1);
            const std::uint32_t b0 = ring_vertex(k + 1, j), b1 = ring_vertex(k + 1, j + 1);
            pushQuad(mesh, a0, b0, b1, a1);
        }
    }
    for (std::uint32_t j = 0; j < segments; ++j)
        pushTriangle(mesh, ring_vertex(rings - 1, j), south, ring_vertex(rings - 1, j + 1));
    return mesh;
}

Result<HostMesh> torus(float major_radius, float minor_radius, std::uint32_t segments, std::uint32_t sides) {
    if (!isPositiveFinite(major_radius) || !isPositiveFinite(minor_radius) || !(minor_radius < major_radius))
        return invalid("torus: needs finite 0 < minor_radius < major_radius");
    if (segments < 3 || sides < 3) return invalid("torus: needs segments >= 3 and sides >= 3");
    if (Result<void> r = checkTriangleBudget("torus", 2ull * segments * sides); !r) return r.error();

    HostMesh mesh;
    mesh.name = "torus";
    mesh.positions.reserve(std::size_t{segments} * sides);
    for (std::uint32_t i = 0; i < segments; ++i) {
        const double phi = 2.0 * kPi * i / segments;
        for (std::uint32_t j = 0; j < sides; ++j) {
            const double theta = 2.0 * kPi * j / sides;
            const double ring = major_radius + minor_radius * std::cos(theta);
            mesh.positions.push_back(toFloat3(ring * std::cos(phi), ring * std::sin(phi), minor_radius * std::sin(theta)));
        }
    }
    // d/dphi x d/dtheta points away from the tube's centre circle, so (i, j) ->
    // (i+1, j) -> (i+1, j+1) is counter-clockwise from outside.
    const auto at = [segments, sides](std::uint32_t i, std::uint32_t j) { return (i % segments) * sides + j % sides; };
    mesh.indices.reserve(6ull * segments * sides);
    for (std::uint32_t i = 0; i < segments; ++i) {
        for (std::uint32_t j = 0; j < sides; ++j) {
            pushQuad(mesh, at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
        }
    }
    return mesh;
}

Result<HostMesh> box(Float3 half_extents, std::uint32_t subdivisions) {
    if (!isPositiveFinite(half_extents.x) || !isPositiveFinite(half_extents.y) || !isPositiveFinite(half_extents.z))
        return invalid("box: half extents must be positive and finite");
    if (subdivisions < 1) return invalid("box: needs subdivisions >= 1");
    const std::uint64_t n = subdivisions;
    if (Result<void> r = checkTriangleBudget("box", 12 * n * n); !r) return r.error();

    HostMesh mesh;
    mesh.name = "box";
    const double half[3] = {half_extents.x, half_extents.y, half_extents.z};
    // Vertices live on the lattice {0..n}^3; faces meet on its edges, so a vertex is
    // keyed by its lattice point and created once: seams are shared, not duplicated.
    std::unordered_map<std::uint64_t, std::uint32_t> index_of;
    index_of.reserve(6 * n * n + 2);
    mesh.positions.reserve(6 * n * n + 2);
    const auto vertex = [&](const std::uint64_t (&lattice)[3]) {
        const std::uint64_t key = (lattice[0] * (n + 1) + lattice[1]) * (n + 1) + lattice[2];
        const auto [it, inserted] = index_of.try_emplace(key, static_cast<std::uint32_t>(mesh.positions.size()));
        if (inserted) {
            double p[3];
            // h * (2i - n) / n is exact at i = 0, n/2 and n, so opposite faces mirror.
            for (int axis = 0; axis < 3; ++axis)
                p[axis] = half[axis] * (2.0 * static_cast<double>(lattice[axis]) - static_cast<double>(n)) /
                          static_cast<double>(n);
            mesh.positions.push_back(toFloat3(p[0], p[1], p[2]));
        }
        return it->second;
    };

    mesh.indices.reserve(36 * n * n);
    for (int axis = 0; axis < 3; ++axis) {
        // (u, v) = the next two axes cyclically, so e_u x e_v = +e_axis: counter-clockwise
        // in (u, v) faces +axis; the face at -h winds the other way.
        const int u_axis = (axis + 1) % 3;
        const int v_axis = (axis + 2) % 3;
        for (const bool positive : {false, true}) {
            for (std::uint64_t a = 0; a < n; ++a) {
                for (std::uint64_t b = 0; b < n; ++b) {
                    std::uint32_t corner[2][2];
                    for (std::uint64_t du = 0; du < 2; ++du) {
                        for (std::uint64_t dv = 0; dv < 2; ++dv) {
                            std::uint64_t lattice[3];
                            lattice[axis] = positive ? n : 0;
                            lattice[u_axis] = a + du;
                            lattice[v_axis] = b + dv;
                            corner[du][dv] = vertex(lattice);
                        }
                    }
                    if (positive) {
                        pushQuad(mesh, corner[0][0], corner[1][0], corner[1][1], corner[0][1]);
                    } else {
                        pushTriangle(mesh, corner[0][0], corner[1][1], corner[1][0]);
                        pushTriangle(mesh, corner[0][0], corner[0][1], corner[1][1]);
                    }
                }
            }
        }
    }
    return mesh;
}

Result<HostMesh> twistedTube(float path_scale, float tube_radius, std::uint32_t segments, std::uint32_t sides,
                             float twist_turns) {
    if (!isPositiveFinite(path_scale) || !isPositiveFinite(tube_radius) || !(tube_radius <= 0.25f * path_scale))
        return invalid("twistedTube: needs finite 0 < tube_radius <= 0.25 * path_scale");
    if (!std::isfinite(twist_turns)) return invalid("twistedTube: twist_turns must be finite");
    if (segments < 8 || sides < 3) return invalid("twistedTube: needs segments >= 8 and sides >= 3");
    if (Result<void> r = checkTriangleBudget("twistedTube", 2ull * segments * sides + 2ull * sides); !r)
        return r.error();

    constexpr double kT0 = -1.5;
    constexpr double kT1 = 1.5;
    const double s = path_scale;
    const double semi_in_plane = tube_radius;
    const double semi_z = 0.6 * tube_radius;

    HostMesh mesh;
    mesh.name = "twisted_tube";
    mesh.positions.reserve((segments + 1ull) * sides + 2);
    for (std::uint32_t i = 0; i <= segments; ++i) {
        const double t = kT0 + (kT1 - kT0) * i / segments;
        const double cx = s * (t * t - 1.0), cy = s * (t * t * t - t);
        // Tangent of the nodal cubic; 2t and 3t^2 - 1 never vanish together.
        double tx = 2.0 * t, ty = 3.0 * t * t - 1.0;
        const double len = std::hypot(tx, ty);
        tx /= len;
        ty /= len;
        // Frame (T, N, Z) with N = T turned +90 degrees in the plane: right-handed, and
        // the path is planar, so it never flips.
        const double nx = -ty, ny = tx;
        const double twist = 2.0 * kPi * twist_turns * (t - kT0) / (kT1 - kT0);
        for (std::uint32_t j = 0; j < sides; ++j) {
            const double psi = 2.0 * kPi * j / sides + twist;
            const double along_n = semi_in_plane * std::cos(psi), along_z = semi_z * std::sin(psi);
            mesh.positions.push_back(toFloat3(cx + along_n * nx, cy + along_n * ny, along_z));
        }
    }
    const auto ring = [sides](std::uint32_t i, std::uint32_t j) { return i * sides + j % sides; };
    const auto start_centre = static_cast<std::uint32_t>(mesh.positions.size());
    mesh.positions.push_back(toFloat3(s * (kT0 * kT0 - 1.0), s * (kT0 * kT0 * kT0 - kT0), 0));
    const std::uint32_t end_centre = start_centre + 1;
    mesh.positions.push_back(toFloat3(s * (kT1 * kT1 - 1.0), s * (kT1 * kT1 * kT1 - kT1), 0));

    // d/dt x d/dpsi = T x (section tangent) points inwards (T x Z = -N), so the
    // outward order is (i, j) -> (i, j+1) -> (i+1, j+1).
    mesh.indices.reserve(6ull * segments * sides + 6ull * sides);
    for (std::uint32_t i = 0; i < segments; ++i) {
        for (std::uint32_t j = 0; j < sides; ++j) {
            pushQuad(mesh, ring(i, j), ring(i, j + 1), ring(i + 1, j + 1), ring(i + 1, j));
        }
    }
    // psi turns from N towards Z, counter-clockwise seen from +T: the end cap (facing
    // +T) follows it, the start cap (facing -T) runs against it.
    for (std::uint32_t j = 0; j < sides; ++j) {
        pushTriangle(mesh, start_centre, ring(0, j + 1), ring(0, j));
        pushTriangle(mesh, end_centre, ring(segments, j), ring(segments, j + 1));
    }
    return mesh;
}

Result<HostMesh> clothGrid(float width, float depth, std::uint32_t nx, std::uint32_t ny, const ClothOptions& options) {
    if (!isPositiveFinite(width) || !isPositiveFinite(depth)) return invalid("clothGrid: width and depth must be positive and finite");
    if (nx < 1 || ny < 1) return invalid("clothGrid: needs nx >= 1 and ny >= 1");
    if (!std::isfinite(options.sag) || !std::isfinite(options.fold_angle))
        return invalid("clothGrid: sag and fold_angle must be finite");
    if (Result<void> r = checkTriangleBudget("clothGrid", 2ull * nx * ny); !r) return r.error();

    HostMesh mesh;
    mesh.name = "cloth";
    const double cos_fold = std::cos(static_cast<double>(options.fold_angle));
    const double sin_fold = std::sin(static_cast<double>(options.fold_angle));
    mesh.positions.reserve((nx + 1ull) * (ny + 1ull));
    for (std::uint32_t j = 0; j <= ny; ++j) {
        const double v = static_cast<double>(j) / ny;
        for (std::uint32_t i = 0; i <= nx; ++i) {
            const double u = static_cast<double>(i) / nx;
            double x = width * (u - 0.5);
            const double y = depth * (v - 0.5);
            double z = -static_cast<double>(options.sag) * std::sin(kPi * u) * std::sin(kPi * v);
            if (x > 0.0) {
                const double folded_x = x * cos_fold - z * sin_fold;
                z = x * sin_fold + z * cos_fold;
                x = folded_x;
            }
            mesh.positions.push_back(toFloat3(x, y, z));
        }
    }
    // Counter-clockwise seen from +Z (the front).
    const auto at = [nx](std::uint32_t i, std::uint32_t j) { return j * (nx + 1) + i; };
    mesh.indices.reserve(6ull * nx * ny);
    for (std::uint32_t j = 0; j < ny; ++j) {
        for (std::uint32_t i = 0; i < nx; ++i) {
            pushQuad(mesh, at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
        }
    }
    return mesh;
}

}  // namespace vkcollide
