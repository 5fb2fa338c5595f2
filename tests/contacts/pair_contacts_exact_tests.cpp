// Contact end points are the exact intersection points correctly rounded to float: against
// a rational reference (GMP) on random intersecting pairs of several kinds (coordinates of
// very different magnitudes, near-parallel planes, coplanar overlaps, subnormals), ties to
// even on constructed midpoints, and the double interpolation the points used to come from
// misrounding some near-parallel pairs the exact construction gets right.
#include <catch2/catch.hpp>

#include <cstdio>
#include <functional>
#include <random>
#include <string>
#include <tuple>
#include <vector>

#include "contacts/pair_contacts.hpp"
#include "narrow/triangle_intersection.hpp"
#include "rational.hpp"

using namespace vkcollide;
using namespace vkcollide::test;
using Tri = std::array<Float3, 3>;

namespace {

bool same(Float3 a, Float3 b) { return a.x == b.x && a.y == b.y && a.z == b.z; }

// A point of one triangle's cut by the other's plane: a vertex (edge -1) or the crossing of
// edge (edge, edge + 1).
struct CutPoint {
    R3 p;
    int edge = -1;
};

std::vector<CutPoint> cutOf(const Tri& t, const Tri& plane) {
    const R3 p0 = r3(plane[0]), p1 = r3(plane[1]), p2 = r3(plane[2]);
    const R3 v[3] = {r3(t[0]), r3(t[1]), r3(t[2])};
    const Rational side[3] = {orient(p0, p1, p2, v[0]), orient(p0, p1, p2, v[1]), orient(p0, p1, p2, v[2])};
    std::vector<CutPoint> cut;
    for (int i = 0; i < 3; ++i) {
        const int j = (i + 1) % 3;
        if (side[i].sign() == 0) cut.push_back({v[i], -1});
        if (side[i].sign() * side[j].sign() < 0) cut.push_back({crossingAt(v[i], v[j], side[i], side[j]), i});
    }
    return cut;
}

// The old construction of a crossing point: interpolated in double, rounded once to float.
Float3 doubleCrossing(const Tri& t, int i, const Tri& plane) {
    struct D {
        double x, y, z;
    };
    const auto d = [](const Float3& f) { return D{f.x, f.y, f.z}; };
    const auto sub = [](D a, D b) { return D{a.x - b.x, a.y - b.y, a.z - b.z}; };
    const D u = sub(d(plane[1]), d(plane[0])), v = sub(d(plane[2]), d(plane[0]));
    const D n{u.y * v.z - u.z * v.y, u.z * v.x - u.x * v.z, u.x * v.y - u.y * v.x};
    const auto dist = [&](const Float3& p) {
        const D w = sub(d(p), d(plane[0]));
        return n.x * w.x + n.y * w.y + n.z * w.z;
    };
    const Float3 &p = t[i], &q = t[(i + 1) % 3];
    const double di = dist(p), dj = dist(q);
    const double s = std::clamp(di / (di - dj), 0.0, 1.0);
    return {static_cast<float>(p.x + s * (double(q.x) - p.x)), static_cast<float>(p.y + s * (double(q.y) - p.y)),
            static_cast<float>(p.z + s * (double(q.z) - p.z))};
}

struct CrossingReference {
    CutPoint lo, hi;
    bool lo_from_a = false, hi_from_a = false;
};

// Crossing planes, both triangles with an area: the overlap of the two cuts along the
// planes' common line, ordered exactly.
CrossingReference crossingReference(const Tri& a, const Tri& b) {
    const std::vector<CutPoint> cut_a = cutOf(a, b), cut_b = cutOf(b, a);
    const R3 line = cross(cross(r3(a[1]) - r3(a[0]), r3(a[2]) - r3(a[0])), cross(r3(b[1]) - r3(b[0]), r3(b[2]) - r3(b[0])));
    const auto extreme = [&](const std::vector<CutPoint>& cut, int direction) {
        std::size_t best = 0;
        for (std::size_t i = 1; i < cut.size(); ++i)
            if (compare(dot(cut[i].p, line), dot(cut[best].p, line)) * direction > 0) best = i;
        return cut[best];
    };
    const CutPoint a_lo = extreme(cut_a, -1), a_hi = extreme(cut_a, 1), b_lo = extreme(cut_b, -1), b_hi = extreme(cut_b, 1);
    CrossingReference r;
    r.lo_from_a = compare(dot(a_lo.p, line), dot(b_lo.p, line)) >= 0;
    r.hi_from_a = compare(dot(a_hi.p, line), dot(b_hi.p, line)) <= 0;
    r.lo = r.lo_from_a ? a_lo : b_lo;
    r.hi = r.hi_from_a ? a_hi : b_hi;
    return r;
}

// Coplanar triangles, both with an area: the overlap polygon's corners, by Sutherland-Hodgman
// in rationals (exact, so the points stay in the plane; the third coordinate follows the
// same parameter).
std::vector<R3> coplanarReference(const Tri& a, const Tri& b) {
    const R3 nb = cross(r3(b[1]) - r3(b[0]), r3(b[2]) - r3(b[0]));
    const double n[3] = {std::fabs(nb.x.approx()), std::fabs(nb.y.approx()), std::fabs(nb.z.approx())};
    const int drop = n[0] >= n[1] && n[0] >= n[2] ? 0 : (n[1] >= n[2] ? 1 : 2);
    const int u = drop == 0 ? 1 : 0, v = drop == 2 ? 1 : 2;
    const auto side = [&](const R3& p, const R3& q, const R3& r) { return (q[u] - p[u]) * (r[v] - p[v]) - (q[v] - p[v]) * (r[u] - p[u]); };
    const R3 c[3] = {r3(b[0]), r3(b[1]), r3(b[2])};
    const int turn = side(c[0], c[1], c[2]).sign();
    std::vector<R3> polygon = {r3(a[0]), r3(a[1]), r3(a[2])};
    for (int e = 0; e < 3 && !polygon.empty(); ++e) {
        std::vector<R3> kept;
        for (std::size_t i = 0; i < polygon.size(); ++i) {
            const R3 &p = polygon[i], &q = polygon[(i + 1) % polygon.size()];
            const Rational sp = Rational(turn) * side(c[e], c[(e + 1) % 3], p), sq = Rational(turn) * side(c[e], c[(e + 1) % 3], q);
            if (sp.sign() >= 0) kept.push_back(p);
            if (sp.sign() * sq.sign() < 0) kept.push_back(crossingAt(p, q, sp, sq));
        }
        polygon = kept;
    }
    return polygon;
}

Rational distance2(const R3& p, const R3& q) { return dot(p - q, p - q); }

// Checks one intersecting pair against the reference; counts in io_old_wrong the chosen
// crossing points the old double interpolation rounds differently. False when the pair is
// of a case the reference does not cover (zero-area triangles).
bool checkPair(const Tri& a, const Tri& b, int& io_old_wrong) {
    const auto flat = [](const Tri& t) {
        const R3 n = cross(r3(t[1]) - r3(t[0]), r3(t[2]) - r3(t[0]));
        return n.x.sign() == 0 && n.y.sign() == 0 && n.z.sign() == 0;
    };
    if (flat(a) || flat(b)) return false;
    const PairContact c = contacts::pairContact(a, b);
    const R3 b0 = r3(b[0]), b1 = r3(b[1]), b2 = r3(b[2]), a0 = r3(a[0]), a1 = r3(a[1]), a2 = r3(a[2]);
    const bool coplanar = orient(b0, b1, b2, a0).sign() == 0 && orient(b0, b1, b2, a1).sign() == 0 && orient(b0, b1, b2, a2).sign() == 0;
    if (coplanar) {
        const std::vector<R3> corners = coplanarReference(a, b);
        REQUIRE(!corners.empty());
        Rational widest;
        for (const R3& p : corners)
            for (const R3& q : corners)
                if (compare(distance2(p, q), widest) > 0) widest = distance2(p, q);
        // The ends are rounded corners, and (chosen on doubles) as far apart as the widest
        // pair up to the approximations' error.
        Rational chosen(-1.0);
        for (const R3& p : corners)
            for (const R3& q : corners)
                if (same(roundToFloat(p), c.start) && same(roundToFloat(q), c.end) && compare(distance2(p, q), chosen) > 0)
                    chosen = distance2(p, q);
        CHECK(chosen.sign() >= 0);
        if (chosen.sign() >= 0) CHECK(chosen.approx() >= widest.approx() * (1 - 1e-9));
        return true;
    }
    const CrossingReference r = crossingReference(a, b);
    // The reference's ends lie on both planes and in order along their line.
    for (const R3* end : {&r.lo.p, &r.hi.p}) {
        CHECK(orient(a0, a1, a2, *end).sign() == 0);
        CHECK(orient(b0, b1, b2, *end).sign() == 0);
    }
    CHECK(compare(dot(r.lo.p, cross(cross(a1 - a0, a2 - a0), cross(b1 - b0, b2 - b0))),
                  dot(r.hi.p, cross(cross(a1 - a0, a2 - a0), cross(b1 - b0, b2 - b0)))) <= 0);
    const Float3 lo = roundToFloat(r.lo.p), hi = roundToFloat(r.hi.p);
    const bool match = (same(c.start, lo) && same(c.end, hi)) || (same(c.start, hi) && same(c.end, lo));
    if (!match) {  // the pair in hex floats, to paste into a closed-form case
        const auto hex = [](const Tri& t) {
            char text[256];
            std::snprintf(text, sizeof text, "{{{%a,%a,%a},{%a,%a,%a},{%a,%a,%a}}}", t[0].x, t[0].y, t[0].z, t[1].x, t[1].y, t[1].z, t[2].x,
                          t[2].y, t[2].z);
            return std::string(text);
        };
        UNSCOPED_INFO("a " << hex(a) << " b " << hex(b));
    }
    CHECK(match);
    for (const auto& [end, from_a, rounded] : {std::tuple{r.lo, r.lo_from_a, lo}, std::tuple{r.hi, r.hi_from_a, hi}})
        if (end.edge >= 0 && !same(from_a ? doubleCrossing(a, end.edge, b) : doubleCrossing(b, end.edge, a), rounded)) ++io_old_wrong;
    return true;
}

float scaled(float u, int exponent) { return std::ldexp(u, exponent); }

}  // namespace

