// The pair path's front (src/narrow/pair_keys.hpp): the form on the calling thread and
// the parallel form give the same slots and keys as a plain reference, on random inputs
// around the size where the automatic choice switches, on 1 and 4 threads; the same first
// bad pair; the whole pair path gives the same result on either side of the switch; and
// few pairs the GPU decided run on the calling thread, with the same result.
#include <catch2/catch.hpp>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <functional>
#include <map>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include "narrow/exact_stage.hpp"
#include "narrow/pair_keys.hpp"
#include "narrow/same_result.hpp"
#include "narrow/scene_builders.hpp"
#include "narrow/sweep_and_prune.hpp"
#include "narrow/workspace.hpp"
#include "support/exact_reference.hpp"
#include "vkcollide/narrow.hpp"
#include "vkcollide/thread_pool.hpp"

using namespace vkcollide;
using narrow::PairKeys;
using narrow::PairKeysForm;

namespace {

struct Front {
    PairKeys keys;
    std::vector<std::uint32_t> slot_ids;
    std::vector<std::uint64_t> pair_keys;
};

Front runFront(Executor& ex, const std::vector<CandidatePair>& pairs, std::uint32_t total, PairKeysForm form,
               NarrowWorkspace& workspace) {
    Front f;
    NarrowWorkspace::Impl& ws = workspace.impl();
    REQUIRE_FALSE(narrow::buildPairKeys(ex, pairs, total, form, ws, f.keys).has_value());
    f.slot_ids.assign(ws.slot_ids.begin(), ws.slot_ids.end());
    f.pair_keys.assign(ws.pair_keys.begin(), ws.pair_keys.end());
    return f;
}

// Slots: the distinct ids ascending; keys: the distinct (lower, higher) slot pairs ascending.
Front reference(const std::vector<CandidatePair>& pairs) {
    std::set<std::uint32_t> ids;
    std::set<std::pair<std::uint32_t, std::uint32_t>> distinct;
    for (const CandidatePair& p : pairs) {
        ids.insert(p.a);
        ids.insert(p.b);
        distinct.insert({std::min(p.a, p.b), std::max(p.a, p.b)});
    }
    Front f;
    f.slot_ids.assign(ids.begin(), ids.end());
    std::map<std::uint32_t, std::uint32_t> slot;
    for (std::uint32_t s = 0; s < f.slot_ids.size(); ++s) slot[f.slot_ids[s]] = s;
    f.keys.slot_count = f.slot_ids.size();
    f.keys.slot_bits = std::max(1, static_cast<int>(std::bit_width(f.slot_ids.empty() ? 0u : f.slot_ids.size() - 1)));
    for (const auto& [a, b] : distinct) f.pair_keys.push_back((std::uint64_t{slot[a]} << f.keys.slot_bits) | slot[b]);
    f.keys.pairs = f.pair_keys.size();
    return f;
}

void requireSame(const Front& a, const Front& b) {
    REQUIRE(a.keys.slot_count == b.keys.slot_count);
    REQUIRE(a.keys.slot_bits == b.keys.slot_bits);
    REQUIRE(a.keys.pairs == b.keys.pairs);
    REQUIRE(a.slot_ids == b.slot_ids);
    REQUIRE(a.pair_keys == b.pair_keys);
}

// n pairs of distinct ids below `total`, drawn from `span` ids spread over [0, total) (few
// spans: many repeats and runs of one lower slot), some reversed repeats.
std::vector<CandidatePair> randomPairs(std::size_t n, std::uint32_t total, std::uint32_t span, std::mt19937_64& rng) {
    std::vector<std::uint32_t> pool(std::min(span, total));
    for (std::uint32_t& id : pool) id = static_cast<std::uint32_t>(rng() % total);
    std::sort(pool.begin(), pool.end());
    pool.erase(std::unique(pool.begin(), pool.end()), pool.end());
    std::vector<CandidatePair> pairs;
    while (pairs.size() < n) {
        if (!pairs.empty() && rng() % 8 == 0) {
            const CandidatePair p = pairs[rng() % pairs.size()];
            pairs.push_back({p.b, p.a});
            continue;
        }
        // A skewed pick: the first four ids in a quarter of the pairs (one triangle in many
        // pairs: long runs of one lower slot).
        const std::size_t r = rng() % pool.size();
        const std::uint32_t a = pool[rng() % 4 == 0 ? r % 4 : r];
        const std::uint32_t b = pool[rng() % pool.size()];
        if (a != b) pairs.push_back({a, b});
    }
    return pairs;
}

// Counts what the narrow phase asks of the executor, and runs its loops on a pool.
class CountingExecutor final : public Executor {
public:
    explicit CountingExecutor(Executor& inner) : inner_(inner) {}
    unsigned threadCount() const noexcept override { return inner_.threadCount(); }
    void parallelFor(std::size_t count, std::size_t grain, const std::function<void(std::size_t, std::size_t)>& body) override {
        ++loops;
        inner_.parallelFor(count, grain, body);
    }
    void prepare(unsigned threads) noexcept override {
        ++prepares;
        inner_.prepare(threads);
    }
    int loops = 0, prepares = 0;

private:
    Executor& inner_;
};

}  // namespace

