// The whole-scene exact reference (tests/support/exact_reference.hpp).
#include <catch2/catch.hpp>

#include <chrono>
#include <cmath>
#include <vector>

#include "narrow/printers.hpp"
#include "vkcollide/thread_pool.hpp"
#include "narrow/scene_builders.hpp"
#include "support/exact_reference.hpp"

using namespace vkcollide;
using namespace vkcollide::test;

namespace {

HostMesh singleTriangle(Float3 a, Float3 b, Float3 c) {
    HostMesh m;
    m.name = "triangle";
    m.positions = {a, b, c};
    m.indices = {0, 1, 2};
    return m;
}

// The faces of makeTetrahedron() that contain vertex `v`.
std::vector<std::uint32_t> facesWith(const HostMesh& m, std::uint32_t v) {
    std::vector<std::uint32_t> faces;
    for (std::uint32_t t = 0; t < m.triangleCount(); ++t) {
        if (m.indices[3 * t] == v || m.indices[3 * t + 1] == v || m.indices[3 * t + 2] == v) faces.push_back(t);
    }
    return faces;
}

}  // namespace

TEST_CASE("Reference: two crossing triangles", "[narrow][reference]") {
    const HostMesh floor = singleTriangle({0, 0, 0}, {2, 0, 0}, {0, 2, 0});
    const HostMesh wall = singleTriangle({-1, 0.5f, -1}, {3, 0.5f, -1}, {1, 0.5f, 1});
    const std::vector<ReferenceObject> scene = {{&wall}, {&floor}};
    const auto pairs = computeReferencePairs(scene);
    REQUIRE(pairs);
    CHECK(*pairs == std::vector<TrianglePair>{{0, 0, 1, 0}});

    // Lifted above the floor by a transform: no contact.
    const std::vector<ReferenceObject> lifted = {{&wall, translation(0, 0, 2)}, {&floor}};
    const auto none = computeReferencePairs(lifted);
    REQUIRE(none);
    CHECK(none->empty());
}

TEST_CASE("Reference: two disjoint tetrahedra", "[narrow][reference]") {
    const HostMesh tetra = makeTetrahedron();
    const std::vector<ReferenceObject> scene = {{&tetra}, {&tetra, translation(1.5f, 0, 0)}};
    const auto pairs = computeReferencePairs(scene);
    REQUIRE(pairs);
    CHECK(pairs->empty());  // and a tetrahedron's own faces are neighbours, never pairs
}

TEST_CASE("Reference: a tetrahedron touching another at a vertex", "[narrow][reference]") {
    const HostMesh tetra = makeTetrahedron();
    // Translated by (1,0,0), the second one's vertex 0 lands exactly on the first one's
    // vertex 1; otherwise it lies in x + y + z > 1, outside the first.
    const std::vector<ReferenceObject> scene = {{&tetra}, {&tetra, translation(1, 0, 0)}};
    const auto pairs = computeReferencePairs(scene);
    REQUIRE(pairs);
    std::vector<TrianglePair> expected;
    for (std::uint32_t a : facesWith(tetra, 1)) {
        for (std::uint32_t b : facesWith(tetra, 0)) expected.push_back({0, a, 1, b});
    }
    CHECK(*pairs == expected);
    CHECK(pairs->size() == 9);

    // One ulp further away: nothing.
    const std::vector<ReferenceObject> apart = {{&tetra}, {&tetra, translation(std::nextafter(1.0f, 2.0f), 0, 0)}};
    const auto none = computeReferencePairs(apart);
    REQUIRE(none);
    CHECK(none->empty());

    // A 3x4 transform (a 90 degree turn about z, then the same contact point):
    // rotated vertex 0 stays at the origin before the shift, vertex 1 -> (0,1,0).
    const Transform turn = transformFrom3x4({0, -1, 0, 1, 1, 0, 0, 0, 0, 0, 1, 0});
    const std::vector<ReferenceObject> turned = {{&tetra}, {&tetra, turn}};
    const auto turned_pairs = computeReferencePairs(turned);
    REQUIRE(turned_pairs);
    CHECK(turned_pairs->size() >= 9);  // also touches along the first one's faces now
}

