// The lean record path (CandidateRecord + TriangleSource) and the pair path
// (runPairNarrowPhase): exact against the reference, identical to the 80-byte path,
// deterministic for every thread count, executor and input order; filters, neighbours,
// repeats, empty inputs and bad input.
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <random>
#include <thread>
#include <vector>

#include "narrow/printers.hpp"
#include "narrow/same_result.hpp"
#include "narrow/scene_builders.hpp"
#include "narrow/sweep_and_prune.hpp"
#include "support/exact_reference.hpp"
#include "vkcollide/narrow.hpp"
#include "vkcollide/thread_pool.hpp"

using namespace vkcollide;
using namespace vkcollide::test;

namespace {

void requireSameStats(const NarrowStats& a, const NarrowStats& b) {
    CHECK(a.candidates == b.candidates);
    CHECK(a.potentially_colliding_triangles == b.potentially_colliding_triangles);
    CHECK(a.sap_pairs == b.sap_pairs);
    CHECK(a.filtered_pairs == b.filtered_pairs);
    CHECK(a.neighbour_pairs == b.neighbour_pairs);
    CHECK(a.triangle_tests == b.triangle_tests);
    CHECK(a.positive_tests == b.positive_tests);
    CHECK(a.input_pairs == b.input_pairs);
}

std::array<float, 12> rows3x4(const Transform& m) {
    std::array<float, 12> r{};
    std::copy(m.begin(), m.begin() + 12, r.begin());
    return r;
}

// Rotation about a tilted axis, then a translation: every world coordinate is rounded.
Transform turned(double angle, Float3 t) {
    const double x = 0.3, y = 1.0, z = 0.2, n = std::sqrt(x * x + y * y + z * z);
    const double ux = x / n, uy = y / n, uz = z / n, c = std::cos(angle), s = std::sin(angle), k = 1 - c;
    const auto f = [](double v) { return static_cast<float>(v); };
    return transformFrom3x4({f(c + ux * ux * k), f(ux * uy * k - uz * s), f(ux * uz * k + uy * s), t.x,
                             f(uy * ux * k + uz * s), f(c + uy * uy * k), f(uy * uz * k - ux * s), t.y,
                             f(uz * ux * k - uy * s), f(uz * uy * k + ux * s), f(c + uz * uz * k), t.z});
}

// Two overlapping spheres (one turned and moved), a self-intersecting object (two spheres
// in one mesh) and a tetrahedron with an exact identity transform.
struct Scene {
    std::vector<HostMesh> meshes;
    std::vector<ReferenceObject> objects;
    std::vector<CandidateTriangle> candidates;  // every triangle, boxes over the scene

    Scene() {
        meshes.push_back(makeSphere(1.0f, {0, 0, 0}, 14, 20));
        meshes.push_back(makeSphere(0.8f, {0, 0, 0}, 12, 18));
        HostMesh folded = makeSphere(0.5f, {0, 0, 1.0f}, 8, 12);
        const HostMesh copy = makeSphere(0.5f, {0.3f, 0, 1.1f}, 8, 12);
        const auto offset = static_cast<std::uint32_t>(folded.positions.size());
        folded.positions.insert(folded.positions.end(), copy.positions.begin(), copy.positions.end());
        for (std::uint32_t i : copy.indices) folded.indices.push_back(i + offset);
        meshes.push_back(folded);
        HostMesh tetra = makeTetrahedron();
        tetra.positions[0] = {-0.0f, 0.9f, -0.0f};  // -0 must survive an identity bit for bit
        meshes.push_back(tetra);
        objects = {{&meshes[0]}, {&meshes[1], turned(0.7, {1.1f, 0.25f, 0.1f})}, {&meshes[2]}, {&meshes[3]}};
        auto c = allTrianglesAsCandidates(objects);
        REQUIRE(c);
        candidates = std::move(*c);
    }

