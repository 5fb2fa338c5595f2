// The benchmark generators (icosphere, frustum, subdivide, twist, bend, draped cloth):
// exact counts, closedness, outward winding by signed volume against the analytic value,
// and that the shapes meant to pass through themselves do (exact reference) while the
// others do not.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <numbers>

#include "support/exact_reference.hpp"
#include "scene/mesh_stats_check.hpp"
#include "vkcollide/scene.hpp"

using namespace vkcollide;

namespace {

using test::kPi;

using test::statsOf;

void checkClosedOutwardVolume(const MeshStats& s) {
    CHECK(s.closed);
    CHECK(s.degenerate_triangles == 0);
    CHECK(s.signed_volume > 0.0);
}

std::size_t selfPairs(const HostMesh& mesh) {
    const test::ReferenceObject object{&mesh, test::kIdentityTransform, true};
    auto pairs = test::computeReferencePairs(std::span(&object, 1), {.threads = 2});
    REQUIRE(pairs);
    return pairs->size();
}

}  // namespace

TEST_CASE("icosphere: 20 * 4^levels triangles, closed, Euler 2, volume converges to the ball's", "[scene][icosphere]") {
    double previous = 1.0;
    for (std::uint32_t levels : {0u, 1u, 3u, 5u}) {
        INFO("levels " << levels);
        auto m = icosphere(1.5f, levels);
        REQUIRE(m);
        CHECK(m->triangleCount() == 20ull << (2 * levels));
        CHECK(m->positions.size() == 10ull * (1ull << (2 * levels)) + 2);
        const MeshStats s = statsOf(*m);
        checkClosedOutwardVolume(s);
        CHECK(s.euler_characteristic == 2);
        const double error = std::fabs(s.signed_volume - 4.0 / 3.0 * kPi * 1.5 * 1.5 * 1.5) / (4.0 / 3.0 * kPi * 3.375);
        CHECK(error < previous);
        previous = error;
    }
    CHECK(previous < 0.01);
    CHECK_FALSE(icosphere(0.0f, 2));
    CHECK_FALSE(icosphere(1.0f, 13));
}

TEST_CASE("frustum: cylinder and cone are closed with the analytic volume", "[scene][frustum]") {
    auto cylinder = frustum(1.0f, 1.0f, 2.0f, 256, 3);
    REQUIRE(cylinder);
    CHECK(cylinder->triangleCount() == 2u * 256 * 3 + 2u * 256);
    MeshStats s = statsOf(*cylinder);
    checkClosedOutwardVolume(s);
    CHECK(s.euler_characteristic == 2);
    CHECK(std::fabs(s.signed_volume - kPi * 2.0) / (kPi * 2.0) < 1e-3);
    auto cone = frustum(1.0f, 0.0f, 3.0f, 256, 4);
    REQUIRE(cone);
    CHECK(cone->triangleCount() == 2u * 256 * 4);
    s = statsOf(*cone);
    checkClosedOutwardVolume(s);
    CHECK(s.euler_characteristic == 2);
    CHECK(std::fabs(s.signed_volume - kPi * 3.0 / 3.0) / kPi < 1e-3);
    CHECK_FALSE(frustum(1.0f, -1.0f, 1.0f, 8, 1));
    CHECK_FALSE(frustum(1.0f, 1.0f, 1.0f, 2, 1));
    CHECK_FALSE(frustum(1.0f, 1.0f, 1.0f, 8, 0));
}

TEST_CASE("subdivide: 4^levels triangles, still closed, same shape and volume", "[scene][subdivide]") {
    auto t = torus(1.0f, 0.3f, 24, 12);
    REQUIRE(t);
    const MeshStats before = statsOf(*t);
    auto fine = subdivide(*t, 2);
    REQUIRE(fine);
    CHECK(fine->triangleCount() == 16 * t->triangleCount());
    const MeshStats after = statsOf(*fine);
    CHECK(after.closed);
    CHECK(after.euler_characteristic == before.euler_characteristic);
    CHECK(after.signed_volume == Approx(before.signed_volume).epsilon(1e-5));
    CHECK(after.surface_area == Approx(before.surface_area).epsilon(1e-5));
    CHECK(selfPairs(*fine) == 0);  // midpoints on flat faces: no new intersection
    auto same = subdivide(*t, 0);
    REQUIRE(same);
    CHECK(same->indices == t->indices);
    HostMesh bad = *t;
    bad.indices.push_back(0);
    CHECK_FALSE(subdivide(bad, 1));
    CHECK_FALSE(subdivide(*t, 20));  // over kMaxGeneratedTriangles
}

