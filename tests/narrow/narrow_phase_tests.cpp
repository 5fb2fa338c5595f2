// runNarrowPhase: validation, filters, neighbours, responses, statistics, determinism.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "narrow/neighbours.hpp"
#include "narrow/printers.hpp"
#include "narrow/same_result.hpp"
#include "vkcollide/thread_pool.hpp"
#include "narrow/triangle_intersection.hpp"
#include "vkcollide/narrow.hpp"

using namespace vkcollide;

namespace {

// A candidate whose box is its own xy extent and whose depth is its z extent.
CandidateTriangle candidate(std::uint32_t object, std::uint32_t triangle, Float3 a, Float3 b, Float3 c,
                            std::array<std::uint32_t, 3> indices = {0, 1, 2}) {
    CandidateTriangle t{};
    t.object = object;
    t.triangle = triangle;
    std::copy(indices.begin(), indices.end(), t.vertex_index);
    t.v[0] = a;
    t.v[1] = b;
    t.v[2] = c;
    t.box[0] = std::min({a.x, b.x, c.x});
    t.box[1] = std::min({a.y, b.y, c.y});
    t.box[2] = std::max({a.x, b.x, c.x});
    t.box[3] = std::max({a.y, b.y, c.y});
    t.zmin = std::min({a.z, b.z, c.z});
    t.zmax = std::max({a.z, b.z, c.z});
    return t;
}

// Object 0: a triangle in z = 0 (normal +z); object 1: a vertical one crossing it
// (normal -y).
CandidateTriangle flat(std::uint32_t object = 0, std::uint32_t triangle = 0) {
    return candidate(object, triangle, {0, 0, 0}, {2, 0, 0}, {0, 2, 0});
}
CandidateTriangle wall(std::uint32_t object = 1, std::uint32_t triangle = 0) {
    return candidate(object, triangle, {-1, 0.5f, -1}, {3, 0.5f, -1}, {1, 0.5f, 1}, {3, 4, 5});
}

// A thin triangle of `object` piercing flat() at (0.25, 0.25, 0), far from wall().
CandidateTriangle needle(std::uint32_t object, std::uint32_t triangle) {
    return candidate(object, triangle, {0.25f, 0.25f, -1}, {0.25f, 0.25f, 1}, {0.1f, 0.1f, 0}, {8, 9, 10});
}


void requireIdentical(const NarrowResult& a, const NarrowResult& b) {
    test::requireSamePairsAndResponses(a, b);
    REQUIRE(a.stats.candidates == b.stats.candidates);
    REQUIRE(a.stats.potentially_colliding_triangles == b.stats.potentially_colliding_triangles);
    REQUIRE(a.stats.sap_pairs == b.stats.sap_pairs);
    REQUIRE(a.stats.filtered_pairs == b.stats.filtered_pairs);
    REQUIRE(a.stats.neighbour_pairs == b.stats.neighbour_pairs);
    REQUIRE(a.stats.triangle_tests == b.stats.triangle_tests);
    REQUIRE(a.stats.positive_tests == b.stats.positive_tests);
}

}  // namespace