TEST_CASE("Reference: self-collision flag and object filter", "[narrow][reference]") {
    // One mesh with two crossing, unconnected triangles.
    HostMesh m;
    m.positions = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {-1, 0.5f, -1}, {3, 0.5f, -1}, {1, 0.5f, 1}};
    m.indices = {0, 1, 2, 3, 4, 5};
    std::vector<ReferenceObject> scene = {{&m}};
    auto pairs = computeReferencePairs(scene);
    REQUIRE(pairs);
    CHECK(*pairs == std::vector<TrianglePair>{{0, 0, 0, 1}});
    scene[0].self_collision = false;
    pairs = computeReferencePairs(scene);
    REQUIRE(pairs);
    CHECK(pairs->empty());

    const HostMesh floor = singleTriangle({0, 0, 0}, {2, 0, 0}, {0, 2, 0});
    const std::vector<ReferenceObject> two = {{&floor}, {&floor, translation(0.5f, 0.5f, 0)}};
    ReferenceOptions options;
    options.may_collide = [](std::uint32_t, std::uint32_t) { return false; };
    pairs = computeReferencePairs(two, options);
    REQUIRE(pairs);
    CHECK(pairs->empty());
}

TEST_CASE("Reference: invalid scenes are rejected", "[narrow][reference][errors]") {
    HostMesh bad = makeTetrahedron("broken");
    bad.indices.back() = 17;
    const std::vector<ReferenceObject> scene = {{&bad}};
    const auto r = computeReferencePairs(scene);
    REQUIRE_FALSE(r);
    CHECK(r.error().code() == ErrorCode::InvalidMesh);
    CHECK_THAT(r.error().message(), Catch::Contains("object 0 ('broken')") && Catch::Contains("out of range"));

    HostMesh nan_mesh = makeTetrahedron();
    nan_mesh.positions[2].z = NAN;
    const std::vector<ReferenceObject> nan_scene = {{&nan_mesh}};
    CHECK(computeReferencePairs(nan_scene).error().code() == ErrorCode::InvalidMesh);

    const HostMesh ok = makeTetrahedron();
    Transform projective = kIdentityTransform;
    projective[14] = 1;
    const std::vector<ReferenceObject> proj_scene = {{&ok, projective}};
    CHECK(computeReferencePairs(proj_scene).error().code() == ErrorCode::InvalidArgument);

    const std::vector<ReferenceObject> null_scene = {{nullptr}};
    CHECK(computeReferencePairs(null_scene).error().code() == ErrorCode::InvalidMesh);
}

TEST_CASE("comparePairs computes precision and recall", "[narrow][reference]") {
    const std::vector<TrianglePair> reference = {{0, 0, 1, 0}, {0, 1, 1, 1}, {0, 2, 1, 2}, {1, 3, 2, 0}};
    // One pair given reversed, one duplicated, one wrong, one missing.
    const std::vector<TrianglePair> found = {{1, 0, 0, 0}, {0, 1, 1, 1}, {0, 1, 1, 1}, {1, 3, 2, 0}, {5, 5, 6, 6}};
    const PairComparison c = comparePairs(found, reference);
    CHECK(c.true_positives == 3);
    CHECK(c.false_positives == 1);
    CHECK(c.false_negatives == 1);
    CHECK(c.precision == Approx(0.75));
    CHECK(c.recall == Approx(0.75));
    CHECK(c.missed == std::vector<TrianglePair>{{0, 2, 1, 2}});
    CHECK(c.spurious == std::vector<TrianglePair>{{5, 5, 6, 6}});

    const PairComparison empty = comparePairs({}, {});
    CHECK(empty.precision == 1.0);
    CHECK(empty.recall == 1.0);
}