    // The same scene as a TriangleSource; objects listed in `gpu` are GPU-only, their
    // triangles' world vertices and indices in `out_table`.
    TriangleSource source(const std::vector<bool>& gpu, std::vector<GpuTriangle>& out_table) const {
        TriangleSource s;
        out_table.clear();
        for (std::size_t o = 0; o < objects.size(); ++o) {
            const HostMesh& m = *objects[o].mesh;
            if (o < gpu.size() && gpu[o]) {
                REQUIRE(s.addGpuMesh(static_cast<std::uint32_t>(m.triangleCount())));
                const std::vector<Float3> world = worldPositions(m, objects[o].transform);
                for (std::uint32_t t = 0; t < m.triangleCount(); ++t) {
                    GpuTriangle g{};
                    g.id = s.triangleBase(static_cast<std::uint32_t>(o)) + t;
                    for (int k = 0; k < 3; ++k) {
                        g.vertex_index[k] = m.indices[3 * t + k];
                        g.v[k] = world[m.indices[3 * t + k]];
                    }
                    out_table.push_back(g);
                }
            } else {
                REQUIRE(s.addHostMesh(m.positions, m.indices, rows3x4(objects[o].transform)));
            }
        }
        s.setGpuTriangles(out_table);
        return s;
    }

    std::vector<CandidateRecord> records() const {
        std::vector<CandidateRecord> r;
        for (const CandidateTriangle& c : candidates) {
            r.push_back({c.object, c.triangle, {c.box[0], c.box[1], c.box[2], c.box[3]}, c.zmin, c.zmax});
        }
        return r;
    }

    // Every box-overlapping pair as global ids (what a GPU pair stage might send).
    std::vector<CandidatePair> pairs(const TriangleSource& s) const {
        std::vector<CandidatePair> out;
        for (const narrow::IndexPair& p : narrow::sweepAndPrunePairs(candidates)) {
            const CandidateTriangle &a = candidates[p.i], &b = candidates[p.j];
            out.push_back({s.triangleBase(a.object) + a.triangle, s.triangleBase(b.object) + b.triangle});
        }
        return out;
    }
};

NarrowOptions someOptions() {
    NarrowOptions options;
    options.self_collision = {false, true, true, false};
    options.may_collide = [](std::uint32_t a, std::uint32_t b) { return !(a == 0 && b == 3); };
    return options;
}

std::vector<ReferenceObject> withSelfCollision(std::vector<ReferenceObject> objects, const NarrowOptions& options) {
    for (std::size_t o = 0; o < objects.size(); ++o) objects[o].self_collision = options.selfCollides(static_cast<std::uint32_t>(o));
    return objects;
}

}  // namespace

TEST_CASE("TriangleSource computes world vertices as the exact reference does", "[narrow][source]") {
    const Scene scene;
    std::vector<GpuTriangle> table;
    const TriangleSource source = scene.source({}, table);
    REQUIRE(source.objectCount() == 4);
    CHECK(source.triangleBase(0) == 0);
    CHECK(source.triangleBase(1) == scene.meshes[0].triangleCount());
    CHECK(source.totalTriangles() == scene.candidates.size());
    // The lean path's world vertices are the 80-byte records' (from worldPositions): same
    // pairs and bit-identical responses, including the -0.0 of the identity object.
    ThreadPool pool(2);
    const auto lean = runNarrowPhase(scene.records(), source, {}, pool);
    const auto full = runNarrowPhase(scene.candidates, {}, pool);
    REQUIRE((lean && full));
    requireSamePairsAndResponses(*full, *lean);
    requireSameStats(full->stats, lean->stats);
    CHECK(lean->stats.neighbour_pairs > 0);
}