TEST_CASE("runNarrowPhase rejects bad candidates and names them", "[narrow][phase][errors]") {
    ThreadPool pool(1);
    std::vector<CandidateTriangle> c = {flat(3, 7), wall()};
    SECTION("non-finite vertex") {
        c[0].v[1].y = NAN;
        const auto r = runNarrowPhase(c, {}, pool);
        REQUIRE_FALSE(r);
        CHECK(r.error().code() == ErrorCode::InvalidArgument);
        CHECK_THAT(r.error().message(), Catch::Contains("object 3 triangle 7") && Catch::Contains("non-finite vertex"));
    }
    SECTION("infinite vertex") {
        c[1].v[2].z = INFINITY;
        const auto r = runNarrowPhase(c, {}, pool);
        REQUIRE_FALSE(r);
        CHECK_THAT(r.error().message(), Catch::Contains("object 1 triangle 0"));
    }
    SECTION("non-finite box") {
        c[0].box[2] = NAN;
        const auto r = runNarrowPhase(c, {}, pool);
        REQUIRE_FALSE(r);
        CHECK_THAT(r.error().message(), Catch::Contains("object 3 triangle 7") && Catch::Contains("box"));
    }
    SECTION("inverted box") {
        std::swap(c[1].zmin, c[1].zmax);
        const auto r = runNarrowPhase(c, {}, pool);
        REQUIRE_FALSE(r);
        CHECK(r.error().code() == ErrorCode::InvalidArgument);
        CHECK_THAT(r.error().message(), Catch::Contains("object 1 triangle 0") && Catch::Contains("zmin <= zmax"));
    }
    SECTION("duplicate triangle") {
        c.push_back(flat(3, 7));
        const auto r = runNarrowPhase(c, {}, pool);
        REQUIRE_FALSE(r);
        CHECK_THAT(r.error().message(), Catch::Contains("object 3 triangle 7") && Catch::Contains("more than once"));
    }
}

TEST_CASE("runNarrowPhase finds duplicates in sorted and unsorted input", "[narrow][phase][errors]") {
    // Candidates in (object, triangle) order, as the GPU writes them, except for one
    // repeated key; at a task border of the parallel validation and inside a task.
    ThreadPool pool(3);
    for (std::uint32_t repeat_at : {1u, 4000u, 8192u, 8193u, 11999u}) {
        std::vector<CandidateTriangle> c;
        for (std::uint32_t i = 0; i < 12000; ++i) {
            const float x = float(i) * 3;
            c.push_back(candidate(i / 5000, i % 5000, {x, 0, 0}, {x + 1, 0, 0}, {x, 1, 0}));
        }
        c[repeat_at].object = c[repeat_at - 1].object;
        c[repeat_at].triangle = c[repeat_at - 1].triangle;
        const auto r = runNarrowPhase(c, {}, pool);
        REQUIRE_FALSE(r);
        CHECK_THAT(r.error().message(), Catch::Contains("triangle " + std::to_string((repeat_at - 1) % 5000) + " appears more than once"));
    }
    std::vector<CandidateTriangle> ok;
    for (std::uint32_t i = 0; i < 12000; ++i) ok.push_back(candidate(0, 11999 - i, {float(i), 0, 0}, {float(i) + 1, 0, 0}, {float(i), 1, 0}));
    CHECK(runNarrowPhase(ok, {}, pool));  // descending keys: sorted, no duplicate
}

TEST_CASE("runNarrowPhase finds a crossing pair with paper statistics", "[narrow][phase]") {
    ThreadPool pool(2);
    const std::vector<CandidateTriangle> c = {wall(5, 9), flat(2, 4), candidate(3, 0, {10, 10, 0}, {11, 10, 0}, {10, 11, 0})};
    const auto r = runNarrowPhase(c, {}, pool);
    REQUIRE(r);
    REQUIRE(r->pairs == std::vector<TrianglePair>{{2, 4, 5, 9}});
    CHECK(r->stats.candidates == 3);
    CHECK(r->stats.potentially_colliding_triangles == 2);
    CHECK(r->stats.sap_pairs == 1);
    CHECK(r->stats.triangle_tests == 1);
    CHECK(r->stats.positive_tests == 1);

    // Responses: n_flat = +z, n_wall = -y; r_flat = normalize(n_wall - n_flat).
    REQUIRE(r->responses.size() == 2);
    const float h = static_cast<float>(std::sqrt(0.5));
    const TriangleResponse& rf = r->responses[0];
    const TriangleResponse& rw = r->responses[1];
    CHECK((rf.object == 2 && rf.triangle == 4 && rf.partner_count == 1));
    CHECK((rw.object == 5 && rw.triangle == 9 && rw.partner_count == 1));
    CHECK(rf.direction.x == Approx(0).margin(1e-7));
    CHECK(rf.direction.y == Approx(-h));
    CHECK(rf.direction.z == Approx(-h));
    CHECK(rw.direction.y == Approx(h));
    CHECK(rw.direction.z == Approx(h));
}

