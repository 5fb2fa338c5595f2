// Where two intersecting triangles meet (contacts::pairContact): crossing, touching at a
// point and along an edge, coplanar overlaps and edges, zero-area triangles, against closed
// forms; and on random intersecting pairs every end point lies on both triangles.
#include <catch2/catch.hpp>

#include <random>

#include "contact_checks.hpp"
#include "contacts/pair_contacts.hpp"
#include "narrow/triangle_intersection.hpp"

using namespace vkcollide;
using namespace vkcollide::contacts;
using Tri = std::array<Float3, 3>;

namespace {

// The contact's end points, in either order, are p and q (exactly: these cases are exact in float).
bool endsAre(const PairContact& c, Float3 p, Float3 q) {
    const auto same = [](Float3 a, Float3 b) { return a.x == b.x && a.y == b.y && a.z == b.z; };
    return (same(c.start, p) && same(c.end, q)) || (same(c.start, q) && same(c.end, p));
}

bool near(Float3 a, Float3 b) { return std::fabs(a.x - b.x) < 1e-6f && std::fabs(a.y - b.y) < 1e-6f && std::fabs(a.z - b.z) < 1e-6f; }

const Tri kFloor{{{0, 0, 0}, {2, 0, 0}, {0, 2, 0}}};  // z = 0, normal +z

}  // namespace

TEST_CASE("pair contacts: crossing, touching and coplanar triangles against closed forms", "[contacts][host]") {
    REQUIRE(narrow::trianglesIntersect(kFloor, Tri{{{-1, 0.5f, -1}, {3, 0.5f, -1}, {1, 0.5f, 1}}}));
    SECTION("two crossing triangles: the overlap of their cuts") {
        const PairContact c = pairContact(kFloor, Tri{{{-1, 0.5f, -1}, {3, 0.5f, -1}, {1, 0.5f, 1}}});
        CHECK(c.shape == ContactShape::Segment);
        CHECK(endsAre(c, {0, 0.5f, 0}, {1.5f, 0.5f, 0}));
        const float h = static_cast<float>(1 / std::sqrt(2.0));
        CHECK(near(c.normal, {0, -h, -h}));  // unit(n_b - n_a) with n_a = +z, n_b = -y
        CHECK(c.area == 0);
    }
    SECTION("a vertex on the face: a point") {
        const PairContact c = pairContact(kFloor, Tri{{{0.5f, 0.5f, 0}, {0.5f, 0.5f, 1}, {1, 0.5f, 1}}});
        CHECK(c.shape == ContactShape::Point);
        CHECK(endsAre(c, {0.5f, 0.5f, 0}, {0.5f, 0.5f, 0}));
    }
    SECTION("an edge lying on the face: a segment") {
        const PairContact c = pairContact(kFloor, Tri{{{0.5f, 0.5f, 0}, {1, 0.5f, 0}, {0.75f, 0.5f, 1}}});
        CHECK(c.shape == ContactShape::Segment);
        CHECK(endsAre(c, {0.5f, 0.5f, 0}, {1, 0.5f, 0}));
    }
    SECTION("coplanar and overlapping: the overlap's area and diameter") {
        const PairContact c = pairContact(kFloor, Tri{{{0.5f, 0.5f, 0}, {2.5f, 0.5f, 0}, {0.5f, 2.5f, 0}}});
        CHECK(c.shape == ContactShape::Coplanar);
        CHECK(c.area == Approx(0.5).epsilon(1e-6));  // the triangle (0.5,0.5) (1.5,0.5) (0.5,1.5)
        CHECK(endsAre(c, {1.5f, 0.5f, 0}, {0.5f, 1.5f, 0}));
        CHECK(near(c.normal, {0, 0, 0}));  // both face +z
    }
    SECTION("coplanar, sharing an edge side by side: the edge") {
        const PairContact c = pairContact(kFloor, Tri{{{0, 0, 0}, {2, 0, 0}, {0, -2, 0}}});
        CHECK(c.shape == ContactShape::Segment);
        CHECK(endsAre(c, {0, 0, 0}, {2, 0, 0}));
        CHECK(c.area == 0);
        CHECK(near(c.normal, {0, 0, -1}));  // facing -z against +z
    }
    SECTION("coplanar, touching at one vertex: a point") {
        const PairContact c = pairContact(kFloor, Tri{{{2, 0, 0}, {3, 0, 0}, {2, -1, 0}}});
        CHECK(c.shape == ContactShape::Point);
        CHECK(endsAre(c, {2, 0, 0}, {2, 0, 0}));
    }
    SECTION("a zero-area triangle through the face: a point") {
        const PairContact c = pairContact(Tri{{{0.5f, 0.5f, -1}, {0.5f, 0.5f, 1}, {0.5f, 0.5f, 0.25f}}}, kFloor);
        CHECK(c.shape == ContactShape::Point);
        CHECK(endsAre(c, {0.5f, 0.5f, 0}, {0.5f, 0.5f, 0}));
    }
    SECTION("a zero-area triangle lying in the face's plane: clipped to the face") {
        const PairContact c = pairContact(kFloor, Tri{{{-1, 0.5f, 0}, {3, 0.5f, 0}, {1, 0.5f, 0}}});
        CHECK(c.shape == ContactShape::Segment);
        CHECK(endsAre(c, {0, 0.5f, 0}, {1.5f, 0.5f, 0}));
        CHECK(c.area == 0);
    }
    SECTION("the order of the pair swaps the normal, not the geometry") {
        const Tri b{{{-1, 0.5f, -1}, {3, 0.5f, -1}, {1, 0.5f, 1}}};
        const PairContact ab = pairContact(kFloor, b), ba = pairContact(b, kFloor);
        CHECK(endsAre(ba, ab.start, ab.end));
        CHECK(near(ba.normal, {-ab.normal.x, -ab.normal.y, -ab.normal.z}));
    }
}

TEST_CASE("pair contacts: on random intersecting pairs the end points lie on both triangles", "[contacts][host]") {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(-1, 1);
    int tested = 0, segments = 0;
    for (int k = 0; k < 20000 && tested < 2000; ++k) {
        Tri a, b;
        for (Float3& p : a) p = {u(rng), u(rng), u(rng)};
        for (Float3& p : b) p = {u(rng), u(rng), u(rng)};
        if (k % 4 == 0) b[0] = a[1];  // a shared vertex now and then: a touching point
        if (!narrow::trianglesIntersect(a, b)) continue;
        ++tested;
        const PairContact c = pairContact(a, b);
        segments += c.shape == ContactShape::Segment;
        for (const Float3& p : {c.start, c.end}) {
            CHECK(test::distanceToTriangle(p, a) < 1e-5);
            CHECK(test::distanceToTriangle(p, b) < 1e-5);
        }
        const double l = std::sqrt(double(c.normal.x) * c.normal.x + double(c.normal.y) * c.normal.y + double(c.normal.z) * c.normal.z);
        CHECK((l == 0 || std::fabs(l - 1) < 1e-6));
    }
    CHECK(tested == 2000);
    CHECK(segments > 1000);
}
