// UseGuard (src/core/use_guard.hpp): a second thread, or a call re-entering from a
// callback, is refused with an error naming both calls; calls one after another pass,
// from any thread.
#include <catch2/catch.hpp>

#include <atomic>
#include <optional>
#include <thread>
#include <vector>

#include "core/use_guard.hpp"

using namespace vkcollide;

TEST_CASE("UseGuard refuses a second thread while a call runs, naming both calls", "[guard]") {
    UseGuard guard("CollisionWorld");
    std::atomic<int> step{0};
    std::optional<Error> seen;
    std::thread other([&] {
        while (step.load() != 1) std::this_thread::yield();
        auto scope = guard.enter("CollisionWorld::collect");
        if (!scope) seen = scope.error();
        step = 2;
    });
    {
        auto scope = guard.enter("CollisionWorld::detect");
        REQUIRE(scope);
        CHECK(guard.busy());
        step = 1;
        while (step.load() != 2) std::this_thread::yield();
    }
    other.join();
    REQUIRE(seen);
    CHECK(seen->code() == ErrorCode::InvalidArgument);
    CHECK_THAT(seen->message(), Catch::Contains("CollisionWorld::collect was called on thread") &&
                                    Catch::Contains("while CollisionWorld::detect runs on thread") &&
                                    Catch::Contains("used from one thread at a time"));
    CHECK_FALSE(guard.busy());
}

TEST_CASE("UseGuard refuses a call re-entering from inside another on the same thread", "[guard]") {
    UseGuard guard("CollisionWorld");
    auto outer = guard.enter("CollisionWorld::detect");
    REQUIRE(outer);
    auto inner = guard.enter("CollisionWorld::removeObject");
    REQUIRE_FALSE(inner);
    CHECK_THAT(inner.error().message(), Catch::Contains("CollisionWorld::removeObject was called from inside CollisionWorld::detect") &&
                                            Catch::Contains("a callback re-entered"));
}

TEST_CASE("UseGuard lets calls in one after another, from different threads, and a moved scope releases once", "[guard]") {
    UseGuard guard("CollisionWorld");
    for (int i = 0; i < 3; ++i) {
        std::thread t([&] {
            auto scope = guard.enter("CollisionWorld::detect");
            CHECK(scope);
        });
        t.join();
    }
    {
        auto first = guard.enter("CollisionWorld::submit");
        REQUIRE(first);
        UseGuard::Scope moved = std::move(*first);
        CHECK(guard.busy());
    }
    CHECK_FALSE(guard.busy());
    auto again = guard.enter("CollisionWorld::collect");
    CHECK(again);
}

TEST_CASE("UseGuard under contention: exactly one of many threads is inside at any time", "[guard]") {
    UseGuard guard("CollisionWorld");
    std::atomic<int> inside{0}, max_inside{0}, admitted{0}, refused{0};
    std::vector<std::thread> threads;
    for (int t = 0; t < 4; ++t)
        threads.emplace_back([&] {
            for (int i = 0; i < 2000; ++i) {
                auto scope = guard.enter("CollisionWorld::detect");
                if (!scope) {
                    ++refused;
                    continue;
                }
                const int now = ++inside;
                int seen = max_inside.load();
                while (now > seen && !max_inside.compare_exchange_weak(seen, now)) {
                }
                --inside;
                ++admitted;
            }
        });
    for (auto& t : threads) t.join();
    CHECK(max_inside.load() == 1);
    CHECK(admitted.load() + refused.load() == 8000);
    CHECK(admitted.load() > 0);
}