TEST_CASE("runNarrowPhase trusts the boxes: no z overlap, no test", "[narrow][phase]") {
    ThreadPool pool(1);
    std::vector<CandidateTriangle> c = {flat(), wall()};
    c[1].zmin = 0.5f;  // pretend the GPU saw the wall only above the floor
    const auto r = runNarrowPhase(c, {}, pool);
    REQUIRE(r);
    CHECK(r->pairs.empty());
    CHECK(r->stats.sap_pairs == 0);
    CHECK(r->stats.potentially_colliding_triangles == 0);
    CHECK(r->stats.triangle_tests == 0);
}

TEST_CASE("Neighbours within an object are skipped, other self-intersections are found", "[narrow][phase][neighbours]") {
    ThreadPool pool(2);
    // Two triangles of object 0 that share vertex index 1 and touch there.
    const CandidateTriangle a = candidate(0, 0, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 1, 2});
    const CandidateTriangle shared_index = candidate(0, 1, {1, 0, 0}, {2, 0, 0}, {1, 1, 1}, {1, 3, 4});
    // Same position as vertex 1 of `a`, but a different index (a seam): still neighbours.
    const CandidateTriangle shared_position = candidate(0, 2, {1, 0, 0}, {2, 0, -1}, {1, -1, 1}, {5, 6, 7});
    // Crosses `a` without sharing anything: a real self-intersection.
    const CandidateTriangle crossing = needle(0, 3);
    const std::vector<CandidateTriangle> c = {a, shared_index, shared_position, crossing};
    const auto r = runNarrowPhase(c, {}, pool);
    REQUIRE(r);
    CHECK(r->pairs == std::vector<TrianglePair>{{0, 0, 0, 3}});
    CHECK(r->stats.neighbour_pairs >= 2);
    CHECK(r->stats.sap_pairs == r->stats.filtered_pairs + r->stats.neighbour_pairs + r->stats.triangle_tests);

    // The same two touching triangles in different objects do collide.
    std::vector<CandidateTriangle> two_objects = {a, shared_index};
    two_objects[1].object = 1;
    const auto r2 = runNarrowPhase(two_objects, {}, pool);
    REQUIRE(r2);
    CHECK(r2->pairs == std::vector<TrianglePair>{{0, 0, 1, 1}});
}

TEST_CASE("NarrowOptions filter object pairs and self-collision", "[narrow][phase][filter]") {
    ThreadPool pool(2);
    const std::vector<CandidateTriangle> c = {
        flat(0, 0), wall(1, 0),
        candidate(2, 0, {-1, 1, -1}, {3, 1, -1}, {1, 1, 1}),  // parallel to the wall, crosses the floor
        needle(0, 1),  // self-crossing object 0
    };
    SECTION("defaults: everything collides") {
        const auto r = runNarrowPhase(c, {}, pool);
        REQUIRE(r);
        CHECK(r->pairs == std::vector<TrianglePair>{{0, 0, 0, 1}, {0, 0, 1, 0}, {0, 0, 2, 0}});
    }
    SECTION("self-collision off for object 0") {
        NarrowOptions options;
        options.self_collision = {false};
        const auto r = runNarrowPhase(c, options, pool);
        REQUIRE(r);
        CHECK(r->pairs == std::vector<TrianglePair>{{0, 0, 1, 0}, {0, 0, 2, 0}});
        // Pairs within an object that does not self-collide are never formed, so they are
        // neither candidate pairs nor filtered ones.
        const auto all = runNarrowPhase(c, {}, pool);
        REQUIRE(all);
        CHECK(r->stats.filtered_pairs == 0);
        CHECK(r->stats.sap_pairs + 1 == all->stats.sap_pairs);
        CHECK(r->stats.sap_pairs == r->stats.filtered_pairs + r->stats.neighbour_pairs + r->stats.triangle_tests);
    }
    SECTION("self-collision off by default, on for object 0") {
        NarrowOptions options;
        options.default_self_collision = false;
        options.self_collision = {true};
        const auto r = runNarrowPhase(c, options, pool);
        REQUIRE(r);
        CHECK(r->pairs.size() == 3);
    }
    SECTION("object pair filter") {
        NarrowOptions options;
        std::vector<std::pair<std::uint32_t, std::uint32_t>> asked;
        options.may_collide = [&](std::uint32_t a, std::uint32_t b) {
            asked.emplace_back(a, b);
            return !(a == 0 && b == 2);
        };
        const auto r = runNarrowPhase(c, options, pool);
        REQUIRE(r);
        CHECK(r->pairs == std::vector<TrianglePair>{{0, 0, 0, 1}, {0, 0, 1, 0}});
        for (const auto& [a, b] : asked) CHECK(a < b);
        CHECK(r->stats.filtered_pairs == 1);
    }
}

