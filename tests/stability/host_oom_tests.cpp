// Host memory running out during a detection is ErrorCode::OutOfMemory, never an exception
// (the API promises none), wherever it happens: reading the records back on the calling
// thread, or in the narrow phase's worker threads. The world stays Ready and detects again.
// This program replaces the global operator new (support/fail_large_allocations.cpp), so it
// is its own executable; it runs without the validation layer, whose own allocations would
// fail too.
#include <catch2/catch.hpp>

#include "support/fail_large_allocations.hpp"
#include "support/pathological_scenes.hpp"
#include "vkcollide/scene.hpp"

using namespace vkcollide;
using namespace vkcollide::test;

TEST_CASE("host memory running out in a detection is OutOfMemory, and the world detects again", "[stability][gpu][failures]") {
    auto ctx = Context::create();
    REQUIRE(ctx);
    // 2,000 slabs: 24,000 candidates, so the records read back take 1.9 MB on this thread.
    auto slabs = slabsOverContact(2000);
    // 600 crossing triangles: 180,000 pairs, so the narrow phase's workers grow arrays of MBs.
    auto crossing = crossingTriangles(600);
    REQUIRE(slabs);
    REQUIRE(crossing);
    crossing->settings.peeling.layer_cap = 8;
    for (const PathologicalCase* c : {&*slabs, &*crossing}) {
        INFO(c->name);
        auto world = CollisionWorld::create(**ctx, {.threads = 2});
        REQUIRE(world);
        for (const SceneObject& o : c->scene.objects) REQUIRE((*world)->addMesh(o.mesh, o.options));
        auto before = (*world)->detect(c->settings);
        REQUIRE(before);
        {
            FailLargeAllocations guard(1 << 20);
            auto r = (*world)->detect(c->settings);
            REQUIRE_FALSE(r);
            CHECK(r.error().code() == ErrorCode::OutOfMemory);
            // The asynchronous form: the failure comes from collect().
            auto submitted = (*world)->submit(c->settings);
            if (submitted) {
                auto collected = (*world)->collect();
                REQUIRE_FALSE(collected);
                CHECK(collected.error().code() == ErrorCode::OutOfMemory);
            } else {
                CHECK(submitted.error().code() == ErrorCode::OutOfMemory);
            }
        }
        CHECK_FALSE((*world)->pending());
        CHECK((*world)->state() == WorldState::Ready);
        auto again = (*world)->detect(c->settings);
        REQUIRE(again);
        CHECK((again->pairs == before->pairs));
    }
}

TEST_CASE("host memory running out copying a mesh (addMesh, updateVertices in flight) is OutOfMemory and changes nothing",
          "[stability][gpu][failures]") {
    auto ctx = Context::create();
    REQUIRE(ctx);
    // 150 x 300 segments: 44,702 vertices, a 536 KB host copy; with the guard at 256 KB,
    // addMesh's copy fails, and so does the host half of updateVertices' first vertex copy.
    auto sphere = uvSphere(1.0f, 300, 150);
    auto other = uvSphere(0.8f, 24, 12);
    REQUIRE(sphere);
    REQUIRE(other);
    for (Float3& p : other->positions) p.x += 1.0f;  // through the sphere's surface
    auto world = CollisionWorld::create(**ctx, {.threads = 2});
    REQUIRE(world);
    {
        FailLargeAllocations guard(256 << 10);
        auto added = (*world)->addMesh(*sphere);
        REQUIRE_FALSE(added);
        CHECK(added.error().code() == ErrorCode::OutOfMemory);
        CHECK(added.error().message().find("addMesh") != std::string::npos);
    }
    CHECK((*world)->objectCount() == 0);
    auto id = (*world)->addMesh(*sphere);
    REQUIRE(id);
    REQUIRE((*world)->addMesh(*other));
    auto before = (*world)->detect();
    REQUIRE(before);
    REQUIRE_FALSE(before->pairs.empty());
    std::vector<Float3> moved = sphere->positions;
    for (Float3& p : moved) p.x += 10;  // apart
    REQUIRE((*world)->submit());
    {
        FailLargeAllocations guard(256 << 10);
        auto updated = (*world)->updateVertices(*id, moved);  // in flight: needs a vertex copy
        REQUIRE_FALSE(updated);
        CHECK(updated.error().code() == ErrorCode::OutOfMemory);
    }
    auto in_flight = (*world)->collect();
    REQUIRE(in_flight);
    CHECK((in_flight->pairs == before->pairs));
    auto unchanged = (*world)->detect();  // the refused update changed nothing
    REQUIRE(unchanged);
    CHECK((unchanged->pairs == before->pairs));
    REQUIRE((*world)->submit());
    REQUIRE((*world)->updateVertices(*id, moved));  // with memory, in flight
    auto old = (*world)->collect();
    REQUIRE(old);
    CHECK((old->pairs == before->pairs));
    auto apart = (*world)->detect();
    REQUIRE(apart);
    CHECK(apart->pairs.empty());
    CHECK((*world)->state() == WorldState::Ready);
}
