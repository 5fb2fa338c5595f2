// Host memory running out during a detection is ErrorCode::OutOfMemory, never an exception
// (the API promises none), wherever it happens: reading the records back on the calling
// thread, or in the narrow phase's worker threads. The world stays Ready and detects again.
// This program replaces the global operator new (as tests/io/oom_tests.cpp does), so it is
// its own executable; it runs without the validation layer, whose own allocations would
// fail too.
#include <catch2/catch.hpp>

#include <atomic>
#include <cstdlib>
#include <limits>
#include <new>

#include "support/pathological_scenes.hpp"

using namespace vkcollide;
using namespace vkcollide::test;

namespace {

std::atomic<std::size_t> g_fail_above{std::numeric_limits<std::size_t>::max()};

struct FailLargeAllocations {
    explicit FailLargeAllocations(std::size_t bytes) { g_fail_above.store(bytes); }
    ~FailLargeAllocations() { g_fail_above.store(std::numeric_limits<std::size_t>::max()); }
    FailLargeAllocations(const FailLargeAllocations&) = delete;
    FailLargeAllocations& operator=(const FailLargeAllocations&) = delete;
};

}  // namespace

// Every replaceable form, so that no allocation is made by one allocator and freed by
// another (AddressSanitizer checks that pairing).
void* operator new(std::size_t bytes) {
    if (bytes > g_fail_above.load(std::memory_order_relaxed)) throw std::bad_alloc();
    if (void* p = std::malloc(bytes ? bytes : 1)) return p;
    throw std::bad_alloc();
}
void* operator new[](std::size_t bytes) { return ::operator new(bytes); }
void* operator new(std::size_t bytes, const std::nothrow_t&) noexcept {
    if (bytes > g_fail_above.load(std::memory_order_relaxed)) return nullptr;
    return std::malloc(bytes ? bytes : 1);
}
void* operator new[](std::size_t bytes, const std::nothrow_t& tag) noexcept { return ::operator new(bytes, tag); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }

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