TEST_CASE("may_collide is asked once per object pair with overlapping boxes, in ascending order", "[narrow][phase][filter]") {
    // Objects 0..3: 0, 1 and 2 stack their floors on each other (many overlapping pairs per
    // object pair), 3 is far away (never asked).
    std::vector<CandidateTriangle> c;
    for (std::uint32_t object : {2u, 0u, 1u}) {
        for (std::uint32_t t = 0; t < 40; ++t) {
            const float x = float(t % 8) * 0.5f, z = float(object) * 0.1f;
            c.push_back(candidate(object, t, {x, 0, z}, {x + 1, 0, z + 0.25f}, {x, 1, z}, {3 * t, 3 * t + 1, 3 * t + 2}));
        }
    }
    c.push_back(candidate(3, 0, {50, 50, 0}, {51, 50, 0}, {50, 51, 0}));
    for (unsigned threads : {1u, 4u}) {
        ThreadPool pool(threads);
        std::vector<std::pair<std::uint32_t, std::uint32_t>> asked;
        NarrowOptions options;
        options.may_collide = [&](std::uint32_t a, std::uint32_t b) {
            asked.emplace_back(a, b);
            return !(a == 0 && b == 2);
        };
        const auto r = runNarrowPhase(c, options, pool);
        REQUIRE(r);
        INFO(threads << " threads");
        CHECK(asked == std::vector<std::pair<std::uint32_t, std::uint32_t>>{{0, 1}, {0, 2}, {1, 2}});
        for (const TrianglePair& p : r->pairs) CHECK_FALSE((p.object_a == 0 && p.object_b == 2));
        CHECK(r->stats.filtered_pairs > 0);
        CHECK(r->stats.sap_pairs == r->stats.filtered_pairs + r->stats.neighbour_pairs + r->stats.triangle_tests);
    }
}

TEST_CASE("Response of coplanar same-facing partners is zero", "[narrow][phase][response]") {
    ThreadPool pool(1);
    const std::vector<CandidateTriangle> c = {flat(0, 0), candidate(1, 0, {0.5f, 0.5f, 0}, {3, 0.5f, 0}, {0.5f, 3, 0})};
    const auto r = runNarrowPhase(c, {}, pool);
    REQUIRE(r);
    REQUIRE(r->pairs.size() == 1);
    REQUIRE(r->responses.size() == 2);
    for (const TriangleResponse& resp : r->responses) {
        CHECK(resp.direction.x == 0);
        CHECK(resp.direction.y == 0);
        CHECK(resp.direction.z == 0);
    }
}

