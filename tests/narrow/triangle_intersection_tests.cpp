// The exact triangle-triangle test: hand-worked cases, then a randomized comparison with
// an independent brute-force oracle.
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>

#include "narrow/exact_predicates.hpp"
#include "narrow/triangle_intersection.hpp"

using vkcollide::Float3;
using namespace vkcollide::narrow;

namespace {

using Tri = std::array<Float3, 3>;

const float kUlp0 = std::nextafter(0.0f, 1.0f);  // smallest positive float

float up(float x) { return std::nextafter(x, INFINITY); }
float down(float x) { return std::nextafter(x, -INFINITY); }

// Both argument orders and all 36 vertex orders (rotations and reflections) must agree.
bool intersectAllOrders(const Tri& a, const Tri& b) {
    const bool expected = trianglesIntersect(a, b);
    static const int kPerm[6][3] = {{0, 1, 2}, {1, 2, 0}, {2, 0, 1}, {0, 2, 1}, {2, 1, 0}, {1, 0, 2}};
    for (const auto& pa : kPerm) {
        for (const auto& pb : kPerm) {
            const Tri a2 = {a[pa[0]], a[pa[1]], a[pa[2]]}, b2 = {b[pb[0]], b[pb[1]], b[pb[2]]};
            REQUIRE(trianglesIntersect(a2, b2) == expected);
            REQUIRE(trianglesIntersect(b2, a2) == expected);
        }
    }
    return expected;
}

// ---- Oracle -------------------------------------------------------------------------
// Two closed triangles (possibly degenerate) intersect iff an edge of one meets the
// other: an extreme point of the (convex) intersection lies on the relative boundary of
// one triangle. The segment-triangle test below shares only the predicates with the
// code under test: coplanar configurations are decided in all three coordinate
// projections at once (for coplanar sets, intersecting <=> every projection
// intersects, since at least one projection is injective on the plane).

struct P2 {
    float x, y;
};

P2 proj(const Float3& p, int axis) { return axis == 0 ? P2{p.y, p.z} : (axis == 1 ? P2{p.x, p.z} : P2{p.x, p.y}); }

int o2(P2 a, P2 b, P2 c) { return orient2d({a.x, a.y}, {b.x, b.y}, {c.x, c.y}); }

bool onSeg(P2 a, P2 b, P2 p) {
    return std::min(a.x, b.x) <= p.x && p.x <= std::max(a.x, b.x) && std::min(a.y, b.y) <= p.y && p.y <= std::max(a.y, b.y);
}

bool segSeg2(P2 a, P2 b, P2 c, P2 d) {
    const int s1 = o2(a, b, c), s2 = o2(a, b, d), s3 = o2(c, d, a), s4 = o2(c, d, b);
    if (((s1 > 0 && s2 < 0) || (s1 < 0 && s2 > 0)) && ((s3 > 0 && s4 < 0) || (s3 < 0 && s4 > 0))) return true;
    return (s1 == 0 && onSeg(a, b, c)) || (s2 == 0 && onSeg(a, b, d)) || (s3 == 0 && onSeg(c, d, a)) ||
           (s4 == 0 && onSeg(c, d, b));
}

bool segTri2(P2 a, P2 b, P2 t0, P2 t1, P2 t2) {
    if (o2(t0, t1, t2) != 0) {
        for (P2 p : {a, b}) {
            const int s0 = o2(t0, t1, p), s1 = o2(t1, t2, p), s2 = o2(t2, t0, p);
            if ((s0 >= 0 && s1 >= 0 && s2 >= 0) || (s0 <= 0 && s1 <= 0 && s2 <= 0)) return true;
        }
    }
    // A degenerate 2D triangle is the union of its edges.
    return segSeg2(a, b, t0, t1) || segSeg2(a, b, t1, t2) || segSeg2(a, b, t2, t0);
}

bool oracleSegTri(const Float3& a, const Float3& b, const Tri& t) {
    const Float3 pts[5] = {a, b, t[0], t[1], t[2]};
    bool coplanar = true;
    for (int skip = 0; skip < 5 && coplanar; ++skip) {
        Float3 q[4];
        int n = 0;
        for (int i = 0; i < 5; ++i) {
            if (i != skip) q[n++] = pts[i];
        }
        coplanar = orient3d(q[0], q[1], q[2], q[3]) == 0;
    }
    if (coplanar) {
        for (int axis = 0; axis < 3; ++axis) {
            if (!segTri2(proj(a, axis), proj(b, axis), proj(t[0], axis), proj(t[1], axis), proj(t[2], axis))) return false;
        }
        return true;
    }
    // Not coplanar: a collinear t (a segment) or a point segment cannot meet the other.
    if (collinear(t[0], t[1], t[2])) return false;
    const int sa = orient3d(t[0], t[1], t[2], a), sb = orient3d(t[0], t[1], t[2], b);
    if (sa * sb > 0 || (sa == 0 && sb == 0)) return false;
    const int e0 = orient3d(a, b, t[0], t[1]), e1 = orient3d(a, b, t[1], t[2]), e2 = orient3d(a, b, t[2], t[0]);
    return (e0 >= 0 && e1 >= 0 && e2 >= 0) || (e0 <= 0 && e1 <= 0 && e2 <= 0);
}

bool oracle(const Tri& a, const Tri& b) {
    for (int e = 0; e < 3; ++e) {
        if (oracleSegTri(a[e], a[(e + 1) % 3], b) || oracleSegTri(b[e], b[(e + 1) % 3], a)) return true;
    }
    return false;
}

const Tri kBase = {Float3{0, 0, 0}, Float3{2, 0, 0}, Float3{0, 2, 0}};  // z = 0, x, y >= 0, x + y <= 2

}  // namespace

