// Sweep-and-prune against the quadratic definition.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "narrow/radix_sort.hpp"
#include "narrow/sweep_and_prune.hpp"
#include "vkcollide/thread_pool.hpp"

using namespace vkcollide;
using narrow::IndexPair;

namespace {

CandidateTriangle boxCandidate(std::uint32_t id, float x0, float y0, float x1, float y1, float z0, float z1) {
    CandidateTriangle c{};
    c.object = 0;
    c.triangle = id;
    c.box[0] = x0;
    c.box[1] = y0;
    c.box[2] = x1;
    c.box[3] = y1;
    c.zmin = z0;
    c.zmax = z1;
    return c;
}

bool overlap(float a0, float a1, float b0, float b1) { return a0 <= b1 && b0 <= a1; }

std::vector<IndexPair> allPairs(const std::vector<CandidateTriangle>& c) {
    std::vector<IndexPair> expected;
    for (std::uint32_t i = 0; i < c.size(); ++i) {
        for (std::uint32_t j = i + 1; j < c.size(); ++j) {
            if (overlap(c[i].box[0], c[i].box[2], c[j].box[0], c[j].box[2]) &&
                overlap(c[i].box[1], c[i].box[3], c[j].box[1], c[j].box[3]) &&
                overlap(c[i].zmin, c[i].zmax, c[j].zmin, c[j].zmax)) {
                expected.push_back({i, j});
            }
        }
    }
    return expected;
}

}  // namespace

TEST_CASE("Sweep and prune keeps closed overlaps in x, y and z", "[narrow][sap]") {
    const std::vector<CandidateTriangle> c = {
        boxCandidate(0, 0.0f, 0.0f, 0.5f, 0.5f, 0.0f, 1.0f),
        boxCandidate(1, 0.5f, 0.5f, 1.0f, 1.0f, 1.0f, 2.0f),  // touches 0 at a corner and in z
        boxCandidate(2, 0.2f, 0.2f, 0.3f, 0.3f, 3.0f, 4.0f),  // inside 0 and 1 in x, y, but deeper
        boxCandidate(3, 0.6f, 0.0f, 0.7f, 0.4f, 0.0f, 5.0f),  // overlaps 1 in x only
        boxCandidate(4, 0.1f, 0.1f, 0.1f, 0.1f, 0.5f, 0.5f),  // a point inside 0
    };
    CHECK(narrow::sweepAndPrunePairs(c) == std::vector<IndexPair>{{0, 1}, {0, 4}});
}

TEST_CASE("Sweep and prune equals the all-pairs definition on random boxes", "[narrow][sap][random]") {
    std::mt19937 rng(7);
    std::uniform_int_distribution<int> grid(0, 20);  // coarse grid: many exact touches
    std::uniform_int_distribution<int> size(0, 3);
    for (int round = 0; round < 20; ++round) {
        std::vector<CandidateTriangle> c;
        for (std::uint32_t i = 0; i < 300; ++i) {
            const float x = float(grid(rng)) / 20, y = float(grid(rng)) / 20, z = float(grid(rng)) / 20;
            c.push_back(boxCandidate(i, x, y, x + float(size(rng)) / 20, y + float(size(rng)) / 20, z,
                                     z + float(size(rng)) / 20));
        }
        const std::vector<IndexPair> expected = allPairs(c);
        REQUIRE(narrow::sweepAndPrunePairs(c) == expected);
    }
}

TEST_CASE("Sweep and prune in cells: tall, deep, wide, flat and touching boxes, any thread count", "[narrow][sap][random]") {
    // Enough boxes for many cells; a mix of sizes so that boxes span several cells, and
    // boxes whose ends fall exactly on shared grid values (and on cell borders).
    std::mt19937 rng(2006);
    std::uniform_int_distribution<int> grid(-40, 40), small(0, 2), kind(0, 9);
    ThreadPool pool1(1), pool3(3);
    for (int round = 0; round < 12; ++round) {
        std::vector<CandidateTriangle> c;
        for (std::uint32_t i = 0; i < 900; ++i) {
            const float x = float(grid(rng)) / 40, y = float(grid(rng)) / 40, z = float(grid(rng)) / 40;
            float w = float(small(rng)) / 40, h = float(small(rng)) / 40, d = float(small(rng)) / 40;
            const int k = kind(rng);
            if (k == 0) h = 1.5f;                 // tall: many strips
            if (k == 1) w = 2.0f;                 // wide: long sweeps
            if (k == 2) h = 0;                    // flat in y
            if (k == 3) d = 1.5f;                 // deep: many slabs
            if (round % 4 == 3) h = d = 0;        // all flat: one cell or many empty ones
            const float y0 = (round % 6 == 5) ? 0.25f : y;  // all at one y
            const float z0 = (round % 6 == 4) ? 0.5f : z;   // all at one depth
            c.push_back(boxCandidate(i, x, y0, x + w, y0 + h, z0, z0 + d));
        }
        if (round == 1) c[7].box[1] = -0.0f;  // -0 next to +0
        if (round == 2) c[9].zmin = -0.0f;
        const std::vector<IndexPair> expected = allPairs(c);
        INFO("round " << round);
        REQUIRE(narrow::sweepAndPrunePairs(c) == expected);
        REQUIRE(narrow::sweepAndPrunePairs(c, &pool1) == expected);
        REQUIRE(narrow::sweepAndPrunePairs(c, &pool3) == expected);
    }
    // The cells are really used (the tests above would pass with a single cell).
    std::vector<CandidateTriangle> c;
    for (std::uint32_t i = 0; i < 1000; ++i) {
        const float y = float(i % 100) / 100, z = float(i / 100) / 10;
        c.push_back(boxCandidate(i, 0, y, 1, y + 0.005f, z, z + 0.05f));
    }
    narrow::GridSweep sweep;
    sweep.build(c, &pool3);
    CHECK(sweep.cellCount() > 50);
    CHECK(sweep.entryCount() < 3 * c.size());
    CHECK(narrow::sweepAndPrunePairs(c, &pool3) == allPairs(c));
}

