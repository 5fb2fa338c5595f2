// vkcollide: procedural test meshes, mesh transforms and mesh statistics.
//
// Every closed generator returns a watertight indexed mesh: vertices on seams and poles
// are shared, every edge is used by exactly two triangles in opposite directions, and
// triangles wind counter-clockwise seen from outside (outward normals, positive signed
// volume). All meshes are centred on the origin unless stated. Units are whatever the
// caller's are.
//
// Errors: InvalidArgument names the broken rule (non-positive size, too few segments,
// a count whose mesh would not fit 32-bit indices, non-finite input).
// Thread safety: all functions are reentrant; they share no state.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "vkcollide/export.hpp"
#include "vkcollide/mesh.hpp"
#include "vkcollide/result.hpp"

namespace vkcollide {

// Above this many triangles a generator refuses (InvalidArgument): the counts are
// meant for tests and benchmarks, and this keeps every index well inside 32 bits.
inline constexpr std::uint64_t kMaxGeneratedTriangles = std::uint64_t{1} << 28;

// Sphere around the origin, poles on ±Z. `segments` >= 3 around the Z axis,
// `rings` >= 2 from pole to pole. One vertex per pole.
// Triangles: 2 * segments * (rings - 1). Vertices: segments * (rings - 1) + 2.
VKCOLLIDE_API Result<HostMesh> uvSphere(float radius, std::uint32_t segments, std::uint32_t rings);

// Torus around the Z axis: tube centre circle of radius `major_radius` in the XY plane,
// tube radius `minor_radius` < major_radius. `segments` >= 3 around Z, `sides` >= 3
// around the tube. Triangles: 2 * segments * sides. Vertices: segments * sides.
VKCOLLIDE_API Result<HostMesh> torus(float major_radius, float minor_radius, std::uint32_t segments, std::uint32_t sides);

// Axis-aligned box [-h, h] per axis; each face is a `subdivisions` x `subdivisions` grid
// of quads (>= 1) sharing the vertices on the box edges.
// Triangles: 12 * n^2. Vertices: 6 * n^2 + 2.
VKCOLLIDE_API Result<HostMesh> box(Float3 half_extents, std::uint32_t subdivisions);

// A closed tube that passes through itself (for self-intersection tests).
//
// The centre line is the nodal cubic c(t) = s * (t^2 - 1, t^3 - t, 0), t in [-1.5, 1.5],
// with s = `path_scale`. It crosses itself at the origin (t = -1 and t = +1, at right
// angles), so the tube intersects itself there: around the origin, within about
// `tube_radius` of it. Nowhere else do parts of the tube meet.
// The cross-section is an ellipse with semi-axes `tube_radius` (in the XY plane) and
// 0.6 * tube_radius (along Z) that turns `twist_turns` full turns along the path. Flat
// fan caps close both ends (at s * (1.25, -1.875, 0) and s * (1.25, 1.875, 0)).
// Requires 0 < tube_radius <= 0.25 * path_scale (the path's tightest bend has radius
// 0.5 * s), `segments` >= 8 along the path and `sides` >= 3.
// Triangles: 2 * segments * sides + 2 * sides. Vertices: (segments + 1) * sides + 2.
// Topologically a sphere (Euler characteristic 2) even though it self-intersects.
VKCOLLIDE_API Result<HostMesh> twistedTube(float path_scale, float tube_radius, std::uint32_t segments, std::uint32_t sides,
                             float twist_turns);

// An open, flat cloth of nx x ny quads (2 triangles each) in the XY plane at z = 0,
// centred on the origin, `width` along X and `depth` along Y, front face +Z.
struct ClothOptions {
    // Sag: the centre drops by `sag` along -Z, falling off as sin(pi u) sin(pi v) so the
    // border stays at z = 0 (a sheet held at its edges).
    float sag = 0.0f;
    // Fold: the half x > 0 turns about the Y axis by this angle in radians, towards +Z
    // for positive angles (a page being turned). 0 keeps the cloth flat.
    float fold_angle = 0.0f;
};
// Triangles: 2 * nx * ny. Vertices: (nx + 1) * (ny + 1). nx, ny >= 1.
VKCOLLIDE_API Result<HostMesh> clothGrid(float width, float depth, std::uint32_t nx, std::uint32_t ny,
                           const ClothOptions& options = {});

// Sphere from a subdivided icosahedron: every level splits each triangle into four at
// its edge midpoints, which are pushed out onto the sphere. Triangles are nearly equal in
// size (no poles). `levels` <= 12. Triangles: 20 * 4^levels. Vertices: 10 * 4^levels + 2.
VKCOLLIDE_API Result<HostMesh> icosphere(float radius, std::uint32_t levels);

// Closed frustum around the Z axis from z = -height/2 (radius `radius_bottom`) to
// z = +height/2 (radius `radius_top`), capped by fans on flat ends: a cylinder when the
// radii are equal, a cone when radius_top is 0 (the apex is one vertex). radius_bottom > 0,
// radius_top >= 0, height > 0, `segments` >= 3 around, `stacks` >= 1 along.
// Triangles: 2 * segments * stacks + 2 * segments (cone: 2 * segments * stacks).
VKCOLLIDE_API Result<HostMesh> frustum(float radius_bottom, float radius_top, float height, std::uint32_t segments,
                         std::uint32_t stacks);

// `levels` rounds of midpoint subdivision: each triangle becomes four (three corner
// triangles and the middle one), winding kept; a midpoint is made once per edge (keyed by
// the two vertex indices), so a closed mesh stays closed and shares its seams. The shape
// does not change (no smoothing). Errors: InvalidMesh for a mesh validateMesh refuses,
// InvalidArgument when the result would exceed kMaxGeneratedTriangles.
// Triangles: 4^levels times the input's.
VKCOLLIDE_API Result<HostMesh> subdivide(const HostMesh& mesh, std::uint32_t levels);

// Deformers, in place; they move vertices and keep indices (so closedness and neighbours
// stay). Errors (the mesh is left unchanged): InvalidArgument for non-finite parameters or
// a result that leaves the float range.
//
// Twist about the Z axis: a vertex at height z turns by `radians_per_unit * z` about Z.
VKCOLLIDE_API Result<void> twistMesh(HostMesh& io_mesh, float radians_per_unit);
// Bend along X around an axis parallel to Z through (0, radius, 0): the vertex (x, y, z)
// goes to angle theta = x / radius on the circle of radius (radius - y), and up by
// pitch * theta / (2 pi): a bar longer than 2 pi radius wraps round more than once and, with
// a pitch smaller than its thickness along Z, passes through itself. The plane x = 0 stays
// where it is. Needs radius > 0 and every vertex at y < radius (else it would fold inside
// out: InvalidArgument naming the vertex).
VKCOLLIDE_API Result<void> bendMesh(HostMesh& io_mesh, float radius, float pitch = 0.0f);

// An open square cloth draped over a sphere centred on the origin, with an optional flap
// folded through the cloth itself. The flat cloth (side `size`, quads x quads, centred over
// the sphere's top) is mapped by arc length: within `contact_angle` of the top it lies on
// the sphere at distance radius + gap from the centre (a negative gap sinks it in); beyond,
// it hangs down the cone tangent there, with `folds` waves around whose depth grows to
// `fold_depth` * radius. The flap is the corner u + v > size * (1 - 2 * flap) (u, v the flat
// coordinates from the centre): it is turned over onto the cloth about that line, rises up
// to `flap_lift` * radius off it and curls back down through it. Front face: away from the
// sphere. Triangles: 2 * quads^2.
struct DrapeOptions {
    float radius = 1.0f;
    float size = 3.0f;
    std::uint32_t quads = 100;
    float gap = 0.0f;
    float contact_angle = 1.0f;  // radians, in (0, pi/2]
    std::uint32_t folds = 7;
    float fold_depth = 0.12f;  // below 0.5 keeps inward waves off the sphere
    float flap = 0.15f;  // in [0, 0.5); 0: no flap
    float flap_lift = 0.08f;
};
VKCOLLIDE_API Result<HostMesh> drapedCloth(const DrapeOptions& options);

// Row-major affine transforms: p' = M * (x, y, z, 1).
using Transform3x4 = std::array<float, 12>;
using Transform4x4 = std::array<float, 16>;  // the last row must be (0, 0, 0, 1)

// Transforms every position of `io_mesh`. A transform with negative determinant
// (a mirror) would turn outward triangles inward, so each triangle's winding is
// reversed too. Errors (the mesh is left unchanged): InvalidArgument for non-finite
// entries, a 4x4 whose last row is not (0, 0, 0, 1), or a result that overflows float.
VKCOLLIDE_API Result<void> transformMesh(HostMesh& io_mesh, const Transform3x4& transform);
VKCOLLIDE_API Result<void> transformMesh(HostMesh& io_mesh, const Transform4x4& transform);

struct MeshStats {
    std::size_t triangle_count = 0;
    std::size_t vertex_count = 0;      // vertices used by at least one triangle
    std::size_t edge_count = 0;        // distinct undirected edges
    std::size_t boundary_edges = 0;    // edges used by one triangle
    std::size_t non_manifold_edges = 0;  // edges used by three or more triangles
    std::size_t misoriented_edges = 0;   // edges used twice in the same direction
    std::size_t degenerate_triangles = 0;  // triangles repeating a vertex index
    Float3 bounds_min{};  // of the used vertices
    Float3 bounds_max{};
    double surface_area = 0.0;
    // Sum over triangles of det(a, b, c) / 6: the enclosed volume for a closed,
    // outward-oriented mesh (positive), meaningless for an open one.
    double signed_volume = 0.0;
    // V - E + F with V = vertex_count: 2 for a sphere, 0 for a torus, 1 for a disc.
    std::int64_t euler_characteristic = 0;
    // Every edge is shared by exactly two triangles with opposite orientation and no
    // triangle is degenerate.
    bool closed = false;
};

// Statistics of a mesh, computed in double. Error: InvalidMesh if an index is out of
// range, the index count is not a multiple of three, or the mesh has no triangle.
VKCOLLIDE_API Result<MeshStats> computeMeshStats(const HostMesh& mesh);

}  // namespace vkcollide