TEST_CASE("Separated, crossing and piercing triangles", "[narrow][tritri]") {
    CHECK_FALSE(intersectAllOrders(kBase, {Float3{0, 0, 1}, Float3{2, 0, 1}, Float3{0, 2, 1}}));  // parallel
    CHECK_FALSE(intersectAllOrders(kBase, {Float3{3, 3, -1}, Float3{3, 3, 1}, Float3{5, 5, 5}}));  // beside
    // Crossing: both cut each other's plane inside the other triangle.
    CHECK(intersectAllOrders(kBase, {Float3{-1, 0.5f, -1}, Float3{3, 0.5f, -1}, Float3{1, 0.5f, 1}}));
    // Piercing: one edge of b goes through the interior of a.
    CHECK(intersectAllOrders(kBase, {Float3{0.5f, 0.5f, -1}, Float3{0.5f, 0.5f, 1}, Float3{5, 5, 5}}));
    // Planes cross inside both supporting planes but the intervals on the line miss.
    CHECK_FALSE(intersectAllOrders(kBase, {Float3{3, -1, -1}, Float3{3, 3, -1}, Float3{3, 1, 1}}));
}

TEST_CASE("Touching triangles count as intersecting", "[narrow][tritri]") {
    SECTION("vertex on face") {
        CHECK(intersectAllOrders(kBase, {Float3{0.5f, 0.5f, 0}, Float3{1, 0.5f, 1}, Float3{0.5f, 1, 1}}));
        CHECK_FALSE(intersectAllOrders(kBase, {Float3{0.5f, 0.5f, kUlp0}, Float3{1, 0.5f, 1}, Float3{0.5f, 1, 1}}));
    }
    SECTION("vertex on vertex") {
        CHECK(intersectAllOrders(kBase, {Float3{0, 0, 0}, Float3{-1, -1, 1}, Float3{-1, -1, -1}}));
        CHECK_FALSE(intersectAllOrders(kBase, {Float3{-kUlp0, 0, 0}, Float3{-1, -1, 1}, Float3{-1, -1, -1}}));
    }
    SECTION("edge on edge") {
        CHECK(intersectAllOrders(kBase, {Float3{1, 0, -1}, Float3{1, 0, 1}, Float3{1, -1, 0}}));
        CHECK_FALSE(intersectAllOrders(kBase, {Float3{1, -kUlp0, -1}, Float3{1, -kUlp0, 1}, Float3{1, -1, 0}}));
    }
    SECTION("vertex on edge") {
        CHECK(intersectAllOrders(kBase, {Float3{1, 1, 0}, Float3{2, 2, 1}, Float3{2, 2, -1}}));  // on the hypotenuse
        CHECK_FALSE(intersectAllOrders(kBase, {Float3{1, up(1), 0}, Float3{2, 2, 1}, Float3{2, 2, -1}}));
    }
    SECTION("edge lying in the other's face") {
        CHECK(intersectAllOrders(kBase, {Float3{0.25f, 0.25f, 0}, Float3{1, 0.25f, 0}, Float3{0.5f, 0.5f, 1}}));
    }
}