TEST_CASE("Narrow phase on all triangles equals the reference", "[narrow][reference][phase]") {
    // Two overlapping spheres (contacts between objects) and a third object made of two
    // overlapping spheres in one mesh (self-intersections).
    const HostMesh a = makeSphere(1.0f, {0, 0, 0}, 24, 32);
    const HostMesh b = makeSphere(0.8f, {1.2f, 0.3f, 0.1f}, 20, 28);
    HostMesh folded = makeSphere(0.5f, {0, 0, 1.0f}, 12, 16);
    {
        const HostMesh copy = makeSphere(0.5f, {0.3f, 0, 1.1f}, 12, 16);
        const auto offset = static_cast<std::uint32_t>(folded.positions.size());
        folded.positions.insert(folded.positions.end(), copy.positions.begin(), copy.positions.end());
        for (std::uint32_t i : copy.indices) folded.indices.push_back(i + offset);
    }
    const std::vector<ReferenceObject> scene = {{&a}, {&b, translation(0.05f, 0, 0)}, {&folded}};
    const auto reference = computeReferencePairs(scene);
    REQUIRE(reference);
    REQUIRE(reference->size() > 50);
    bool has_self = false;
    for (const TrianglePair& p : *reference) has_self |= p.object_a == 2 && p.object_b == 2;
    CHECK(has_self);

    const auto candidates = allTrianglesAsCandidates(scene);
    REQUIRE(candidates);
    ThreadPool pool(2);
    const auto narrow = runNarrowPhase(*candidates, {}, pool);
    REQUIRE(narrow);
    CHECK(narrow->pairs == *reference);
    const PairComparison c = comparePairs(narrow->pairs, *reference);
    CHECK(c.precision == 1.0);
    CHECK(c.recall == 1.0);
    CHECK(narrow->stats.neighbour_pairs > 0);

    // Self-collision off for the folded object on both sides.
    std::vector<ReferenceObject> no_self = scene;
    no_self[2].self_collision = false;
    NarrowOptions options;
    options.self_collision = {true, true, false};
    const auto reference2 = computeReferencePairs(no_self);
    const auto narrow2 = runNarrowPhase(*candidates, options, pool);
    REQUIRE((reference2 && narrow2));
    CHECK(narrow2->pairs == *reference2);
    CHECK(reference2->size() < reference->size());
}

TEST_CASE("Reference handles 200K triangles in seconds", "[.][narrow][reference][perf]") {
    // Hidden (run with "[perf]"): meant for optimised builds.
    const HostMesh a = makeSphere(1.0f, {0, 0, 0}, 250, 200);
    const HostMesh b = makeSphere(1.0f, {0, 0, 0}, 250, 200);
    const std::vector<ReferenceObject> scene = {{&a}, {&b, translation(1.0f, 0.1f, 0)}};
    const auto start = std::chrono::steady_clock::now();
    const auto pairs = computeReferencePairs(scene);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    REQUIRE(pairs);
    WARN(a.triangleCount() + b.triangleCount() << " triangles, " << pairs->size() << " pairs, " << seconds << " s");
    CHECK(seconds < 10.0);
}

TEST_CASE("classifyContact tells crossing pairs from touching ones", "[reference]") {
    using test::Contact;
    const std::array<Float3, 3> floor{Float3{-1, -1, 0}, Float3{1, -1, 0}, Float3{0, 1, 0}};
    // Through the floor: vertices on both sides of each other's plane.
    CHECK(test::classifyContact(floor, {Float3{0, 0, -1}, Float3{0, 0, 1}, Float3{0.5f, -2, 0.2f}}) == Contact::Crossing);
    // A vertex resting on the floor, the rest above.
    CHECK(test::classifyContact(floor, {Float3{0, 0, 0}, Float3{0, 0.5f, 1}, Float3{0.5f, 0, 1}}) == Contact::Touching);
    // An edge lying in the floor.
    CHECK(test::classifyContact(floor, {Float3{-0.2f, 0, 0}, Float3{0.2f, 0, 0}, Float3{0, 0, 1}}) == Contact::Touching);
    // Coplanar overlap.
    CHECK(test::classifyContact(floor, {Float3{0, 0, 0}, Float3{2, 0, 0}, Float3{0, 2, 0}}) == Contact::Touching);
    // A wall through the floor's plane that meets the floor only at the floor's corner
    // (-1, -1, 0): the wall straddles the floor's plane, the floor does not straddle the wall's.
    CHECK(test::classifyContact(floor, {Float3{-1, -2, -1}, Float3{-1, 2, -1}, Float3{-1, 0, 1}}) == Contact::Touching);
    CHECK(test::classifyContact({Float3{-1, -2, -1}, Float3{-1, 2, -1}, Float3{-1, 0, 1}}, floor) == Contact::Touching);
}
