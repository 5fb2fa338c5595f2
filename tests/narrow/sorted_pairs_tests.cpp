// runSortedPairs (src/narrow/sorted_pairs.hpp): the GPU's sorted pairs arrive as two global
// triangle ids each (8 bytes, half a TrianglePair over the bus) and the host names them
// (object, triangle) as it copies them into the result. Named right across empty objects
// and chunk boundaries, whatever order an engine's executor runs the chunks in; responses
// independent of the executor; a list out of range or out of order fails by name.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "common/config.h"
#include "narrow/same_result.hpp"
#include "narrow/scene_builders.hpp"
#include "narrow/sorted_pairs.hpp"
#include "vkcollide/narrow.hpp"
#include "vkcollide/thread_pool.hpp"

using namespace vkcollide;
using namespace vkcollide::test;

namespace {

// Objects: empty, sphere, empty, empty, sphere, tetrahedron, empty (empty ones share their
// neighbour's first id, at the start, between and at the end).
struct Source {
    std::vector<HostMesh> meshes;
    TriangleSource source;

    Source() {
        meshes.push_back(HostMesh{"empty", {}, {}});
        meshes.push_back(makeSphere(1.0f, {0, 0, 0}, 40, 60));
        meshes.push_back(HostMesh{"empty", {}, {}});
        meshes.push_back(HostMesh{"empty", {}, {}});
        meshes.push_back(makeSphere(0.8f, {0.5f, 0, 0}, 30, 40));
        meshes.push_back(makeTetrahedron());
        meshes.push_back(HostMesh{"empty", {}, {}});
        for (const HostMesh& m : meshes) REQUIRE(source.addHostMesh(m.positions, m.indices));
    }
};

// The pair (a, b) as the result names it, by a walk over the objects' ranges.
TrianglePair named(const TriangleSource& s, std::uint32_t a, std::uint32_t b) {
    TrianglePair p{0, 0, 0, 0};
    for (std::uint32_t o = 0; o < s.objectCount(); ++o) {
        if (a >= s.triangleBase(o) && a < s.triangleBase(o + 1)) p.object_a = o, p.triangle_a = a - s.triangleBase(o);
        if (b >= s.triangleBase(o) && b < s.triangleBase(o + 1)) p.object_b = o, p.triangle_b = b - s.triangleBase(o);
    }
    return p;
}

// `count` distinct pairs a < b over the source's ids, ascending, both ends in every object
// with triangles (the first and last ids included).
std::vector<CandidatePair> sortedPairs(const TriangleSource& s, std::size_t count, unsigned seed) {
    const std::uint32_t total = s.totalTriangles();
    std::mt19937 rng(seed);
    std::uniform_int_distribution<std::uint32_t> id(0, total - 1);
    std::vector<std::uint64_t> keys{std::uint64_t{0} << 32 | (total - 1)};
    while (keys.size() < count) {
        std::uint32_t a = id(rng), b = id(rng);
        if (a == b) continue;
        if (a > b) std::swap(a, b);
        keys.push_back(std::uint64_t{a} << 32 | b);
    }
    std::sort(keys.begin(), keys.end());
    keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
    std::vector<CandidatePair> pairs;
    for (std::uint64_t k : keys) pairs.push_back({static_cast<std::uint32_t>(k >> 32), static_cast<std::uint32_t>(k)});
    return pairs;
}

// An engine's executor that runs a loop's tasks last to first.
CallbackExecutor backwards() {
    return CallbackExecutor(3, [](std::size_t n, const std::function<void(std::size_t)>& run) {
        for (std::size_t k = n; k-- > 0;) run(k);
    });
}

}  // namespace