TEST_CASE("Lean records equal the reference and the 80-byte path, host and GPU-only meshes", "[narrow][source][reference]") {
    const Scene scene;
    const NarrowOptions options = someOptions();
    const auto reference = computeReferencePairs(withSelfCollision(scene.objects, options), {options.may_collide, 2});
    REQUIRE(reference);
    REQUIRE(reference->size() > 50);
    ThreadPool pool(3);
    const auto full = runNarrowPhase(scene.candidates, options, pool);
    REQUIRE(full);
    CHECK(full->pairs == *reference);
    for (const std::vector<bool>& gpu : {std::vector<bool>{}, std::vector<bool>{false, true, false, false},
                                         std::vector<bool>{true, true, true, true}}) {
        std::vector<GpuTriangle> table;
        const TriangleSource source = scene.source(gpu, table);
        INFO("GPU-only objects: " << table.size() << " table entries");
        const auto lean = runNarrowPhase(scene.records(), source, options, pool);
        REQUIRE(lean);
        CHECK(lean->pairs == *reference);
        requireSamePairsAndResponses(*full, *lean);
        requireSameStats(full->stats, lean->stats);
        // Table order does not matter.
        std::vector<GpuTriangle> reversed(table.rbegin(), table.rend());
        TriangleSource shuffled = source;
        shuffled.setGpuTriangles(reversed);
        const auto again = runNarrowPhase(scene.records(), shuffled, options, pool);
        REQUIRE(again);
        requireSamePairsAndResponses(*lean, *again);
    }
}

TEST_CASE("Lean and pair paths are identical for every thread count, executor and input order", "[narrow][source][pairs][threads]") {
    const Scene scene;
    const NarrowOptions options = someOptions();
    std::vector<GpuTriangle> table;
    const TriangleSource source = scene.source({false, false, true, false}, table);
    ThreadPool pool1(1);
    const auto lean = runNarrowPhase(scene.records(), source, options, pool1);
    REQUIRE(lean);
    std::vector<CandidatePair> pairs = scene.pairs(source);
    const auto from_pairs = runPairNarrowPhase(pairs, source, options, pool1);
    REQUIRE(from_pairs);
    // The pair path tests exactly the record path's candidate pairs here.
    requireSamePairsAndResponses(*lean, *from_pairs);
    CHECK(from_pairs->stats.input_pairs == pairs.size());
    CHECK(from_pairs->stats.positive_tests == lean->stats.positive_tests);

    std::mt19937 rng(31);
    std::vector<CandidateRecord> records = scene.records();
    // Repeats (some reversed) and a shuffle must not change anything but input_pairs.
    std::vector<CandidatePair> noisy = pairs;
    for (std::size_t k = 0; k < pairs.size(); k += 3) noisy.push_back({pairs[k].b, pairs[k].a});
    for (std::size_t k = 0; k < pairs.size(); k += 7) noisy.push_back(pairs[k]);
    const CallbackExecutor engine(3, [](std::size_t task_count, const std::function<void(std::size_t)>& run) {
        std::vector<std::thread> threads;
        for (std::size_t t = 0; t < 3; ++t) threads.emplace_back([&, t] {
            for (std::size_t k = t; k < task_count; k += 3) run(k);
        });
        for (std::thread& thread : threads) thread.join();
    });
    for (unsigned threads : {2u, 4u, 7u, 0u}) {
        std::shuffle(records.begin(), records.end(), rng);
        std::shuffle(noisy.begin(), noisy.end(), rng);
        ThreadPool pool(threads == 0 ? 1 : threads);
        CallbackExecutor engine_copy = engine;
        Executor& ex = threads == 0 ? static_cast<Executor&>(engine_copy) : static_cast<Executor&>(pool);
        INFO((threads == 0 ? "engine executor" : "threads: ") << threads);
        NarrowWorkspace workspace;
        const auto r = runNarrowPhase(records, source, options, ex, workspace);
        REQUIRE(r);
        requireSamePairsAndResponses(*lean, *r);
        requireSameStats(lean->stats, r->stats);
        const auto p = runPairNarrowPhase(noisy, source, options, ex, workspace);
        REQUIRE(p);
        requireSamePairsAndResponses(*from_pairs, *p);
        CHECK(p->stats.input_pairs == noisy.size());
        CHECK(p->stats.sap_pairs == from_pairs->stats.sap_pairs);
        CHECK(p->stats.triangle_tests == from_pairs->stats.triangle_tests);
        CHECK(p->stats.filtered_pairs == from_pairs->stats.filtered_pairs);
        CHECK(p->stats.neighbour_pairs == from_pairs->stats.neighbour_pairs);
    }
}

