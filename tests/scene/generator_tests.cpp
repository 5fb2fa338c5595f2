// Generators: exact counts, closedness, orientation (signed volume against the analytic
// volume), Euler characteristic, and the twisted tube's self-intersection.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include "scene/scene_test_util.hpp"
#include "scene/mesh_stats_check.hpp"
#include "vkcollide/scene.hpp"

using namespace vkcollide;

namespace {

using test::kPi;

using test::statsOf;

void checkClosedAndOutward(const MeshStats& s) {
    CHECK(s.closed);
    CHECK(s.boundary_edges == 0);
    CHECK(s.misoriented_edges == 0);
    CHECK(s.non_manifold_edges == 0);
    CHECK(s.degenerate_triangles == 0);
    CHECK(s.signed_volume > 0.0);
}

double relativeError(double value, double expected) { return std::fabs(value - expected) / std::fabs(expected); }

void checkInvalidArgument(const Result<HostMesh>& r) {
    REQUIRE_FALSE(r);
    CHECK(r.error().code() == ErrorCode::InvalidArgument);
}

}  // namespace

TEST_CASE("uvSphere: counts, closed, Euler 2, volume converges", "[scene][sphere]") {
    double previous_error = 1.0;
    for (const std::uint32_t n : {8u, 16u, 64u}) {
        INFO("segments " << 2 * n << ", rings " << n);
        const Result<HostMesh> sphere = uvSphere(2.0f, 2 * n, n);
        REQUIRE(sphere);
        CHECK(sphere->triangleCount() == 2ull * (2 * n) * (n - 1));
        CHECK(sphere->positions.size() == (2ull * n) * (n - 1) + 2);
        const MeshStats s = statsOf(*sphere);
        checkClosedAndOutward(s);
        CHECK(s.euler_characteristic == 2);
        // The inscribed polyhedron is a little smaller; the gap shrinks like 1/n^2.
        const double exact = 4.0 / 3.0 * kPi * 8.0;
        CHECK(s.signed_volume < exact);
        const double error = relativeError(s.signed_volume, exact);
        CHECK(error < 12.0 / (n * n));
        CHECK(error < previous_error);
        previous_error = error;
        CHECK(relativeError(s.surface_area, 4.0 * kPi * 4.0) < 12.0 / (n * n));
        CHECK(s.bounds_max.z == 2.0f);
        CHECK(s.bounds_min.z == -2.0f);
    }
    const Result<HostMesh> smallest = uvSphere(1.0f, 3, 2);  // a triangular bipyramid
    REQUIRE(smallest);
    CHECK(smallest->triangleCount() == 6);
    checkClosedAndOutward(statsOf(*smallest));
}

TEST_CASE("torus: counts, closed, Euler 0, volume 2 pi^2 R r^2", "[scene][torus]") {
    const Result<HostMesh> ring = torus(3.0f, 1.0f, 96, 48);
    REQUIRE(ring);
    CHECK(ring->triangleCount() == 2ull * 96 * 48);
    CHECK(ring->positions.size() == 96ull * 48);
    const MeshStats s = statsOf(*ring);
    checkClosedAndOutward(s);
    CHECK(s.euler_characteristic == 0);
    CHECK(relativeError(s.signed_volume, 2.0 * kPi * kPi * 3.0 * 1.0) < 0.005);
    CHECK(relativeError(s.surface_area, 4.0 * kPi * kPi * 3.0 * 1.0) < 0.005);
    CHECK(s.bounds_max.x == Approx(4.0).epsilon(1e-6));
}

TEST_CASE("box: counts, shared seams, exact volume and area", "[scene][box]") {
    for (const std::uint32_t n : {1u, 2u, 5u}) {
        INFO("subdivisions " << n);
        const Result<HostMesh> b = box(Float3{1.0f, 2.0f, 0.5f}, n);
        REQUIRE(b);
        CHECK(b->triangleCount() == 12ull * n * n);
        CHECK(b->positions.size() == 6ull * n * n + 2);  // seams shared: V = E - F + 2
        const MeshStats s = statsOf(*b);
        checkClosedAndOutward(s);
        CHECK(s.euler_characteristic == 2);
        CHECK(s.signed_volume == Approx(8.0).epsilon(1e-12));
        CHECK(s.surface_area == Approx(8.0 * (2.0 + 1.0 + 0.5)).epsilon(1e-12));
        CHECK(s.bounds_min.x == -1.0f);
        CHECK(s.bounds_max.y == 2.0f);
        CHECK(s.bounds_max.z == 0.5f);
    }
}

TEST_CASE("twistedTube: closed, Euler 2, Pappus volume", "[scene][tube]") {
    const float scale = 2.0f, radius = 0.4f;
    const std::uint32_t segments = 240, sides = 24;
    const Result<HostMesh> tube = twistedTube(scale, radius, segments, sides, 1.5f);
    REQUIRE(tube);
    CHECK(tube->triangleCount() == 2ull * segments * sides + 2ull * sides);
    CHECK(tube->positions.size() == (segments + 1ull) * sides + 2);
    const MeshStats s = statsOf(*tube);
    checkClosedAndOutward(s);
    CHECK(s.euler_characteristic == 2);

    // Pappus: swept volume = section area x path length (the crossing region is swept
    // twice and counted twice by the signed volume, as by Pappus). The section is the
    // ellipse's inscribed `sides`-gon, so its area is used, not pi a b.
    double length = 0.0;
    constexpr int kSteps = 100000;
    for (int i = 0; i < kSteps; ++i) {
        const double t = -1.5 + 3.0 * (i + 0.5) / kSteps;
        length += scale * std::hypot(2.0 * t, 3.0 * t * t - 1.0) * (3.0 / kSteps);
    }
    const double section = 0.5 * sides * std::sin(2.0 * kPi / sides) * radius * (0.6 * radius);
    CHECK(relativeError(s.signed_volume, section * length) < 0.005);
}