TEST_CASE("exact contact points: ties round to even, subnormals included", "[contacts][host][exact]") {
    const Tri floor{{{0, 0, 0}, {2, 0, 0}, {0, 2, 0}}};
    const float one = 1, up1 = std::nextafter(one, 2.0f), up2 = std::nextafter(up1, 2.0f);
    const float tiny = std::numeric_limits<float>::denorm_min();
    // Edge p..q crosses z = 0 halfway: x is the midpoint of p.x and q.x.
    struct Case {
        float px, qx, x;
    } cases[] = {{one, up1, one}, {up1, up2, up2}, {0, tiny, 0}, {tiny, 2 * tiny, 2 * tiny}, {3 * tiny, 4 * tiny, 4 * tiny}};
    for (const Case& k : cases) {
        const Tri a{{{k.px, 0.25f, -1}, {k.qx, 0.25f, 1}, {k.px, 0.5f, 1}}};
        const PairContact c = contacts::pairContact(floor, a);
        CHECK(c.shape == ContactShape::Segment);
        const Float3 tie{k.x, 0.25f, 0}, other{k.px, 0.375f, 0};
        CHECK(((same(c.start, tie) && same(c.end, other)) || (same(c.start, other) && same(c.end, tie))));
    }
}

TEST_CASE("exact contact points: pairs the double interpolation got far wrong", "[contacts][host][exact]") {
    // Found by the random test below. Mixed magnitudes: the double interpolation of a's
    // edge 2 clamps to its vertex a[2] (about 2^-68), the exact crossing is near 2^50.
    const Tri a1{{{0x1.a2a5ep+90f, -0x1.09756p+91f, -0x1.0be93ap+92f},
                  {0x1.b998ep+32f, 0x1.4291p+33f, 0x1.829b68p+33f},
                  {-0x1.adebf8p-68f, -0x1.ec2b98p-68f, -0x1.79749cp-68f}}};
    const Tri b1{{{0x1.798bfep+90f, -0x1.f80c18p+90f, -0x1.18fa14p+92f},
                  {0x1.a8251cp+71f, 0x1.473cfp+33f, 0x1.9c8e4p+67f},
                  {-0x1.a12dep+51f, 0x1.853318p+28f, -0x1.d8fd9ap-25f}}};
    // Planes 2^-23 and 2^-60 off z = 0: the double z of a's edge 2 crossing is 4,946 ulps off.
    const Tri a2{{{0x1.3c8278p-1f, -0x1.31fa9p-2f, 0x1.a90368p-24f},
                  {0x1.f63d8cp-1f, 0x1.76f6ep-1f, -0x1.ffdd7cp-23f},
                  {0x1.2f16cp-2f, 0x1.135f38p-2f, -0x1.d3d354p-23f}}};
    const Tri b2{{{0x1.fc47d4p-1f, 0x1.b78ep-4f, 0x1.3fdf48p-61f},
                  {0x1.240cap-4f, 0x1.9c19p-7f, 0x1.e8dc3p-60f},
                  {0x1.7d8ee8p-2f, -0x1.ceb6e8p-3f, -0x1.815d18p-62f}}};
    const Float3 exact1{0x1.7ef2d2p+49f, -0x1.e5a4dep+49f, -0x1.ea217ep+50f};
    const Float3 exact2{0x1.08fb48p-1f, -0x1.f18f06p-4f, 0x1.55195cp-65f};
    for (const auto& [a, b, end, edge, of_a] : {std::tuple{a1, b1, exact1, 2, true}, std::tuple{a2, b2, exact2, 2, true}}) {
        REQUIRE(narrow::trianglesIntersect(a, b));
        const PairContact c = contacts::pairContact(a, b);
        CHECK((same(c.start, end) || same(c.end, end)));
        CHECK(!same(of_a ? doubleCrossing(a, edge, b) : doubleCrossing(b, edge, a), end));
        int old_wrong = 0;
        CHECK(checkPair(a, b, old_wrong));  // and the whole contact against the reference
        CHECK(old_wrong >= 1);
    }
}