TEST_CASE("sorted pairs: global ids are named (object, triangle) across empty objects and chunks, on any executor", "[narrow][sorted]") {
    Source src;
    const TriangleSource& s = src.source;
    const std::vector<CandidatePair> pairs = sortedPairs(s, 3 * narrow::kSortedPairGrain + 123, 7);  // four chunks
    REQUIRE(pairs.size() > 3 * narrow::kSortedPairGrain);
    std::vector<TrianglePair> expected;
    for (const CandidatePair& p : pairs) expected.push_back(named(s, p.a, p.b));
    // The first id is the first sphere's (past the empty object 0), the last the tetrahedron's
    // (before the empty object 6); the three middle objects are all met.
    const TrianglePair ends{1, 0, 5, s.triangleCount(5) - 1};
    REQUIRE(std::find(expected.begin(), expected.end(), ends) != expected.end());
    for (std::uint32_t o : {1u, 4u, 5u})
        REQUIRE(std::any_of(expected.begin(), expected.end(), [o](const TrianglePair& p) { return p.object_a == o || p.object_b == o; }));

    ThreadPool one(1), four(4);
    CallbackExecutor reversed = backwards();
    NarrowWorkspace ws;
    auto reference = narrow::runSortedPairs(pairs, s, {}, one, ws);
    REQUIRE(reference);
    CHECK(reference->pairs == expected);
    CHECK(reference->stats.input_pairs == pairs.size());
    CHECK(reference->responses.size() == reference->stats.candidates);
    for (Executor* ex : {static_cast<Executor*>(&four), static_cast<Executor*>(&reversed)}) {
        auto r = narrow::runSortedPairs(pairs, s, {}, *ex, ws);
        REQUIRE(r);
        CHECK(r->pairs == expected);
        requireSamePairsAndResponses(*r, *reference);
    }
    // max_pairs keeps the first pairs, named the same; the responses cover those only.
    NarrowOptions few;
    few.max_pairs = narrow::kSortedPairGrain + 5;
    auto cut = narrow::runSortedPairs(pairs, s, few, reversed, ws);
    REQUIRE(cut);
    CHECK(cut->pairs == std::vector<TrianglePair>(expected.begin(), expected.begin() + static_cast<std::ptrdiff_t>(few.max_pairs)));
    CHECK(cut->pairs_left_out == pairs.size() - few.max_pairs);
    // No pairs: an empty result, and no loop over every triangle (the host's responses'
    // marks and slots, many tasks over a source of 2^24 triangles): no task runs.
    std::size_t tasks = 0;
    CallbackExecutor counting(3, [&tasks](std::size_t n, const std::function<void(std::size_t)>& run) {
        for (std::size_t k = 0; k < n; ++k, ++tasks) run(k);
    });
    TriangleSource big;
    REQUIRE(big.addGpuMesh(1u << 24));
    auto none = narrow::runSortedPairs({}, big, {}, counting, ws);
    REQUIRE(none);
    CHECK(none->pairs.empty());
    CHECK(none->responses.empty());
    CHECK(none->pairs_left_out == 0);
    CHECK(tasks == 0);
}

TEST_CASE("sorted pairs: a list out of range or out of order fails naming its first bad pair", "[narrow][sorted]") {
    Source src;
    const TriangleSource& s = src.source;
    const std::uint32_t total = s.totalTriangles();
    std::vector<CandidatePair> pairs = sortedPairs(s, 2 * narrow::kSortedPairGrain, 11);
    ThreadPool pool(2);
    NarrowWorkspace ws;
    struct Bad {
        const char* what;
        std::size_t at;
        CandidatePair pair;
    };
    const std::size_t late = narrow::kSortedPairGrain + 17;  // in the second chunk
    for (const Bad& bad : {Bad{"b past the last triangle", late, {pairs[late].a, total}}, Bad{"a equal to b", 3, {pairs[3].a, pairs[3].a}},
                           Bad{"a above b", late, {pairs[late].b, pairs[late].a}}, Bad{"a repeat", late, pairs[late - 1]},
                           Bad{"out of order", late, pairs[late - 2]}}) {
        INFO(bad.what);
        std::vector<CandidatePair> broken = pairs;
        broken[bad.at] = bad.pair;
        auto r = narrow::runSortedPairs(broken, s, {}, pool, ws);
        REQUIRE_FALSE(r);
        CHECK(r.error().code() == ErrorCode::VulkanError);
        const std::string expected_start = "sorted pairs: pair " + std::to_string(bad.at) + " ";
        CHECK(r.error().message().rfind(expected_start, 0) == 0);
        CHECK(r.error().message().find("of " + std::to_string(total) + ")") != std::string::npos);
    }
}