TEST_CASE("Coplanar triangles", "[narrow][tritri]") {
    CHECK(intersectAllOrders(kBase, {Float3{0.5f, 0.5f, 0}, Float3{3, 0.5f, 0}, Float3{0.5f, 3, 0}}));  // overlap
    CHECK(intersectAllOrders(kBase, {Float3{0.25f, 0.25f, 0}, Float3{0.5f, 0.25f, 0}, Float3{0.25f, 0.5f, 0}}));  // inside
    CHECK(intersectAllOrders(kBase, {Float3{0, 0, 0}, Float3{2, 0, 0}, Float3{0, -2, 0}}));   // shared edge
    CHECK(intersectAllOrders(kBase, {Float3{1, 0, 0}, Float3{3, 0, 0}, Float3{2, -1, 0}}));   // partial edge
    CHECK(intersectAllOrders(kBase, {Float3{2, 0, 0}, Float3{3, 0, 0}, Float3{2, -1, 0}}));   // one vertex
    CHECK(intersectAllOrders(kBase, {Float3{1, 1, 0}, Float3{3, 1, 0}, Float3{1, 3, 0}}));    // vertex on edge
    CHECK_FALSE(intersectAllOrders(kBase, {Float3{1, up(1), 0}, Float3{3, 1, 0}, Float3{1, 3, 0}}));  // 1 ulp off
    CHECK_FALSE(intersectAllOrders(kBase, {Float3{2, 1, 0}, Float3{3, 1, 0}, Float3{3, 2, 0}}));      // disjoint
    // Star of David: edges cross, no vertex inside the other.
    CHECK(intersectAllOrders({Float3{0, 0, 0}, Float3{4, 0, 0}, Float3{2, 4, 0}},
                             {Float3{0, 3, 0}, Float3{2, -1, 0}, Float3{4, 3, 0}}));
    // A tilted common plane z = 0.5x + 0.25y (all values exact in float).
    const Tri a = {Float3{0, 0, 0}, Float3{2, 0, 1}, Float3{0, 2, 0.5f}};
    CHECK(intersectAllOrders(a, {Float3{1, 1, 0.75f}, Float3{3, 1, 1.75f}, Float3{1, 3, 1.25f}}));
    CHECK_FALSE(intersectAllOrders(a, {Float3{1.5f, 1.5f, 1.125f}, Float3{3, 1, 1.75f}, Float3{1, 3, 1.25f}}));
}

TEST_CASE("Near-coplanar triangles one ulp apart", "[narrow][tritri]") {
    const float e = kUlp0;
    CHECK_FALSE(intersectAllOrders(kBase, {Float3{0.25f, 0.25f, e}, Float3{1, 0.25f, e}, Float3{0.25f, 1, e}}));
    CHECK(intersectAllOrders(kBase, {Float3{0.25f, 0.25f, e}, Float3{1, 0.25f, e}, Float3{0.25f, 1, -e}}));
    CHECK(intersectAllOrders(kBase, {Float3{0.25f, 0.25f, e}, Float3{1, 0.25f, e}, Float3{0.25f, 1, 0}}));
    // Tilted plane: lift one vertex of an overlapping coplanar triangle by 1 ulp in z; the
    // triangle still touches a's plane along the edge between the other two vertices.
    const Tri a = {Float3{0, 0, 0}, Float3{2, 0, 1}, Float3{0, 2, 0.5f}};
    CHECK(intersectAllOrders(a, {Float3{0.5f, 0.5f, up(0.375f)}, Float3{1, 0.5f, 0.625f}, Float3{0.5f, 1, 0.5f}}));
    // All three lifted: parallel-ish but strictly above the plane.
    CHECK_FALSE(intersectAllOrders(a, {Float3{0.5f, 0.5f, up(0.375f)}, Float3{1, 0.5f, up(0.625f)},
                                       Float3{0.5f, 1, up(0.5f)}}));
    // One vertex above, one below: crosses.
    CHECK(intersectAllOrders(a, {Float3{0.5f, 0.5f, up(0.375f)}, Float3{1, 0.5f, down(0.625f)},
                                 Float3{0.5f, 1, up(0.5f)}}));
}

