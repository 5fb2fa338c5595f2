// transformMesh and computeMeshStats on hand-built meshes.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

#include "vkcollide/scene.hpp"
#include "scene/mesh_stats_check.hpp"

using namespace vkcollide;

namespace {

// The unit tetrahedron (0, e_x, e_y, e_z), outward: volume 1/6.
HostMesh tetrahedron() {
    HostMesh m;
    m.name = "tetra";
    m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    m.indices = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
    return m;
}

using test::statsOf;

}  // namespace

TEST_CASE("computeMeshStats: tetrahedron by hand", "[scene][stats]") {
    const MeshStats s = statsOf(tetrahedron());
    CHECK(s.triangle_count == 4);
    CHECK(s.vertex_count == 4);
    CHECK(s.edge_count == 6);
    CHECK(s.euler_characteristic == 2);
    CHECK(s.closed);
    CHECK(s.signed_volume == Approx(1.0 / 6.0));
    CHECK(s.surface_area == Approx(1.5 + std::sqrt(3.0) / 2.0));
    CHECK(s.bounds_min.x == 0.0f);
    CHECK(s.bounds_max.z == 1.0f);
}

TEST_CASE("computeMeshStats: broken meshes are not closed", "[scene][stats]") {
    SECTION("one triangle flipped") {
        HostMesh m = tetrahedron();
        std::swap(m.indices[1], m.indices[2]);
        const MeshStats s = statsOf(m);
        CHECK_FALSE(s.closed);
        CHECK(s.misoriented_edges == 3);
        CHECK(s.boundary_edges == 0);
    }
    SECTION("one triangle missing") {
        HostMesh m = tetrahedron();
        m.indices.resize(9);
        const MeshStats s = statsOf(m);
        CHECK_FALSE(s.closed);
        CHECK(s.boundary_edges == 3);
        CHECK(s.euler_characteristic == 1);
    }
    SECTION("three triangles on one edge") {
        HostMesh m = tetrahedron();
        m.positions.push_back({1, 1, 1});
        m.indices.insert(m.indices.end(), {1, 2, 4});
        const MeshStats s = statsOf(m);
        CHECK_FALSE(s.closed);
        CHECK(s.non_manifold_edges == 1);
    }
    SECTION("a degenerate triangle") {
        HostMesh m = tetrahedron();
        m.indices.insert(m.indices.end(), {1, 1, 2});
        const MeshStats s = statsOf(m);
        CHECK_FALSE(s.closed);
        CHECK(s.degenerate_triangles == 1);
    }
    SECTION("unused vertices do not count") {
        HostMesh m = tetrahedron();
        m.positions.push_back({100, 100, 100});
        const MeshStats s = statsOf(m);
        CHECK(s.vertex_count == 4);
        CHECK(s.bounds_max.x == 1.0f);
        CHECK(s.closed);
    }
}

TEST_CASE("computeMeshStats: invalid meshes are errors", "[scene][stats]") {
    HostMesh m = tetrahedron();
    m.indices[5] = 4;
    Result<MeshStats> s = computeMeshStats(m);
    REQUIRE_FALSE(s);
    CHECK(s.error().code() == ErrorCode::InvalidMesh);
    CHECK(s.error().message() == "mesh 'tetra': index 5 = 4 is out of range (4 vertices)");
    m = tetrahedron();
    m.indices.pop_back();
    CHECK(computeMeshStats(m).error().code() == ErrorCode::InvalidMesh);
    CHECK(computeMeshStats(HostMesh{}).error().code() == ErrorCode::InvalidMesh);
}

TEST_CASE("transformMesh: affine 3x4 and 4x4", "[scene][transform]") {
    HostMesh m = tetrahedron();
    // Scale x by 2, rotate nothing, translate by (1, 2, 3).
    REQUIRE(transformMesh(m, Transform3x4{2, 0, 0, 1, 0, 1, 0, 2, 0, 0, 1, 3}));
    CHECK(m.positions[1].x == 3.0f);
    CHECK(m.positions[1].y == 2.0f);
    CHECK(m.positions[3].z == 4.0f);
    CHECK(statsOf(m).signed_volume == Approx(2.0 / 6.0));

    // A quarter turn about Z as 4x4: (x, y) -> (-y, x).
    HostMesh r = tetrahedron();
    REQUIRE(transformMesh(r, Transform4x4{0, -1, 0, 0, 1, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}));
    CHECK(r.positions[1].x == 0.0f);
    CHECK(r.positions[1].y == 1.0f);
    CHECK(r.indices == tetrahedron().indices);
}

TEST_CASE("transformMesh: mirrors keep triangles outward", "[scene][transform]") {
    HostMesh m = tetrahedron();
    REQUIRE(transformMesh(m, Transform3x4{-1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0}));
    CHECK(m.positions[1].x == -1.0f);
    const MeshStats s = statsOf(m);
    CHECK(s.closed);
    CHECK(s.signed_volume == Approx(1.0 / 6.0));
}

TEST_CASE("transformMesh: bad transforms leave the mesh unchanged", "[scene][transform]") {
    const HostMesh original = tetrahedron();
    HostMesh m = original;
    const auto unchanged = [&] {
        CHECK(m.indices == original.indices);
        for (std::size_t i = 0; i < m.positions.size(); ++i) CHECK(m.positions[i].x == original.positions[i].x);
    };
    Result<void> r = transformMesh(m, Transform4x4{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 1, 1});
    REQUIRE_FALSE(r);
    CHECK(r.error().code() == ErrorCode::InvalidArgument);
    unchanged();
    r = transformMesh(m, Transform3x4{std::numeric_limits<float>::quiet_NaN(), 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0});
    REQUIRE_FALSE(r);
    unchanged();
    // Vertex 1 (x = 1) lands at 4e38, beyond float range; vertex 0 (x = 0) at 2e38.
    r = transformMesh(m, Transform3x4{2e38f, 0, 0, 2e38f, 0, 1, 0, 0, 0, 0, 1, 0});
    REQUIRE_FALSE(r);
    CHECK(r.error().message() == "transformMesh: 'tetra' vertex 1 leaves the float range");
    unchanged();
}