TEST_CASE("Pair keys: serial and parallel forms equal the reference around the switch", "[narrow][pairs][threads]") {
    ThreadPool one(1), four(4);
    NarrowWorkspace workspace;  // reused across every call, as a frame loop does
    std::mt19937_64 rng(13);
    const std::size_t s = narrow::kSerialPairsBelow;
    struct Case {
        std::uint32_t total, span;
    };
    // Dense ids (the parallel form's marker per id), sparse ids (its sort of the ends),
    // ids up to 2^32 - 2, a tiny id range with repeats everywhere.
    const std::vector<Case> cases = {{5000, 5000}, {3000000, 20000}, {0xffffffffu, 100000}, {40, 40}, {1u << 20, 64}};
    for (const Case& c : cases) {
        for (std::size_t n : {std::size_t{0}, std::size_t{1}, std::size_t{2}, std::size_t{33}, std::size_t{700}, s - 1, s, s + 1}) {
            if (c.total < 3 && n > 0) continue;
            const std::vector<CandidatePair> pairs = randomPairs(n, c.total, c.span, rng);
            const Front expected = reference(pairs);
            for (ThreadPool* pool : {&one, &four}) {
                INFO("total " << c.total << ", span " << c.span << ", pairs " << n << ", threads " << pool->threadCount());
                requireSame(runFront(*pool, pairs, c.total, PairKeysForm::Serial, workspace), expected);
                requireSame(runFront(*pool, pairs, c.total, PairKeysForm::Parallel, workspace), expected);
                requireSame(runFront(*pool, pairs, c.total, PairKeysForm::Automatic, workspace), expected);
            }
        }
    }
}

TEST_CASE("Pair keys: both forms name the same first bad pair", "[narrow][pairs][errors]") {
    ThreadPool four(4);
    NarrowWorkspace workspace;
    std::mt19937_64 rng(7);
    for (std::size_t n : {std::size_t{5}, std::size_t{3000}, narrow::kSerialPairsBelow + 100}) {
        for (int round = 0; round < 4; ++round) {
            std::vector<CandidatePair> pairs = randomPairs(n, 100000, 100000, rng);
            std::vector<std::size_t> bad = {rng() % n, rng() % n};
            pairs[bad[0]] = {pairs[bad[0]].a, pairs[bad[0]].a};  // an id paired with itself
            pairs[bad[1]] = {100000, pairs[bad[1]].b};           // an id out of range
            const std::size_t first = std::min(bad[0], bad[1]);
            for (PairKeysForm form : {PairKeysForm::Serial, PairKeysForm::Parallel}) {
                PairKeys keys;
                const std::optional<std::size_t> found = narrow::buildPairKeys(four, pairs, 100000, form, workspace.impl(), keys);
                REQUIRE(found.has_value());
                CHECK(*found == first);
            }
        }
    }
}