TEST_CASE("Degenerate triangles are segments or points", "[narrow][tritri]") {
    const Float3 c{0.5f, 0.5f, 0};
    CHECK(intersectAllOrders(kBase, {Float3{0.5f, 0.5f, -1}, Float3{0.5f, 0.5f, 1}, c}));  // segment through
    CHECK_FALSE(intersectAllOrders(kBase, {Float3{0.5f, 0.5f, kUlp0}, Float3{0.5f, 0.5f, 1}, Float3{0.5f, 0.5f, 2}}));
    CHECK(intersectAllOrders(kBase, {c, c, c}));  // point on the face
    CHECK_FALSE(intersectAllOrders(kBase, {Float3{0.5f, 0.5f, kUlp0}, Float3{0.5f, 0.5f, kUlp0}, Float3{0.5f, 0.5f, kUlp0}}));
    CHECK(intersectAllOrders(kBase, {Float3{1, 1, 0}, Float3{1, 1, 0}, Float3{1, 1, 0}}));  // point on edge
    CHECK(intersectAllOrders(kBase, {Float3{-1, 1, 0}, Float3{3, 1, 0}, Float3{1, 1, 0}}));  // coplanar segment across
    CHECK_FALSE(intersectAllOrders(kBase, {Float3{-1, -1, 0}, Float3{-3, -1, 0}, Float3{-2, -1, 0}}));

    const Tri seg_x = {Float3{0, 0, 0}, Float3{1, 0, 0}, Float3{2, 0, 0}};
    CHECK(intersectAllOrders(seg_x, {Float3{1, -1, 0}, Float3{1, 1, 0}, Float3{1, 0, 0}}));       // crossing segments
    CHECK_FALSE(intersectAllOrders(seg_x, {Float3{1, -1, kUlp0}, Float3{1, 1, kUlp0}, Float3{1, 0, kUlp0}}));
    CHECK(intersectAllOrders(seg_x, {Float3{2, 0, 0}, Float3{3, 0, 0}, Float3{2.5f, 0, 0}}));      // collinear touching
    CHECK_FALSE(intersectAllOrders(seg_x, {Float3{up(2), 0, 0}, Float3{3, 0, 0}, Float3{2.5f, 0, 0}}));
    CHECK(intersectAllOrders(seg_x, {Float3{1, 0, 0}, Float3{1, 0, 0}, Float3{1, 0, 0}}));         // point on segment
    const Float3 p{1, 2, 3};
    CHECK(intersectAllOrders({p, p, p}, {p, p, p}));
    CHECK_FALSE(intersectAllOrders({p, p, p}, {Float3{1, 2, up(3)}, Float3{1, 2, up(3)}, Float3{1, 2, up(3)}}));
}