TEST_CASE("twist and bend keep the mesh closed and outward, and a bend past a full turn with a small pitch self-intersects",
          "[scene][deform]") {
    auto bar = frustum(0.2f, 0.2f, 8.0f, 24, 200);
    REQUIRE(bar);
    // Elliptic section, then along X.
    REQUIRE(transformMesh(*bar, Transform3x4{1, 0, 0, 0, 0, 0.5f, 0, 0, 0, 0, 1, 0}));
    REQUIRE(twistMesh(*bar, 2.0f * static_cast<float>(kPi) / 4.0f));
    REQUIRE(transformMesh(*bar, Transform3x4{0, 0, 1, 0, 0, 1, 0, 0, -1, 0, 0, 0}));
    const MeshStats straight = statsOf(*bar);
    checkClosedOutwardVolume(straight);
    CHECK(selfPairs(*bar) == 0);
    HostMesh half = *bar;
    REQUIRE(bendMesh(half, 8.0f / static_cast<float>(kPi)));  // half a turn: no contact
    checkClosedOutwardVolume(statsOf(half));
    CHECK(selfPairs(half) == 0);
    HostMesh wrapped = *bar;
    const float radius = 8.0f / (2.0f * static_cast<float>(kPi) * 1.2f);  // 1.2 turns
    REQUIRE(bendMesh(wrapped, radius, 0.15f));
    const MeshStats w = statsOf(wrapped);
    checkClosedOutwardVolume(w);
    CHECK(w.signed_volume == Approx(straight.signed_volume).epsilon(0.02));
    CHECK(selfPairs(wrapped) > 0);
    HostMesh far = *bar;
    REQUIRE(bendMesh(far, radius, 1.0f));  // pitch above the thickness: the turns miss each other
    CHECK(selfPairs(far) == 0);
    HostMesh fold = *bar;
    CHECK_FALSE(bendMesh(fold, 0.1f));  // y >= radius for part of the section
    for (std::size_t i = 0; i < fold.positions.size(); ++i) REQUIRE(fold.positions[i].y == bar->positions[i].y);
    CHECK_FALSE(twistMesh(fold, std::numeric_limits<float>::infinity()));
}

TEST_CASE("drapedCloth: an open sheet over the sphere whose flap passes through it", "[scene][drape]") {
    DrapeOptions o;
    o.quads = 40;
    o.gap = 0.01f;
    o.flap = 0.0f;
    auto plain = drapedCloth(o);
    REQUIRE(plain);
    CHECK(plain->triangleCount() == 2u * 40 * 40);
    const MeshStats s = statsOf(*plain);
    CHECK(s.boundary_edges == 4u * 40);
    CHECK(s.degenerate_triangles == 0);
    CHECK(s.euler_characteristic == 1);
    // Never inside the sphere it rests on: every vertex at least radius + gap from the centre,
    // up to float rounding.
    for (const Float3& p : plain->positions) CHECK(std::sqrt(p.x * p.x + p.y * p.y + p.z * p.z) >= 1.0099f);
    CHECK(selfPairs(*plain) == 0);
    o.flap = 0.15f;
    auto flapped = drapedCloth(o);
    REQUIRE(flapped);
    CHECK(selfPairs(*flapped) > 0);
    o.flap = 0.5f;
    CHECK_FALSE(drapedCloth(o));
    o.flap = 0.1f;
    o.contact_angle = 2.0f;
    CHECK_FALSE(drapedCloth(o));
}
