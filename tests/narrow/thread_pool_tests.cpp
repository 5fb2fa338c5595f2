#include <catch2/catch.hpp>

#include <atomic>
#include <thread>
#include <vector>

#include "vkcollide/thread_pool.hpp"

using vkcollide::ThreadPool;

TEST_CASE("ThreadPool covers every index exactly once", "[narrow][threads]") {
    for (unsigned threads : {1u, 2u, 4u, 7u}) {
        ThreadPool pool(threads);
        CHECK(pool.threadCount() == threads);
        for (std::size_t count : {std::size_t(0), std::size_t(1), std::size_t(5), std::size_t(1000)}) {
            for (std::size_t grain : {std::size_t(0), std::size_t(1), std::size_t(3), std::size_t(64)}) {
                // Catch2 assertions are not thread safe: record, then check here.
                std::vector<std::atomic<int>> seen(count);
                std::atomic<std::size_t> largest_chunk{0};
                pool.parallelFor(count, grain, [&](std::size_t begin, std::size_t end) {
                    std::size_t size = end - begin, prev = largest_chunk.load();
                    while (size > prev && !largest_chunk.compare_exchange_weak(prev, size)) {
                    }
                    for (std::size_t i = begin; i < end; ++i) seen[i].fetch_add(1);
                });
                CHECK(largest_chunk.load() <= std::max<std::size_t>(grain, 1));
                for (std::size_t i = 0; i < count; ++i) REQUIRE(seen[i].load() == 1);
            }
        }
    }
}

TEST_CASE("ThreadPool with 0 threads uses the hardware concurrency", "[narrow][threads]") {
    ThreadPool pool(0);
    CHECK(pool.threadCount() == std::max(1u, std::thread::hardware_concurrency()));
}

TEST_CASE("ThreadPool serialises loops submitted from several threads", "[narrow][threads]") {
    ThreadPool pool(3);
    std::atomic<long> total{0};
    std::vector<std::thread> submitters;
    for (int s = 0; s < 4; ++s) {
        submitters.emplace_back([&] {
            for (int k = 0; k < 50; ++k) {
                pool.parallelFor(100, 7, [&](std::size_t begin, std::size_t end) {
                    total.fetch_add(static_cast<long>(end - begin));
                });
            }
        });
    }
    for (std::thread& t : submitters) t.join();
    CHECK(total.load() == 4L * 50L * 100L);
}
