#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdint>
#include <random>
#include <vector>

#include "narrow/radix_sort.hpp"
#include "vkcollide/thread_pool.hpp"

using vkcollide::ThreadPool;
using vkcollide::narrow::Buffer;

namespace {

// Keys (value << low_bits) | position: ascending in the low bits, as the narrow phase
// builds them, with values of `value_bits` bits repeating often.
std::vector<std::uint64_t> positionKeys(std::size_t n, int value_bits, int low_bits, std::uint32_t seed) {
    std::mt19937_64 rng(seed);
    std::vector<std::uint64_t> keys(n);
    const std::uint64_t values = std::uint64_t{1} << value_bits;
    for (std::size_t i = 0; i < n; ++i) keys[i] = ((rng() % values) << low_bits) | (low_bits > 0 ? i : 0);
    return keys;
}

Buffer<std::uint64_t> toBuffer(const std::vector<std::uint64_t>& v) {
    Buffer<std::uint64_t> b;
    b.resize(v.size());
    std::copy(v.begin(), v.end(), b.begin());
    return b;
}

}  // namespace

// Skipping the low bits must give what a full sort gives when the input ascends in them:
// both the serial path (below kSerialBelow) and the parallel one, any thread count.
TEST_CASE("radix sorts that skip already-ordered low bits equal a full sort", "[narrow][radix]") {
    for (unsigned threads : {1u, 3u, 8u}) {
        ThreadPool pool(threads);
        for (std::size_t n : {std::size_t(0), std::size_t(1), std::size_t(100), std::size_t(5000), std::size_t(70000)}) {
            for (int low_bits : {0, 5, 17, 32}) {
                if (low_bits > 0 && (std::uint64_t{1} << low_bits) < n) continue;  // positions must fit
                for (int value_bits : {1, 9, 23}) {
                    std::vector<std::uint64_t> expected = positionKeys(n, value_bits, low_bits, 7u + unsigned(n) + unsigned(low_bits));
                    Buffer<std::uint64_t> a = toBuffer(expected), b = toBuffer(expected), scratch;
                    std::sort(expected.begin(), expected.end());
                    vkcollide::narrow::parallelRadixSort(pool, a, scratch, value_bits + low_bits, low_bits);
                    vkcollide::narrow::parallelSortKeys(pool, b, scratch, value_bits + low_bits, low_bits);
                    INFO("threads " << threads << ", n " << n << ", low bits " << low_bits << ", value bits " << value_bits);
                    REQUIRE(std::equal(a.begin(), a.end(), expected.begin(), expected.end()));
                    REQUIRE(std::equal(b.begin(), b.end(), expected.begin(), expected.end()));
                }
            }
        }
    }
}

// With first_bit 0 they are plain sorts of arbitrary keys.
TEST_CASE("radix sorts of unordered keys", "[narrow][radix]") {
    ThreadPool pool(4);
    std::mt19937_64 rng(11);
    for (std::size_t n : {std::size_t(3), std::size_t(40000)}) {
        for (int bits : {8, 30, 64}) {
            std::vector<std::uint64_t> expected(n);
            for (auto& k : expected) k = bits == 64 ? rng() : rng() & ((std::uint64_t{1} << bits) - 1);
            Buffer<std::uint64_t> a = toBuffer(expected), b = toBuffer(expected), scratch;
            std::sort(expected.begin(), expected.end());
            vkcollide::narrow::parallelRadixSort(pool, a, scratch, bits);
            vkcollide::narrow::parallelSortKeys(pool, b, scratch, bits);
            REQUIRE(std::equal(a.begin(), a.end(), expected.begin(), expected.end()));
            REQUIRE(std::equal(b.begin(), b.end(), expected.begin(), expected.end()));
        }
    }
}

// resizeFresh: v.resize() within the capacity; beyond it, value-initialised elements in new
// memory that the executor's threads touched first.
TEST_CASE("resizeFresh sizes a vector as resize() does, growing it through the executor", "[narrow]") {
    struct Pair {
        std::uint32_t a = 7, b = 0, c = 0, d = 0;  // a non-zero default: value-initialised, not only zeroed
    };
    const Pair old{1, 2, 3, 4};
    const auto fresh = [](const Pair& p) { return p.a == 7 && p.b == 0 && p.c == 0 && p.d == 0; };
    for (unsigned threads : {1u, 4u}) {
        ThreadPool pool(threads);
        std::vector<Pair> v(3, old);
        for (std::size_t n : {std::size_t(2), std::size_t(300000), std::size_t(1000), std::size_t(700000)}) {
            const bool grows = n > v.capacity();
            const std::size_t kept = grows ? 0 : std::min(n, v.size());
            vkcollide::narrow::resizeFresh(v, n, pool);
            REQUIRE(v.size() == n);
            CHECK(std::all_of(v.begin(), v.begin() + std::ptrdiff_t(kept), [&](const Pair& p) { return p.a == old.a && p.d == old.d; }));
            CHECK(std::all_of(v.begin() + std::ptrdiff_t(kept), v.end(), fresh));
            std::fill(v.begin(), v.end(), old);
        }
    }
}

// The two-array resizeFresh (a result's pairs and responses): each array as the one-array
// form sizes it, whichever of them grows (both at once: the last size but one).
TEST_CASE("resizeFresh sizes two vectors at once as resize() does, growing either or both", "[narrow]") {
    struct Pair {
        std::uint32_t a = 7, b = 0, c = 0, d = 0;
    };
    struct Response {
        double x = 0.5, y = 0;
        std::uint32_t id = 9;
    };
    const Pair old_pair{1, 2, 3, 4};
    const Response old_response{1.0, 2.0, 3};
    for (unsigned threads : {1u, 4u}) {
        ThreadPool pool(threads);
        std::vector<Pair> pairs(3, old_pair);
        std::vector<Response> responses(5, old_response);
        const std::size_t sizes[][2] = {{2, 4}, {300000, 3}, {300000, 200000}, {1000, 900000}, {700000, 900000}, {1500000, 1200000},
                                        {0, 0}};
        for (const auto& size : sizes) {
            INFO("sizes " << size[0] << ", " << size[1] << " on " << threads << " threads");
            const std::size_t kept_pairs = size[0] > pairs.capacity() ? 0 : std::min(size[0], pairs.size());
            const std::size_t kept_responses = size[1] > responses.capacity() ? 0 : std::min(size[1], responses.size());
            vkcollide::narrow::resizeFresh(pairs, size[0], responses, size[1], pool);
            REQUIRE(pairs.size() == size[0]);
            REQUIRE(responses.size() == size[1]);
            for (std::size_t i = 0; i < pairs.size(); ++i) {
                const bool kept = i < kept_pairs;
                REQUIRE(pairs[i].a == (kept ? old_pair.a : 7u));
                REQUIRE(pairs[i].d == (kept ? old_pair.d : 0u));
            }
            for (std::size_t i = 0; i < responses.size(); ++i) {
                const bool kept = i < kept_responses;
                REQUIRE(responses[i].x == (kept ? old_response.x : 0.5));
                REQUIRE(responses[i].id == (kept ? old_response.id : 9u));
            }
            std::fill(pairs.begin(), pairs.end(), old_pair);
            std::fill(responses.begin(), responses.end(), old_response);
        }
    }
}
