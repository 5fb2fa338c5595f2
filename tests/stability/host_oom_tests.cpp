// Host memory running out during a detection is ErrorCode::OutOfMemory, never an exception
// (the API promises none), wherever it happens: reading the records back on the calling
// thread, or in the narrow phase's worker threads. The world stays Ready and detects again.
// This program replaces the global operator new (support/fail_large_allocations.cpp), so it
// is its own executable; it runs without the validation layer, whose own allocations would
// fail too.
#include <catch2/catch.hpp>

#include "support/fail_large_allocations.hpp"
#include "support/pathological_scenes.hpp"

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
    crossing->settings.layer_cap = 8;
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