TEST_CASE("Sweep and prune tiles give the pairs exactly once", "[narrow][sap]") {
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f), size(0.0f, 0.05f);
    std::vector<CandidateTriangle> c;
    for (std::uint32_t i = 0; i < 4000; ++i) {
        const float x = unit(rng), y = unit(rng), z = unit(rng);
        c.push_back(boxCandidate(i, x, y, x + size(rng), y + size(rng), z, z + size(rng)));
    }
    narrow::GridSweep sweep;
    sweep.build(c, nullptr);
    REQUIRE(sweep.tileCount() > 1);
    std::vector<IndexPair> pairs;
    narrow::GridSweep::TileCells cells;
    for (std::size_t begin = 0; begin < sweep.tileCount(); begin += 3) {
        sweep.sweepTiles(begin, std::min(sweep.tileCount(), begin + 3), cells, [&](std::uint32_t i, std::uint32_t j) {
            CHECK(i < j);
            pairs.push_back({i, j});
        });
    }
    std::sort(pairs.begin(), pairs.end());
    CHECK(pairs == allPairs(c));
}

TEST_CASE("Sweep and prune skips pairs of objects that do not self-collide", "[narrow][sap]") {
    // Three objects of random boxes; object 1 does not self-collide. Cells holding only
    // object 1 are skipped; the pairs must still be exactly the allowed overlaps.
    std::mt19937 rng(23);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f), size(0.0f, 0.04f);
    std::vector<CandidateTriangle> c;
    for (std::uint32_t i = 0; i < 3000; ++i) {
        const float x = unit(rng), y = unit(rng), z = unit(rng);
        CandidateTriangle t = boxCandidate(i, x, y, x + size(rng), y + size(rng), z, z + size(rng));
        t.object = i < 2000 ? 1 : (i % 2 ? 0 : 2);  // object 1 covers most cells alone
        c.push_back(t);
    }
    NarrowOptions options;
    options.self_collision = {true, false, true};
    narrow::SweepInput in;
    in.count = c.size();
    in.box = {reinterpret_cast<const narrow::BoxZ*>(&c[0].box[0]), sizeof(CandidateTriangle)};
    in.object = {&c[0].object, sizeof(CandidateTriangle)};
    in.options = &options;
    for (unsigned threads : {1u, 4u}) {
        ThreadPool pool(threads);
        narrow::GridSweep sweep;
        sweep.build(in, &pool);
        std::vector<IndexPair> pairs;
        narrow::GridSweep::TileCells cells;
        sweep.sweepTiles(0, sweep.tileCount(), cells, [&](std::uint32_t i, std::uint32_t j) { pairs.push_back({i, j}); });
        std::sort(pairs.begin(), pairs.end());
        std::vector<IndexPair> expected;
        for (const IndexPair& p : allPairs(c)) {
            if (!(c[p.i].object == 1 && c[p.j].object == 1)) expected.push_back(p);
        }
        CHECK(pairs == expected);
    }
}

TEST_CASE("Radix sort orders 64-bit keys stably", "[narrow][sort]") {
    std::mt19937_64 rng(5);
    for (unsigned threads : {1u, 3u}) {
        ThreadPool pool(threads);
        // Below and above kSerialBelow: the serial and the parallel path.
        for (std::size_t n : {std::size_t(0), std::size_t(1), std::size_t(2047), std::size_t(2048), std::size_t(5000)}) {
            narrow::Buffer<narrow::KeyIndex> items, scratch;
            items.resize(n);
            for (std::size_t i = 0; i < n; ++i) {
                // Few distinct high bytes, some duplicates, some keys using all 64 bits.
                const std::uint64_t r = rng();
                const std::uint64_t key = (i % 7 == 0) ? r : ((r % 50) << 32) | (r % 300);
                items[i] = {key, static_cast<std::uint32_t>(i)};
            }
            std::vector<narrow::KeyIndex> expected(items.begin(), items.end());
            std::stable_sort(expected.begin(), expected.end(), [](const auto& a, const auto& b) { return a.key < b.key; });
            narrow::parallelRadixSort(pool, items, scratch, 64);
            REQUIRE(items.size() == expected.size());
            for (std::size_t i = 0; i < n; ++i) {
                REQUIRE(items[i].key == expected[i].key);
                REQUIRE(items[i].index == expected[i].index);
            }
        }
    }
}

TEST_CASE("Radix sort can leave a payload in the low bits unsorted", "[narrow][sort]") {
    std::mt19937 rng(9);
    ThreadPool pool(3);
    for (std::size_t n : {std::size_t(100), std::size_t(3000), std::size_t(9000)}) {  // serial, serial, parallel
        // High half: a key with many ties; low half: the original position.
        narrow::Buffer<std::uint64_t> items, scratch;
        items.resize(n);
        for (std::size_t i = 0; i < n; ++i) items[i] = (std::uint64_t{rng() % 40} << 32) | i;
        std::vector<std::uint64_t> expected(items.begin(), items.end());
        std::stable_sort(expected.begin(), expected.end(), [](auto a, auto b) { return (a >> 32) < (b >> 32); });
        narrow::parallelRadixSort(pool, items, scratch, 64, 32);
        // Ties keep their order: sorted by the whole key.
        CHECK(std::vector<std::uint64_t>(items.begin(), items.end()) == expected);
    }
}