TEST_CASE("Pair path: statistics, neighbours, self-collision and the object filter", "[narrow][pairs]") {
    // Object 0: a floor triangle and three more sharing an index, a position, nothing with it.
    HostMesh floor;
    floor.positions = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0},          // 0: the floor
                       {2, 0, 0}, {1, -1, 1}, {1, 1, -1},        // triangle 1 reuses the position of vertex 1
                       {0.25f, 0.25f, -1}, {0.25f, 0.25f, 1}, {0.1f, 0.1f, 0}};  // triangle 3: a needle through the floor
    floor.indices = {0, 1, 2, 3, 4, 5, 1, 4, 5, 6, 7, 8};  // triangle 2 shares index 1 with the floor
    HostMesh wall;  // object 1: crosses the floor
    wall.positions = {{-1, 0.5f, -1}, {3, 0.5f, -1}, {1, 0.5f, 1}};
    wall.indices = {0, 1, 2};
    TriangleSource source;
    REQUIRE(*source.addHostMesh(floor.positions, floor.indices) == 0);
    REQUIRE(*source.addHostMesh(wall.positions, wall.indices) == 1);
    REQUIRE(source.totalTriangles() == 5);
    const std::vector<CandidatePair> pairs = {{0, 1}, {2, 0}, {0, 3}, {4, 0}, {0, 4}, {3, 4}, {1, 0}};
    ThreadPool pool(2);

    const auto r = runPairNarrowPhase(pairs, source, {}, pool);
    REQUIRE(r);
    // (0,1) position neighbours, (0,2) index neighbours, (0,3) needle crosses the floor,
    // (0,4) wall crosses the floor, (3,4) needle misses the wall.
    CHECK(r->pairs == std::vector<TrianglePair>{{0, 0, 0, 3}, {0, 0, 1, 0}});
    CHECK(r->stats.input_pairs == 7);
    CHECK(r->stats.sap_pairs == 5);
    CHECK(r->stats.candidates == 5);
    CHECK(r->stats.potentially_colliding_triangles == 5);
    CHECK(r->stats.neighbour_pairs == 2);
    CHECK(r->stats.filtered_pairs == 0);
    CHECK(r->stats.triangle_tests == 3);
    CHECK(r->stats.positive_tests == 2);
    REQUIRE(r->responses.size() == 3);
    CHECK(r->responses[0].partner_count == 2);

    NarrowOptions no_self;
    no_self.default_self_collision = false;
    const auto r2 = runPairNarrowPhase(pairs, source, no_self, pool);
    REQUIRE(r2);
    CHECK(r2->pairs == std::vector<TrianglePair>{{0, 0, 1, 0}});
    CHECK(r2->stats.filtered_pairs == 3);  // the three pairs within object 0
    CHECK(r2->stats.sap_pairs == r2->stats.filtered_pairs + r2->stats.neighbour_pairs + r2->stats.triangle_tests);

    NarrowOptions filter;
    std::vector<std::pair<std::uint32_t, std::uint32_t>> asked;
    filter.may_collide = [&](std::uint32_t a, std::uint32_t b) {
        asked.emplace_back(a, b);
        return false;
    };
    const auto r3 = runPairNarrowPhase(pairs, source, filter, pool);
    REQUIRE(r3);
    CHECK(r3->pairs == std::vector<TrianglePair>{{0, 0, 0, 3}});
    CHECK(asked == std::vector<std::pair<std::uint32_t, std::uint32_t>>{{0, 1}});
    CHECK(r3->stats.filtered_pairs == 2);
}

TEST_CASE("Lean and pair paths accept empty inputs", "[narrow][source][pairs]") {
    ThreadPool pool(2);
    TriangleSource empty;
    const auto a = runNarrowPhase(std::span<const CandidateRecord>{}, empty, {}, pool);
    const auto b = runPairNarrowPhase({}, empty, {}, pool);
    REQUIRE((a && b));
    CHECK(a->pairs.empty());
    CHECK(b->pairs.empty());
    CHECK(b->stats.sap_pairs == 0);
    const HostMesh tetra = makeTetrahedron();
    TriangleSource one;
    REQUIRE(one.addHostMesh(tetra.positions, tetra.indices));
    REQUIRE(one.addGpuMesh(0));  // an empty GPU mesh is allowed
    const auto c = runPairNarrowPhase({}, one, {}, pool);
    REQUIRE(c);
    CHECK(c->stats.candidates == 0);
}