TEST_CASE("exact contact points: random pairs against a rational reference", "[contacts][host][exact]") {
    std::mt19937 rng(2026);
    std::uniform_real_distribution<float> u(-1, 1);
    std::uniform_int_distribution<int> exponent(-100, 100), offset(20, 60);
    const auto point = [&] { return Float3{u(rng), u(rng), u(rng)}; };
    // Each kind: a pair generator; the test takes the pairs that intersect.
    const auto uniform = [&](Tri& a, Tri& b, int k) {
        for (Float3& p : a) p = point();
        for (Float3& p : b) p = point();
        if (k % 4 == 0) b[0] = a[1];  // a shared vertex now and then
    };
    const auto magnitudes = [&](Tri& a, Tri& b, int) {  // every vertex at its own scale, 2^-100..2^100
        for (Float3& p : a) {
            const int e = exponent(rng);
            p = {scaled(u(rng), e), scaled(u(rng), e), scaled(u(rng), e)};
        }
        // b straddles a: near a's vertices, pushed apart along a rough normal, and one free.
        const int e = exponent(rng);
        b[0] = {a[0].x * (1 + u(rng) / 8), a[0].y * (1 + u(rng) / 8), a[0].z * (1 + u(rng) / 8)};
        b[1] = {a[1].x * (1 + u(rng) / 8) + scaled(u(rng), e), a[1].y * (1 + u(rng) / 8), a[1].z * (1 + u(rng) / 8) + scaled(u(rng), e)};
        b[2] = {scaled(u(rng), exponent(rng)), scaled(u(rng), exponent(rng)), scaled(u(rng), exponent(rng))};
    };
    const auto near_parallel = [&](Tri& a, Tri& b, int) {  // both within 2^-20..2^-60 of z = 0
        const int ea = -offset(rng), eb = -offset(rng);
        for (Float3& p : a) p = {u(rng), u(rng), scaled(u(rng), ea)};
        for (Float3& p : b) p = {u(rng), u(rng), scaled(u(rng), eb)};
    };
    const auto coplanar = [&](Tri& a, Tri& b, int k) {  // z = x/2 + y/4 + 1/8 on a 2^-8 grid: exact floats
        std::uniform_int_distribution<int> grid(-512, 512);
        for (Tri* t : {&a, &b})
            for (Float3& p : *t) {
                const float x = static_cast<float>(grid(rng)) / 256, y = static_cast<float>(grid(rng)) / 256;
                p = {x, y, k % 2 ? 0.25f : x / 2 + y / 4 + 0.125f};
            }
    };
    const auto subnormal = [&](Tri& a, Tri& b, int k) {  // the uniform pairs scaled to subnormals, or across 2^-126
        uniform(a, b, k);
        const int e = k % 2 ? -128 : -122;
        for (Tri* t : {&a, &b})
            for (Float3& p : *t) p = {scaled(p.x, e), scaled(p.y, e), scaled(p.z, e)};
    };
    struct Kind {
        const char* name;
        std::function<void(Tri&, Tri&, int)> make;
        int wanted;
    };
    const Kind kinds[] = {{"uniform", uniform, 2000},
                          {"magnitudes", magnitudes, 1000},
                          {"near-parallel", near_parallel, 2000},
                          {"coplanar", coplanar, 1000},
                          {"subnormal", subnormal, 1000}};
    for (const Kind& kind : kinds) {
        INFO(kind.name);
        int tested = 0, old_wrong = 0;
        for (int k = 0; k < 200 * kind.wanted && tested < kind.wanted; ++k) {
            Tri a, b;
            kind.make(a, b, k);
            if (narrow::trianglesIntersect(a, b) && checkPair(a, b, old_wrong)) ++tested;
        }
        CHECK(tested == kind.wanted);
        // The near-parallel planes' crossings are where double interpolation misrounds.
        if (std::string(kind.name) == "near-parallel") CHECK(old_wrong > 0);
        WARN(kind.name << ": " << tested << " pairs, old double construction misrounded " << old_wrong << " of the crossing ends");
    }
}
