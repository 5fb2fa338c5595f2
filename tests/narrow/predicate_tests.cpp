// The exact predicates against an independent big-integer evaluation.
#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <cstdint>
#include <random>

#include "narrow/exact_predicates.hpp"
#include "support/big_orient.hpp"

using vkcollide::Float3;
using vkcollide::narrow::Float2;
using namespace vkcollide::narrow;
using vkcollide::test::bigOrient2d;
using vkcollide::test::bigOrient3d;

namespace {

// Random floats over a wide exponent range, including subnormals and huge values.
float wideFloat(std::mt19937& rng) {
    std::uniform_real_distribution<float> mantissa(-1.0f, 1.0f);
    std::uniform_int_distribution<int> exponent(-150, 126);
    return std::ldexp(mantissa(rng), exponent(rng));
}

Float3 nudge(Float3 p, std::mt19937& rng) {
    std::uniform_int_distribution<int> which(0, 5);
    const int w = which(rng);
    float* c = w / 2 == 0 ? &p.x : (w / 2 == 1 ? &p.y : &p.z);
    *c = std::nextafter(*c, (w % 2) ? INFINITY : -INFINITY);
    return p;
}

}  // namespace

TEST_CASE("orient3d signs of hand-worked configurations", "[narrow][predicates]") {
    const Float3 o{0, 0, 0}, x{1, 0, 0}, y{0, 1, 0}, z{0, 0, 1};
    CHECK(orient3d(o, x, y, z) == 1);   // z is on the side of x cross y
    CHECK(orient3d(o, y, x, z) == -1);  // swapping two points flips the sign
    CHECK(orient3d(o, x, y, Float3{0.25f, 0.5f, 0}) == 0);
    CHECK(orient3d(o, x, Float3{2, 0, 0}, z) == 0);  // collinear base
    // 1 ulp above and below the plane z = 0.
    CHECK(orient3d(o, x, y, Float3{0.3f, 0.3f, std::nextafter(0.0f, 1.0f)}) == 1);
    CHECK(orient3d(o, x, y, Float3{0.3f, 0.3f, -std::nextafter(0.0f, 1.0f)}) == -1);
    // A plane with inexact float normal: points exactly on it, built from exact sums.
    const Float3 a{0.1f, 0.2f, 0.3f}, b{1.1f, 0.7f, 2.3f}, c{-0.9f, 3.2f, 0.3f};
    CHECK(orient3d(a, b, c, a) == 0);
    CHECK(orient3d(a, b, c, b) == 0);
}

TEST_CASE("orient2d signs of hand-worked configurations", "[narrow][predicates]") {
    CHECK(orient2d({0, 0}, {1, 0}, {0, 1}) == 1);
    CHECK(orient2d({0, 0}, {0, 1}, {1, 0}) == -1);
    CHECK(orient2d({0, 0}, {1, 1}, {3, 3}) == 0);
    // Three points that round to collinear in naive float arithmetic but are not.
    const float e = std::nextafter(1.0f, 2.0f);
    CHECK(orient2d({0.5f, 0.5f}, {12.0f, 12.0f}, {24.0f, 24.0f}) == 0);
    CHECK(orient2d({0.5f, 0.5f}, {12.0f, 12.0f}, {24.0f * e, 24.0f}) == -1);
    CHECK(orient2d({0.5f, 0.5f}, {12.0f, 12.0f}, {24.0f, 24.0f * e}) == 1);
}