TEST_CASE("Triangle test matches the brute-force oracle on random cases", "[narrow][tritri][random]") {
    std::mt19937 rng(20061);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    std::uniform_int_distribution<int> grid2(0, 2), grid4(0, 4), pick(0, 2), coin(0, 1);

    const auto gridTri = [&](std::uniform_int_distribution<int>& g, float scale) {
        Tri t;
        for (Float3& q : t) q = {float(g(rng)) * scale, float(g(rng)) * scale, float(g(rng)) * scale};
        return t;
    };
    const auto randomTri = [&] {
        Tri t;
        for (Float3& q : t) q = {unit(rng), unit(rng), unit(rng)};
        return t;
    };
    const auto nudge = [&](Float3 q) {
        float* c = pick(rng) == 0 ? &q.x : (coin(rng) ? &q.y : &q.z);
        *c = coin(rng) ? up(*c) : down(*c);
        return q;
    };

    int positives = 0, total = 0;
    for (int mode = 0; mode < 6; ++mode) {
        for (int iter = 0; iter < 4000; ++iter) {
            Tri a, b;
            switch (mode) {
                case 0: a = randomTri(); b = randomTri(); break;                       // generic
                case 1: a = gridTri(grid2, 1.0f); b = gridTri(grid2, 1.0f); break;      // tiny grid: coplanar, touching, degenerate
                case 2: a = gridTri(grid4, 0.1f); b = gridTri(grid4, 0.1f); break;      // inexact grid: near-coplanar
                case 3: {                                                              // shared vertices or edges
                    a = gridTri(grid4, 0.25f);
                    b = gridTri(grid4, 0.25f);
                    b[0] = a[pick(rng)];
                    if (coin(rng)) b[1] = a[pick(rng)];
                    break;
                }
                case 4: {  // b in a's plane (exact dyadic combinations), then maybe 1 ulp off
                    a = gridTri(grid4, 0.5f);
                    for (Float3& q : b) {
                        const float s = float(grid4(rng) - 1) * 0.5f, t = float(grid4(rng) - 1) * 0.5f;
                        q = {a[0].x + s * (a[1].x - a[0].x) + t * (a[2].x - a[0].x),
                             a[0].y + s * (a[1].y - a[0].y) + t * (a[2].y - a[0].y),
                             a[0].z + s * (a[1].z - a[0].z) + t * (a[2].z - a[0].z)};
                        if (coin(rng) && coin(rng)) q = nudge(q);
                    }
                    break;
                }
                default: {  // b's vertices 1 ulp around a's vertices and edge midpoints
                    a = randomTri();
                    for (Float3& q : b) {
                        const Float3 m = a[pick(rng)], n = a[pick(rng)];
                        q = {0.5f * (m.x + n.x), 0.5f * (m.y + n.y), 0.5f * (m.z + n.z)};
                        if (coin(rng)) q = nudge(q);
                    }
                    if (coin(rng)) b[0] = {unit(rng), unit(rng), unit(rng)};
                    break;
                }
            }
            const bool expected = oracle(a, b);
            INFO("mode " << mode << " iteration " << iter);
            REQUIRE(trianglesIntersect(a, b) == expected);
            REQUIRE(trianglesIntersect(b, a) == expected);
            const Tri a_rotated = {a[1], a[2], a[0]}, b_flipped = {b[0], b[2], b[1]};
            REQUIRE(trianglesIntersect(a_rotated, b_flipped) == expected);
            positives += expected;
            ++total;
        }
    }
    // Both outcomes well represented.
    CHECK(positives > total / 10);
    CHECK(positives < total * 9 / 10);
}

TEST_CASE("Coplanar contacts of tilted grids give the same answers as on the axes", "[narrow][tritri]") {
    // Triangles of two grids on the plane z = 0 (offset by a fraction of a cell, some
    // coincident), then the same triangles through a linear map with dyadic entries,
    // exact in float: intersection is invariant under an invertible linear map, so the
    // answers must not change, though no tilted difference is zero (the exact paths and
    // their shortcuts run, and the coplanar pairs skip the second plane's sides).
    std::mt19937 rng(777);
    std::uniform_int_distribution<int> cell(-16, 16), offset(0, 3), corner(0, 1);
    const float m[9] = {1.0f, 0.25f, 0.125f, -0.125f, 1.0f, 0.375f, 0.375f, -0.25f, 1.0f};
    const auto tilt = [&](const Tri& t) {
        Tri out;
        for (int i = 0; i < 3; ++i) {
            const Float3& p = t[i];
            out[i] = {m[0] * p.x + m[1] * p.y + m[2] * p.z, m[3] * p.x + m[4] * p.y + m[5] * p.z, m[6] * p.x + m[7] * p.y + m[8] * p.z};
        }
        return out;
    };
    // Half of a grid cell (u, v) of size 1/8, shifted by `shift` / 32 in x.
    const auto half = [&](int u, int v, int shift, int which) {
        const float x = float(u) / 8.0f + float(shift) / 32.0f, y = float(v) / 8.0f, s = 1.0f / 8.0f;
        return which == 0 ? Tri{{{x, y, 0}, {x + s, y, 0}, {x + s, y + s, 0}}} : Tri{{{x, y, 0}, {x + s, y + s, 0}, {x, y + s, 0}}};
    };
    int hits = 0, misses = 0;
    for (int iter = 0; iter < 4000; ++iter) {
        const int u = cell(rng) / 8, v = cell(rng) / 8;
        const Tri a = half(u, v, 0, corner(rng));
        const Tri b = half(u + cell(rng) / 12, v + cell(rng) / 12, offset(rng), corner(rng));
        const bool flat = intersectAllOrders(a, b);
        INFO("iteration " << iter);
        REQUIRE(intersectAllOrders(tilt(a), tilt(b)) == flat);
        (flat ? hits : misses) += 1;
    }
    CHECK(hits > 1000);
    CHECK(misses > 500);
}