TEST_CASE("Pair path: the same result on either side of the serial front's switch", "[narrow][pairs][threads]") {
    // Two overlapping spheres; their box-overlapping pairs sent with repeats, once as one
    // pair fewer than the switch (the front on the calling thread) and once as one more
    // (the parallel front): one set of distinct pairs, so the results must be identical.
    const HostMesh a = test::makeSphere(1.0f, {0, 0, 0}, 24, 32);
    const HostMesh b = test::makeSphere(0.9f, {0.8f, 0.1f, 0.05f}, 22, 30);
    const std::vector<test::ReferenceObject> objects = {{&a}, {&b}};
    auto candidates = test::allTrianglesAsCandidates(objects);
    REQUIRE(candidates);
    TriangleSource source;
    REQUIRE(source.addHostMesh(a.positions, a.indices));
    REQUIRE(source.addHostMesh(b.positions, b.indices));
    std::vector<CandidatePair> distinct;
    for (const narrow::IndexPair& p : narrow::sweepAndPrunePairs(*candidates)) {
        const CandidateTriangle &x = (*candidates)[p.i], &y = (*candidates)[p.j];
        if (x.object != y.object) distinct.push_back({source.triangleBase(x.object) + x.triangle, source.triangleBase(y.object) + y.triangle});
    }
    const std::size_t s = narrow::kSerialPairsBelow;
    REQUIRE(distinct.size() > 100);
    REQUIRE(distinct.size() < s - 1);
    std::mt19937 rng(11);
    const auto padded = [&](std::size_t n) {
        std::vector<CandidatePair> pairs = distinct;
        while (pairs.size() < n) {
            const CandidatePair p = distinct[rng() % distinct.size()];
            pairs.push_back(rng() % 2 ? p : CandidatePair{p.b, p.a});
        }
        std::shuffle(pairs.begin(), pairs.end(), rng);
        return pairs;
    };
    const std::vector<CandidatePair> below = padded(s - 1), above = padded(s + 1);
    NarrowOptions options;
    options.default_self_collision = false;
    ThreadPool one(1), four(4);
    const auto expected = runPairNarrowPhase(distinct, source, options, one);
    REQUIRE(expected);
    REQUIRE(!expected->pairs.empty());
    NarrowWorkspace workspace;
    for (ThreadPool* pool : {&one, &four}) {
        for (const std::vector<CandidatePair>* pairs : {&below, &above}) {
            const auto got = runPairNarrowPhase(*pairs, source, options, *pool, workspace);
            REQUIRE(got);
            test::requireSamePairsAndResponses(*got, *expected);
            CHECK(got->stats.sap_pairs == expected->stats.sap_pairs);
            CHECK(got->stats.candidates == expected->stats.candidates);
            CHECK(got->stats.triangle_tests == expected->stats.triangle_tests);
            CHECK(got->stats.input_pairs == pairs->size());
        }
    }
}

TEST_CASE("Pair path: few decided pairs run on the calling thread, with the same result", "[narrow][pairs][threads]") {
    // The intersecting pairs of two overlapping spheres, as the GPU's exact decision sends
    // them (NarrowOptions::pairs_decided): below kSerialDecidedBelow pairs the executor is
    // never asked for a loop or a wake-up; with repeats up to the limit it is; the pairs and
    // responses are those of the tested path either way.
    const HostMesh a = test::makeSphere(1.0f, {0, 0, 0}, 24, 32);
    const HostMesh b = test::makeSphere(0.9f, {0.8f, 0.1f, 0.05f}, 22, 30);
    TriangleSource source;
    REQUIRE(source.addHostMesh(a.positions, a.indices));
    REQUIRE(source.addHostMesh(b.positions, b.indices));
    std::vector<CandidatePair> all;  // every pair of the two objects: the tests decide
    for (std::uint32_t i = 0; i < source.triangleBase(1); ++i)
        for (std::uint32_t j = source.triangleBase(1); j < source.totalTriangles(); ++j) all.push_back({i, j});
    NarrowOptions tested;
    tested.default_self_collision = false;
    ThreadPool pool(4);
    const auto expected = runPairNarrowPhase(all, source, tested, pool);
    REQUIRE(expected);
    std::vector<CandidatePair> hits;
    for (const TrianglePair& p : expected->pairs)
        hits.push_back({source.triangleBase(p.object_a) + p.triangle_a, source.triangleBase(p.object_b) + p.triangle_b});
    REQUIRE(hits.size() > 100);
    REQUIRE(hits.size() < narrow::kSerialDecidedBelow);
    std::vector<CandidatePair> repeated = hits;  // the same distinct pairs, at the limit
    std::mt19937 rng(5);
    while (repeated.size() < narrow::kSerialDecidedBelow) {
        const CandidatePair p = hits[rng() % hits.size()];
        repeated.push_back(rng() % 2 ? p : CandidatePair{p.b, p.a});
    }
    std::shuffle(repeated.begin(), repeated.end(), rng);
    NarrowOptions decided = tested;
    decided.pairs_decided = true;
    for (const bool at_limit : {false, true}) {
        INFO((at_limit ? "at the limit" : "below it"));
        CountingExecutor counting(pool);
        const auto got = runPairNarrowPhase(at_limit ? repeated : hits, source, decided, counting);
        REQUIRE(got);
        test::requireSamePairsAndResponses(*got, *expected);
        CHECK(got->stats.triangle_tests == 0);
        if (at_limit) {
            CHECK(counting.loops > 0);
            CHECK(counting.prepares == 1);
        } else {
            CHECK(counting.loops == 0);
            CHECK(counting.prepares == 0);
        }
    }
    // The same few pairs, tested: the pool is used.
    CountingExecutor counting(pool);
    REQUIRE(runPairNarrowPhase(hits, source, tested, counting));
    CHECK(counting.loops > 0);
}