TEST_CASE("runNarrowPhase gives identical results for any thread count and input order", "[narrow][phase][threads]") {
    std::mt19937 rng(99);
    std::uniform_real_distribution<float> pos(0.0f, 1.0f), offset(-0.08f, 0.08f);
    std::uniform_int_distribution<int> grid(0, 10);
    std::vector<CandidateTriangle> c;
    for (std::uint32_t i = 0; i < 3000; ++i) {
        const std::uint32_t object = i % 6;
        Float3 v[3];
        if (i % 3 == 0) {  // snapped to a grid: many exact touches and coplanar pairs
            const Float3 base{float(grid(rng)) / 10, float(grid(rng)) / 10, float(grid(rng)) / 10};
            for (Float3& p : v) p = {base.x + float(grid(rng) % 3) / 10, base.y + float(grid(rng) % 3) / 10, base.z};
        } else {
            const Float3 base{pos(rng), pos(rng), pos(rng)};
            for (Float3& p : v) p = {base.x + offset(rng), base.y + offset(rng), base.z + offset(rng)};
        }
        c.push_back(candidate(object, i / 6, v[0], v[1], v[2], {3 * i, 3 * i + 1, 3 * i + 2}));
    }
    NarrowOptions options;
    options.self_collision = {true, false, true};
    options.may_collide = [](std::uint32_t a, std::uint32_t b) { return (a + b) % 5 != 0; };

    ThreadPool pool1(1);
    const auto reference = runNarrowPhase(c, options, pool1);
    REQUIRE(reference);
    REQUIRE(reference->pairs.size() > 100);
    REQUIRE(std::is_sorted(reference->pairs.begin(), reference->pairs.end()));
    for (const TrianglePair& p : reference->pairs) {
        REQUIRE(std::pair(p.object_a, p.triangle_a) < std::pair(p.object_b, p.triangle_b));
    }

    // Against the definition: all box-overlapping, allowed, non-neighbour pairs, tested.
    std::vector<TrianglePair> brute;
    for (std::size_t i = 0; i < c.size(); ++i) {
        for (std::size_t j = i + 1; j < c.size(); ++j) {
            const CandidateTriangle &a = c[i], &b = c[j];
            if (a.box[0] > b.box[2] || b.box[0] > a.box[2] || a.box[1] > b.box[3] || b.box[1] > a.box[3] ||
                a.zmin > b.zmax || b.zmin > a.zmax) {
                continue;
            }
            if (a.object == b.object ? !options.selfCollides(a.object)
                                     : !options.may_collide(std::min(a.object, b.object), std::max(a.object, b.object))) {
                continue;
            }
            if (a.object == b.object && narrow::areNeighbours(a.vertex_index, a.v, b.vertex_index, b.v)) continue;
            if (!narrow::trianglesIntersect(a.v, b.v)) continue;
            TrianglePair p{a.object, a.triangle, b.object, b.triangle};
            if (std::pair(b.object, b.triangle) < std::pair(a.object, a.triangle)) p = {b.object, b.triangle, a.object, a.triangle};
            brute.push_back(p);
        }
    }
    std::sort(brute.begin(), brute.end());
    CHECK(reference->pairs == brute);
    CHECK(reference->stats.neighbour_pairs > 0);  // grid triangles share positions

    for (unsigned threads : {2u, 4u, 7u}) {
        ThreadPool pool(threads);
        const auto r = runNarrowPhase(c, options, pool);
        REQUIRE(r);
        INFO(threads << " threads");
        requireIdentical(*reference, *r);
    }
    std::vector<CandidateTriangle> shuffled = c;
    std::shuffle(shuffled.begin(), shuffled.end(), rng);
    ThreadPool pool3(3);
    const auto r = runNarrowPhase(shuffled, options, pool3);
    REQUIRE(r);
    requireIdentical(*reference, *r);
}