TEST_CASE("Bad ids and bad geometry are named errors", "[narrow][source][pairs][errors]") {
    const HostMesh tetra = makeTetrahedron("tetra");
    HostMesh broken = makeTetrahedron("broken");
    broken.indices[4] = 9;  // triangle 1 points past the 4 vertices
    HostMesh nan_mesh = makeTetrahedron("nan");
    nan_mesh.positions[3].y = NAN;  // used by triangles 1, 2 and 3
    TriangleSource source;
    REQUIRE(source.addHostMesh(tetra.positions, tetra.indices));   // object 0: ids 0..3
    REQUIRE(source.addHostMesh(broken.positions, broken.indices)); // object 1: ids 4..7
    REQUIRE(source.addHostMesh(nan_mesh.positions, nan_mesh.indices)); // object 2: ids 8..11
    REQUIRE(source.addGpuMesh(2));                                 // object 3: ids 12..13
    ThreadPool pool(2);
    const auto record = [](std::uint32_t object, std::uint32_t triangle) {
        return CandidateRecord{object, triangle, {0, 0, 1, 1}, 0, 1};
    };
    const auto message = [](const auto& r) { return r ? std::string("no error") : r.error().message(); };

    SECTION("records naming what the source does not have") {
        const std::vector<CandidateRecord> a = {record(0, 0), record(7, 0)};
        const auto r = runNarrowPhase(a, source, {}, pool);
        REQUIRE_FALSE(r);
        CHECK(r.error().code() == ErrorCode::InvalidArgument);
        CHECK_THAT(message(r), Catch::Contains("object 7 triangle 0") && Catch::Contains("4 objects"));
        const std::vector<CandidateRecord> b = {record(0, 4)};
        CHECK_THAT(message(runNarrowPhase(b, source, {}, pool)), Catch::Contains("object 0 triangle 4") && Catch::Contains("4 triangles"));
        std::vector<CandidateRecord> c = {record(0, 1), record(0, 1)};
        CHECK_THAT(message(runNarrowPhase(c, source, {}, pool)), Catch::Contains("object 0 triangle 1 appears more than once"));
        c = {record(0, 1)};
        c[0].box[2] = -1;
        CHECK_THAT(message(runNarrowPhase(c, source, {}, pool)), Catch::Contains("empty box"));
    }
    SECTION("an index out of range, a non-finite vertex") {
        const std::vector<CandidateRecord> a = {record(0, 0), record(1, 1)};
        const auto r = runNarrowPhase(a, source, {}, pool);
        REQUIRE_FALSE(r);
        CHECK(r.error().code() == ErrorCode::InvalidMesh);
        CHECK_THAT(message(r), Catch::Contains("object 1 triangle 1") && Catch::Contains("index 9 is out of range"));
        const std::vector<CandidatePair> p = {{0, 9}};
        const auto q = runPairNarrowPhase(p, source, {}, pool);
        REQUIRE_FALSE(q);
        CHECK(q.error().code() == ErrorCode::InvalidMesh);
        CHECK_THAT(message(q), Catch::Contains("object 2 triangle 1") && Catch::Contains("not finite"));
    }
    SECTION("pairs with ids out of range or a triangle paired with itself") {
        std::vector<CandidatePair> p = {{0, 1}, {2, 14}};
        const auto r = runPairNarrowPhase(p, source, {}, pool);
        REQUIRE_FALSE(r);
        CHECK(r.error().code() == ErrorCode::InvalidArgument);
        CHECK_THAT(message(r), Catch::Contains("pair 1 (2, 14)") && Catch::Contains("14 triangles"));
        p = {{0, 1}, {1, 2}, {5, 5}};
        CHECK_THAT(message(runPairNarrowPhase(p, source, {}, pool)),
                   Catch::Contains("pair 2 (5, 5)") && Catch::Contains("object 1 triangle 1 with itself"));
    }
    SECTION("GPU-only triangles: missing from the table, or twice in it") {
        const std::vector<CandidatePair> p = {{0, 12}};
        auto r = runPairNarrowPhase(p, source, {}, pool);
        REQUIRE_FALSE(r);
        CHECK_THAT(message(r), Catch::Contains("object 3 triangle 0 (global id 12) has no entry in the GPU triangle table"));
        std::vector<GpuTriangle> table(2);
        table[0].id = 13;
        table[1].id = 13;
        TriangleSource with_table = source;
        with_table.setGpuTriangles(table);
        r = runPairNarrowPhase(p, with_table, {}, pool);
        REQUIRE_FALSE(r);
        CHECK_THAT(message(r), Catch::Contains("id 13 appears more than once"));
        table[1].id = 12;
        table[1].v[1].x = INFINITY;
        with_table.setGpuTriangles(table);
        r = runPairNarrowPhase(p, with_table, {}, pool);
        REQUIRE_FALSE(r);
        CHECK_THAT(message(r), Catch::Contains("object 3 triangle 0") && Catch::Contains("not finite"));
    }
    SECTION("building a source") {
        TriangleSource s;
        const std::vector<std::uint32_t> four = {0, 1, 2, 3};
        auto a = s.addHostMesh(tetra.positions, four);
        REQUIRE_FALSE(a);
        CHECK(a.error().code() == ErrorCode::InvalidMesh);
        CHECK_THAT(a.error().message(), Catch::Contains("object 0") && Catch::Contains("multiple of 3"));
        Transform3x4 bad = TriangleSource::kIdentity;
        bad[5] = NAN;
        CHECK_FALSE(s.addHostMesh(tetra.positions, tetra.indices, bad));
        REQUIRE(s.addGpuMesh(3));
        CHECK_FALSE(s.setTransform(0, TriangleSource::kIdentity));  // a GPU-only mesh
        CHECK_FALSE(s.setTransform(5, TriangleSource::kIdentity));  // no such object
        REQUIRE(s.addHostMesh(tetra.positions, tetra.indices));
        CHECK(s.setTransform(1, TriangleSource::kIdentity));
        CHECK_FALSE(s.setHostGeometry(1, tetra.positions, four));
        CHECK(s.setHostGeometry(1, tetra.positions, tetra.indices));
        CHECK_FALSE(s.addGpuMesh(0xffffffffu));  // past 2^32 - 1 triangles in all
        s.clear();
        CHECK(s.objectCount() == 0);
        CHECK(s.totalTriangles() == 0);
    }
}