TEST_CASE("orient3d and orient2d agree with big-integer arithmetic", "[narrow][predicates]") {
    std::mt19937 rng(12345);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    std::uniform_int_distribution<int> small(-4, 4);
    int zeros = 0;
    for (int iter = 0; iter < 3000; ++iter) {
        Float3 p[4];
        const int mode = iter % 4;
        for (Float3& q : p) {
            if (mode == 0) q = {unit(rng), unit(rng), unit(rng)};
            if (mode == 1) q = {wideFloat(rng), wideFloat(rng), wideFloat(rng)};
            if (mode == 2) q = {float(small(rng)) * 0.1f, float(small(rng)) * 0.1f, float(small(rng)) * 0.1f};
            if (mode == 3) q = {float(small(rng)), float(small(rng)), float(small(rng))};
        }
        if (iter % 8 == 3 || iter % 8 == 6) {
            // d = a + s(b - a) + t(c - a) with small integers: exactly coplanar on the
            // integer grid (mode 3), nearly so on the 0.1 grid (mode 2); then sometimes
            // nudge by one ulp to land just off the plane.
            const float s = float(small(rng)), t = float(small(rng));
            const Float3 a{float(small(rng)), float(small(rng)), float(small(rng))};
            p[0] = a;
            p[3] = {a.x + s * (p[1].x - a.x) + t * (p[2].x - a.x), a.y + s * (p[1].y - a.y) + t * (p[2].y - a.y),
                    a.z + s * (p[1].z - a.z) + t * (p[2].z - a.z)};
            if (iter % 16 >= 8) p[3] = nudge(p[3], rng);
        }
        const int expected = bigOrient3d(p[0], p[1], p[2], p[3]);
        zeros += expected == 0;
        INFO("iteration " << iter);
        REQUIRE(orient3d(p[0], p[1], p[2], p[3]) == expected);
        REQUIRE(orient3dExact(p[0], p[1], p[2], p[3]) == expected);
        REQUIRE(orient3d(p[1], p[0], p[2], p[3]) == -expected);
        // The shared-plane form gives the same signs, and its collinearity filter is
        // right whenever it answers.
        const PlaneOrientation plane(p[0], p[1], p[2]);
        REQUIRE(plane.side(p[3]) == expected);
        REQUIRE(plane.side(p[0]) == 0);
        if (plane.certainlyNotCollinear()) {
            const auto projected = [&](int i, int axis) {
                return axis == 0 ? Float2{p[i].y, p[i].z} : (axis == 1 ? Float2{p[i].z, p[i].x} : Float2{p[i].x, p[i].y});
            };
            bool some_nonzero = false;
            for (int axis = 0; axis < 3; ++axis) {
                some_nonzero = some_nonzero || bigOrient2d(projected(0, axis), projected(1, axis), projected(2, axis)) != 0;
            }
            REQUIRE(some_nonzero);
        }

        const Float2 a{p[0].x, p[0].y}, b{p[1].x, p[1].y}, c{p[2].x, p[2].y};
        const int expected2 = bigOrient2d(a, b, c);
        REQUIRE(orient2d(a, b, c) == expected2);
        REQUIRE(orient2dExact(a, b, c) == expected2);
    }
    CHECK(zeros > 100);  // the degenerate cases were actually exercised
}

TEST_CASE("Exact predicates on coordinates spanning 10 to 70 binades", "[narrow][predicates]") {
    // Differences that are exact in double (narrow spans) and that are not (wide spans),
    // with coplanar or collinear constructions and one-ulp nudges: both expansion paths of
    // the exact fallback against big integers.
    std::mt19937 rng(4242);
    std::uniform_int_distribution<int> small(-3, 3), spread(10, 70), coin(0, 1);
    std::uniform_real_distribution<float> unit(0.5f, 1.0f);
    int zeros = 0;
    for (int iter = 0; iter < 4000; ++iter) {
        const int width = spread(rng);  // binades spanned
        const int top = std::uniform_int_distribution<int>(-100, 100)(rng);
        const auto value = [&] {
            const int e = top - std::uniform_int_distribution<int>(0, width)(rng);
            float v = std::ldexp(unit(rng), e);
            if (coin(rng)) v = -v;
            if (small(rng) == 0) v = 0;
            return v;
        };
        Float3 p[4];
        for (Float3& q : p) q = {value(), value(), value()};
        if (iter % 2 == 0) {
            // d = a + s (b - a) + t (c - a) with small integers, where exact in float.
            const float s = float(small(rng)), t = float(small(rng));
            p[3] = {p[0].x + s * (p[1].x - p[0].x) + t * (p[2].x - p[0].x), p[0].y + s * (p[1].y - p[0].y) + t * (p[2].y - p[0].y),
                    p[0].z + s * (p[1].z - p[0].z) + t * (p[2].z - p[0].z)};
            if (!std::isfinite(p[3].x) || !std::isfinite(p[3].y) || !std::isfinite(p[3].z)) p[3] = p[0];
            if (iter % 4 == 2) p[3] = nudge(p[3], rng);
        }
        const int expected = bigOrient3d(p[0], p[1], p[2], p[3]);
        zeros += expected == 0;
        INFO("iteration " << iter << " width " << width);
        REQUIRE(orient3dExact(p[0], p[1], p[2], p[3]) == expected);
        REQUIRE(orient3d(p[0], p[1], p[2], p[3]) == expected);
        const Float2 a{p[0].x, p[0].y}, b{p[1].x, p[1].y};
        Float2 c{p[2].x, p[2].y};
        if (iter % 2 == 0) c = {p[3].x, p[3].y};
        const int expected2 = bigOrient2d(a, b, c);
        REQUIRE(orient2dExact(a, b, c) == expected2);
        REQUIRE(orient2d(a, b, c) == expected2);
    }
    CHECK(zeros > 20);  // coplanar cases occur (many constructions round off the plane)
}