TEST_CASE("A reused workspace gives the results of fresh calls", "[narrow][phase][workspace]") {
    // Inputs of different sizes and orders through one workspace: nothing of an earlier
    // call may leak into a later one.
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> pos(0.0f, 1.0f), offset(-0.06f, 0.06f);
    const auto scene = [&](std::uint32_t count) {
        std::vector<CandidateTriangle> c;
        for (std::uint32_t i = 0; i < count; ++i) {
            const Float3 base{pos(rng), pos(rng), pos(rng)};
            Float3 v[3];
            for (Float3& p : v) p = {base.x + offset(rng), base.y + offset(rng), base.z + offset(rng)};
            c.push_back(candidate(i % 4, i / 4, v[0], v[1], v[2], {3 * i, 3 * i + 1, 3 * i + 2}));
        }
        return c;
    };
    std::vector<std::vector<CandidateTriangle>> inputs = {scene(4000), scene(300), scene(2500)};
    inputs.push_back(inputs[0]);
    std::shuffle(inputs.back().begin(), inputs.back().end(), rng);  // unsorted keys: the sorting path
    inputs.push_back({});                                            // empty
    inputs.push_back(scene(1000));
    NarrowOptions options;
    options.may_collide = [](std::uint32_t a, std::uint32_t b) { return a + b != 3; };
    options.self_collision = {true, false};
    for (unsigned threads : {1u, 3u}) {
        ThreadPool pool(threads);
        NarrowWorkspace workspace;
        for (std::size_t k = 0; k < inputs.size(); ++k) {
            INFO(threads << " threads, input " << k);
            const auto fresh = runNarrowPhase(inputs[k], options, pool);
            const auto reused = runNarrowPhase(inputs[k], options, pool, workspace);
            REQUIRE((fresh && reused));
            requireIdentical(*fresh, *reused);
            if (k == 2) {  // a moved-from workspace still works
                NarrowWorkspace other = std::move(workspace);
                const auto moved = runNarrowPhase(inputs[k], options, pool, workspace);
                REQUIRE(moved);
                requireIdentical(*fresh, *moved);
                workspace = std::move(other);
            }
        }
    }
}

TEST_CASE("runNarrowPhase's pairs come out sorted whatever the number of radix passes over the hits", "[narrow][phase][order]") {
    // The record path sorts its hits by (lower slot, higher slot) keys of 32 + bits(slots)
    // bits, 8 per pass, the buffers swapping each pass: up to 2^16 slots take six passes,
    // more take seven (an odd count, where the sorted keys end in the scratch buffer). Hits
    // above and below the serial sort's threshold; far-away candidates add slots, not hits.
    struct Case {
        std::uint32_t crossings, loners;
    };
    for (const Case k : {Case{2000, 0}, Case{2000, 70000}, Case{40000, 0}}) {
        std::vector<CandidateTriangle> c;
        std::vector<TrianglePair> want;
        for (std::uint32_t i = 0; i < k.crossings; ++i) {  // object 0's flat and object 1's needle at x = 4 i
            const float x = 4.0f * float(i);
            c.push_back(candidate(0, i, {x, 0, 0}, {x + 2, 0, 0}, {x, 2, 0}));
            c.push_back(candidate(1, i, {x + 0.25f, 0.25f, -1}, {x + 0.25f, 0.25f, 1}, {x + 0.1f, 0.1f, 0}, {8, 9, 10}));
            want.push_back({0, i, 1, i});
        }
        for (std::uint32_t i = 0; i < k.loners; ++i) {  // object 2, far above everything, apart from each other
            const float x = 4.0f * float(i);
            c.push_back(candidate(2, i, {x, 0, 100}, {x + 1, 0, 100}, {x, 1, 100}));
        }
        std::shuffle(c.begin(), c.end(), std::mt19937(k.crossings + k.loners));
        for (unsigned threads : {1u, 4u}) {
            INFO(k.crossings << " crossings, " << k.loners << " loners, " << threads << " threads");
            ThreadPool pool(threads);
            const auto r = runNarrowPhase(c, NarrowOptions{}, pool);
            REQUIRE(r);
            CHECK(r->pairs == want);
        }
    }
}
