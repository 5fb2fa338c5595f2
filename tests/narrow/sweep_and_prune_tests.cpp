// Sweep-and-prune against the quadratic definition.
#include <catch2/catch.hpp>

#include <random>
#include <vector>

#include "narrow/sweep_and_prune.hpp"

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
        REQUIRE(narrow::sweepAndPrunePairs(c) == expected);
    }
}