TEST_CASE("Pair path with ids spread over a huge source (slots by sorting the ends)", "[narrow][pairs]") {
    // Object 0: a big GPU-only mesh of which the table holds a few triangles; object 1: a
    // host floor. Two million ids and a few pairs: the path that sorts the pairs' ends.
    // The record path on the same source gives the expected result.
    HostMesh floor;
    floor.positions = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0, 0, 0.5f}, {2, 0, 0.5f}, {0, 2, 0.5f}};
    floor.indices = {0, 1, 2, 3, 4, 5};
    TriangleSource source;
    REQUIRE(*source.addGpuMesh(2000000) == 0);
    REQUIRE(*source.addHostMesh(floor.positions, floor.indices) == 1);
    std::vector<GpuTriangle> table;
    for (std::uint32_t t : {7u, 1234567u, 1999999u, 42u}) {
        const float x = 0.1f * float(table.size());
        GpuTriangle g{t, {3 * t, 3 * t + 1, 3 * t + 2}, {{x, 0.2f, -1}, {x, 0.2f, 1}, {x + 0.1f, 0.5f, 0.25f}}};
        table.push_back(g);
    }
    source.setGpuTriangles(table);
    const std::uint32_t floor0 = source.triangleBase(1), floor1 = floor0 + 1;
    std::vector<CandidatePair> pairs = {{7, floor0}, {floor1, 1234567}, {1999999, floor0}, {42, floor1}, {floor0, 7}, {7, 42}};
    std::vector<CandidateRecord> records;
    for (std::uint32_t t : {7u, 1234567u, 1999999u, 42u}) records.push_back({0, t, {0, 0, 1, 1}, 0, 1});
    records.push_back({1, 0, {0, 0, 1, 1}, 0, 1});
    records.push_back({1, 1, {0, 0, 1, 1}, 0, 1});
    NarrowOptions options;
    options.default_self_collision = false;
    ThreadPool pool(3);
    const auto p = runPairNarrowPhase(pairs, source, options, pool);
    const auto r = runNarrowPhase(records, source, options, pool);
    REQUIRE((p && r));
    REQUIRE(!r->pairs.empty());
    // The records pair every GPU triangle with both floors; the pairs name a subset.
    std::vector<TrianglePair> expected;
    for (const TrianglePair& t : r->pairs) {
        const std::uint32_t a = source.triangleBase(t.object_a) + t.triangle_a, b = source.triangleBase(t.object_b) + t.triangle_b;
        if (std::any_of(pairs.begin(), pairs.end(), [&](const CandidatePair& c) {
                return (c.a == a && c.b == b) || (c.a == b && c.b == a);
            })) {
            expected.push_back(t);
        }
    }
    CHECK(p->pairs == expected);
    CHECK(p->stats.input_pairs == 6);
    CHECK(p->stats.sap_pairs == 5);
    CHECK(p->stats.filtered_pairs == 1);  // (7, 42): one object, no self-collision
    CHECK(p->stats.candidates == 6);
}