TEST_CASE("twistedTube passes through itself at the origin only", "[scene][tube]") {
    const float scale = 1.0f, radius = 0.2f;
    const Result<HostMesh> tube = twistedTube(scale, radius, 64, 10, 1.0f);
    REQUIRE(tube);
    const std::vector<test::Vec3> points = test::selfIntersectionPoints(*tube);
    CHECK(points.size() >= 8);
    // Two tubes of radius r crossing at right angles meet within sqrt(2) r of the
    // crossing point; allow for the facets.
    for (const test::Vec3& p : points) CHECK(std::sqrt(test::dot(p, p)) < 1.6 * radius);

    // The checker finds nothing on surfaces that do not self-intersect.
    const Result<HostMesh> ring = torus(1.0f, 0.3f, 24, 12);
    REQUIRE(ring);
    CHECK(test::selfIntersectionPoints(*ring).empty());
    // The crossing comes from the path, not from the twist.
    const Result<HostMesh> untwisted = twistedTube(1.0f, 0.2f, 64, 10, 0.0f);
    REQUIRE(untwisted);
    CHECK_FALSE(test::selfIntersectionPoints(*untwisted).empty());
}

TEST_CASE("clothGrid: open sheet, counts, sag and fold", "[scene][cloth]") {
    const Result<HostMesh> flat = clothGrid(4.0f, 2.0f, 8, 6);
    REQUIRE(flat);
    CHECK(flat->triangleCount() == 2ull * 8 * 6);
    CHECK(flat->positions.size() == 9ull * 7);
    const MeshStats s = statsOf(*flat);
    CHECK_FALSE(s.closed);
    CHECK(s.boundary_edges == 2ull * (8 + 6));
    CHECK(s.misoriented_edges == 0);
    CHECK(s.euler_characteristic == 1);  // a disc
    CHECK(s.surface_area == Approx(8.0).epsilon(1e-12));
    CHECK(s.bounds_min.z == 0.0f);
    CHECK(s.bounds_max.z == 0.0f);
    // Front face +Z: every triangle's normal points up.
    for (std::size_t t = 0; t < flat->triangleCount(); ++t) {
        const auto a = test::toVec(flat->positions[flat->indices[3 * t]]);
        const auto b = test::toVec(flat->positions[flat->indices[3 * t + 1]]);
        const auto c = test::toVec(flat->positions[flat->indices[3 * t + 2]]);
        CHECK(test::cross(test::sub(b, a), test::sub(c, a))[2] > 0.0);
    }

    const Result<HostMesh> sagging = clothGrid(4.0f, 2.0f, 8, 6, ClothOptions{0.5f, 0.0f});
    REQUIRE(sagging);
    const MeshStats sag = statsOf(*sagging);
    CHECK(sag.bounds_min.z == Approx(-0.5));  // the centre vertex (4, 3)
    CHECK(sag.bounds_max.z == 0.0f);          // the border
    CHECK(sag.surface_area > 8.0);

    const Result<HostMesh> folded = clothGrid(4.0f, 2.0f, 8, 6, ClothOptions{0.0f, static_cast<float>(kPi / 2)});
    REQUIRE(folded);
    const MeshStats fold = statsOf(*folded);
    CHECK_FALSE(fold.closed);
    CHECK(fold.bounds_max.x == Approx(0.0).margin(1e-6));  // the x > 0 half stands up
    CHECK(fold.bounds_max.z == Approx(2.0));
    CHECK(fold.surface_area == Approx(8.0).epsilon(1e-6));  // folding does not stretch
}

TEST_CASE("Generators reject bad arguments", "[scene]") {
    checkInvalidArgument(uvSphere(0.0f, 8, 4));
    checkInvalidArgument(uvSphere(std::nanf(""), 8, 4));
    checkInvalidArgument(uvSphere(1.0f, 2, 4));
    checkInvalidArgument(uvSphere(1.0f, 8, 1));
    checkInvalidArgument(uvSphere(1.0f, 1u << 20, 1u << 20));  // over the triangle budget, nothing allocated
    checkInvalidArgument(torus(1.0f, 1.0f, 8, 8));
    checkInvalidArgument(torus(1.0f, 0.5f, 2, 8));
    checkInvalidArgument(box(Float3{1.0f, -1.0f, 1.0f}, 1));
    checkInvalidArgument(box(Float3{1.0f, 1.0f, 1.0f}, 0));
    checkInvalidArgument(box(Float3{1.0f, 1.0f, 1.0f}, 1u << 20));
    checkInvalidArgument(twistedTube(1.0f, 0.3f, 64, 8, 0.0f));  // too fat for the tightest bend
    checkInvalidArgument(twistedTube(1.0f, 0.2f, 4, 8, 0.0f));
    checkInvalidArgument(twistedTube(1.0f, 0.2f, 64, 8, INFINITY));
    checkInvalidArgument(clothGrid(1.0f, 1.0f, 0, 4));
    checkInvalidArgument(clothGrid(1.0f, 1.0f, 4, 4, ClothOptions{std::nanf(""), 0.0f}));
}
