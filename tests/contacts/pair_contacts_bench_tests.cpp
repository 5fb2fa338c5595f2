// The cost of one pair's contact geometry on the host, on one thread (hidden: run with
// `vkcollide_pair_contacts_host_tests "[.bench]"`): crossing pairs from the random test's
// distribution, and coplanar overlaps, each pair's contact computed in a loop.
#include <catch2/catch.hpp>

#include <chrono>
#include <cstdio>
#include <random>
#include <vector>

#include "contacts/pair_contacts.hpp"
#include "narrow/triangle_intersection.hpp"

using namespace vkcollide;
using Tri = std::array<Float3, 3>;

namespace {

// ns per pair over `rounds` passes of contacts::pairContact on every pair.
double nsPerPair(const std::vector<std::pair<Tri, Tri>>& pairs, int rounds) {
    float sink = 0;
    const auto start = std::chrono::steady_clock::now();
    for (int r = 0; r < rounds; ++r)
        for (const auto& [a, b] : pairs) sink += contacts::pairContact(a, b).start.x;
    const double ns = std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - start).count();
    CHECK(sink == sink);  // keeps the loop
    return ns / (double(pairs.size()) * rounds);
}

}  // namespace

TEST_CASE("pair contacts: host cost a pair", "[.bench][contacts]") {
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> u(-1, 1);
    std::vector<std::pair<Tri, Tri>> crossing, coplanar;
    while (crossing.size() < 100000) {
        Tri a, b;
        for (Float3& p : a) p = {u(rng), u(rng), u(rng)};
        for (Float3& p : b) p = {u(rng), u(rng), u(rng)};
        if (narrow::trianglesIntersect(a, b)) crossing.push_back({a, b});
    }
    while (coplanar.size() < 100000) {  // both in z = 0.25: an overlap clipped in the plane
        Tri a, b;
        for (Float3& p : a) p = {u(rng), u(rng), 0.25f};
        for (Float3& p : b) p = {u(rng), u(rng), 0.25f};
        if (narrow::trianglesIntersect(a, b)) coplanar.push_back({a, b});
    }
    std::printf("kind,pairs,ns_per_pair\n");
    std::printf("crossing,%zu,%.1f\n", crossing.size() * 10, nsPerPair(crossing, 10));
    std::printf("coplanar,%zu,%.1f\n", coplanar.size() * 10, nsPerPair(coplanar, 10));
}