TEST_CASE("Pair path with many hits: serial and parallel stages agree bit for bit", "[narrow][pairs][threads]") {
    // A sphere and a copy turned by 3 degrees: the surfaces cross all over, more than 8K
    // colliding pairs, so one thread sums the responses by the counting sort on the
    // calling thread and four threads by the parallel radix form (exact_stage.cpp), the
    // checks, slots and key sorts run their parallel forms, and the tests run in many
    // small tasks. The record path on the same source is the third opinion.
    const HostMesh sphere = makeSphere(1.0f, {0, 0, 0}, 64, 128);
    const std::vector<ReferenceObject> objects = {{&sphere}, {&sphere, turned(3.0 * 3.14159265358979 / 180.0, {0, 0, 0})}};
    auto candidates = allTrianglesAsCandidates(objects);
    REQUIRE(candidates);
    TriangleSource source;
    for (const ReferenceObject& o : objects) REQUIRE(source.addHostMesh(o.mesh->positions, o.mesh->indices, rows3x4(o.transform)));
    std::vector<CandidatePair> pairs;
    for (const narrow::IndexPair& p : narrow::sweepAndPrunePairs(*candidates)) {
        const CandidateTriangle &a = (*candidates)[p.i], &b = (*candidates)[p.j];
        if (a.object != b.object) pairs.push_back({source.triangleBase(a.object) + a.triangle, source.triangleBase(b.object) + b.triangle});
    }
    std::shuffle(pairs.begin(), pairs.end(), std::mt19937(5));
    NarrowOptions options;
    options.default_self_collision = false;
    ThreadPool one(1), four(4);
    const auto serial = runPairNarrowPhase(pairs, source, options, one);
    REQUIRE(serial);
    REQUIRE(serial->pairs.size() > 8192);
    NarrowWorkspace workspace;
    for (int round = 0; round < 2; ++round) {  // the second reuses the workspace
        four.prepare(4);
        const auto parallel = runPairNarrowPhase(pairs, source, options, four, workspace);
        REQUIRE(parallel);
        requireSamePairsAndResponses(*serial, *parallel);
        requireSameStats(serial->stats, parallel->stats);
    }
    std::vector<CandidateRecord> records;
    for (const CandidateTriangle& c : *candidates) records.push_back({c.object, c.triangle, {c.box[0], c.box[1], c.box[2], c.box[3]}, c.zmin, c.zmax});
    const auto lean = runNarrowPhase(records, source, options, four);
    REQUIRE(lean);
    requireSamePairsAndResponses(*serial, *lean);
}