TEST_CASE("Shared coordinates (axis-aligned contacts, the filters' zero shortcut) agree with big-integer arithmetic",
          "[narrow][predicates]") {
    // Coordinates from a few values, so that many differences are exactly zero (points on
    // common axis-aligned planes and lines, as boxes resting on boxes give), mixed with
    // values one ulp apart, subnormals and huge ones, where a product may be tiny or a
    // difference inexact.
    std::mt19937 rng(20261125);
    const float values[] = {0.0f, 1.0f, -1.0f, 0.5f, std::nextafter(1.0f, 2.0f), 3.0f, 1e-45f, -1e-45f, 1e-38f, 1e30f, -1e30f, 7.25e-20f};
    std::uniform_int_distribution<int> pick(0, static_cast<int>(std::size(values)) - 1);
    std::uniform_int_distribution<int> free_axis(0, 3);
    auto point = [&](int fixed) {
        Float3 p{values[pick(rng)], values[pick(rng)], values[pick(rng)]};
        if (fixed == 0) p.x = 1.0f;  // all four points on x = 1 in this draw
        if (fixed == 1) p.y = 1.0f;
        if (fixed == 2) p.z = 1.0f;
        return p;
    };
    int zeros = 0;
    for (int i = 0; i < 200000; ++i) {
        const int fixed = free_axis(rng);
        const Float3 a = point(fixed), b = point(fixed), c = point(fixed), d = point(fixed);
        const int expected = bigOrient3d(a, b, c, d);
        zeros += expected == 0;
        REQUIRE(orient3d(a, b, c, d) == expected);
        REQUIRE(PlaneOrientation(a, b, c).side(d) == expected);
        const Float2 p{a.x, a.y}, q{b.x, b.y}, r{c.x, c.z};
        REQUIRE(orient2d(p, q, r) == bigOrient2d(p, q, r));
    }
    CHECK(zeros > 100000);  // the shortcut's case is most of them
}

TEST_CASE("Tilted grids (coplanar contacts off the axes, the exact-product shortcuts) agree with big-integer arithmetic",
          "[narrow][predicates]") {
    // Points of a grid of few bits mapped by a linear map with dyadic entries: the plane
    // through three of them holds the fourth exactly but no difference is zero, so the
    // filters fail and the exact paths run; the products have few bits, so the exact
    // paths' shortcuts (exact products and sums in double) decide. Mixed with one-ulp
    // nudges and with grids of many bits (products and sums that round), where the
    // shortcuts must hand over to the expansions. One PlaneOrientation serves several d
    // (its cached cross product).
    std::mt19937 rng(13003);
    std::uniform_int_distribution<int> cell(-64, 64), entry(-8, 8), kind(0, 3);
    int zeros = 0, collinear = 0;
    for (int iter = 0; iter < 20000; ++iter) {
        const int k = kind(rng);
        const float scale = k == 3 ? 1.0f / 3.0f : 1.0f / 64.0f;  // 1/3: many bits
        float m[9];
        for (float& e : m) e = float(entry(rng)) / 8.0f;
        m[0] += 1, m[4] += 1, m[8] += 1;
        const auto grid = [&](int u, int v, int w) {
            const float x = float(u) * scale, y = float(v) * scale, z = float(w) * scale;
            return Float3{m[0] * x + m[1] * y + m[2] * z, m[3] * x + m[4] * y + m[5] * z, m[6] * x + m[7] * y + m[8] * z};
        };
        const int plane_w = cell(rng);  // every point on the grid's plane w = plane_w
        const Float3 a = grid(cell(rng), cell(rng), plane_w), b = grid(cell(rng), cell(rng), plane_w),
                     c = grid(cell(rng), cell(rng), plane_w);
        const PlaneOrientation plane(a, b, c);
        for (int j = 0; j < 4; ++j) {
            Float3 d = grid(cell(rng), cell(rng), j == 3 ? plane_w + 1 : plane_w);
            if (k == 1 && j == 2) d = nudge(d, rng);
            const int expected = bigOrient3d(a, b, c, d);
            zeros += expected == 0;
            INFO("iteration " << iter << " point " << j);
            REQUIRE(orient3d(a, b, c, d) == expected);
            REQUIRE(orient3dExact(a, b, c, d) == expected);
            REQUIRE(plane.side(d) == expected);
            const Float2 p{a.x, a.y}, q{b.x, b.y}, r{d.x, d.y};
            const int expected2 = bigOrient2d(p, q, r);
            REQUIRE(orient2d(p, q, r) == expected2);
            REQUIRE(orient2dExact(p, q, r) == expected2);
        }
        // Collinear in 2D: three grid points on one line (a shared diagonal of a grid).
        const int u = cell(rng) / 2, v = cell(rng) / 2, du = cell(rng) / 4, dv = cell(rng) / 4;
        const Float3 s0 = grid(u, v, plane_w), s1 = grid(u + du, v + dv, plane_w), s2 = grid(u + 2 * du, v + 2 * dv, plane_w);
        const Float2 p{s0.x, s0.z}, q{s1.x, s1.z}, r{s2.x, s2.z};
        const int expected2 = bigOrient2d(p, q, r);
        collinear += expected2 == 0;
        REQUIRE(orient2d(p, q, r) == expected2);
        REQUIRE(orient2dExact(p, q, r) == expected2);
    }
    CHECK(zeros > 20000);     // the coplanar case is most of them
    CHECK(collinear > 10000);  // and the collinear one
}
